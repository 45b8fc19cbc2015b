"""Field checks for reading a project file: each malformed field is one sentence naming where.

A hostile or damaged file may hold a huge integer, null, an object or NaN where a number
belongs; these helpers turn every such case into a FieldError instead of an OverflowError,
TypeError or a NaN that travels on into the mixer or a device.
"""

from __future__ import annotations

import json
import math
from typing import Any

from timeline.errors import FieldError

MAX_ID = 2**62  # the project's id counter; anything larger was not written by an editor
_MISSING = object()


def refuse_constant(name: str) -> float:
    """json.loads parse_constant hook: NaN and Infinity are never in a saved project."""
    raise FieldError(f"it holds {name}, which is not a number a project can contain")


def obj(value: Any, where: str) -> dict:
    """The value as a JSON object, or FieldError."""
    if not isinstance(value, dict):
        raise FieldError(f"{where} should be an object")
    return value


def get(value: Any, key: str, kind: type, where: str) -> Any:
    """value[key], which must be of `kind` (str, list, dict or bool; never a bool for others)."""
    if type(value) is dict:  # the common case first: a value of exactly the wanted type
        item = value.get(key, _MISSING)
        if type(item) is kind and (kind is not str or item.isascii()):
            return item
    value = obj(value, where)
    if key not in value:
        raise FieldError(f"{where} has no {key!r}")
    item = value[key]
    if not isinstance(item, kind) or (kind is not bool and isinstance(item, bool)):
        raise FieldError(f"{where}.{key} should be {_NAMES[kind]}")
    if kind is str:
        try:
            item.encode("utf-8")
        except UnicodeEncodeError:  # "\ud800" in the JSON: no character, printed or saved
            raise FieldError(f"{where}.{key} is not text (it holds a lone surrogate)") from None
    return item


def as_number(item: Any, where: str) -> float:
    """A JSON number as a finite float; a huge integer, NaN or any non-number is refused."""
    if isinstance(item, bool) or not isinstance(item, (int, float)):
        raise FieldError(f"{where} should be a number, not {_describe(item)}")
    try:
        number = float(item)
    except OverflowError:
        raise FieldError(f"{where} is a number too large to use") from None
    if not math.isfinite(number):
        raise FieldError(f"{where} should be a finite number, not {number}")
    return number


def number(
    value: Any,
    key: str,
    where: str,
    default: float | None = None,
    *,
    positive: bool = False,
) -> float:
    """value[key] as a finite float (default if absent and a default is given)."""
    if type(value) is dict:  # the common case first: a finite float within range
        item = value.get(key, _MISSING)
        if type(item) is float and math.isfinite(item) and (item > 0 or not positive):
            return item
    value = obj(value, where)
    if key not in value and default is not None:
        return default
    if key not in value:
        raise FieldError(f"{where} has no {key!r}")
    result = as_number(value[key], f"{where}.{key}")
    if positive and result <= 0:
        raise FieldError(f"{where}.{key} should be above zero, not {result:g}")
    return result


def integer(value: Any, key: str, where: str, low: int, high: int) -> int:
    """value[key] as an int in [low, high]."""
    item = get(value, key, int, where)
    if not low <= item <= high:
        raise FieldError(f"{where}.{key} is {_short(item)}, outside {low}..{high}")
    return item


def flag(value: Any, key: str, where: str, default: bool = False) -> bool:
    """value[key] as a true/false flag (absent: default); a string or number is refused."""
    if key not in obj(value, where):
        return default
    return get(value, key, bool, where)


def text(value: Any, key: str, where: str, default: str) -> str:
    """value[key] as a string (absent: default)."""
    if key not in obj(value, where):
        return default
    item = get(value, key, str, where)
    if not item.isascii():
        try:
            item.encode("utf-8")
        except UnicodeEncodeError:  # "\ud800" in the JSON: no character, printed or saved
            raise FieldError(
                f"{where}.{key} is not valid text (it holds a lone surrogate)"
            ) from None
    return item


def json_safe(value: Any, where: str) -> Any:
    """Free-form content (metadata) that can be written back as strict JSON."""
    try:
        json.dumps(value, allow_nan=False)
    except (ValueError, TypeError):
        raise FieldError(f"{where} holds a value that is not finite JSON") from None
    return value


def _describe(item: Any) -> str:
    if item is None:
        return "null"
    return {bool: "true/false", str: "text", list: "a list", dict: "an object"}.get(
        type(item), type(item).__name__
    )


def _short(item: int) -> str:
    digits = str(item)
    return digits if len(digits) < 20 else f"a {len(digits)}-digit number"


_NAMES = {str: "text", list: "a list", dict: "an object", bool: "true or false", int: "an integer"}
