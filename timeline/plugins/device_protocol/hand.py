"""The hand on the knob: hold, turn, push or let go, with a named grip (pinch, grasp)."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from timeline.errors import HandSpecError
from timeline.plugins.device_protocol.hand_models import DEFAULT_MODEL, HAND_MODELS

HAND_MODES = ("hold", "turn", "push", "free")
_HAND_RE = re.compile(
    r"^\s*(?:([a-z]+)\s*-\s*)?(hold|turn|push|free)\s*(?::\s*([^:\s]+)\s*)?$", re.IGNORECASE
)
NAMED = [f"{name}-" for name in HAND_MODELS if name != DEFAULT_MODEL]
DEFAULT_TURN_DEG_PER_S = 90.0
DEFAULT_PUSH_MNM = 20.0


@dataclass(frozen=True)
class Hand:
    """What the user's hand does: hold still, turn at a speed, push with a torque, or let go.

    `value` is degrees per second for `turn` and mNm for `push` (ignored otherwise). The grip
    (hold, turn) is a spring-damper between the knob and the hand's target angle; a pushing hand
    adds its inertia and a torque that ramps in over `push_ramp` seconds. A named `model` (see
    hand_models.py: pinch, grasp) sets the grip stiffness, damping and inertia from its source.
    """

    mode: str = "hold"
    value: float = 0.0
    grip_stiffness: float = 1.0  # N*m/rad
    grip_damping: float = 5e-3  # N*m*s/rad
    inertia: float = 2e-5  # kg*m^2 of fingers on the knob
    push_ramp: float = 0.01  # s
    model: str = DEFAULT_MODEL  # a name in HAND_MODELS; a named one sets the three values above

    def __post_init__(self) -> None:
        if self.mode not in HAND_MODES:
            raise HandSpecError(f"unknown hand {self.mode!r} (choose from {', '.join(HAND_MODES)})")
        named = HAND_MODELS.get(self.model)
        if named is None:
            raise HandSpecError(
                f"unknown hand model {self.model!r} (choose from {', '.join(HAND_MODELS)})"
            )
        if self.model != DEFAULT_MODEL:
            object.__setattr__(self, "grip_stiffness", named.stiffness)
            object.__setattr__(self, "grip_damping", named.damping)
            object.__setattr__(self, "inertia", named.inertia)
        for name in ("value", "grip_stiffness", "grip_damping", "inertia", "push_ramp"):
            if not math.isfinite(float(getattr(self, name))):
                raise HandSpecError(f"the hand's {name.replace('_', ' ')} must be a finite number")
        if min(self.grip_stiffness, self.grip_damping, self.inertia, self.push_ramp) < 0:
            raise HandSpecError("the hand's grip, inertia and push ramp cannot be negative")

    @classmethod
    def parse(cls, text: str) -> Hand:
        """Read `hold`, `free`, `turn[:DEG_PER_S]`, `push[:MNM]`, a model (`pinch`, `grasp`:
        holding) or a model and a mode joined by a dash (`pinch-turn:90`, `grasp-push:20`)."""
        spec = (text or "").strip()
        if spec.lower() in HAND_MODELS:
            return cls("hold", 0.0, model=spec.lower())
        match = _HAND_RE.match(spec)
        if not match:
            raise HandSpecError(
                f"cannot read hand {text!r} (use hold, free, turn:DEG_PER_S or push:MNM,"
                f" optionally after a named hand and a dash: {', '.join(NAMED)})"
            )
        model, mode, raw = (
            (match.group(1) or DEFAULT_MODEL).lower(),
            match.group(2).lower(),
            match.group(3),
        )
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
        return cls(mode, value, model=model)

    def __str__(self) -> str:
        action = self.mode if self.mode in ("hold", "free") else f"{self.mode}:{self.value:g}"
        if self.model == DEFAULT_MODEL:
            return action
        return self.model if self.mode == "hold" else f"{self.model}-{action}"

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
