"""IdSequence: an immutable sequence of ids that appends in O(log n), for palette tabs.

A palette tab lists every tile added to it; copying a 16,000-entry tuple on each add made building
a project through edits O(n) per edit. IdSequence keeps the ids in two persistent maps (position
-> id, id -> how many times it is listed), so an append shares all but O(log n) of the previous
sequence, `in` is O(log n), and the old value stays unchanged for undo and variants. It compares
equal to any tuple or list of the same ids, in the same order.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from typing import Any, overload

from immutables import Map


class IdSequence(Sequence[str]):
    """An immutable, persistent sequence of ids (append-only growth in O(log n))."""

    __slots__ = ("_at", "_counts")

    def __init__(self, ids: Iterable[str] = ()) -> None:
        at: Map = Map()
        counts: Map = Map()
        with at.mutate() as at_m, counts.mutate() as counts_m:
            for i, item in enumerate(ids):
                at_m[i] = item
                counts_m[item] = counts_m.get(item, 0) + 1
            self._at, self._counts = at_m.finish(), counts_m.finish()

    @classmethod
    def of(cls, ids: Iterable[str]) -> IdSequence:
        """ids as an IdSequence (the same object if it already is one)."""
        return ids if isinstance(ids, IdSequence) else cls(ids)

    def __len__(self) -> int:
        return len(self._at)

    @overload
    def __getitem__(self, index: int) -> str: ...

    @overload
    def __getitem__(self, index: slice) -> tuple[str, ...]: ...

    def __getitem__(self, index: int | slice) -> str | tuple[str, ...]:
        if isinstance(index, slice):
            return tuple(self)[index]
        size = len(self._at)
        position = index + size if index < 0 else index
        if not 0 <= position < size:
            raise IndexError("id index out of range")
        return self._at[position]

    def __iter__(self) -> Iterator[str]:
        at = self._at
        return (at[i] for i in range(len(at)))

    def __contains__(self, item: object) -> bool:
        return item in self._counts

    def __add__(self, more: Iterable[str]) -> IdSequence:
        """A new sequence with `more` appended; this one is unchanged."""
        grown = IdSequence.__new__(IdSequence)
        at, counts = self._at, self._counts
        for item in more:
            at = at.set(len(at), item)
            counts = counts.set(item, counts.get(item, 0) + 1)
        grown._at, grown._counts = at, counts
        return grown

    def __eq__(self, other: Any) -> bool:
        if isinstance(other, IdSequence):
            if self._at is other._at:
                return True
        elif not isinstance(other, (tuple, list)):
            return NotImplemented
        return len(self) == len(other) and all(a == b for a, b in zip(self, other, strict=True))

    def __hash__(self) -> int:
        return hash(tuple(self))

    def __repr__(self) -> str:
        return f"IdSequence({tuple(self)!r})"
