"""A finding: what limit a design crosses, where, by how much, and what to change."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

AREAS = ("device", "perception")


@dataclass(frozen=True)
class Finding:
    """One crossed limit over one span of the timeline.

    `start`/`stop` are seconds (time projects) or radians (position projects); `value` is the
    worst value reached in the span (a band loss: its median) and `limit` the limit it crossed,
    both in `unit`.
    """

    kind: str
    area: str  # "device" or "perception"
    what: str
    start: float
    stop: float
    axis: str  # "time" or "position"
    value: float
    limit: float
    unit: str
    advice: str
    layer: str = ""  # the torque-law term or track the finding is about (d, k, b, m, a track)

    def where(self) -> str:
        """The span as a person reads it: seconds, or degrees on a position axis."""
        if self.axis == "position":
            return f"{math.degrees(self.start):.1f} to {math.degrees(self.stop):.1f} deg"
        return f"{self.start:.3f} to {self.stop:.3f} s"

    def by_how_much(self) -> str:
        """The worst value against the limit."""
        return f"{self.value:.4g} {self.unit} against a limit of {self.limit:.4g} {self.unit}"

    def describe(self) -> str:
        """One line: what, where, by how much, what to change."""
        return f"{self.kind}: {self.what} at {self.where()} ({self.by_how_much()}); {self.advice}"

    def as_dict(self) -> dict[str, object]:
        """A JSON-ready mapping (infinities as strings)."""
        out: dict[str, object] = asdict(self)
        for key in ("value", "limit", "start", "stop"):
            value = float(out[key])  # type: ignore[arg-type]
            out[key] = value if math.isfinite(value) else str(value)
        return out


def spans(mask: np.ndarray, join: int = 0) -> list[tuple[int, int]]:
    """Index ranges [first, last] of the runs of True in a boolean array.

    Runs separated by fewer than `join` False samples count as one (an oscillating layer that
    crosses a limit every half cycle is one finding, not one per half cycle).
    """
    edges = np.diff(np.concatenate([[0], np.asarray(mask, dtype=np.int8), [0]]))
    firsts = np.flatnonzero(edges == 1)
    lasts = np.flatnonzero(edges == -1) - 1
    if join > 0 and firsts.size > 1:
        keep = np.concatenate([[True], firsts[1:] - lasts[:-1] - 1 >= join])
        firsts, lasts = firsts[keep], np.append(lasts[np.flatnonzero(keep)[1:] - 1], lasts[-1])
    return list(zip(firsts.tolist(), lasts.tolist(), strict=True))
