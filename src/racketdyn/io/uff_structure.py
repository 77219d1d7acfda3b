"""The structure of a Universal File, checked before pyuff reads it: nothing lost silently.

pyuff finds data sets by pairing ``    -1`` delimiter lines two by two and reads each block as
the data set its second line names.  One delimiter missing or doubled shifts that pairing:
two data sets merge into one (the second one's numbers read as part of the first, or lost),
or a block of text falls between two sets and is skipped, and every later set can vanish
without a word.  A file cut short after an opening delimiter still ends with ``    -1``.
This module walks the file as pyuff will (the same delimiter rule) and checks, for every data
set, what the format prescribes:

- delimiters pair up, and nothing but blank lines lies between a closing delimiter and the
  next opening one;
- the line after an opening delimiter names a data set (``    58``, ``    58b …``);
- a data set 58 has its eleven header lines, and as many values (ASCII) or bytes (binary) as
  its record 7 says (number of points × 1 or 2 for complex × 1 or 2 for an uneven abscissa);
- a data set 15 has one node per line (four whole numbers, three coordinates); a data set 2411
  two lines per node; a data set 164 its three lines.

Written here because pyuff has no such check (it pairs delimiters blindly, see
``docs/uff-and-csv.md``, pyuff traps).  Every problem is an :class:`~racketdyn.errors.InputError`
naming the file, the data set (counted from 1 in the file's order, as pyuff counts them) and the
line.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from racketdyn.errors import InputError

__all__ = ["DataSetBlock", "check_structure"]

_DELIMITER = b"    -1"
_BLANKS_TO_80 = b" " * 74
_TYPE_LINE = re.compile(rb"^\s*(\d{1,6})([bB]?)(?=\s|$)")
#: A number as Fortran and Python write it (NaN and infinities count: the readers refuse them).
_NUMBER = re.compile(rb"[-+]?(?:(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?|(?i:nan|inf(?:inity)?))")
_INTEGER = re.compile(rb"^[-+]?\d+$")
#: Header lines of a data set 58 after its type line (ID lines 1–5, records 6–11).
HEADER_58 = 11
#: Bytes per value of a binary data set 58 by ordinate data type (record 7, field 1).
_BYTES_58 = {2: 4, 4: 8, 5: 8, 6: 16}
_COMPLEX_58 = (5, 6)


@dataclass(frozen=True)
class DataSetBlock:
    """One data set as found in the file.

    Attributes
    ----------
    number : int
        Its number, counted from 1 in the order of the file.
    type : int
        Data set type (15, 58, 164, 2411 …).
    binary : bool
        A binary data set (``58b``).
    line : int
        Line of its opening delimiter (from 1).
    """

    number: int
    type: int
    binary: bool
    line: int


def _delimiters(raw: bytes) -> list[int]:
    """Offsets of the ``    -1`` delimiters, by pyuff's rule (UFF.refresh, pyuff 2.5)."""
    found: list[int] = []
    index, size = -1, len(raw)
    while True:
        index = raw.find(_DELIMITER, index + 1)
        if index == -1:
            return found
        end = index + 6
        if (
            end == size
            or raw[end] in (10, 13)
            or (end + 74 < size and raw[end : end + 74] == _BLANKS_TO_80)
        ):
            found.append(index)


class _Lines:
    """Line numbers of byte offsets, counted on from the last offset asked for.

    The check asks in file order (every data set's opening line), so the whole file is
    counted once; counting from its start for each data set made reading a 69-point,
    10-average export quadratic (22 s for 56 MiB).
    """

    def __init__(self, raw: bytes) -> None:
        self.raw = raw
        self._offset = 0
        self._line = 1

    def at(self, offset: int) -> int:
        if offset < self._offset:  # asked out of order: count from the start again
            self._offset, self._line = 0, 1
        self._line += self.raw.count(b"\n", self._offset, offset)
        self._offset = offset
        return self._line


def _line_end(raw: bytes, offset: int) -> int:
    """Offset just after the line starting at ``offset`` (its line break included)."""
    end = raw.find(b"\n", offset)
    return len(raw) if end == -1 else end + 1


def _shown(line: bytes) -> str:
    text = line.decode("ascii", "replace").strip()
    return repr(text[:40] + ("…" if len(text) > 40 else ""))


def check_structure(path: Path, raw: bytes) -> list[DataSetBlock]:
    """Check the structure of a Universal File and list its data sets.

    Parameters
    ----------
    path : Path
        The file (for messages).
    raw : bytes
        Its contents.

    Returns
    -------
    list of DataSetBlock
        The data sets in the file's order, as pyuff will number them.

    Raises
    ------
    InputError
        An unpaired or misplaced delimiter, text between data sets, a damaged type line, or a
        data set whose length disagrees with its header, naming the data set and the line.
    """
    lines = _Lines(raw)
    offsets = _delimiters(raw)
    blocks: list[DataSetBlock] = []
    previous_end = 0
    for k in range(0, len(offsets), 2):
        number = k // 2 + 1
        opening = offsets[k]
        between = raw[previous_end:opening]
        if between.strip():
            stray = previous_end + (len(between) - len(between.lstrip()))
            raise InputError(
                f"{path}: line {lines.at(stray)}: {_shown(raw[stray : _line_end(raw, stray)])} "
                f"lies outside any data set (before data set {number}): a '    -1' line is "
                "missing or extra; export the file again"
            )
        line_start = raw.rfind(b"\n", 0, opening) + 1
        if raw[line_start:opening].strip():
            raise InputError(
                f"{path}: line {lines.at(opening)}: a line ends in '    -1', which readers take "
                "for a data set delimiter; export the file again"
            )
        if k + 1 >= len(offsets):
            raise InputError(
                f"{path}: data set {number} (opened at line {lines.at(opening)}) has no closing "
                "'    -1' line: the file is truncated or a delimiter is missing; export the "
                "file again"
            )
        closing = offsets[k + 1]
        blocks.append(_check_block(path, raw, lines, number, opening, closing))
        previous_end = _line_end(raw, closing)
    tail = raw[previous_end:]
    if offsets and tail.strip():
        stray = previous_end + (len(tail) - len(tail.lstrip()))
        raise InputError(
            f"{path}: line {lines.at(stray)}: {_shown(raw[stray : _line_end(raw, stray)])} "
            f"follows the last data set ({len(blocks)}) outside any data set: the file is "
            "truncated or a '    -1' line is missing; export the file again"
        )
    if offsets and tail and not tail.endswith((b"\n", b"\r")):
        raise InputError(
            f"{path}: the file ends inside a line after data set {len(blocks)}, its last "
            "complete one: it was cut while being written or copied (the next data set's "
            "'    -1' begun); copy or export it again"
        )
    return blocks


def _check_block(
    path: Path, raw: bytes, lines: _Lines, number: int, opening: int, closing: int
) -> DataSetBlock:
    """Check one block between two delimiters."""
    body_start = _line_end(raw, opening)
    line_no = lines.at(opening)
    if body_start >= closing:
        raise InputError(
            f"{path}: data set {number} (line {line_no}) is empty: two '    -1' lines follow "
            "each other where a data set should begin (an extra delimiter?); export the file "
            "again"
        )
    type_end = _line_end(raw, body_start)
    type_line = raw[body_start:type_end].rstrip(b"\r\n")
    match = _TYPE_LINE.match(type_line)
    if match is None:
        raise InputError(
            f"{path}: data set {number}, line {line_no + 1}: {_shown(type_line)} is not a data "
            "set type (a number such as 58 or 58b); the header is damaged, export the file "
            "again"
        )
    kind, binary = int(match.group(1)), bool(match.group(2))
    block = DataSetBlock(number, kind, binary, line_no)
    where = f"{path}: data set {number} ({kind}{'b' if binary else ''}, line {line_no})"
    if kind == 58:
        _check_58(where, raw, lines, type_line, type_end, closing, binary)
    elif kind in (15, 2411, 164) and not binary:
        body = raw[type_end:closing].splitlines()
        first_line = lines.at(type_end)
        if kind == 15:
            _check_nodes(where, body, first_line, 1)
        elif kind == 2411:
            _check_nodes(where, body, first_line, 2)
        elif len([b for b in body if b.strip()]) != 3:
            raise InputError(
                f"{where}: a units data set has 3 lines, this one {len(body)}; a '    -1' "
                "line is missing or the set is damaged; export the file again"
            )
    return block


def _fields(line: bytes) -> list[bytes]:
    return line.split()


def _check_58(
    where: str,
    raw: bytes,
    lines: _Lines,
    type_line: bytes,
    header_start: int,
    closing: int,
    binary: bool,
) -> None:
    """Header lines and the number of values (ASCII) or bytes (binary) of a data set 58."""
    offset = header_start
    header: list[bytes] = []
    for _ in range(HEADER_58):
        if offset >= closing:
            raise InputError(
                f"{where}: has {len(header)} of its {HEADER_58} header lines; the set is cut "
                "short or a '    -1' line is misplaced; export the file again"
            )
        end = _line_end(raw, offset)
        header.append(raw[offset:end].rstrip(b"\r\n"))
        offset = end
    first_line = lines.at(header_start)
    _check_record_6(where, header[5], first_line + 5)
    for k in (8, 9, 10, 11):
        _check_fixed(where, header[k - 1], first_line + k - 1, k, _RECORDS_8_TO_11, 4)
    record7 = _fields(header[6])
    if len(record7) < 3 or not all(_INTEGER.match(f) for f in record7[:3]):
        raise InputError(
            f"{where}, line {first_line + 6}: record 7 {_shown(header[6])} must "
            "start with the ordinate data type, the number of points and the abscissa spacing; "
            "the header is damaged, export the file again"
        )
    ord_type, n_points, spacing = (int(f) for f in record7[:3])
    if ord_type not in _BYTES_58 or n_points < 0:
        raise InputError(
            f"{where}, line {first_line + 6}: record 7 gives ordinate data type "
            f"{ord_type} and {n_points} points; the type must be 2, 4, 5 or 6; the header is "
            "damaged, export the file again"
        )
    per_point = (2 if ord_type in _COMPLEX_58 else 1) + (1 if spacing == 0 else 0)
    if binary:
        size = 4 if ord_type in (2, 5) else 8
        expected = n_points * (_BYTES_58[ord_type] + (size if spacing == 0 else 0))
        data = raw[offset:closing]
        # the line break before the closing delimiter is not data (pyuff reads whole values)
        extra = data[expected:]
        if len(data) < expected or len(extra) > 2 or extra.strip():
            raise InputError(
                f"{where}: holds {len(data)} bytes of binary data, its header says {n_points} "
                f"points ({expected} bytes); the set is cut short or its data hold a '    -1' "
                "line; export the file again"
            )
        return
    body = raw[offset:closing]
    count = len(_NUMBER.findall(body))
    expected = n_points * per_point
    if count != expected:
        raise InputError(
            f"{where}: holds {count} numbers from line {lines.at(offset)} but its header says "
            f"{n_points} points ({expected} numbers, record 7); a line or a '    -1' line is "
            "missing or extra; export the file again"
        )


#: Record 6 of a data set 58 as pyuff reads it: (width, name) per field, None for a text field
#: (the entity names).  pyuff reads a field that is not a whole number as 0, silently (a
#: direction −3 becomes +, a node 0), so the check reads them first.
_RECORD_6: tuple[tuple[int, str | None], ...] = (
    (5, "function type"),
    (10, "function number"),
    (5, "version"),
    (10, "load case"),
    (11, None),
    (10, "response node"),
    (4, "response direction"),
    (11, None),
    (10, "reference node"),
    (4, "reference direction"),
)
#: Records 8–11 (abscissa, ordinate, denominator, z axis): their four whole numbers.
_RECORDS_8_TO_11: tuple[tuple[int, str | None], ...] = (
    (10, "data type"),
    (5, "length unit exponent"),
    (5, "force unit exponent"),
    (5, "temperature unit exponent"),
)
#: Function types the format defines (record 6, field 1): 0 general … 4 FRF … 28.
FUNCTION_TYPES = range(29)


def _check_fixed(
    where: str,
    line: bytes,
    line_no: int,
    record: int,
    layout: tuple[tuple[int, str | None], ...],
    required: int,
) -> list[int]:
    """The whole numbers of a header record read by pyuff's fixed widths: each a whole number
    (the first ``required`` ones present), else an error naming the record and the field."""
    numbers: list[int] = []
    start = 0
    for k, (width, name) in enumerate(layout, start=1):
        text = line[start : start + width].strip()
        start += width
        if name is None:
            continue
        if _INTEGER.match(text) or (not text and k > required):
            numbers.append(int(text) if text else 0)
            continue
        shown = repr(text.decode("ascii", "replace")) if text else "nothing"
        raise InputError(
            f"{where}, line {line_no}: record {record}, field {k} ({name}) reads {shown}, not a "
            "whole number: the header is damaged; export the file again"
        )
    return numbers


def _check_record_6(where: str, line: bytes, line_no: int) -> None:
    function_type = _check_fixed(where, line, line_no, 6, _RECORD_6, 1)[0]
    if function_type not in FUNCTION_TYPES:
        raise InputError(
            f"{where}, line {line_no}: record 6, field 1 gives function type {function_type}, "
            f"which the format does not define ({FUNCTION_TYPES[0]}–{FUNCTION_TYPES[-1]}): the "
            "header is damaged; export the file again"
        )


def _check_nodes(where: str, body: list[bytes], first_line: int, per_node: int) -> None:
    """Node data sets: 15 (one line per node: 4 whole numbers and x, y, z) or 2411 (2 lines)."""
    rows = [(first_line + i, line) for i, line in enumerate(body) if line.strip()]
    if len(rows) % per_node:
        raise InputError(
            f"{where}: {len(rows)} lines for nodes of {per_node} lines each; a line is missing "
            "or extra; export the file again"
        )
    for j in range(0, len(rows), per_node):
        line_no, line = rows[j]
        fields = _fields(line)
        numbers = fields[:4]
        coordinates = fields[4:] if per_node == 1 else _fields(rows[j + 1][1])
        good = len(numbers) == 4 and all(_INTEGER.match(f) for f in numbers)
        good = good and len(coordinates) == 3
        good = good and all(_NUMBER.fullmatch(f) for f in coordinates)
        if not good:
            shown = line if good or per_node == 1 else rows[j + 1][1]
            raise InputError(
                f"{where}, line {line_no}: {_shown(shown)} is not a node (a node number, three "
                "whole numbers and x, y, z); the set is damaged or a '    -1' line is missing; "
                "export the file again"
            )
