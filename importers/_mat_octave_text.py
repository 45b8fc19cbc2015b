"""Octave's default `save` format (text): its numeric variables and strings as arrays.

The layout, as Octave writes it (ls-oct-text.cc): a "# Created by Octave ..." comment, then per
variable "# name: NAME" and "# type: TYPE" lines followed by

* scalar, bool, intNN scalar: one line holding the value;
* matrix, bool matrix: "# rows: R" and "# columns: C", then R lines of C values; or
  "# ndims: N", a line of N sizes and the values one per line in column-major order
  (N-d arrays, and every intNN matrix);
* string, sq_string: "# elements: E", then per row "# length: L" and a line of L characters;
* range: "# base, limit, increment" and a line of three numbers (a row vector);
* complex values, structs, cells and sparse matrices: read past (a struct's fields and a cell's
  elements are not variables of the file); anything else is passed over.

Values are numbers as C's strtod reads them, plus Inf, -Inf, NaN and NA.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from timeline.errors import FormatError

SIGNATURES = (b"# Created by Octave", b"# name:")


def is_octave_text(head: bytes) -> bool:
    """True when a file starts as Octave's text format does."""
    return head.lstrip().startswith(SIGNATURES)


def _number(token: str) -> float:
    return float("nan") if token == "NA" else float(token)


class _Lines:
    def __init__(self, text: str) -> None:
        self.lines = text.splitlines()
        self.at = 0

    def next(self) -> str:
        while self.at < len(self.lines) and not self.lines[self.at].strip():
            self.at += 1
        if self.at == len(self.lines):
            raise FormatError("ends in the middle of a variable")
        line = self.lines[self.at]
        self.at += 1
        return line

    def field(self, name: str) -> int:
        line = self.next()
        prefix = f"# {name}:"
        if not line.startswith(prefix):
            raise FormatError(f"has {line.strip()[:40]!r} where '{prefix}' belongs")
        return int(line[len(prefix) :])

    def numbers(self) -> list[float]:
        return [_number(t) for t in self.next().split()]


def _matrix(lines: _Lines) -> np.ndarray:
    head = lines.next()
    if head.startswith("# ndims:"):
        dims = [int(v) for v in lines.next().split()]
        count = int(np.prod(dims))
        flat = [_number(lines.next().strip()) for _ in range(count)]
        return np.array(flat, dtype=np.float64).reshape(dims, order="F")
    lines.at -= 1
    rows, cols = lines.field("rows"), lines.field("columns")
    data = np.array([lines.numbers() for _ in range(rows)], dtype=np.float64)
    return data.reshape(rows, cols)


def _string(lines: _Lines) -> np.ndarray:
    elements = lines.field("elements")
    rows = []
    for _ in range(elements):
        length = lines.field("length")
        line = lines.lines[lines.at] if lines.at < len(lines.lines) else ""
        lines.at += 1
        rows.append(line[:length])
    return np.array("\n".join(rows))


def _variable(kind: str, lines: _Lines) -> np.ndarray | None:
    integer = kind.startswith(("int", "uint"))
    if kind in ("scalar", "bool") or (integer and kind.endswith(" scalar")):
        return np.array([[_number(lines.next().strip())]])
    if kind in ("matrix", "bool matrix") or (integer and kind.endswith(" matrix")):
        return _matrix(lines)
    if kind in ("string", "sq_string"):
        return _string(lines)
    if kind == "range":
        lines.next()  # "# base, limit, increment"
        base, limit, step = lines.numbers()[:3]
        count = int(np.floor((limit - base) / step + 1e-10)) + 1 if step else 1
        return (base + step * np.arange(max(count, 0))).reshape(1, -1)
    _skip(kind, lines)
    return None


def _skip(kind: str, lines: _Lines) -> None:
    """Read past a value of a type we do not import, nested values included, so a struct's
    fields are not taken for variables; an unknown type is left for the scan to pass over."""
    if kind in ("scalar struct", "struct"):
        lines.field("ndims")
        lines.next()  # the sizes
        _skip_elements(lines, lines.field("length"))
    elif kind == "cell":
        head = lines.next()
        if head.startswith("# ndims:"):
            count = int(np.prod([int(v) for v in lines.next().split()]))
        else:
            lines.at -= 1
            count = lines.field("rows") * lines.field("columns")
        _skip_elements(lines, count)
    elif kind == "complex scalar":
        lines.next()
    elif kind == "complex matrix":
        head = lines.next()
        if head.startswith("# ndims:"):
            count = int(np.prod([int(v) for v in lines.next().split()]))
        else:
            lines.at -= 1
            count = lines.field("rows")
            lines.field("columns")
        for _ in range(count):
            lines.next()
    elif kind in ("sparse matrix", "sparse bool matrix", "sparse complex matrix"):
        count = lines.field("nnz")
        lines.field("rows")
        lines.field("columns")
        for _ in range(count):
            lines.next()


def _skip_elements(lines: _Lines, count: int) -> None:
    """Read past `count` nested "# name:" / "# type:" values."""
    for _ in range(count):
        lines.next()  # "# name: ..."
        kind = lines.next().strip()[len("# type:") :].strip()
        _variable(kind, lines)


def load(path: Path) -> dict[str, np.ndarray]:
    """The file's numeric variables and strings by name, in Matlab's orientation."""
    lines = _Lines(path.read_text(encoding="utf-8", errors="replace"))
    found: dict[str, np.ndarray] = {}
    try:
        while lines.at < len(lines.lines):
            line = lines.lines[lines.at].strip()
            lines.at += 1
            if not line.startswith("# name:"):
                continue
            name = line[len("# name:") :].strip()
            kind_line = lines.next().strip()
            if not kind_line.startswith("# type:"):
                continue
            value = _variable(kind_line[len("# type:") :].strip(), lines)
            if value is not None:
                found[name] = value
    except (ValueError, IndexError) as exc:
        raise FormatError(f"{path.name} is not a readable Octave text file ({exc})") from None
    except FormatError as exc:
        raise FormatError(f"{path.name} is not a readable Octave text file: it {exc}") from None
    return found
