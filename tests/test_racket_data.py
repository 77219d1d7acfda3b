"""Issue 25, item 8: racketdyn on racket data — its own virtual rig, a racket not the paper's.

A 305 g racket of 98 sq in with its first bending at 150 Hz (the paper's file with mass, head
area and first_bending_hz changed; since issue 22's sixth session, the rig on the frame's shape,
strung at 260 N, not 246 N: at 246 N its membrane, 663.9 Hz, sat 0.5 Hz from its 3-node
twisting, 664.4 Hz, one peak to any identification, where the tests below were written for a
membrane 14 Hz above that twisting — 260 N puts it there again), measured on the rig with
noise (``rig --response-snr 40 --force-snr 50``, seed 1, 10 averages, both supports) and its
FRFs estimated with a 0.1 s exponential window (``frf --exp-window 0.1``, as
docs/commands/rig.md shows).  The records
are simulated and the FRFs estimated in memory (what ``rig`` writes and ``frf`` reads, without
the ASCII UFF: 8 s instead of 25 s); the identification is the CLI's
(:func:`racketdyn.modal.identify.identify`, then
:func:`racketdyn.racket_modal.identify.name_if_racket` with the racket given).

The rig's truth for this racket (played bed, free, frame's shape, 260 N): 2-node bending
150.0 Hz, 2-node twisting 361.0, 3-node bending 412.1, 3-node twisting 664.5, string-bed
membrane 678.5 (the all-in-phase mode), 4-node bending 849.4, 4-node twisting 885.0,
string-bed membrane (1, 0) 1011.1, 5-node twisting 1106.6, … (on the smooth frame at 246 N: 413.3,
665.1, 679.2, 838.5, 885.9, 989.9, 1105.1).  Each test reproduced its failure before the fix.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import racketdyn as rd
from costly import costly
from lab_rackets import TRIAL_RACKET_100
from racketdyn.io import load_racket
from racketdyn.io.uff import write_frf_uff
from racketdyn.measurement.records import FrfSet
from racketdyn.modal.identify import ONE_PEAK_LINES, SELECTION, Identification, identify
from racketdyn.modal.mac import mac
from racketdyn.modal.model import ModalModel
from racketdyn.racket_modal.identify import name_if_racket
from racketdyn.rig import (
    Acquisition,
    HammerBlows,
    HammerFaults,
    SensorNoise,
    accelerometer_index,
    hammer_points,
    rig_model,
    simulate_hammer_test,
    string_contact_time,
)
from racketdyn.rig.hammer import FRAME_PULSE_S
from racketdyn.workflows.setup import Setup

PAPER_FILE = Path(__file__).parents[1] / "src/racketdyn/data/kawazoe_2002.toml"
EXPONENTIAL_WINDOW_S = 0.1


def trial_racket_file(folder: Path) -> Path:
    """The trial's racket: the paper's file with mass 305 g, head 98 sq in, bending 150 Hz,
    strung at 260 N (module docstring)."""
    text = PAPER_FILE.read_text(encoding="utf-8")
    for old, new in (
        ('name = "Kawazoe test racket (360 g, 97 sq in)"', 'name = "Trial racket (305 g)"'),
        ("mass_kg = 0.360 ", "mass_kg = 0.305 "),
        ("area_cm2 = 628.0 ", "area_cm2 = 632.0 "),
        ("first_bending_hz = 120.0 ", "first_bending_hz = 150.0 "),
        ("tension_n = 246.0 ", "tension_n = 260.0 "),
    ):
        assert old in text, old
        text = text.replace(old, new)
    path = folder / "trial_racket.toml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def racket_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return trial_racket_file(tmp_path_factory.mktemp("racket"))


@pytest.fixture(scope="module")
def racket(racket_file: Path) -> rd.Racket:
    return load_racket(racket_file)


def measured_frfs(
    racket: rd.Racket,
    support: str,
    noise: SensorNoise | None = None,
    averages: int = 10,
    windows_s: tuple[float | None, float | None] = (None, EXPONENTIAL_WINDOW_S),
    seed: int | np.random.Generator = 1,
) -> tuple[FrfSet, ModalModel]:
    """The rig's FRFs of ``support`` as ``rig --response-snr 40 --force-snr 50`` then ``frf
    --exp-window 0.1`` give them (same points, pulses, seed), and the rig's modal truth;
    ``noise`` (default those SNRs; ``SensorNoise()``: the rig's own), ``averages`` and the
    force and exponential windows (s) as ``rig`` and ``frf`` take them, ``seed`` the random
    stream."""
    locations, nodes = hammer_points(racket)
    reference = accelerometer_index(racket, locations)
    durations = np.full(len(nodes), FRAME_PULSE_S)
    on_bed = racket.head.contains(locations)
    contact = "free" if support == "free" else "pinned"
    durations[on_bed] = string_contact_time(racket, locations[on_bed], contact)
    model = rig_model(racket, support)
    records = simulate_hammer_test(
        model,
        locations,
        nodes,
        (float(locations[reference, 0]), float(locations[reference, 1])),
        nodes[reference],
        acquisition=Acquisition(n_averages=averages),
        blows=HammerBlows(pulse_duration_s=tuple(durations)),
        noise=SensorNoise(force_snr_db=50.0, response_snr_db=40.0) if noise is None else noise,
        seed=seed,
    )
    from racketdyn.measurement.frf import estimate_frfs

    force_window, exponential_window = windows_s
    frfs = estimate_frfs(
        records, force_window_s=force_window, exponential_window_s=exponential_window
    ).frfs
    assert frfs is not None
    truth = model.modal_truth(locations, max_frequency_hz=0.5 / records.sampling_interval_s)
    return frfs, truth.select([k for k, f in enumerate(truth.frequency) if f > 15.0])


@pytest.fixture(scope="module")
@costly
def measured(racket: rd.Racket) -> dict[str, tuple[FrfSet, ModalModel]]:
    return {support: measured_frfs(racket, support) for support in ("free", "hand")}


@pytest.fixture(scope="module")
def frf_files(
    measured: dict[str, tuple[FrfSet, ModalModel]], tmp_path_factory: pytest.TempPathFactory
) -> dict[str, Path]:
    """The measured FRFs as ``frf`` writes them (``frfs.uff``), one file per support."""
    folder = tmp_path_factory.mktemp("frfs")
    return {
        support: write_frf_uff(frfs, folder / f"frfs_{support}.uff")
        for support, (frfs, _) in measured.items()
    }


def identified(
    measured: dict[str, tuple[FrfSet, ModalModel]], racket: rd.Racket, support: str
) -> Identification:
    """``identify FRFS --racket FILE --support SUPPORT`` on the measured FRFs."""
    found, _ = name_if_racket(identify(measured[support][0], support=support), racket, True)
    return found


@pytest.fixture(scope="module")
@costly
def found(
    measured: dict[str, tuple[FrfSet, ModalModel]], racket: rd.Racket
) -> dict[str, Identification]:
    """:func:`identified` for both supports, once."""
    return {support: identified(measured, racket, support) for support in measured}


def load_racket_text(text: str) -> rd.Racket:
    """A racket from a racket file's text."""
    import tempfile

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "racket.toml"
        path.write_text(text, encoding="utf-8")
        return load_racket(path)


def nearest(model: ModalModel, frequency_hz: float) -> int:
    k = int(np.argmin(np.abs(model.frequency - frequency_hz)))
    assert abs(model.frequency[k] / frequency_hz - 1) < 0.005, (frequency_hz, model.frequency)
    return k


@pytest.mark.slow
def test_the_all_in_phase_membrane_mode_is_named_from_its_shape(
    measured: dict[str, tuple[FrfSet, ModalModel]], found: dict[str, Identification]
) -> None:
    """(a) The membrane mode (truth 679.2 Hz) was ``mode 4``, kind ``unknown``: its strings
    moved 12.8 times the frame in mean square (between 4 and 40, "the shape does not say"),
    because the 3-node twisting 14 Hz below leaked into its hoop points — odd in y, large on
    the hoop.  Its symmetric part has every string point in phase (1.00) and the frame still
    (101 times less in mean square): the membrane.  With it named, the 4-node bending above
    it keeps its node count (it was ``bending mode (838.4 Hz)``)."""
    truth = measured["free"][1]
    model = found["free"].model
    k = nearest(model, truth.frequency[truth.names.index("string-bed membrane")])
    assert (model.names[k], model.kinds[k]) == ("string-bed membrane", "string-bed")
    bending = nearest(model, truth.frequency[truth.names.index("4-node bending")])
    assert model.names[bending] == "4-node bending"


def test_a_clean_peak_stable_in_too_few_orders_is_kept(
    measured: dict[str, tuple[FrfSet, ModalModel]], found: dict[str, Identification]
) -> None:
    """(b) The 3-node twisting (truth 665.1 Hz, 14 Hz below the membrane) was dropped: stable
    in 10 of 60 orders (< 12), peak 2600 × the noise — below the kept modes' median (3100),
    so not even named ``unsettled``.  Every twisting mode above it was then named a node
    short (885.9 Hz "3-node twisting", 1105 Hz "4-node" …).  Fitted with the kept modes, the
    data hold its peak (the fit near it 5.9 × worse without it; a pole of noise: 1.0): kept,
    and said.

    Re-derived on the rig's frame shape (issue 22, sixth session; 260 N, module docstring): the
    free 3-node twisting (664.5 Hz) is stable in 13 orders now, a mode by the rules themselves,
    and the twisting modes above it keep their node counts.  The same rule shows on the held
    racket: its 1493.3 Hz peak (the truth's fourth membrane mode, 1492.8 Hz) is stable in 11 of
    60 orders and the fit near it 3.7 × better with it: kept, and said."""
    truth = measured["free"][1]
    model = found["free"].model
    for name in ("3-node twisting", "4-node twisting", "5-node twisting", "6-node twisting"):
        k = nearest(model, truth.frequency[truth.names.index(name)])
        assert model.names[k] == name
    held = found["hand"]
    (line,) = held.model.metadata["kept"]
    assert line.startswith("1493.3")
    assert "better with it" in line
    hand_truth = measured["hand"][1]
    # the truth's fourth membrane mode held, named from its nodal lines since the tenth session
    k = nearest(
        held.model, hand_truth.frequency[hand_truth.names.index("string-bed membrane (2, 0)")]
    )
    assert held.selected.n_orders[k] < 12
    assert not held.selected.pinned.any()
    # a weaker one (the truth's fifth membrane mode, 1564.0 Hz: 8 of 60 orders, the fit 1.8 ×
    # better with it) is named with the pin that keeps it
    (row,) = [d for d in held.dropped_modes if abs(d.frequency_hz - 1566.1) < 2.0]
    assert row.stage == "unsettled"
    assert f"`pin_hz` {row.frequency_hz:.1f} keeps it" in row.reason


@pytest.mark.slow
def test_identify_and_compare_give_a_mode_one_name(
    frf_files: dict[str, Path], racket_file: Path, tmp_path: Path
) -> None:
    """(c) ``identify`` of the hand-held FRFs named its modes in order of frequency: the hand
    damps the 3- and 4-node twisting (ζ 10 and 5 %) out of the identification, so its
    1074.8 Hz mode was "3-node twisting", its 1398 Hz "4-node", its 1730 Hz "5-node", while
    ``compare`` named the same modes after their free MAC pairs "5-", "6-" and "7-node
    twisting" (the truth's).  ``identify --names-from`` the free test's model names them as
    ``compare`` does, and without it the naming line says the counts may be short and what
    gives them.  (On the rig's frame shape at 260 N the three modes are identified at 1079.5,
    1402.4 and 1741.4 Hz; the truth's 1079.3, 1402.5 and 1740.8 Hz.)"""
    from racketdyn.workflows.identify import run_compare, run_identify

    compared = run_compare(
        frf_files["free"], frf_files["hand"], tmp_path / "c", setup=Setup(racket=racket_file)
    )
    assert compared.free is not None
    assert compared.hand is not None
    free = run_identify(frf_files["free"], tmp_path / "free", setup=Setup(racket=racket_file))
    assert free.identification is not None
    assert free.identification.model.names == compared.free.model.names
    hand = run_identify(
        frf_files["hand"],
        tmp_path / "hand",
        support="hand",
        names_from=tmp_path / "free" / "modal_model.json",
        setup=Setup(racket=racket_file),
    )
    assert hand.identification is not None
    assert hand.identification.model.names == compared.hand.model.names
    model = hand.identification.model
    assert model.names[nearest(model, 1079.5)] == "5-node twisting"
    assert model.names[nearest(model, 1741.4)] == "7-node twisting"
    alone = run_identify(
        frf_files["hand"], tmp_path / "alone", support="hand", setup=Setup(racket=racket_file)
    )
    assert alone.identification is not None
    assert "`names_from`" in alone.identification.model.metadata["naming"]


def test_a_name_holding_a_frequency_is_not_given_to_another_mode(
    found: dict[str, Identification],
) -> None:
    """(c) A free bending mode whose order the shapes could not give is named with its own
    frequency ("bending mode (838.4 Hz)", as the 4-node bending was before (a)); ``compare``
    gave that name to its hand-held pair at 799.7 Hz.  The pair is named the same way with
    its own frequency.  (On the rig's frame shape at 260 N the pair is identified at 849.0 Hz
    free and 822.6 Hz held.)"""
    from racketdyn.workflows.identify import name_after_pairs

    free = found["free"].model
    hand = found["hand"].model
    k = nearest(free, 849.0)
    names = list(free.names)
    names[k] = f"bending mode ({free.frequency[k]:.1f} Hz)"
    paired = name_after_pairs(replace(free, names=tuple(names)), hand)
    j = nearest(hand, 822.6)
    assert paired.names[j] == f"bending mode ({hand.frequency[j]:.1f} Hz)"


def test_the_report_says_a_prediction_took_modes_of_unknown_kind(
    found: dict[str, Identification], racket_file: Path, tmp_path: Path
) -> None:
    """(d) The trial's identified free model keeps two modes the shapes cannot name (1365 Hz,
    the truth's 5-node bending coupled with the bed; 1476 Hz, its membrane 4), kind
    ``unknown`` (on the rig's frame shape at 260 N one: 1522.1 Hz, the truth's fifth membrane
    mode).  ``predict --modal`` takes them as frame modes and says so on the console;
    the report, built from the same folder, did not say a word.  It says which modes, and
    what they were taken as, in "Frame vibration" and "At a glance"."""
    from racketdyn.report import write_report
    from racketdyn.workflows.predict import PredictOptions, run_predict

    model = found["free"].model
    # the trial's 1522.1 Hz mode (the truth's (2, 0) membrane veering with the 5-node bending,
    # 52/48 strings/frame in strain energy, its partner not identified) was ``unknown``; since
    # the eleventh session its frame's shape names it (docs/develop.md): left unknown here, as
    # identify named it then, for the report to say
    k = nearest(model, 1522.1)
    names, kinds = list(model.names), list(model.kinds)
    names[k], kinds[k] = f"mode {k + 1} (1522.1 Hz)", "unknown"
    model = replace(model, names=tuple(names), kinds=tuple(kinds))
    unknown = [n for n, kind in zip(model.names, model.kinds, strict=True) if kind == "unknown"]
    assert unknown
    path = tmp_path / "modal_model.json"
    model.write_json(path)
    out = tmp_path / "run"
    run_predict(
        out / "predict",
        setup=Setup(racket=racket_file, modal_model=path),
        options=PredictOptions(speeds=[20.0], supports=["free"], grid=3),
    )
    page = " ".join(write_report(out).read_text(encoding="utf-8").split())
    glance = page.split("At a glance")[1].split("</ul>")[0]
    for name in unknown:
        assert name in page.split("Frame vibration")[-1]
        assert name in glance
    assert "unknown kind" in glance


@pytest.mark.slow
def test_a_fragment_of_a_named_edge_mode_is_not_named_again(racket: rd.Racket) -> None:
    """(b) found by the demo on this racket (``demo --racket``: noise 50/60 dB, 3 % double hits,
    1 % overloads, ``--band 40,850``): the 4-node bending (838.1 Hz) sits in the band's edge
    margin and is named with the ``--band`` that keeps it; a fragment of its peak at 833.8 Hz
    (5 orders) was named again, ``unsettled`` with ``--pin 833.8``.  A candidate that is one
    peak with a named row is that row's.

    Re-derived on the rig's frame shape (issue 22, sixth session), with the trial's file at its
    own 246 N (the 4-node bending at 844.6 Hz) and the band's top 11.4 Hz above it, 856 Hz, as
    850 Hz was above 838.1 Hz: the edge row (846.7 Hz, 4 orders) has the damping of an edge
    fragment (0.15 %, the mode's 0.5 %), so by half-power widths alone the 843.3 Hz candidate
    (8 orders) was not one peak with it and was kept as well — the mode twice.  One peak is
    now within a half-power width or three lines, as the edge scan has it."""
    racket = replace(racket, strings=replace(racket.strings, tension_n=246.0))
    locations, nodes = hammer_points(racket)
    reference = accelerometer_index(racket, locations)
    durations = np.full(len(nodes), FRAME_PULSE_S)
    on_bed = racket.head.contains(locations)
    durations[on_bed] = string_contact_time(racket, locations[on_bed], "free")
    records = simulate_hammer_test(
        rig_model(racket, "free"),
        locations,
        nodes,
        (float(locations[reference, 0]), float(locations[reference, 1])),
        nodes[reference],
        acquisition=Acquisition(n_averages=10),
        blows=HammerBlows(pulse_duration_s=tuple(durations)),
        noise=SensorNoise(force_snr_db=60.0, response_snr_db=50.0),
        faults=HammerFaults(double_hit_probability=0.03, overload_probability=0.01),
        seed=1,
    )
    from racketdyn.measurement.frf import estimate_frfs
    from racketdyn.measurement.quality import QualitySettings

    frfs = estimate_frfs(
        records, exponential_window_s=0.1, quality=QualitySettings(overload_level_n=200.0)
    ).frfs
    assert frfs is not None
    found = identify(frfs, (40.0, 856.0))
    named = [d for d in found.dropped_modes if d.stage != "selection" and d.frequency_hz > 800]
    assert [(round(d.frequency_hz), d.stage) for d in named] == [(847, "edge")]
    lines = ONE_PEAK_LINES * float(np.median(np.diff(frfs.frequency)))
    assert not np.any(np.abs(found.model.frequency - named[0].frequency_hz) < lines)


HELD_TRIAL_CASES = {
    "rig-noise": (SensorNoise(), (0.01, None)),  # ``rig`` then ``frf --force-window 0.01``
    "40-50dB-exp-window": (
        SensorNoise(force_snr_db=50.0, response_snr_db=40.0),
        (0.01, EXPONENTIAL_WINDOW_S),
    ),
}
"""The eleventh trial's racket held in the hand, measured two ways: noise and the windows of
``frf`` (force, exponential; s)."""


@pytest.fixture(scope="module", params=list(HELD_TRIAL_CASES))
@costly
def held_trial(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> tuple[FrfSet, ModalModel, Identification]:
    """The eleventh trial's racket file as the user wrote it (``TRIAL_RACKET_100``), held: the
    rig's FRFs of one of :data:`HELD_TRIAL_CASES` (the rig's stream of seed 1), its truth,
    and ``identify`` of them with default options (≈ 3 s each)."""
    from racketdyn.workflows.rig import support_stream

    path = tmp_path_factory.mktemp("trial") / "trial.toml"
    path.write_text(TRIAL_RACKET_100, encoding="utf-8")
    noise, windows_s = HELD_TRIAL_CASES[request.param]
    frfs, truth = measured_frfs(
        load_racket(path),
        "hand",
        noise,
        10,
        windows_s,
        seed=np.random.default_rng(support_stream(1, "hand")),
    )
    return frfs, truth, identify(frfs, support="hand")


def test_a_close_pair_of_the_held_racket_is_parted_with_the_default_band(
    held_trial: tuple[FrfSet, ModalModel, Identification],
) -> None:
    """The eleventh trial's racket file as the user wrote it (the paper's file with only mass,
    area and first bending changed puts the pair 17 Hz apart), held in the hand: its 3-node
    bending and 2-node twisting, 0.14 Hz apart under one peak (ζ 0.97 and 4.1 %).  With the
    default band (40–1953 Hz) the LSCF resolves them only from order 27 on, and the
    twisting's own poles settle in too few orders.  The trial's FRFs
    (``rig``'s noise, ``frf --force-window 0.01``) kept 353.88 Hz (ζ 0.99 %) and a pole of
    both at 354.07 Hz (ζ 1.2 %, the twisting's damping 71 % low), dropped 354.82 Hz (ζ 3.96 %)
    for its orders and lost the mass scaling; at 40/50 dB with the exponential window the
    twisting was not found at all.  Fitted on their own lines, both modes are within 0.1 % of
    the rig's truth in frequency and 20 % in damping with mass-normalised shapes, or the one
    the data hold too weakly is named."""
    _, truth, found = held_trial
    model = found.model
    pair = [truth.names.index("3-node bending"), truth.names.index("2-node twisting")]
    assert len(pair) == 2
    assert abs(truth.frequency[pair[0]] - truth.frequency[pair[1]]) < 0.5
    assert model.scaling == "mass"
    identified = np.flatnonzero(np.abs(model.frequency / truth.frequency[pair[0]] - 1) < 0.01)
    rows = [
        d
        for d in found.dropped_modes
        if d.stage == "unsettled" and abs(d.frequency_hz / truth.frequency[pair[0]] - 1) < 0.01
    ]
    found_pair = [
        (float(model.frequency[k]), float(model.damping_ratio[k])) for k in identified
    ] + [(d.frequency_hz, d.damping_ratio) for d in rows]
    assert len(identified) >= 1
    assert len(found_pair) == 2, found_pair
    for row in rows:  # a mode the data hold too weakly is named with the band that keeps it
        assert "`band_hz` 40," in row.reason
        assert "keeps it" in row.reason
    for (f, zeta), k in zip(
        sorted(found_pair, key=lambda p: p[1]),
        sorted(pair, key=lambda k: truth.damping_ratio[k]),
        strict=True,
    ):
        assert abs(f / truth.frequency[k] - 1) < 1e-3, (f, truth.frequency[k])
        assert abs(zeta / truth.damping_ratio[k] - 1) < 0.2, (zeta, truth.damping_ratio[k])


def test_a_broad_mode_under_a_narrow_ones_peak_is_found_with_the_default_band(
    held_trial: tuple[FrfSet, ModalModel, Identification],
) -> None:
    """The same held racket's 4-node bending and 4-node twisting: 827.3 Hz (ζ 0.57 %) and
    837.1 Hz (ζ 3.6 %), 10 Hz apart, the twisting's half-power width (60 Hz) six times the
    bending's, so its peak is a shoulder of the bending's.  It is strong at the frame's edge
    (40 × the FRFs' noise there) where the bed's points, struck through the strings' long
    contact, carry 30–300 × more noise at 830 Hz: an LSCF over the band, every FRF alike,
    settles it in at most 6 of 60 orders (rig noise: 841.5 Hz ζ 2.4 %; at 40/50 dB in none),
    and the local fit of the pair, every FRF alike, ran to the 971 Hz membrane.  Each FRF
    weighted by the noise its coherence says, the local fit gives both: within 0.1 % of the
    rig's truth in frequency and 20 % in damping, the twisting's shape the truth's."""
    _, truth, found = held_trial
    model = found.model
    assert model.scaling == "mass"
    for name in ("4-node bending", "4-node twisting"):
        k = truth.names.index(name)
        near = np.flatnonzero(np.abs(model.frequency / truth.frequency[k] - 1) < 0.005)
        assert near.size == 1, (name, model.frequency[near], truth.frequency[k])
        (j,) = near
        assert abs(model.frequency[j] / truth.frequency[k] - 1) < 1e-3, (
            name,
            model.frequency[j],
            truth.frequency[k],
        )
        assert abs(model.damping_ratio[j] / truth.damping_ratio[k] - 1) < 0.2, (
            name,
            model.damping_ratio[j],
            truth.damping_ratio[k],
        )
        shapes = mac(model.mode_shapes[:, j : j + 1], truth.mode_shapes[:, k : k + 1])
        assert shapes[0, 0] > 0.9, (name, shapes[0, 0])


@pytest.mark.slow  # a rig's hammer test and its FRFs, simulated (≈ 3 s)
def test_a_pair_the_selection_parted_is_not_fitted_twice(tmp_path: Path) -> None:
    """The paper's file with mass 300 g, area 645 cm² and first bending 145 Hz (the brief's
    racket; held, its 2-node twisting 354.53 Hz, ζ 3.9 %, and 3-node bending 371.42 Hz, ζ
    0.98 %, one peak by their half-power widths) on the rig with its own noise: the selection
    keeps both modes, and the refit of the close pair started from the bending and a fragment
    of it found the twisting again beside the twisting kept (353.53 and 354.60 Hz, shapes
    unscaled).  A mode kept within one peak of the pair the refit gives is that pair's."""
    from racketdyn.workflows.rig import support_stream

    text = PAPER_FILE.read_text(encoding="utf-8")
    for old, new in (
        ("mass_kg = 0.360 ", "mass_kg = 0.300 "),
        ("area_cm2 = 628.0 ", "area_cm2 = 645.0 "),
        ("first_bending_hz = 120.0 ", "first_bending_hz = 145.0 "),
    ):
        text = text.replace(old, new)
    path = tmp_path / "racket.toml"
    path.write_text(text, encoding="utf-8")
    frfs, truth = measured_frfs(
        load_racket(path),
        "hand",
        SensorNoise(),
        10,
        (0.01, None),
        seed=np.random.default_rng(support_stream(1, "hand")),
    )
    model = identify(frfs, support="hand").model
    assert model.scaling == "mass"
    for name in ("2-node twisting", "3-node bending"):
        k = truth.names.index(name)
        (j,) = np.flatnonzero(np.abs(model.frequency / truth.frequency[k] - 1) < 0.01)
        assert abs(model.frequency[j] / truth.frequency[k] - 1) < 1e-3
        assert abs(model.damping_ratio[j] / truth.damping_ratio[k] - 1) < 0.2


def test_a_pair_fits_second_mode_says_where_it_came_from(
    held_trial: tuple[FrfSet, ModalModel, Identification], tmp_path: Path
) -> None:
    """The close pair's second mode (the 2-node twisting at 354.1 Hz, the 4-node twisting at
    836.7 Hz) is fitted on the FRFs' own lines, not from a cluster of the band's orders: it
    reported the orders of the candidate it started from (9 of 60; 0 for the twisting the
    broad-mode search found hidden under the 4-node bending's peak), and that candidate's row
    (351.62 Hz, "stable in 9 of 60 orders"; 841.48 Hz, 6) stayed in ``dropped_modes.csv``
    beside the kept mode, as a mode left out.  Its ``orders_stable`` is now empty in
    ``modes.csv`` and None in run.json's record, and no candidate stable in more than three
    orders the pair's second stands for (within its half-power width, its damping within the
    selection's tolerance) is listed as left out; the line saying the pair was kept names the
    candidate it started from."""
    import csv

    _, truth, found = held_trial
    selected = found.selected
    assert selected.pair_fitted is not None
    seconds = np.flatnonzero(selected.pair_fitted)
    twisting = [
        truth.frequency[truth.names.index(n)] for n in ("2-node twisting", "4-node twisting")
    ]
    assert sorted(np.round(selected.frequency[seconds])) == sorted(np.round(twisting)), (
        selected.frequency[seconds]
    )
    found.write_modes_csv(tmp_path / "modes.csv")
    with (tmp_path / "modes.csv").open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    record = found.model.metadata["orders_stable"]
    tolerance = 1 + SELECTION.damping_tolerance
    for k in range(selected.n_modes):
        second = k in seconds
        assert (rows[k]["orders_stable"] == "") == second, rows[k]
        assert (record[k] is None) == second, record
        if not second:
            continue
        f, zeta = selected.frequency[k], selected.damping_ratio[k]
        stale = [
            d
            for d in found.dropped_modes
            if d.orders_stable > 3
            and abs(d.frequency_hz - f) < zeta * f
            and (
                abs(np.log(d.damping_ratio / zeta)) < np.log(tolerance)
                or any(
                    f"candidate at {d.frequency_hz:.2f} Hz" in line
                    for line in found.model.metadata["kept"]
                )
            )
        ]
        assert not stale, (f, [(d.frequency_hz, d.reason) for d in stale])


def test_a_lone_veering_member_is_not_named_confidently(
    measured: dict[str, tuple[FrfSet, ModalModel]],
    found: dict[str, Identification],
    racket: rd.Racket,
) -> None:
    """The free 5-node bending (truth 1422.3 Hz) veers with the bed's (2, 0) mode (1522.1 Hz,
    52/48 strings/frame in strain energy).  Both identified, the pair's rule names them as the
    truth does.  With the bending not found (as the eleventh session's identification had it),
    the 1522.1 Hz mode, matching the 5-node bending on the frame (0.96) and the (2, 0) bed mode
    on the strings (0.73), took the bending's name with nothing said: its name now comes with a
    note naming both (the naming line's "uncertain"), or says the mix itself."""
    from racketdyn.racket_modal.beam import reference_shapes
    from racketdyn.racket_modal.shapes import classify_modes, naming_words

    truth = measured["free"][1]
    model = found["free"].model
    bending, membrane = "5-node bending", "string-bed membrane (2, 0)"
    partner = nearest(model, truth.frequency[truth.names.index(bending)])
    member = nearest(model, truth.frequency[truth.names.index(membrane)])
    reference = reference_shapes(racket)
    assert (model.names[partner], model.names[member]) == (bending, membrane)
    notes = naming_words(model, racket.head, None, reference)[1]
    assert not notes[partner], notes
    assert not notes[member], notes
    alone = model.select([k for k in range(model.n_modes) if k != partner])
    k = member - (partner < member)
    names, kinds = classify_modes(alone, racket.head, None, reference)
    note = naming_words(alone, racket.head, None, reference)[1][k]
    said = names[k] + " " + note
    assert kinds[k] == "unknown" or (bending in said and "(2, 0)" in said), (names[k], note)


def test_a_held_twisting_mode_is_named_against_the_frame_in_the_hand(
    held_trial: tuple[FrfSet, ModalModel, Identification],
) -> None:
    """The held 4-node twisting (truth 837.1 Hz; the rig names its truth by the sign changes of
    its own twist along the racket) was named "3-node twisting" by ``identify --racket``, then
    (fourteenth session) "3- or 4-node twisting": the held 3-node twisting (629.1 Hz, ζ 9.2 %)
    is not found, and the hoop's seven mirrored points (x 0.34–0.67 m) match the FREE frame's
    3-node twisting at 0.82 and its 4-node at 0.69.  A held test's counts are read against the
    frame held by the hand (:class:`racketdyn.hand.Hand`, the rig's): the mode is the 4-node
    twisting, named alone with nothing uncertain about it, and the naming line says the
    counts were read against the frame in the hand."""
    _, truth, found = held_trial
    racket = load_racket_text(TRIAL_RACKET_100)
    assert found.model.support == "hand"
    named, naming = name_if_racket(found, racket, True)
    model = named.model
    k = nearest(model, truth.frequency[truth.names.index("4-node twisting")])
    assert model.names[k] == "4-node twisting", model.names[k]
    assert f"{model.frequency[k]:.1f} Hz" not in naming, naming
    assert "held in the hand" in naming, naming
    for name in ("2-node twisting", "5-node twisting", "4-node bending", "5-node bending"):
        j = nearest(model, truth.frequency[truth.names.index(name)])
        assert model.names[j] == name, (name, model.names[j])


def test_a_held_mode_between_two_counts_is_still_named_with_both(
    held_trial: tuple[FrfSet, ModalModel, Identification],
) -> None:
    """Read against the frame in the hand, a held mode whose count the points truly cannot
    tell keeps both counts in its name.  With the hoop's mirrored points only on the head's
    upper half (x 0.5–0.64 m: three pairs, 0.505, 0.572 and 0.629 m, as a lab striking the
    hoop there), three samples of the twist cannot part the higher counts: the held 7-node
    twisting (truth 1831.3 Hz) matches the held frame's 6- and 7-node alike and is named
    "6- or 7-node twisting".  Every held twisting mode found is named by its own count, or by
    two of which one is its own; never by another count alone."""
    from racketdyn.hand import Hand
    from racketdyn.racket_modal.beam import reference_shapes
    from racketdyn.racket_modal.shapes import classify_modes, naming_words

    _, truth, found = held_trial
    racket = load_racket_text(TRIAL_RACKET_100)
    model = found.model
    xy = model.locations
    hoop = (racket.head.normalised_radius(xy) >= 0.95) & (np.abs(xy[:, 1]) > 0.01)
    kept = ~hoop | ((xy[:, 0] >= 0.5) & (xy[:, 0] <= 0.64))
    assert np.count_nonzero(hoop & kept) == 6
    sparse = replace(model, locations=xy[kept], mode_shapes=model.mode_shapes[kept])
    reference = reference_shapes(racket, Hand())
    names, _ = classify_modes(sparse, racket.head, None, reference)
    notes = naming_words(sparse, racket.head, None, reference)[1]
    both = []
    for k, name in enumerate(truth.names):
        near = np.flatnonzero(np.abs(sparse.frequency / truth.frequency[k] - 1) < 0.005)
        if truth.kinds[k] != "twisting" or near.size != 1:
            continue
        (j,) = near
        count = name.split("-")[0]
        if " or " in names[j]:
            low, high = names[j].removesuffix("-node twisting").split("- or ")
            assert count in (low, high), (name, names[j])
            assert f"{low}-" in notes[j], notes[j]  # the naming line says why
            assert f"{high}-node" in notes[j], notes[j]
            both.append(name)
        else:
            assert names[j] == name, (name, names[j])
    assert "7-node twisting" in both, both
    assert names[nearest(sparse, 837.1)] == "4-node twisting"


def test_the_held_reference_is_the_rigs_frame_in_the_hand() -> None:
    """The frame's own modes held by the hand (:func:`reference_shapes` with a
    :class:`racketdyn.hand.Hand`: the beam with the hand's mass, roll inertia, springs to the
    arm and the shoulder's spring, as the rig and the impact model hold it) against the rig's
    held racket (the same beam with the strings a coupled membrane and the point masses at
    their (x, y)), along the whole beam: each held twisting mode's twist θ(x) and each bending
    mode's w(x) of the same node count match at MAC ≥ 0.95 (the rig's 4-node bending veers
    with its membrane: 0.955; the twisting ≥ 0.988), closer than the free frame's (the 5-node
    twisting 0.74 free, the 4-node 0.88)."""
    from racketdyn.racket_modal.beam import reference_shapes

    racket = load_racket_text(TRIAL_RACKET_100)
    rig = rig_model(racket, "hand")
    held = reference_shapes(racket, rig.hand)
    free = reference_shapes(racket)
    assert rig.hand is not None
    n = rig.nodes_x.size
    assert held.frame_x is not None
    assert np.allclose(held.frame_x, rig.nodes_x)
    checked = 0
    for k, name in enumerate(rig.names):
        if rig.frequency[k] > 2000 or rig.kinds[k] not in ("bending", "twisting"):
            continue
        count = int(name.split("-")[0])
        if rig.kinds[k] == "twisting":
            shape = rig.modes[2 * n : 3 * n, k : k + 1]
            ours, theirs = held.twisting, free.twisting
            j, i = held.twisting_nodes.index(count), free.twisting_nodes.index(count)
        else:
            shape = rig.modes[0 : 2 * n : 2, k : k + 1]
            ours, theirs = held.bending, free.bending
            j, i = held.bending_nodes.index(count), free.bending_nodes.index(count)
        in_hand = mac(shape, ours[:, j : j + 1])[0, 0]
        on_sponge = mac(shape, theirs[:, i : i + 1])[0, 0]
        assert in_hand >= 0.95, (name, in_hand)
        assert in_hand > on_sponge, (name, in_hand, on_sponge)
        checked += 1
    assert checked >= 10
