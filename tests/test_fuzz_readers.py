"""Issue 26, "Must hold": a fuzz test of every reader of a user's file.

Each reader gets a small valid file of its own kind, damaged by a few seeded mutations
(truncation, byte flips, deleted, doubled and swapped lines, swapped fields, NaN/inf and huge
numbers, junk), and must either return data that is valid (finite where it must be) or raise
racketdyn's one-line :class:`~racketdyn.errors.InputError` — never another exception, never a
warning (warnings are errors in the test run).  Hypothesis draws the mutations with a fixed
seed (``derandomize``) and a bounded number of examples, so the run is the same every time and
takes seconds; a failing mutant is shrunk to its smallest form.

Every crash found was fixed with a plain regression test reproducing it
(``tests/test_bad_files.py``, "found by the fuzz test").
"""

from __future__ import annotations

import dataclasses
import logging
import math
import random
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from racketdyn.errors import InputError
from racketdyn.impact.uncertainty import Spread
from racketdyn.io import (
    default_racket,
    load_racket,
    read_e_bg_table,
    read_frf_uff,
    read_frfs,
    read_hammer_csv,
    read_hammer_uff,
    read_load_deflection,
    read_measured,
    read_points,
    write_frf_uff,
    write_hammer_csv,
    write_hammer_uff,
)
from racketdyn.io.measured import MeasuredRebound
from racketdyn.io.uncertainty_file import racket_spreads, read_spreads
from racketdyn.measurement.records import FrfSet, HammerRecords
from racketdyn.modal.model import ModalModel
from racketdyn.racket import Racket
from racketdyn.racket_modal import check_on_racket
from racketdyn.sweep.spec import SweepSpec
from racketdyn.sweep.spec_file import load_sweep_spec
from test_uff import _frfs, _records

FIXTURES = Path(__file__).parent / "fixtures"
RACKET_TOML = (
    Path(__file__).resolve().parents[1] / "src" / "racketdyn" / "data" / "kawazoe_2002.toml"
)

SPECIAL = (
    "nan",
    "NaN",
    "inf",
    "-inf",
    "1e308",
    "-1e308",
    "1e300",
    "9e999",
    "1e-320",
    "0",
    "-0",
    "-1",
    "99999999999999999999",
    "",
    "x",
    '"',
    "[",
    "{",
    "true",
    "-1",
)
"""What a number may be replaced with: non-finite, huge, tiny, zero, negative, not a number,
and the characters that open a quoted field, an array or a table."""

NUMBER = re.compile(rb"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][-+]?\d+)?")


# --------------------------------------------------------------------------------------------
# the valid files
# --------------------------------------------------------------------------------------------


def _text(path: Path) -> bytes:
    return path.read_bytes()


def _frf_uff(folder: Path) -> bytes:
    return _text(write_frf_uff(_frfs(), folder / "frfs.uff"))


def _hammer_uff(folder: Path) -> bytes:
    return _text(write_hammer_uff(_records(), folder / "hammer.uff"))


def _hammer_csv(folder: Path) -> bytes:
    path, _ = write_hammer_csv(_records(), folder / "hammer.csv", folder / "points.csv")
    lines = path.read_bytes().splitlines(keepends=True)
    header = next(i for i, line in enumerate(lines) if line.startswith(b"node,"))
    return b"".join(lines[: header + 1] + lines[header + 1 :: 16])  # every 16th sample


def _geometry_csv(folder: Path) -> bytes:
    _, geometry = write_hammer_csv(_records(), folder / "hammer.csv", folder / "points.csv")
    return _text(geometry)


def _geometry_15(folder: Path) -> bytes:
    lines = _frf_uff(folder).splitlines(keepends=True)
    assert lines[1].strip() == b"15"
    return b"".join(lines[:6])


GEOMETRY_2411 = b"""    -1
  2411
         3         0         0        11
   4.5000000000000000D-01   0.0000000000000000D+00   0.0000000000000000D+00
         7         0         0        11
   5.5000000000000000D-01   2.0000000000000000D-02   0.0000000000000000D+00
        12         0         0        11
   6.0000000000000000D-01  -3.0000000000000000D-02   0.0000000000000000D+00
    -1
"""

MEASURED = b"""# a ball-cannon test
x_m,y_m,ball_speed_mps,racket_speed_mps,support,rebound_ratio,rebound_ratio_sd
0.50,0.0,20,0,free,0.39,0.01
0.55,0.03,25,0,pinned,0.30,0.02
0.45,-0.02,20,3,hand,0.35,0.01
"""

UNCERTAINTY = b"""[e_bg]
range = [0.80, 0.88]
[first_bending_hz]
range = [140.0, 200.0]
[location_m]
sd = 0.010
[ball_speed_mps]
sd = 1.0
[frame_damping_scale]
values = [0.5, 1.0, 2.0]
"""

E_BG_TABLE = b"""# e_BG against speed
speed_mps,e_bg
10,0.86
20,0.82
30,0.78
"""

LOAD_DEFLECTION = b"""deflection_m,force_n
0.001,50
0.002,130
0.004,330
0.006,700
"""

POINTS = b"""point,x_m,y_m
centre,0.50,0.00
throat,0.40,0.01
tip,0.60,-0.02
"""


def _sweep_spec_text() -> bytes:
    """docs/sweep-file.md's example (27 designs), as a user would start from it."""
    text = (RACKET_TOML.parents[3] / "docs" / "sweep-file.md").read_text(encoding="utf-8")
    return text.split("```toml\n", 1)[1].split("```", 1)[0].encode()


SWEEP_SPEC = _sweep_spec_text()


def _racket_toml(folder: Path) -> bytes:
    del folder
    return RACKET_TOML.read_bytes() + b"\n[uncertainty.e_bg]\nrange = [0.80, 0.88]\n"


def _modal_json(folder: Path) -> bytes:
    frfs = _frfs()
    model = ModalModel(
        frequency=np.array([120.0, 330.0]),
        damping_ratio=np.array([0.01, 0.02]),
        locations=np.column_stack([frfs.locations, np.zeros(3)]),
        mode_shapes=np.array([[0.5, -0.2], [0.8, 0.3], [1.2, -0.6]]),
        names=("mode 1 (120.0 Hz)", "mode 2 (330.0 Hz)"),
    )
    model.write_json(folder / "modal.json")
    return _text(folder / "modal.json")


# --------------------------------------------------------------------------------------------
# what valid data is
# --------------------------------------------------------------------------------------------


def _finite(*arrays: object) -> bool:
    return all(bool(np.all(np.isfinite(np.asarray(a, dtype=float)))) for a in arrays)


def _valid_frfs(frfs: object) -> bool:
    return (
        isinstance(frfs, FrfSet)
        and frfs.n_points > 0
        and _finite(frfs.frequency, frfs.values.real, frfs.values.imag)
        and bool(np.all(np.diff(frfs.frequency) > 0))
    )


def _valid_records(records: object) -> bool:
    return (
        isinstance(records, HammerRecords)
        and len(records.nodes) > 0
        and math.isfinite(records.sampling_interval_s)
        and records.sampling_interval_s > 0
        and _finite(*records.force, *records.response)
    )


def _valid_table(table: object) -> bool:
    return isinstance(table, tuple) and len(table) > 0 and _finite(*table)


def _numbers_finite(value: object, depth: int = 0) -> bool:
    """Every number in ``value`` (a dataclass, tuple, dict or array, walked 4 deep) finite;
    ``None`` and text pass.  For the readers whose results may hold no NaN at all."""
    if depth > 4 or value is None or isinstance(value, str | Path):
        return True
    if isinstance(value, bool | int):
        return True
    if isinstance(value, float | np.floating | np.ndarray):
        return _finite(value)
    if isinstance(value, tuple | list):
        return all(_numbers_finite(v, depth + 1) for v in value)
    if isinstance(value, dict):
        return all(_numbers_finite(v, depth + 1) for v in value.values())
    if dataclasses.is_dataclass(value):
        return all(
            _numbers_finite(getattr(value, f.name), depth + 1) for f in dataclasses.fields(value)
        )
    return True


def _valid_modal(model: object) -> bool:
    return (
        isinstance(model, ModalModel)
        and model.frequency.size > 0
        and _finite(model.frequency, model.damping_ratio, model.mode_shapes)
        and bool(np.all(model.frequency > 0))
        and bool(np.all((model.damping_ratio >= 0) & (model.damping_ratio < 1)))
    )


def _valid_measured(rows: object) -> bool:
    return isinstance(rows, MeasuredRebound) and len(rows) > 0 and _numbers_finite(rows)


def _valid_racket(racket: object) -> bool:
    return isinstance(racket, Racket) and racket.mass_kg > 0 and _numbers_finite(racket)


def _valid_spec(spec: object) -> bool:
    return isinstance(spec, SweepSpec) and len(spec.designs) > 0 and _numbers_finite(spec)


def _valid_spreads(spreads: object) -> bool:
    return (
        isinstance(spreads, tuple)
        and all(isinstance(s, Spread) for s in spreads)
        and _numbers_finite(spreads)
    )


@dataclass(frozen=True)
class Reader:
    """One reader: how its valid file is made, how it is read, and what valid data is."""

    name: str
    suffix: str
    valid_file: Callable[[Path], bytes]
    read: Callable[[Path, Path], object]  # (the damaged file, a folder of valid companions)
    valid: Callable[[object], bool]
    heavy: bool = False  # a read of 5-10 ms: fewer mutants


def _frfs_only(folder: Path) -> Path:
    """racketdyn's FRF file without its data set 15: the FRFs a geometry file completes."""
    path = folder / "frfs_only.uff"
    if not path.exists():
        lines = _frf_uff(folder).splitlines(keepends=True)
        path.write_bytes(b"".join(lines[6:]))
    return path


def _hammer_csv_file(folder: Path) -> Path:
    path = folder / "hammer_valid.csv"
    if not path.exists():
        path.write_bytes(_hammer_csv(folder))
    return path


def _points(path: Path) -> tuple[object, ...]:
    locations, labels = read_points(path)
    assert len(labels) == len(locations)
    return (locations,)


def _racket_model(path: Path) -> ModalModel:
    """A modal model as ``predict --modal`` takes it for the built-in racket."""
    model = ModalModel.read_json(path)
    check_on_racket(model, default_racket(), str(path))
    return model


def _racket(path: Path) -> object:
    racket = load_racket(path)
    racket_spreads(path)
    return racket


READERS = [
    Reader("UFF 58 FRFs", ".uff", _frf_uff, lambda p, _: read_frfs(p), _valid_frfs, heavy=True),
    Reader(
        "UFF 58 FRFs (another system's export)",
        ".uff",
        lambda _: _text(FIXTURES / "testlab_like_frf.uff"),
        lambda p, _: read_frf_uff(p),
        _valid_frfs,
        heavy=True,
    ),
    Reader(
        "UFF 58 time records",
        ".uff",
        _hammer_uff,
        lambda p, _: read_hammer_uff(p),
        _valid_records,
        heavy=True,
    ),
    Reader(
        "UFF 15 geometry",
        ".uff",
        _geometry_15,
        lambda p, f: read_frfs(_frfs_only(f), geometry=p),
        _valid_frfs,
        heavy=True,
    ),
    Reader(
        "UFF 2411 geometry",
        ".uff",
        lambda _: GEOMETRY_2411,
        lambda p, f: read_frfs(_frfs_only(f), geometry=p),
        _valid_frfs,
        heavy=True,
    ),
    Reader("hammer CSV", ".csv", _hammer_csv, lambda p, _: read_hammer_csv(p), _valid_records),
    Reader(
        "geometry CSV",
        ".csv",
        _geometry_csv,
        lambda p, f: read_hammer_csv(_hammer_csv_file(f), p),
        _valid_records,
    ),
    Reader(
        "measured-rebound CSV",
        ".csv",
        lambda _: MEASURED,
        lambda p, _: read_measured(p),
        _valid_measured,
    ),
    Reader("racket TOML", ".toml", _racket_toml, lambda p, _: _racket(p), _valid_racket),
    Reader(
        "uncertainty TOML",
        ".toml",
        lambda _: UNCERTAINTY,
        lambda p, _: read_spreads(p),
        _valid_spreads,
    ),
    Reader(
        "e_BG table", ".csv", lambda _: E_BG_TABLE, lambda p, _: read_e_bg_table(p), _valid_table
    ),
    Reader(
        "load-deflection table",
        ".csv",
        lambda _: LOAD_DEFLECTION,
        lambda p, _: read_load_deflection(p),
        _valid_table,
    ),
    Reader("points CSV", ".csv", lambda _: POINTS, lambda p, _: _points(p), _valid_table),
    Reader(
        "modal-model JSON", ".json", _modal_json, lambda p, _: ModalModel.read_json(p), _valid_modal
    ),
    Reader(
        "modal-model JSON for a racket",
        ".json",
        lambda _: (Path(__file__).parent / "data" / "demo_modal_model_free.json").read_bytes(),
        lambda p, _: _racket_model(p),
        _valid_modal,
        heavy=True,
    ),
    Reader(
        "sweep spec TOML",
        ".toml",
        lambda _: SWEEP_SPEC,
        lambda p, _: load_sweep_spec(p),
        _valid_spec,
        heavy=True,
    ),
]


# --------------------------------------------------------------------------------------------
# mutations
# --------------------------------------------------------------------------------------------

KINDS = (
    "truncate",
    "flip byte",
    "delete line",
    "double line",
    "swap lines",
    "swap fields",
    "special number",
    "scale number",
    "insert junk",
)


def mutate(data: bytes, kind: str, a: int, b: int, pick: int) -> bytes:
    """``data`` damaged once: ``a`` and ``b`` choose where (taken modulo the size), ``pick``
    what is put there."""
    if not data:
        return data
    lines = data.splitlines(keepends=True)
    i, j = a % len(lines), b % len(lines)
    if kind == "truncate":
        return data[: a % len(data)]
    if kind == "flip byte":
        at = a % len(data)
        return data[:at] + bytes([data[at] ^ (1 + pick % 255)]) + data[at + 1 :]
    if kind == "delete line":
        return b"".join(lines[:i] + lines[i + 1 :])
    if kind == "double line":
        return b"".join(lines[: i + 1] + lines[i:])
    if kind == "swap lines":
        lines[i], lines[j] = lines[j], lines[i]
        return b"".join(lines)
    if kind == "swap fields":
        fields = re.split(rb"(,|\s+)", lines[i])
        words = [k for k, f in enumerate(fields) if f.strip(b", \t\r\n")]
        if len(words) >= 2:
            p, q = words[a % len(words)], words[b % len(words)]
            fields[p], fields[q] = fields[q], fields[p]
            lines[i] = b"".join(fields)
        return b"".join(lines)
    numbers = list(NUMBER.finditer(data))
    if kind in ("special number", "scale number") and numbers:
        found = numbers[a % len(numbers)]
        if kind == "special number":
            new = SPECIAL[pick % len(SPECIAL)].encode()
        else:
            text = found.group().replace(b"D", b"E").replace(b"d", b"e")
            new = repr(float(text) * (1e3, 1e-3, -1.0, 1e100, 1e250)[pick % 5]).encode()
        return data[: found.start()] + new + data[found.end() :]
    junk = (b"\x00", b"\xff\xfe", b"-1\n", b"    -1\n", b"\n", b",,,\n", b"\t", b"\xc3", b'"')
    at = a % len(data)
    return data[:at] + junk[pick % len(junk)] + data[at:]


WEIGHTS = (1, 1, 1, 1, 1, 1, 3, 1, 3)
"""How often each of :data:`KINDS` is drawn: a number replaced and junk inserted three times as
often as the rest (they reach the parsers of the values, where the crashes were)."""


def _mutations(seed: int) -> list[tuple[str, int, int, int]]:
    """1-3 mutations drawn uniformly from ``seed``: hypothesis draws the seed (its own draws of
    kinds and positions lean to the first and the smallest, which left quotes and huge node
    numbers untried in 250 examples)."""
    rng = random.Random(seed)
    return [
        (
            rng.choices(KINDS, WEIGHTS)[0],
            rng.randrange(2**20),
            rng.randrange(2**20),
            rng.randrange(256),
        )
        for _ in range(rng.randint(1, 3))
    ]


MUTATIONS = st.integers(0, 2**32 - 1).map(_mutations)

HEAVY_EXAMPLES = 50
LIGHT_EXAMPLES = 250
"""Mutants per reader: a Universal File read costs 5-10 ms (pyuff), as do a sweep spec and a
racket's modal model; a CSV, TOML or JSON table well under 1 ms.  The 8 heavy readers × 50 and
8 others × 250 take ≈ 15-20 s on the loaded 2-core machine.  Run on the code before the fixes,
this test fails for five of the six CSV readers (both crashes); 30 a reader with hypothesis's
own draws of kinds and positions found none.  A run of 3,000-4,000 a reader (the same
mutator, outside the suite) found two more: a warning leaking from read_hammer_uff and a sweep
range's huge ``num`` (tests/test_bad_files.py)."""

HEAVY = [r for r in READERS if r.heavy]
LIGHT = [r for r in READERS if not r.heavy]


def _records_in(result: object) -> int | None:
    """Records a time-record or FRF reader returned: averages, or FRFs."""
    if isinstance(result, HammerRecords):
        return sum(len(force) for force in result.force)
    if isinstance(result, FrfSet):
        return result.n_points
    return None


_VALID: dict[str, tuple[bytes, int | None]] = {}


def _valid_file(reader: Reader, folder: Path) -> tuple[bytes, int | None]:
    """The reader's valid file and the records it holds, read (and checked) once."""
    if reader.name not in _VALID:
        original = reader.valid_file(folder)
        whole = reader.read(_write(folder, reader, original), folder)
        assert reader.valid(whole), f"{reader.name}: the valid file reads as invalid"
        _VALID[reader.name] = original, _records_in(whole)
    return _VALID[reader.name]


def _check_mutant(
    reader: Reader,
    folder: Path,
    caplog: pytest.LogCaptureFixture,
    mutations: list[tuple[str, int, int, int]],
) -> None:
    """The damaged file reads as valid data or raises one-line InputError; a UFF read with
    fewer records than the valid file has said so (a warning)."""
    data, records = _valid_file(reader, folder)
    for kind, a, b, pick in mutations:
        data = mutate(data, kind, a, b, pick)
    path = _write(folder, reader, data)
    caplog.clear()
    try:
        result = reader.read(path, folder)
    except InputError as error:
        message = str(error)
        assert message.strip(), f"{reader.name}: an empty message"
        assert "\n" not in message, f"{reader.name}: a message of several lines: {message}"
        return
    assert reader.valid(result), f"{reader.name}: read without error, data not valid: {result!r}"
    fewer = (records or 0) - (_records_in(result) or 0)
    # racketdyn's files say how many records they hold (ID line 3, "# records: N"); another
    # system's file cut between records is a smaller valid file (docs/uff-and-csv.md)
    counted = "another system" not in reader.name and (
        reader.suffix == ".uff" or b"# records: " in data
    )
    if fewer > 0 and counted:
        assert any(r.levelno >= logging.WARNING for r in caplog.records), (
            f"{reader.name}: {fewer} records lost without a word"
        )


_SETTINGS = {
    "derandomize": True,
    "deadline": None,
    "database": None,
    "suppress_health_check": [HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
}


def _fuzz_test(readers: list[Reader], examples: int, name: str) -> Callable[..., None]:
    """A test of ``readers``, ``examples`` mutants each (one body for both budgets)."""

    @pytest.mark.parametrize("reader", readers, ids=[r.name for r in readers])
    @settings(max_examples=examples, **_SETTINGS)  # type: ignore[arg-type]
    @given(mutations=MUTATIONS)
    def test(
        reader: Reader,
        tmp_path_factory: pytest.TempPathFactory,
        caplog: pytest.LogCaptureFixture,
        mutations: list[tuple[str, int, int, int]],
    ) -> None:
        _check_mutant(reader, _folder(tmp_path_factory, reader), caplog, mutations)

    test.__name__ = test.__qualname__ = name
    return test


test_every_damaged_universal_file_reads_valid_or_is_one_input_error = _fuzz_test(
    HEAVY, HEAVY_EXAMPLES, "test_every_damaged_universal_file_reads_valid_or_is_one_input_error"
)
test_every_damaged_table_reads_valid_or_is_one_input_error = pytest.mark.slow(
    _fuzz_test(LIGHT, LIGHT_EXAMPLES, "test_every_damaged_table_reads_valid_or_is_one_input_error")
)


_FOLDERS: dict[str, Path] = {}


def _folder(factory: pytest.TempPathFactory, reader: Reader) -> Path:
    """One folder a reader for all its mutants (its valid companions made once)."""
    if reader.name not in _FOLDERS:
        _FOLDERS[reader.name] = factory.mktemp("fuzz")
    return _FOLDERS[reader.name]


def _write(folder: Path, reader: Reader, data: bytes) -> Path:
    path = folder / f"damaged{reader.suffix}"
    path.write_bytes(data)
    return path
