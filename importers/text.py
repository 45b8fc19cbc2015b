"""CSV and TXT tables: one column at a given rate, or a time column and value columns.

Comment lines start with #, % or //. A header is the first line with a word in it, or (the
Matlab-friendly .txt we write) the last comment line just before the data with one name per
column. Columns are separated by commas, tabs, semicolons or spaces.

A project's rendered layers end with a units line (importers/_units.py): re-imported, each column
goes back on a track of its kind at the values written. A position project's axis column is
`angle_deg`, in degrees; older files' `angle` column is read in radians, as they wrote it.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np

from importers import _units
from importers._bounded_read import read_at_most
from importers._columns import (
    AXIS_NAMES,
    finite_values,
    placed_tile,
    positive_rate,
    rate_from_axis,
)
from timeline.plugins.file_formats import FormatError, Imported, Layers, Progress
from timeline.tiles import Tile

COMMENTS = ("#", "%", "//")
MAX_BYTES = 2**31
ROW_BLOCK = 4096  # rows formatted by one string operation when writing
# the whole token after "rate=", a unit our writers add allowed: "1_000" or "10kHz" were read as
# 1 and 10 when only the leading digits were taken
_RATE_COMMENT = re.compile(r"\b(?:rate|fs)\s*[=:]\s*([^\s,;]+)", re.IGNORECASE)
_RATE_UNITS = ("/s", "/deg", "/rad", "hz")


def _rate_number(token: str) -> str:
    """The number of a rate comment's token, without a unit of _RATE_UNITS (else the token,
    whole, for the sentence that refuses it)."""
    number = next((token[: -len(u)] for u in _RATE_UNITS if token.lower().endswith(u)), token)
    return number if _is_number(number) else token


def _delimiter(line: str) -> str | None:
    for d in (",", "\t", ";"):
        if d in line:
            return d
    return None  # runs of spaces


def _split(line: str, delimiter: str | None) -> list[str]:
    return [t.strip() for t in line.split(delimiter)] if delimiter else line.split()


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def _decode(path: Path) -> str:
    """The file's text, refused by its size before it is read (and again if it grew)."""
    too_large = FormatError(
        f"{path.name} is larger than {MAX_BYTES >> 30} GiB, the most a text table may be"
    )
    raw = read_at_most(path, MAX_BYTES, too_large)
    if b"\x00" in raw:
        raise FormatError(f"{path.name} is not a text file")
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise FormatError(f"{path.name} is not a UTF-8 text file") from None


class Table:
    """A parsed text table: column names (may be empty), values (rows x columns), a rate comment."""

    def __init__(self, text: str, name: str) -> None:
        self.name = name
        self.names: list[str] = []
        self.rate: float | None = None
        lines = text.splitlines()
        comments: list[str] = []
        first = 0
        while first < len(lines):
            line = lines[first].strip()
            if line and not line.startswith(COMMENTS):
                break
            if line:
                body = line.lstrip("#%/ \t")
                comments.append(body)
                match = _RATE_COMMENT.search(body)
                if match:
                    self.rate = positive_rate(_rate_number(match.group(1)), name)
            first += 1
        if first == len(lines):
            raise FormatError(f"{name} holds no data rows")
        delimiter = _delimiter(lines[first])
        tokens = _split(lines[first].strip(), delimiter)
        if not all(_is_number(t) for t in tokens):
            self.names = tokens
            first += 1
        elif comments and len(_split(comments[-1], delimiter)) == len(tokens):
            candidate = _split(comments[-1], delimiter)
            if not any(_is_number(t) for t in candidate):
                self.names = candidate
        rows = [ln for ln in lines[first:] if ln.strip() and not ln.strip().startswith(COMMENTS)]
        if self.rate is None:  # our files put the rate in a comment after the data
            for line in lines[first:]:
                match = line.strip().startswith(COMMENTS) and _RATE_COMMENT.search(line)
                if match:
                    self.rate = positive_rate(_rate_number(match.group(1)), name)
        if not rows:
            raise FormatError(f"{name} has a header but no data rows")
        try:
            values = np.loadtxt(rows, delimiter=delimiter, ndmin=2, dtype=np.float64)
        except ValueError as exc:
            detail = str(exc).splitlines()[0].split("; use `usecols`")[0]  # numpy's own advice
            raise FormatError(f"{name} has a row that is not all numbers ({detail})") from None
        if self.names and len(self.names) != values.shape[1]:
            raise FormatError(
                f"{name} has {len(self.names)} column names "
                f"but {values.shape[1]} columns of numbers"
            )
        self.values = values

    def has_axis_column(self) -> bool:
        """True when the first column is a time (or angle) axis."""
        if self.values.shape[1] < 2:
            return False
        if self.names:
            return self.names[0].strip().lower() in AXIS_NAMES
        axis = self.values[:, 0]
        steps = np.diff(axis)
        return len(axis) > 1 and bool(np.all(steps > 0))

    def column(self, choice: str | int | None, first_value: int) -> int:
        """The index of the chosen column: by name, by number from 1, or the first value column."""
        if choice is None:
            return first_value
        if self.names and str(choice) in self.names:
            return self.names.index(str(choice))
        try:
            number = int(choice)
        except (TypeError, ValueError):
            names = ", ".join(self.names) or "none"
            raise FormatError(f"{self.name} has no column {choice!r} (columns: {names})") from None
        if not 1 <= number <= self.values.shape[1]:
            raise FormatError(f"{self.name} has {self.values.shape[1]} columns; no column {number}")
        return number - 1


class TextFormat:
    """Comma/tab/space separated text: a tile per chosen column; layers with a time column."""

    name = "csv"
    extensions = (".csv", ".txt", ".tsv", ".dat")
    reads = "tile"
    writes = "layers"
    options = ("column", "rate")

    def read(
        self,
        path: Path,
        *,
        progress: Progress | None = None,
        column: str | int | None = None,
        rate: float | None = None,
        **options: Any,
    ) -> Tile | Imported:
        """Read one column as a sampled tile; its rate from the time column, a comment or `rate`."""
        path = Path(path)
        text = _decode(path)
        table = Table(text, path.name)
        units = _units.parse(text)
        with_axis = table.has_axis_column()
        index = table.column(column, 1 if with_axis else 0)
        values = finite_values(table.values[:, index], path.name)
        start = 0.0
        if with_axis:
            if index == 0:
                raise FormatError(f"column 1 of {path.name} is its time axis, not a value column")
            axis = finite_values(table.values[:, 0], path.name)
            degrees = bool(table.names) and table.names[0].strip().lower() == _units.ANGLE_DEG
            file_rate = table.rate or (rate_from_axis(axis, path.name) if len(axis) > 1 else None)
            if degrees:  # samples per degree in the file, per radian on the timeline
                axis = np.radians(axis)
                file_rate = None if file_rate is None else file_rate * 180.0 / np.pi
            start = float(axis[0])
        else:
            file_rate = table.rate
        if units is not None and units.rate is not None:
            file_rate = units.rate  # exact, where the axis column gives it to a few ulps
        chosen = file_rate or rate
        if chosen is None:
            raise FormatError(f"{path.name} has no time column: give its rate")
        if progress is not None:
            progress(1.0)
        label = table.names[index] if table.names else f"column {index + 1}"
        if units is not None and label in units.kinds:
            names = [label] if column is not None else [n for n in table.names if n in units.kinds]
            columns = [(n, finite_values(table.values[:, table.names.index(n)], path.name))
                       for n in names]  # fmt: skip
            return _units.kind_placements(columns, units, chosen, start, path.stem, str(path))
        tile = placed_tile(values, chosen, start, f"{path.stem} {label}", str(path))
        return _units.as_shape(tile, path.name)

    def write(self, source: Layers, path: Path, **options: Any) -> None:
        """A time column then one column per layer, 17 significant digits (exact round trip).

        .csv has a header row (spreadsheets, readtable); .txt is tab separated with the header as
        a % comment, so Matlab's `load` reads it as a plain matrix.
        """
        path = Path(path)
        names = [_units.axis_column(source.axis), *source.columns]
        table = np.zeros((source.length, len(names)))
        table[:, 0] = _units.axis_values(source.axis, source.start, source.rate, source.length)
        for i, col in enumerate(source.columns.values(), start=1):
            table[: len(col), i] = col
        if path.suffix.lower() == ".csv":
            header, delimiter, comments = ",".join(names), ",", ""
        else:
            header, delimiter, comments = "\t".join(names), "\t", "% "
        rate = _units.file_rate(source.axis, source.rate)
        # after the rows, so the header stays the first line for pandas, numpy and readmatrix
        units = _units.describe(list(source.columns), source.axis, source.rate)
        footer = [] if units is None else [units]
        if not _axis_gives_rate(table[:, 0], rate):
            footer.append(f"rate={rate!r}")
        with open(path, "w", encoding="utf-8", newline="") as f:
            f.write(f"{comments}{header}\n")
            f.writelines(_rows(table, delimiter))
            for line in footer:
                f.write(f"{comments or '# '}{line}\n")


def _rows(table: np.ndarray, delimiter: str) -> Iterator[str]:
    """The table's rows as text, 17 significant digits (the bytes np.savetxt writes with
    "%.17g"), ROW_BLOCK rows per string operation instead of one call per row."""
    row = delimiter.join(["%.17g"] * table.shape[1]) + "\n"
    for lo in range(0, len(table), ROW_BLOCK):
        block = table[lo : lo + ROW_BLOCK]
        yield (row * len(block)) % tuple(block.ravel().tolist())


def _axis_gives_rate(axis: np.ndarray, rate: float) -> bool:
    """True when reading the written time column back yields exactly this rate."""
    try:
        return len(axis) > 1 and rate_from_axis(axis, "") == rate
    except FormatError:
        return False


FORMAT = TextFormat()
