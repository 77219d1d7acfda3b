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


TRANSMISSIBILITY_HZ, TRANSMISSIBILITY_ZETA = 219.0, 0.011


def _transmissibility_uff(path: Path, denominator: int = 12) -> Path:
    """A base-excited shaker test's acceleration over acceleration as Siemens LMS Test.Lab
    exports it (LolloCappo/pyLMS's ``data/FRF.mat``, "FRF Point2/Point1", unit "/"): function
    type 4, ordinate 12 over denominator 12, 10-1000 Hz at 1 Hz; one mode at 219 Hz, ζ 1.1 %,
    by the single-degree-of-freedom law of base excitation,
    T = (ωn² + 2iζωnω)/(ωn² - ω² + 2iζωnω) = 1 + ω²/(ωn² - ω² + 2iζωnω)."""
    import pyuff

    f = np.arange(10.0, 1001.0)
    wn, w, zeta = 2 * np.pi * TRANSMISSIBILITY_HZ, 2 * np.pi * f, TRANSMISSIBILITY_ZETA
    t = (wn**2 + 2j * zeta * wn * w) / (wn**2 - w**2 + 2j * zeta * wn * w)
    dataset = pyuff.prepare_58(
        binary=0, func_type=4, rsp_node=2, rsp_dir=3, ref_node=1, ref_dir=3, data=t, x=f,
        id1="FRF Point2/Point1", abscissa_spacing=1, abscissa_spec_data_type=18,
        abscissa_axis_units_lab="Hz", ordinate_spec_data_type=12,
        ordinate_axis_units_lab="m/s^2", orddenom_spec_data_type=denominator,
        orddenom_axis_units_lab="m/s^2" if denominator == 12 else "m/s",
    )  # fmt: skip
    pyuff.UFF(str(path)).write_sets(dataset, mode="overwrite")
    return path


def test_a_transmissibility_gives_its_modes_with_unscaled_shapes(tmp_path: Path) -> None:
    # pyLMS's Test.Lab export of a shaker test (the base's acceleration as the reference) was
    # refused "the FRF must be per force (record 10, field 1 = 13), not per quantity 12": every
    # mode lost.  Its poles are the structure's (T = 1 + ω² Σ …, an accelerance's form with
    # the base's inertia load for the force); with no force the shapes cannot be scaled.
    frfs = read_frfs(_transmissibility_uff(tmp_path / "frf.uff"), require_coordinates=False)
    assert frfs.metadata["transmissibility"] == "acceleration over acceleration"
    found = identify(frfs)
    assert found.model.n_modes == 1
    np.testing.assert_allclose(found.model.frequency, [TRANSMISSIBILITY_HZ], rtol=1e-4)
    np.testing.assert_allclose(found.model.damping_ratio, [TRANSMISSIBILITY_ZETA], rtol=0.02)
    assert found.model.scaling == "unscaled"
    assert "transmissibility" in found.scaling_note
    assert "force" in found.scaling_note


def test_a_ratio_of_unlike_responses_is_one_line(tmp_path: Path) -> None:
    with pytest.raises(InputError) as error:
        read_frfs(_transmissibility_uff(tmp_path / "frf.uff", denominator=11))
    message = str(error.value)
    assert "\n" not in message
    assert "acceleration over velocity" in message
    assert "per newton" in message


def _sub_line_mode(seed: int) -> FrfSet:
    """pyLMS's transmissibility (1 Hz lines) as the law of base excitation gives it: 219 Hz
    (ζ 1.1 %), 603.5 Hz (ζ 0.6 %) and a mode at 78.6 Hz, ζ 0.15 %, whose half-power width
    (0.24 Hz) is under a line: on the real file a bump of +0.5 on a baseline of 0.8 at 79 Hz,
    sdypy 78.61-78.65 Hz at every band and order; 0.3 % noise."""
    f = np.arange(10.0, 1001.0)
    w = 2 * np.pi * f
    t = np.ones_like(w, dtype=complex)
    for f_n, zeta, a in ((219.0, 0.011, 1.0), (603.5, 0.006, -0.05), (78.6, 0.0015, 0.005)):
        wn = 2 * np.pi * f_n
        t += a * w**2 / (wn**2 - w**2 + 2j * zeta * wn * w)
    rng = np.random.default_rng(seed)
    t += 0.003 * np.abs(t) * (rng.standard_normal(t.size) + 1j * rng.standard_normal(t.size))
    return FrfSet(
        frequency=f,
        values=t[None, :],
        nodes=(1,),
        locations=np.zeros((1, 2)),
        frf_type="accelerance",
        reference_node=2,
        reference_location=(0.0, 0.0),
        source="a mode under a line wide",
        metadata={"transmissibility": "acceleration over acceleration"},
    )


def test_a_mode_under_a_line_wide_where_the_fit_misses_is_named_with_its_pin() -> None:
    # pyLMS's 78.6 Hz: its poles stable in 3 of 60 orders (a pole 687 × the noise), left out
    # with a row in dropped_modes.csv only, while the misfit said "modes or lines the model
    # lacks, most at 79, 77, 81 Hz" with no option that keeps it.
    frfs = _sub_line_mode(seed=1)
    found = identify(frfs)
    assert not np.any(np.abs(found.model.frequency - 78.6) < 1.0)
    assert found.misfit is not None
    (left_out,) = found.misfit.left_out_hz
    assert abs(left_out - 78.6) < 1.0
    assert "`pin_hz` keeps a mode" in found.misfit.sentence()
    pinned = identify(frfs, pin_hz=[round(left_out, 1)])
    assert np.min(np.abs(pinned.model.frequency - 78.6)) < 0.1


def test_shapes_at_one_point_cannot_be_interpolated_and_say_so() -> None:
    # compare on pyLMS's transmissibility (one point, a geometry given) stopped with scipy's
    # "ValueError: At least 2 data points are required when `degree` is 1 …" and a traceback:
    # a thin-plate spline needs one point more than its dimensions.
    from racketdyn.modal.model import ModalModel

    model = ModalModel(
        frequency=np.array([219.0, 603.8]),
        damping_ratio=np.array([0.011, 0.007]),
        locations=np.array([[0.1, 0.0]]),
        mode_shapes=np.array([[1.0, 1.0]]),
        names=("mode 1", "mode 2"),
        source="one point",
    )
    with pytest.raises(InputError) as error:
        model.mode_shapes_at([[0.1, 0.0], [0.2, 0.0]])
    message = str(error.value)
    assert "\n" not in message
    assert "1 point" in message
    assert "2 or more" in message


def _stepped_sine(seed: int = 0, mode: tuple[float, float] = (80.25, 0.0013)) -> FrfSet:
    """A stepped-sine test round one mode as the Brake-Reuss beam's
    (mattiacenedese/BRBtesting, ``ForcedFrequencyResponses.mat``): 41 lines, 79.2-81.2 Hz at
    0.05 Hz, an accelerance peak at 80.25 Hz (ζ 0.13 %: its half-power points 0.21 Hz apart;
    ``mode``, Hz and ζ); 0.5 % noise."""
    f = 79.2 + 0.05 * np.arange(41)
    w, wn, zeta = 2 * np.pi * f, 2 * np.pi * mode[0], mode[1]
    h = -(w**2) / (wn**2 - w**2 + 2j * zeta * wn * w) / 0.35
    rng = np.random.default_rng(seed)
    h += 0.005 * np.abs(h) * (rng.standard_normal(f.size) + 1j * rng.standard_normal(f.size))
    return FrfSet(
        frequency=f,
        values=h[None, :],
        nodes=(2,),
        locations=np.zeros((1, 2)),
        frf_type="accelerance",
        reference_node=1,
        reference_location=(0.0, 0.0),
        source="a stepped sine round one mode",
    )


def test_a_short_stepped_sine_takes_the_orders_its_lines_allow() -> None:
    # The beam's force-controlled levels were refused with default options: "band 40–81.2 Hz
    # holds 41 lines; max_order 60 needs more than 120: widen the band or lower max_order" —
    # the file holds no more lines, and the default order is racketdyn's own choice.
    found = identify(_stepped_sine())
    np.testing.assert_allclose(found.model.frequency, [80.25], rtol=1e-4)
    np.testing.assert_allclose(found.model.damping_ratio, [0.0013], rtol=0.05)
    assert "41 lines" in found.model.metadata["orders_note"]


def test_a_max_order_given_beyond_the_lines_names_the_order_that_fits() -> None:
    with pytest.raises(InputError) as error:
        identify(_stepped_sine(), max_order=60)
    message = str(error.value)
    assert "\n" not in message
    assert "20 or lower" in message
    assert "widen" not in message  # the band already holds every line of the FRFs


def test_no_settled_pole_at_a_clear_peak_names_its_pin_and_no_order_the_lines_lack() -> None:
    # The beam's higher force levels (a jointed, amplitude-dependent mode): "no mode found …
    # yet no pole of the fit settles over the orders: raise --max-order or pin a mode (--pin)",
    # at the order 41 lines allow and with no frequency to pin.
    from racketdyn.modal.identify import _no_mode_cause

    frfs = _stepped_sine()
    words = _no_mode_cause([80.3], 20, frfs, (79.2, 81.2))
    assert "`pin_hz` 80.30" in words
    assert "max_order" not in words


def test_a_peak_as_wide_as_the_band_names_the_pin_that_keeps_it() -> None:
    # The beam's response-controlled levels 6 and 7 (ζ 0.58-0.65 %: the 2 Hz band holds the
    # peak and little more): its pole, stable in 16-18 orders, left out at the band's edge
    # margin, and "no mode found … holds no clear peak of the data above its noise: raise
    # --max-order or pin a mode (--pin)", with no frequency and an order the lines cannot hold.
    with pytest.raises(InputError) as error:
        identify(_stepped_sine(mode=(80.5, 0.006)))
    message = str(error.value)
    assert "`pin_hz` 80.5" in message
    assert "max_order" not in message


def test_a_candidate_beside_a_kept_mode_is_not_named_as_left_out() -> None:
    # pyuff's showcase: candidates at 957.14 and 959.23 Hz beside its kept 958.5 Hz mode stand
    # 30 times over the noise; one peak, one mode: the misfit must not name them.
    from racketdyn.modal.identify import _left_out_in_data

    frfs, selected = _merged_partner_case()
    beside = DroppedMode(
        301.0, 0.005, 3, "selection", "stable in 3 of 60 orders (< 12)", peak_to_noise=500.0
    )
    apart = replace(beside, frequency_hz=420.0)
    assert _left_out_in_data((beside, apart), selected, frfs) == [420.0]


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
