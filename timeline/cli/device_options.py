"""`--device-option KEY=VALUE` of `play` and `check`: the options given to a device plugin."""

from __future__ import annotations

from typing import Any

from timeline.errors import HapticTimelineError


def parse_option(text: str) -> tuple[str, Any]:
    """KEY=VALUE with VALUE read as an integer (0x.. too), a number, true/false, or text."""
    key, sep, value = text.partition("=")
    if not sep or not key.strip():
        raise HapticTimelineError(f"a device option is KEY=VALUE, not {text!r}")
    key, value = key.strip().replace("-", "_"), value.strip()
    if value.lower() in ("true", "yes", "on"):
        return key, True
    if value.lower() in ("false", "no", "off"):
        return key, False
    for convert in (lambda v: int(v, 0), float):
        try:
            return key, convert(value)
        except ValueError:
            pass
    return key, value


def device_options(texts: list[str]) -> dict[str, Any]:
    """The options of repeated --device-option flags (a key given twice: the last one)."""
    return dict(parse_option(text) for text in texts)
