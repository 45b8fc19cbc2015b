"""What a device reports: telemetry, live pieces of it, and stability flags."""

from __future__ import annotations

import csv
import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np

from timeline.errors import DeviceError
from timeline.plugins.device_protocol.lateness import Lateness

TELEMETRY_COLUMNS = ("time", "angle", "velocity", "torque")


@dataclass(frozen=True)
class LiveTelemetry:
    """A piece of telemetry as it arrives while playing (for a live scope)."""

    time: np.ndarray  # s since play start
    angle: np.ndarray  # rad from the anchor
    torque: np.ndarray  # N*m applied

    def __len__(self) -> int:
        return len(self.time)


Monitor = Callable[[LiveTelemetry], None]


@dataclass(frozen=True, eq=False)
class StabilityFlag:
    """Samples where a rule of stable rendering was broken.

    `margins` say by how much each flagged sample went past the limit, in the rule's unit
    (positive = beyond it); `limit` describes the rule.
    """

    kind: str  # "passivity", "negative-damping", "mass-cancels-inertia", "blow-up", ...
    message: str
    times: np.ndarray
    margins: np.ndarray
    unit: str = ""

    @property
    def count(self) -> int:
        return int(self.times.size)

    @property
    def first_time(self) -> float:
        return float(self.times[0]) if self.times.size else math.nan

    @property
    def worst_margin(self) -> float:
        return float(self.margins.max()) if self.margins.size else math.nan

    def describe(self) -> str:
        """One line for a summary."""
        if not self.count:
            return f"{self.kind}: {self.message}"
        return (
            f"{self.kind}: {self.message} ({self.count} samples from {self.first_time:.4f} s, "
            f"worst {self.worst_margin:.4g} {self.unit} beyond the limit)"
        )


def merge_flags(flags: Iterable[StabilityFlag]) -> tuple[StabilityFlag, ...]:
    """Join flags of the same kind (e.g. from successive blocks) in time order."""
    by_kind: dict[str, list[StabilityFlag]] = {}
    for f in flags:
        by_kind.setdefault(f.kind, []).append(f)
    merged = []
    for kind, group in by_kind.items():
        merged.append(
            StabilityFlag(
                kind,
                group[0].message,
                np.concatenate([f.times for f in group]),
                np.concatenate([f.margins for f in group]),
                group[0].unit,
            )
        )
    return tuple(merged)


# Net energy (J) at or below this reads as zero: the per-sample sum's round-off (+9.8e-63 J on a
# held knob), far under the work of 1 mNm over one encoder count (1 mNm x 1.745e-5 rad = 17 nJ).
ENERGY_TOLERANCE = 1e-9


@dataclass(frozen=True, eq=False)
class Telemetry:
    """What a device reports after playing: per-sample arrays, layers and flags.

    angle is rad from the anchor (the angle when playback started), velocity rad/s, torque the
    N*m the motor applied, energy the cumulative energy (J) the device put into the knob and
    hand: motor work minus what its own friction dissipated (positive = active), saturated True
    where the torque was clamped. `layers` maps a layer name to the values rendered per sample.
    `lateness` counts the blocks handed over late when the device plays in real time.
    """

    rate: float
    time: np.ndarray
    angle: np.ndarray
    velocity: np.ndarray
    torque: np.ndarray
    energy: np.ndarray
    saturated: np.ndarray
    layers: dict[str, np.ndarray] = field(default_factory=dict)
    flags: tuple[StabilityFlag, ...] = ()
    warnings: tuple[str, ...] = ()
    lateness: Lateness | None = None

    def __len__(self) -> int:
        return int(self.time.size)

    @property
    def peak_torque(self) -> float:
        """Largest |torque| applied (N*m)."""
        return float(np.abs(self.torque).max()) if self.torque.size else 0.0

    @property
    def time_saturated(self) -> float:
        """Seconds the torque spent clamped at the device maximum."""
        return float(np.count_nonzero(self.saturated)) / self.rate

    @property
    def energy_injected(self) -> float:
        """Net energy (J) the device put into knob and hand over the run; positive = active."""
        return float(self.energy[-1]) if self.energy.size else 0.0

    def flag(self, kind: str) -> StabilityFlag | None:
        """The flag of a kind, or None when that rule was never broken."""
        return next((f for f in self.flags if f.kind == kind), None)

    @classmethod
    def concatenate(cls, parts: Sequence[Telemetry]) -> Telemetry:
        """Join telemetry of successive blocks of one run."""
        if not parts:
            raise DeviceError("there is no telemetry to join")
        names = list(dict.fromkeys(n for p in parts for n in p.layers))

        def cat(attr: str) -> np.ndarray:
            return np.concatenate([getattr(p, attr) for p in parts])

        layers = {
            n: np.concatenate([p.layers.get(n, np.zeros(len(p))) for p in parts]) for n in names
        }
        return cls(
            parts[0].rate,
            cat("time"),
            cat("angle"),
            cat("velocity"),
            cat("torque"),
            cat("energy"),
            cat("saturated"),
            layers,
            merge_flags(f for p in parts for f in p.flags),
            tuple(dict.fromkeys(w for p in parts for w in p.warnings)),
            next((p.lateness for p in reversed(parts) if p.lateness is not None), None),
        )

    def summary(self, kind: str = "kinesthetic") -> list[str]:
        """Human-readable summary lines: peak output, saturation, energy (knobs), flags.

        A vibrotactile device's output is a fraction of its full scale and it has no angle, so
        its peak is given in percent and no energy is reported.
        """
        lines = [f"played {len(self) / self.rate:.3f} s ({len(self)} samples at {self.rate:g} Hz)"]
        clamped = ""
        if self.time_saturated > 0:  # the device clamping safely: said, never a stop
            clamped = ": the device clamped its output to its limit there, and the play went on"
        if kind == "vibrotactile":
            lines += [
                f"peak output {self.peak_torque * 100:.1f}% of full scale",
                f"at full scale {self.time_saturated:.4f} s{clamped}",
            ]
        else:
            lines += [
                f"peak torque {self.peak_torque * 1e3:.2f} mNm",
                f"saturated {self.time_saturated:.4f} s{clamped}",
                self._energy_line(),
            ]
        lines += [f"flag {f.describe()}" for f in self.flags] or ["no stability flags"]
        lines += [f"warning: {w}" for w in self.warnings]
        if self.lateness is not None:
            lines.append(self.lateness.describe())
        return lines

    def _energy_line(self) -> str:
        """The net energy, 0 within ENERGY_TOLERANCE; what makes it positive when it is."""
        energy = self.energy_injected
        if abs(energy) <= ENERGY_TOLERANCE:
            return f"energy injected by the device 0 mJ (within {ENERGY_TOLERANCE:g} J: passive)"
        text = f"energy injected by the device {energy * 1e3:+.4g} mJ"
        if energy < 0:
            return text + " (passive)"
        drive = self.layers.get("d")
        if drive is not None and np.any(drive):
            return text + " (active: the drive layer pushes the hand, as a drive does)"
        return text + " (active: the springs, dampers and masses gave energy back)"

    def write_csv(self, path: str, layer_names: dict[str, str] | None = None) -> None:
        """Write time, angle (rad), velocity (rad/s), torque (N*m), then the layers.

        `layer_names` picks and names the layer columns (all layers by their keys when None);
        a name that clashes with a telemetry column gets the suffix `_layer`.
        """
        chosen = layer_names if layer_names is not None else {k: k for k in self.layers}
        keys = [k for k in chosen if k in self.layers]
        names = [
            f"{chosen[k]}_layer" if chosen[k] in TELEMETRY_COLUMNS else chosen[k] for k in keys
        ]
        columns = [
            self.time,
            self.angle,
            self.velocity,
            self.torque,
            *(self.layers[k] for k in keys),
        ]
        data = np.column_stack(columns) if len(self) else np.zeros((0, len(columns)))
        with open(path, "w", newline="") as fh:
            writer = csv.writer(fh)
            writer.writerow([*TELEMETRY_COLUMNS, *names])
            writer.writerows((repr(float(v)) for v in row) for row in data)
