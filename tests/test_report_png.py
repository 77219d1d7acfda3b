"""The report embeds each figure with a 256-colour palette: the same picture, fewer bytes."""

from __future__ import annotations

import io
from pathlib import Path

import matplotlib
import numpy as np
import pytest
from PIL import Image

from racketdyn.report.figures import PAGE_PNG_COLOURS, embed_png, page_png

matplotlib.use("Agg")


def _figure_png(path: Path, alpha: bool = False) -> bytes:
    """A figure like the commands' own: antialiased noisy lines, text, a shaded image."""
    import matplotlib.pyplot as plt

    rng = np.random.default_rng(3)
    fig, (a, b) = plt.subplots(1, 2, figsize=(8, 3.5), dpi=150)
    f = np.linspace(0, 2500, 4000)
    a.semilogy(f, 1 + np.abs(np.sin(f / 80)) * 100 + rng.normal(0, 3, f.size) ** 2)
    a.set_xlabel("frequency (Hz)")
    a.set_title("accelerance FRF, ζ = 0.50 %")
    b.imshow(np.add.outer(np.sin(np.linspace(0, 3, 60)), np.cos(np.linspace(0, 4, 80))))
    fig.savefig(path, transparent=alpha)
    plt.close(fig)
    return path.read_bytes()


def _pixels(data: bytes) -> np.ndarray:
    with Image.open(io.BytesIO(data)) as image:
        return np.asarray(image.convert("RGBA"), dtype=int)


@pytest.mark.parametrize("alpha", [False, True])
def test_the_page_shows_the_same_picture_in_fewer_bytes(tmp_path: Path, alpha: bool) -> None:
    data = _figure_png(tmp_path / "figure.png", alpha)
    embedded = page_png(data)
    assert embedded.startswith(b"\x89PNG\r\n\x1a\n")
    assert len(embedded) < 0.6 * len(data)  # the demo's figures: 0.32 of their files
    original, shown = _pixels(data), _pixels(embedded)
    assert shown.shape == original.shape
    with Image.open(io.BytesIO(embedded)) as image:
        assert image.mode == "P"
        assert len(image.getcolors(maxcolors=1000) or []) <= PAGE_PNG_COLOURS
    error = np.abs(shown - original)
    # antialiased edges and shading move by a few levels of 255; nothing else changes
    assert error.mean() < 2.0
    assert np.quantile(error, 0.999) <= 24
    if alpha:  # the transparent background stays transparent
        assert np.array_equal(shown[..., 3] == 0, original[..., 3] == 0)


def test_a_png_that_is_already_small_is_kept(tmp_path: Path) -> None:
    buffer = io.BytesIO()
    Image.new("P", (200, 150), 7).save(buffer, format="png")
    assert page_png(buffer.getvalue()) == buffer.getvalue()


def test_a_damaged_png_is_embedded_as_it_is_with_a_warning(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    data = _figure_png(tmp_path / "figure.png")[:5000]  # cut in its image data
    path = tmp_path / "cut.png"
    path.write_bytes(data)
    figure = embed_png(path, "cut.png")
    assert figure is not None
    assert "cut.png" in caplog.text
