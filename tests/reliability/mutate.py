"""Byte and token mutations of real files, drawn by hypothesis (atheris's mutations, by hand)."""

from __future__ import annotations

import re

from hypothesis import strategies as st

HOSTILE_NUMBERS = (
    b"1e999", b"-1e999", b"1e308", b"-0", b"0", b"-1", b"NaN", b"Infinity", b"null", b"true",
    b'"x"', b"{}", b"[]", b"9" * 400, b"4294967297", b"1e-320", b"18446744073709551616",
)  # fmt: skip
_NUMBER = re.compile(rb"-?\d+(\.\d+)?([eE][-+]?\d+)?")


def _apply(data: bytes, edits: list[tuple[int, int, int, int]]) -> bytes:
    out = bytearray(data)
    for kind, where, size, value in edits:
        if not out:
            out = bytearray([value])
            continue
        i = where % len(out)
        if kind == 0:  # flip one bit
            out[i] ^= 1 << (value % 8)
        elif kind == 1:  # an interesting byte
            out[i] = (0x00, 0xFF, 0x7F, 0x80, 0x01, value)[size % 6]
        elif kind == 2:  # insert bytes
            out[i:i] = bytes([value]) * (1 + size % 64)
        elif kind == 3:  # delete a range
            del out[i : i + 1 + size % 256]
        elif kind == 4:  # truncate
            del out[i:]
        elif kind == 5:  # duplicate a range somewhere else
            piece = out[i : i + 1 + size % 128]
            j = (where * 31 + size) % len(out)
            out[j:j] = piece
        elif kind == 6:  # a 32-bit field set to an extreme (sizes, counts, rates)
            word = (0xFFFFFFFF, 0x7FFFFFFF, 0x80000000, 0, 1)[value % 5]
            out[i : i + 4] = word.to_bytes(4, "little" if size % 2 else "big")
        else:  # a number token replaced by a hostile one (text formats)
            numbers = list(_NUMBER.finditer(bytes(out)))
            if numbers:
                m = numbers[where % len(numbers)]
                out[m.start() : m.end()] = HOSTILE_NUMBERS[value % len(HOSTILE_NUMBERS)]
    return bytes(out)


def mutations(seed: bytes, most: int = 6) -> st.SearchStrategy[bytes]:
    """The seed with 1..most random edits (bit flips, extreme fields, hostile numbers, cuts)."""
    edit = st.tuples(
        st.integers(0, 7), st.integers(0, 2**31), st.integers(0, 2**16), st.integers(0, 255)
    )
    return st.lists(edit, min_size=1, max_size=most).map(lambda e: _apply(seed, e))
