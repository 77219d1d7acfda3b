"""Traits of real exports the project had not seen (issue 25's hidden judge), each reproduced
without the file: the file, its source and what racketdyn made of it are in docs/develop.md
("the hidden judge", the fourteenth and fifteenth sessions' rounds)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from racketdyn.errors import InputError
from racketdyn.io.frf_layout import read_frfs
from racketdyn.measurement import HammerRecords
from racketdyn.measurement.frf import estimate_frfs
from racketdyn.measurement.records import FrfSet
from racketdyn.modal.identify import _with_peaks_only, identify
from racketdyn.modal.poles import DroppedMode, SelectedPoles, pole_of
from racketdyn.testing.records import Modes, records_for
from test_frf_table import FREQUENCY, MODES_HZ, Z_M, _accelerance

MODES = Modes(
    frequency=np.array([60.0, 170.0, 330.0]),
    damping_ratio=np.array([0.01, 0.01, 0.01]),
    constants=np.array([[6.0, 4.0, 9.0], [-3.0, 2.5, -5.0]]),
)


def _sub_sample_hits(**faults: object) -> HammerRecords:
    """Hits of 0.6 ms sampled at 1024 Hz through the anti-alias filter, as lvm_read's record."""
    return records_for(
        MODES, pulse_s=0.6e-3, dt=1 / 1024, n_samples=4096, pretrigger_samples=85, **faults
    )  # type: ignore[arg-type]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_hit_shorter_than_a_sample_rings_but_is_one_hit(seed: int) -> None:
    # ladisk/lvm_read's LabVIEW record (1024 Hz, a metal tip): the hit lasts less than a
    # sample, so the converter's anti-alias filter spreads it over its neighbours with lobes
    # of alternating sign, up to 28 % of the peak after it and 16 % before.  Each lobe of the
    # compression's sign read as a second hit, and the first lobe above the detection level as
    # the pulse's start, which moved by up to three samples from hit to hit (two clean hits
    # both rejected, "double hit" and "trigger").  A hammer pushes: a bump with a pull (a lobe
    # of the other sign as deep as the bump is high) between it and the pulse is the filter's
    # ringing, and the pulse starts where its own lobe does.
    records = _sub_sample_hits(n_averages=4, force_noise=1e-4, start_jitter_s=1 / 1024, seed=seed)
    estimate = estimate_frfs(records)
    assert [c.reasons for c in estimate.checks] == [()] * 8


def test_a_second_hit_through_the_same_filter_is_still_one() -> None:
    # The ringing rule must not hide a real second hit sampled alike: 8 ms after the first,
    # half its size.
    records = _sub_sample_hits(n_averages=2, second_hit=(8e-3, 0.5))
    assert all("double hit" in c.reasons for c in estimate_frfs(records).checks)


def _bare_exports(folder: Path, units_line: str | None) -> Path:
    """Receptances of test_frf_table's two-mode beam written as leekunhwee/Vibration-Signal-
    Processing's tool-tip test has them (a tap-test program's export): three numbers a line,
    frequency, real and imaginary part, no header, the 0 Hz line included; the units (m/N) are
    in the lab's notes only."""
    w = 2 * np.pi * FREQUENCY
    lines = ["file,node,x_m,y_m,z_m,direction"]
    if units_line is not None:
        lines.insert(0, units_line)
    for k, z in enumerate(Z_M, start=1):
        receptance = _accelerance(z, 0.2) / np.where(w > 0, -(w**2), 1.0)
        receptance[0] = 0.7  # the 0 Hz line: what a division by -ω² leaves there
        rows = np.column_stack([FREQUENCY, receptance.real, receptance.imag])
        np.savetxt(folder / f"Point_{k}_Channel_1_CH1.txt", rows, fmt="%.6e", delimiter="\t")
        lines.append(f"Point_{k}_Channel_1_CH1.txt,{k},0,0,{z},+x")
    lines.append("reference,2,,,,+x")
    table = folder / "frfs.csv"
    table.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return table


def test_exports_without_a_header_take_their_units_from_the_table(tmp_path: Path) -> None:
    # The tool-tip test's five files were refused: "no 'Frequency Real Imaginary' header …
    # (export the FRF as real and imaginary parts)", which they are.  The table now says the
    # units of exports that do not ('# units: m/N', response over force).
    frfs = read_frfs(_bare_exports(tmp_path, "# units: m/N"))
    assert frfs.frf_type == "receptance"
    w = 2 * np.pi * FREQUENCY[1:]
    expected = _accelerance(Z_M[3], 0.2)[1:] / -(w**2)
    np.testing.assert_allclose(frfs.values[3, 1:], expected, rtol=1e-5, atol=1e-12)
    found = identify(frfs)
    np.testing.assert_allclose(np.sort(found.model.frequency), MODES_HZ, rtol=1e-4)


def test_exports_without_a_header_or_units_are_one_line_naming_the_fix(tmp_path: Path) -> None:
    with pytest.raises(InputError) as error:
        read_frfs(_bare_exports(tmp_path, None))
    message = str(error.value)
    assert "\n" not in message
    assert "Point_1_Channel_1_CH1.txt" in message
    assert "# units: m/N" in message


def test_a_clipped_pulse_is_an_overload_and_no_double_hit() -> None:
    # At the merge of the ringing rule (fourteenth session) the rig's overloads read as double
    # hits too (tests/test_rig_chain.py, 6 of 140 averages): find_peaks gives a clipped pulse's
    # plateau at its middle, argmax at its first sample, so the pulse's own peak was taken
    # for a second one.
    from racketdyn.measurement.quality import QualitySettings, check_average

    dt, pretrigger = 1e-5, 0.002
    t = np.arange(2048) * dt
    pulse = 300.0 * np.sin(np.pi * np.clip((t - pretrigger) / 1e-3, 0.0, 1.0))
    force = np.minimum(pulse, 200.0)  # the channel's rail at 200 N: a plateau of many samples
    response = np.sin(2 * np.pi * 300.0 * t) * np.exp(-t / 0.05)
    check = check_average(1, 0, force, response, dt, pretrigger, QualitySettings())
    assert "force overload" in check.reasons
    assert "double hit" not in check.reasons


def _merged_partner_case() -> tuple[FrfSet, SelectedPoles]:
    """Badiane's spruce plate (48 kHz, 0.5 Hz lines, one FRF): the selection merged two
    clusters of one peak at 1370 Hz, kept the one stable in more orders — 1366.84 Hz, ζ 0.78 %
    — and the modal constants then found no peak for it (the fit 1.29 × better with it): the
    peak was left with no mode, and its partner's row said "merged into 1366.84 Hz", a mode
    the table did not hold.  Here: two modes (300 Hz; 500 Hz, ζ 0.4 %) at five points; the
    selection kept 300 Hz and, for the 500 Hz peak, a broad pole (503 Hz, ζ 3 %) stable in
    more orders than the 500 Hz one merged into it."""
    points = np.linspace(0.1, 0.9, 5)
    frequency = np.arange(0.0, 1000.0, 0.5)
    w = 2 * np.pi * frequency
    values = np.zeros((points.size, frequency.size), dtype=complex)
    for f_n, zeta, shape in (
        (300.0, 0.005, np.sin(np.pi * points)),
        (500.0, 0.004, np.cos(2 * np.pi * points)),
    ):
        wn = 2 * np.pi * f_n
        values += (shape * shape[1])[:, None] * (-(w**2) / (wn**2 - w**2 + 2j * zeta * wn * w))
    rng = np.random.default_rng(5)
    values += 1e-3 * np.abs(values).max() * rng.standard_normal(values.shape)
    frfs = FrfSet(
        frequency=frequency,
        values=values,
        nodes=(1, 2, 3, 4, 5),
        locations=np.column_stack([points, np.zeros_like(points)]),
        frf_type="accelerance",
        reference_node=2,
        reference_location=(float(points[1]), 0.0),
        source="a merged pair's survivor with no peak",
    )
    kept_f, kept_zeta = np.array([300.0, 503.0]), np.array([0.005, 0.03])
    partner = DroppedMode(
        500.0,
        0.004,
        27,
        "merged",
        "one peak with the mode at 503.00 Hz, merged into it: 3 Hz apart, within their "
        "half-power width 17 Hz (2ζf), shapes alike (MAC 1.00 ≥ 0.9); kept the one stable in "
        "more orders (30 against 27)",
        peak_to_noise=200.0,
        merged_into_hz=503.0,
    )
    selected = SelectedPoles(
        frequency=kept_f,
        damping_ratio=kept_zeta,
        pole=pole_of(kept_f, kept_zeta),
        n_orders=np.array([40, 30]),
        frequency_spread_hz=np.array([0.01, 0.5]),
        damping_spread=np.array([1e-4, 1e-3]),
        peak_to_noise=np.array([300.0, 150.0]),
        residues=np.ones((points.size, 2), dtype=complex),
        pinned=np.zeros(2, dtype=bool),
        band_hz=(100.0, 900.0),
        exponential_window_s=None,
        n_orders_computed=60,
        nodes=frfs.nodes,
        dropped=(f"500.00 Hz, ζ = 0.0040, 27 orders: {partner.reason}",),
        dropped_modes=(partner,),
    )
    return frfs, selected


def test_a_merged_mode_takes_the_place_of_its_survivor_when_that_has_no_peak() -> None:
    frfs, selected = _merged_partner_case()
    fitted, no_peak = _with_peaks_only(frfs, selected, (100.0, 900.0))
    assert fitted.selected.frequency.tolist() == [300.0, 500.0]
    assert [round(d.frequency_hz, 2) for d in no_peak] == [503.0]
    assert "in its place" in no_peak[0].reason
    # no row left saying a mode was merged into one the model does not hold
    assert not [d for d in fitted.selected.dropped_modes if d.stage == "merged"]


def test_a_merged_row_whose_mode_is_left_out_says_so() -> None:
    # Neither holds the peak (the partner as broad as the survivor): both left out, and the
    # partner's row no longer reads as if the mode it was merged into were kept.
    frfs, selected = _merged_partner_case()
    (partner,) = selected.dropped_modes
    broad = replace(partner, frequency_hz=506.0, damping_ratio=0.04)
    fitted, _ = _with_peaks_only(frfs, replace(selected, dropped_modes=(broad,)), (100.0, 900.0))
    assert fitted.selected.frequency.tolist() == [300.0]
    (row,) = fitted.selected.dropped_modes
    assert "503.00 Hz was then left out" in row.reason
    assert row.fit_gain < 1.5


def test_a_clear_peak_whose_poles_the_fit_hardly_needs_is_named_with_its_pin() -> None:
    # Badiane's plate with the force window its frf step asks for, default band 40-6392 Hz:
    # the clear peak at 1370.5 Hz (6.7 × its surroundings) had two poles near it whose
    # constants the fit hardly needed (1365.72 Hz, 1.25 ×; 1397.34 Hz, 1.43 ×): each row said
    # "no peak in the data", the peak counted as explained by them, and the mode was lost
    # with no option named.  Here the 500 Hz peak is held only by a pole broader than it
    # (506 Hz, ζ 4 %, merged partner of another broad one): its row names the pin at the peak,
    # and the pin keeps the mode.
    from racketdyn.modal.peaks import resolved_peaks

    frfs, selected = _merged_partner_case()
    (partner,) = selected.dropped_modes
    broad = replace(partner, frequency_hz=506.0, damping_ratio=0.04)
    band = (100.0, 900.0)
    peaks = resolved_peaks(frfs, band)
    assert any(abs(p - 500.0) <= 0.5 for p in peaks)
    fitted, rows = _with_peaks_only(
        frfs, replace(selected, dropped_modes=(broad,)), band, peaks=peaks
    )
    assert fitted.selected.frequency.tolist() == [300.0]
    named = [d for d in rows if "`pin_hz`" in d.reason]
    assert len(named) == 1, [d.reason for d in rows]
    assert "no peak in the data" not in named[0].reason
    pin = float(named[0].reason.split("`pin_hz` ")[1].split()[0])
    assert abs(pin - 500.0) <= 0.5  # the peak's line
    again = identify(frfs, band_hz=band, pin_hz=[pin])
    assert np.min(np.abs(again.model.frequency / 500.0 - 1)) <= 1e-3
