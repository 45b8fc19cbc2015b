"""Named actuator profiles and the `--actuator` spelling (`lra:F0[:Q]`, `voice-coil:LOW-HIGH`).

The named profiles are typical parts, not a particular datasheet: an LRA at 175 Hz with Q 10
(docs/references.md: -3 dB band ~17.5 Hz, ring-down ~18 ms) and a wideband voice coil (tactors
driven from an audio amplifier, Syntacts' approach). Peak accelerations are typical values at full
scale on a hand-held mass; replace them with your part's datasheet numbers.
"""

from __future__ import annotations

import re

from timeline.errors import DeviceError, HapticTimelineError
from timeline.plugins.device_protocol import Actuator

PROFILES = {
    "lra-175": Actuator("lra", "lra-175", resonance=175.0, q=10.0, peak_acceleration=1.5),
    "lra-235": Actuator("lra", "lra-235", resonance=235.0, q=12.0, peak_acceleration=1.5),
    "voice-coil": Actuator("voice-coil", "voice-coil", low=40.0, high=800.0, peak_acceleration=3.0),
}
_SPEC = re.compile(
    r"^(?:lra:(?P<f0>[\d.]+)(?::(?P<q>[\d.]+))?|voice-coil:(?P<lo>[\d.]+)-(?P<hi>[\d.]+))$"
)


def actuator(spec: str) -> Actuator:
    """A named profile, or `lra:F0[:Q]` / `voice-coil:LOW-HIGH` (Hz); one sentence if neither."""
    text = spec.strip().lower()
    if text in PROFILES:
        return PROFILES[text]
    match = _SPEC.match(text)
    try:
        if match and match.group("f0"):
            return Actuator("lra", text, resonance=float(match.group("f0")),
                            q=float(match.group("q") or 10.0))  # fmt: skip
        if match:
            return Actuator("voice-coil", text, low=float(match.group("lo")),
                            high=float(match.group("hi")))  # fmt: skip
    except ValueError:
        pass
    except DeviceError as exc:  # a value out of range
        raise HapticTimelineError(f"cannot use actuator {spec!r}: {exc}") from None
    raise HapticTimelineError(
        f"unknown actuator {spec!r} (choose {', '.join(PROFILES)}, lra:F0[:Q] or "
        "voice-coil:LOW-HIGH in Hz)"
    )
