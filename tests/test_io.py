"""Racket files and CSV tables: equivalent spellings agree, bad files are named clearly."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import racketdyn as rd
from racketdyn.errors import InputError
from racketdyn.io import read_load_deflection, read_points

DEFAULT_TEXT = (Path(rd.__file__).parent / "data" / "kawazoe_2002.toml").read_text()


def _racket(tmp_path: Path, text: str) -> rd.Racket:
    path = tmp_path / "racket.toml"
    path.write_text(text)
    return rd.load_racket(path)


def test_swingweight_spelling_gives_the_same_racket(tmp_path: Path, racket: rd.Racket) -> None:
    swing = racket.swingweight_kgcm2
    text = DEFAULT_TEXT.replace("inertia_cg_kgm2 = 0.0131", f"swingweight_kgcm2 = {swing!r}")
    again = _racket(tmp_path, text)
    assert again.inertia_cg_kgm2 == pytest.approx(0.0131, rel=1e-12)
    assert again.roll_inertia_kgm2 == pytest.approx(racket.roll_inertia_kgm2, rel=1e-12)


def test_half_width_and_twistweight_spellings(tmp_path: Path, racket: rd.Racket) -> None:
    text = DEFAULT_TEXT.replace("area_cm2 = 628.0", f"half_width_m = {racket.head.half_width_m!r}")
    text = text.replace("grip_m = 0.070", "grip_m = 0.070\ntwistweight_kgcm2 = 14.0")
    again = _racket(tmp_path, text)
    assert again.head.area_m2 == pytest.approx(racket.head.area_m2, rel=1e-12)
    assert again.twistweight_kgcm2 == pytest.approx(14.0, rel=1e-12)


def test_point_masses_and_string_file(tmp_path: Path, racket: rd.Racket, ball: rd.Ball) -> None:
    # a measured string bed replaces the Kawazoe law; the fit reproduces a cubic exactly
    x = np.linspace(0, 0.03, 16)
    rows = "\n".join(f"{d:.17g},{3.0e4 * d + 2.0e7 * d**3:.17g}" for d in x)
    (tmp_path / "bed.csv").write_text("# measured bed\ndeflection_m,force_n\n" + rows + "\n")
    text = DEFAULT_TEXT.replace("[modal]", 'load_deflection_file = "bed.csv"\n\n[modal]')
    text += '\n[[point_masses]]\nmass_kg = 0.005\nx_m = 0.675\nlabel = "12 o\'clock"\n'
    leaded = _racket(tmp_path, text)
    assert leaded.mass_properties.mass_kg == pytest.approx(0.365)
    law = rd.string_bed_law(leaded, ball)
    np.testing.assert_allclose(law.coefficients, (3.0e4, 0.0, 2.0e7), rtol=1e-7, atol=1e-3)


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        ("mass_kg = 0.360", "mass_kg = 0.360\nmass_kg = 0.1", "malformed TOML"),
        (
            "inertia_cg_kgm2 = 0.0131",
            "inertia_cg_kgm2 = 0.0131\nswingweight_kgcm2 = 290.0",
            "not both",
        ),
        ("mass_kg = 0.360", 'mass_kg = "heavy"', "mass_kg must be a number"),
        ("mains = 16", "mains = 16.5", "mains must be a whole number"),
        ("[modal]", "[modal]\nfile = 'missing.json'", "no such modal model file"),
        ("schema_version = 1", "schema_version = 2", "schema_version 2"),
        ("[strings]", "[strung]", "unknown top-level key 'strung'"),
    ],
)
def test_bad_racket_files(tmp_path: Path, old: str, new: str, message: str) -> None:
    def load_with_modes() -> None:
        rd.modal_model_for(_racket(tmp_path, DEFAULT_TEXT.replace(old, new)))

    with pytest.raises(InputError, match=message):
        load_with_modes()


def test_swingweight_too_small_is_explained(tmp_path: Path) -> None:
    text = DEFAULT_TEXT.replace("inertia_cg_kgm2 = 0.0131", "swingweight_kgcm2 = 100.0")
    # 100 kg·cm² is implausible too (issue 13): allowed, to reach the geometric check
    text += "\n[checks]\nallow_implausible = true\n"
    with pytest.raises(InputError, match=r"swingweight_kgcm2 .* must exceed"):
        _racket(tmp_path, text)


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ("x_m,y_m\n0.5,0.0,7\n", "line 2 has 3 values for 2 columns"),
        ("point,x_m,y_m\n,0.5,0.0\n", "line 2: the point column is empty"),
        ("# comment\n\nx_m,y_m\n0.5,0.0\n0.5,oops\n", "line 5, column y_m"),
        ("x_m,y_m\n0.5,nan\n", "not a finite number"),
        ("x_m,y_m\n", "no impact points"),
        ("", "empty"),
    ],
)
def test_bad_points_files(tmp_path: Path, content: str, message: str) -> None:
    path = tmp_path / "points.csv"
    path.write_text(content)
    with pytest.raises(InputError, match=message):
        read_points(path)


def test_points_and_load_deflection_read(tmp_path: Path) -> None:
    (tmp_path / "p.csv").write_text("point, x_m, y_m\ncentre, 0.505, 0.0\ntop, 0.60, 0.01\n")
    locations, labels = read_points(tmp_path / "p.csv")
    np.testing.assert_array_equal(locations, [[0.505, 0.0], [0.60, 0.01]])
    assert labels == ["centre", "top"]
    (tmp_path / "l.csv").write_text("deflection_m,force_n\n0,0\n0.01,250\n")
    deflection, force = read_load_deflection(tmp_path / "l.csv")
    np.testing.assert_array_equal(force, [0.0, 250.0])
    assert deflection[1] == 0.01
