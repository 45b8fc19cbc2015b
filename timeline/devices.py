"""The host-side device protocol: what a device declares, what it plays, what it reports.

A device plays coefficient blocks of the torque law

    tau = d - k*theta - b*theta_dot - m*theta_ddot

(time mode) or a position program of tables over angle (position mode), and returns telemetry.
Plugins are found by name through the `haptic_timeline.devices` entry point group; this module
never imports a particular plugin.
"""

from __future__ import annotations

import abc
import csv
import math
import re
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from types import TracebackType
from typing import Any

import numpy as np

from timeline import plugins
from timeline.errors import HapticTimelineError

KINDS = ("kinesthetic", "vibrotactile")
TELEMETRY_COLUMNS = ("time", "angle", "velocity", "torque")

Progress = Callable[[float, float | None], None]  # (seconds played, total seconds or None)


@dataclass(frozen=True)
class LiveTelemetry:
    """A piece of telemetry as it arrives while playing (for a live scope)."""

    time: np.ndarray  # s since play start
    angle: np.ndarray  # rad from the anchor
    torque: np.ndarray  # N*m applied

    def __len__(self) -> int:
        return len(self.time)


Monitor = Callable[[LiveTelemetry], None]


class DeviceError(HapticTimelineError):
    """A device is missing, refused a request or failed while playing."""


class HandSpecError(HapticTimelineError):
    """A --hand specification could not be understood."""


@dataclass(frozen=True)
class DeviceInfo:
    """What a device declares about itself."""

    name: str
    kind: str  # "kinesthetic" or "vibrotactile"
    rate: float  # Hz: samples per second it renders
    max_output: float  # N*m (kinesthetic) or fraction of full scale (vibrotactile)
    resolution: float  # rad per encoder count (0 when the device has no encoder)
    firmware: str = ""

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise DeviceError(
                f"a device's kind must be kinesthetic or vibrotactile, not {self.kind!r}"
            )
        for name in ("rate", "max_output"):
            value = float(getattr(self, name))
            if not math.isfinite(value) or value <= 0:
                raise DeviceError(
                    f"a device's {name.replace('_', ' ')} must be positive, not {value}"
                )
        if not math.isfinite(float(self.resolution)) or self.resolution < 0:
            raise DeviceError(
                f"a device's resolution must be zero or positive, not {self.resolution}"
            )

    @property
    def period(self) -> float:
        """Seconds per sample."""
        return 1.0 / self.rate


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

        def fix(a: np.ndarray | None) -> np.ndarray | None:
            return None if a is None else np.where(np.isfinite(a), a, 0.0)

        return CoefficientBlock(fix(self.d), fix(self.k), fix(self.b), fix(self.m))


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
            arr = np.where(np.isfinite(a := _as_array(name, values)), a, 0.0)
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

    def __post_init__(self) -> None:
        if not (math.isfinite(self.duration) and self.duration > 0):
            raise DeviceError(f"a position program needs a positive duration, not {self.duration}")


Program = Iterable[CoefficientBlock] | PositionProgram

HAND_MODES = ("hold", "turn", "push", "free")
_HAND_RE = re.compile(r"^\s*(hold|turn|push|free)\s*(?::\s*([^:\s]+)\s*)?$", re.IGNORECASE)
DEFAULT_TURN_DEG_PER_S = 90.0
DEFAULT_PUSH_MNM = 20.0


@dataclass(frozen=True)
class Hand:
    """What the user's hand does: hold still, turn at a speed, push with a torque, or let go.

    `value` is degrees per second for `turn` and mNm for `push` (ignored otherwise). The grip
    (hold, turn) is a spring-damper between the knob and the hand's target angle; a pushing hand
    adds its inertia and a torque that ramps in over `push_ramp` seconds.
    """

    mode: str = "hold"
    value: float = 0.0
    grip_stiffness: float = 1.0  # N*m/rad
    grip_damping: float = 5e-3  # N*m*s/rad
    inertia: float = 2e-5  # kg*m^2 of fingers on the knob
    push_ramp: float = 0.01  # s

    def __post_init__(self) -> None:
        if self.mode not in HAND_MODES:
            raise HandSpecError(f"unknown hand {self.mode!r} (choose from {', '.join(HAND_MODES)})")
        for name in ("value", "grip_stiffness", "grip_damping", "inertia", "push_ramp"):
            if not math.isfinite(float(getattr(self, name))):
                raise HandSpecError(f"the hand's {name.replace('_', ' ')} must be a finite number")
        if min(self.grip_stiffness, self.grip_damping, self.inertia, self.push_ramp) < 0:
            raise HandSpecError("the hand's grip, inertia and push ramp cannot be negative")

    @classmethod
    def parse(cls, text: str) -> Hand:
        """Read `hold`, `free`, `turn[:DEG_PER_S]` or `push[:MNM]`."""
        match = _HAND_RE.match(text or "")
        if not match:
            raise HandSpecError(
                f"cannot read hand {text!r} (use hold, free, turn:DEG_PER_S or push:MNM)"
            )
        mode, raw = match.group(1).lower(), match.group(2)
        if raw is not None and mode in ("hold", "free"):
            raise HandSpecError(f"hand {mode!r} takes no value (got {raw!r})")
        default = {"turn": DEFAULT_TURN_DEG_PER_S, "push": DEFAULT_PUSH_MNM}.get(mode, 0.0)
        try:
            value = default if raw is None else float(raw)
        except ValueError:
            raise HandSpecError(
                f"hand {mode!r} needs a number after the colon, not {raw!r}"
            ) from None
        if not math.isfinite(value):
            raise HandSpecError(f"hand {mode!r} needs a finite number, not {raw!r}")
        return cls(mode, value)

    def __str__(self) -> str:
        return self.mode if self.mode in ("hold", "free") else f"{self.mode}:{self.value:g}"

    @property
    def turn_speed(self) -> float:
        """rad/s the grip moves at (0 unless turning)."""
        return math.radians(self.value) if self.mode == "turn" else 0.0

    @property
    def push_torque(self) -> float:
        """N*m the hand pushes with once ramped in (0 unless pushing)."""
        return self.value * 1e-3 if self.mode == "push" else 0.0

    @property
    def grips(self) -> bool:
        """True when the hand holds the knob through a spring-damper grip."""
        return self.mode in ("hold", "turn")

    @property
    def touches(self) -> bool:
        """True when the hand's inertia is on the knob."""
        return self.mode != "free"


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


@dataclass(frozen=True, eq=False)
class Telemetry:
    """What a device reports after playing: per-sample arrays, layers and flags.

    angle is rad from the anchor (the angle when playback started), velocity rad/s, torque the
    N*m the motor applied, energy the cumulative energy (J) the device put into the knob and
    hand: motor work minus what its own friction dissipated (positive = active), saturated True
    where the torque was clamped. `layers` maps a layer name to the values rendered per sample.
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
        )

    def summary(self, kind: str = "kinesthetic") -> list[str]:
        """Human-readable summary lines: peak output, saturation, energy (knobs), flags.

        A vibrotactile device's output is a fraction of its full scale and it has no angle, so
        its peak is given in percent and no energy is reported.
        """
        lines = [f"played {len(self) / self.rate:.3f} s ({len(self)} samples at {self.rate:g} Hz)"]
        if kind == "vibrotactile":
            lines += [
                f"peak output {self.peak_torque * 100:.1f}% of full scale",
                f"at full scale {self.time_saturated:.4f} s",
            ]
        else:
            lines += [
                f"peak torque {self.peak_torque * 1e3:.2f} mNm",
                f"saturated {self.time_saturated:.4f} s",
                f"energy injected by the device {self.energy_injected * 1e3:+.4g} mJ"
                + (" (active)" if self.energy_injected > 0 else " (passive)"),
            ]
        lines += [f"flag {f.describe()}" for f in self.flags] or ["no stability flags"]
        lines += [f"warning: {w}" for w in self.warnings]
        return lines

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


class Device(abc.ABC):
    """A device plugin: declares itself, opens, plays a program, reports telemetry."""

    @property
    @abc.abstractmethod
    def info(self) -> DeviceInfo:
        """What the device declares (rate, kind, limits)."""

    def open(self) -> None:  # noqa: B027 - devices without a connection need nothing here
        """Connect to the device (idempotent)."""

    def close(self) -> None:  # noqa: B027
        """Release the device (idempotent); the output ends at zero."""

    def __enter__(self) -> Device:
        self.open()
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    @abc.abstractmethod
    def play(
        self,
        program: Program,
        hand: Hand | None = None,
        progress: Progress | None = None,
        monitor: Monitor | None = None,
    ) -> Telemetry:
        """Play coefficient blocks (or a position program) and return what happened.

        `monitor`, if given, receives each piece of telemetry as the device reports it.
        """

    @classmethod
    def discover(cls) -> list[str]:
        """Describe each unit of this device type that is present (empty when none)."""
        return []


def device_names() -> list[str]:
    """Names of the registered device plugins."""
    return sorted(plugins.load_group(plugins.DEVICES))


def open_device(name: str = "sim", **options: Any) -> Device:
    """Find a device plugin by name, construct it with options, open it and return it."""
    cls = plugins.get(plugins.DEVICES, name)
    try:
        device = cls(**options)
    except TypeError as exc:
        if not options:
            raise
        raise DeviceError(f"the {name} device does not take those options ({exc})") from None
    device.open()
    return device
