"""What a device plays: coefficient blocks (time mode) or tables over angle (position mode)."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np

from timeline.errors import DeviceError


def _as_array(name: str, values: Any) -> np.ndarray:
    arr = np.asarray(values, dtype=np.float64).reshape(-1)
    if arr.ndim != 1:
        raise DeviceError(f"coefficient {name} must be one-dimensional")
    return arr


@dataclass(frozen=True, eq=False)
class CoefficientBlock:
    """One block of per-sample coefficients d, k, b (and m when the project has a mass layer).

    Values may be non-finite when they come from outside; every backend must call `safe()` (or
    do the same) before the values reach hardware.
    """

    d: np.ndarray
    k: np.ndarray
    b: np.ndarray
    m: np.ndarray | None = None

    def __post_init__(self) -> None:
        arrays = {"d": self.d, "k": self.k, "b": self.b}
        if self.m is not None:
            arrays["m"] = self.m
        lengths = set()
        for name, values in arrays.items():
            arr = _as_array(name, values)
            object.__setattr__(self, name, arr)
            lengths.add(arr.size)
        if len(lengths) != 1:
            raise DeviceError(
                f"coefficient arrays of one block differ in length ({sorted(lengths)})"
            )

    def __len__(self) -> int:
        return int(self.d.size)

    @classmethod
    def split(
        cls,
        d: np.ndarray,
        k: np.ndarray,
        b: np.ndarray,
        m: np.ndarray | None,
        size: int,
    ) -> list[CoefficientBlock]:
        """Cut whole coefficient arrays into blocks of `size` samples (the last may be shorter)."""
        return [
            cls(
                d[i : i + size],
                k[i : i + size],
                b[i : i + size],
                None if m is None else m[i : i + size],
            )
            for i in range(0, len(d), max(1, size))
        ]

    @classmethod
    def zeros(cls, n: int, mass: bool = False) -> CoefficientBlock:
        """A block of n samples that renders no torque."""
        z = np.zeros(n)
        return cls(z, z, z, z if mass else None)

    @property
    def nonfinite(self) -> int:
        """How many values are NaN or infinite."""
        arrays = (self.d, self.k, self.b) + (() if self.m is None else (self.m,))
        return int(sum(np.count_nonzero(~np.isfinite(a)) for a in arrays))

    def safe(self) -> CoefficientBlock:
        """The block with every NaN or infinite value replaced by 0 (no force)."""
        if not self.nonfinite:
            return self

        def fix(a: np.ndarray) -> np.ndarray:
            return np.where(np.isfinite(a), a, 0.0)

        m = None if self.m is None else fix(self.m)
        return CoefficientBlock(fix(self.d), fix(self.k), fix(self.b), m)


@dataclass(frozen=True, eq=False)
class PositionTable:
    """Equation 1 as tables over angle: T(theta), B(theta), M(theta).

    Sample i sits at table angle `start + i/rate` (rad); between samples values are linear,
    beyond the ends the end values hold. `damping` and `mass` are None when absent.
    """

    start: float
    rate: float  # samples per radian
    torque: np.ndarray
    damping: np.ndarray | None = None
    mass: np.ndarray | None = None

    def __post_init__(self) -> None:
        n = None
        for name in ("torque", "damping", "mass"):
            values = getattr(self, name)
            if values is None:
                continue
            arr = _as_array(name, values).copy()
            if not np.isfinite(arr).all():
                i = int(np.flatnonzero(~np.isfinite(arr))[0])
                raise DeviceError(
                    f"the position table's {name} at sample {i} is {arr[i]}, not a finite number"
                )
            object.__setattr__(self, name, arr)
            if n is not None and arr.size != n:
                raise DeviceError("position tables of one program differ in length")
            n = arr.size
        if not n:
            raise DeviceError("a position table needs at least one sample")
        if not (math.isfinite(self.rate) and self.rate > 0 and math.isfinite(self.start)):
            raise DeviceError("a position table needs a finite start and a positive rate")

    @property
    def stop(self) -> float:
        """Table angle of the last sample."""
        return self.start + (self.torque.size - 1) / self.rate

    def angles(self) -> np.ndarray:
        """Table angle of every sample."""
        return self.start + np.arange(self.torque.size) / self.rate


@dataclass(frozen=True, eq=False)
class PositionProgram:
    """A position-mode program: tables, how long to play them, and where the knob starts.

    `origin` is the table angle under the knob when playback starts (theta = 0 there).
    """

    table: PositionTable
    duration: float
    origin: float = 0.0
    live: Callable[[], PositionTable] | None = None  # tables that edits may replace while playing

    def __post_init__(self) -> None:
        if not (math.isfinite(self.duration) and self.duration > 0):
            raise DeviceError(f"a position program needs a positive duration, not {self.duration}")

    def table_now(self) -> PositionTable:
        """The tables to render from now on: the live source's latest, else the fixed table.

        A device reads this once per chunk it simulates or sends, so an edit is felt at the
        next chunk.
        """
        return self.table if self.live is None else self.live()


Program = Iterable[CoefficientBlock] | PositionProgram
