"""Our fields in an OTIO file's metadata, read strictly: each value as what it means or a sentence.

OTIO metadata is free JSON, and other tools (or people) rewrite it: a flag may arrive as the text
"false", a number as "0.5" or "1e400". A flag is read as true or false from a boolean, 0 or 1, or
the words true/false/yes/no/on/off; a number from a number or a number's text, and it must be
finite. Anything else refuses the file with one sentence naming the field.
"""

from __future__ import annotations

import math
from typing import Any

from timeline.model import Fade
from timeline.plugins.file_formats import FormatError, TrackInfo

_TRUE = {"true", "yes", "on", "1"}
_FALSE = {"false", "no", "off", "0"}
NUMBERS = ("source_in", "source_out", "stretch", "loop_phase", "gain", "scale", "offset", "pivot")


def flag(value: Any, what: str) -> bool:
    """A yes/no field: a boolean, 0 or 1, or a word such as "false"."""
    if isinstance(value, bool):
        return value
    if isinstance(value, (int, float)) and value in (0, 1):
        return bool(value)
    if isinstance(value, str) and value.strip().lower() in _TRUE | _FALSE:
        return value.strip().lower() in _TRUE
    raise FormatError(f"{what} must be true or false, not {_shown(value)}")


def number(value: Any, what: str) -> float:
    """A finite number, given as a number or as its text."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        result = float(value)
    elif isinstance(value, str):
        try:
            result = float(value.strip())
        except ValueError:
            raise FormatError(f"{what} must be a number, not {_shown(value)}") from None
    else:
        raise FormatError(f"{what} must be a number, not {_shown(value)}")
    if not math.isfinite(result):
        raise FormatError(f"{what} must be a finite number, not {_shown(value)}")
    return result


def text(value: Any, what: str) -> str:
    if not isinstance(value, str):
        raise FormatError(f"{what} must be text, not {_shown(value)}")
    return value


def _shown(value: Any) -> str:
    shown = repr(value)
    return shown if len(shown) <= 40 else shown[:37] + "..."


def _field(meta: Any, key: str, what: str) -> Any:
    try:
        return meta[key]
    except (KeyError, TypeError, IndexError):
        raise FormatError(f"{what} has no {key.replace('_', ' ')}") from None


def track_info(meta: Any, name: str) -> TrackInfo:
    """A track's settings from its metadata."""
    what = f"a track's haptic settings in {name}"
    key = str(_field(meta, "track", what))
    label = text(_field(meta, "name", what), f"a track's name in {name}")
    return TrackInfo(
        key,
        label,
        text(_field(meta, "kind", what), f"the kind of track {label!r} in {name}"),
        number(_field(meta, "gain", what), f"the gain of track {label!r} in {name}"),
        flag(_field(meta, "mute", what), f"the mute of track {label!r} in {name}"),
        flag(_field(meta, "solo", what), f"the solo of track {label!r} in {name}"),
    )


def clip_fields(meta: Any, name: str) -> dict[str, Any]:
    """A clip's timeline.model.Clip fields (all but its id, tile and start) from its metadata."""
    what = f"a clip's haptic settings in {name}"
    out: dict[str, Any] = {
        k: number(_field(meta, k, what), f"a clip's {k.replace('_', ' ')} in {name}")
        for k in NUMBERS
    }
    out["stretch_mode"] = text(
        _field(meta, "stretch_mode", what), f"a clip's stretch mode in {name}"
    )
    out["reverse"] = flag(_field(meta, "reverse", what), f"a clip's reverse in {name}")
    for key in ("fade_in", "fade_out"):
        fade = _field(meta, key, what)
        label = f"a clip's {key.replace('_', ' ')} in {name}"
        out[key] = Fade(
            number(_field(fade, "length", label), f"{label}'s length"),
            text(_field(fade, "shape", label), f"{label}'s shape"),
        )
    return out


def start(meta: Any, name: str, axis: str) -> float:
    """A clip's start; never before 0 (where it would never play) but on the position axis."""
    at = number(
        _field(meta, "start", f"a clip's haptic settings in {name}"), f"a clip's start in {name}"
    )
    if axis != "position" and at < 0:
        raise FormatError(
            f"a clip in {name} starts at {at:g} s, before the timeline's start at 0, where it "
            "would never play"
        )
    return at
