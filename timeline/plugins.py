"""Plugin discovery through entry points; timeline/ never imports a particular plugin."""

from __future__ import annotations

import warnings
from functools import cache
from typing import Any

from timeline.errors import PluginError

TRACKS = "haptic_timeline.tracks"
IMPORTERS = "haptic_timeline.importers"
DEVICES = "haptic_timeline.devices"


@cache
def load_group(group: str) -> dict[str, Any]:
    """Load every plugin of an entry-point group, skipping broken ones with a warning."""
    from importlib.metadata import entry_points  # 30 ms: only when a plugin is first needed

    found: dict[str, Any] = {}
    for ep in sorted(entry_points(group=group), key=lambda e: e.name):
        try:
            found[ep.name] = ep.load()
        except Exception as exc:  # a broken third-party plugin must not take the host down
            warnings.warn(f"plugin {ep.name!r} in {group} failed to load: {exc}", stacklevel=2)
    return found


def get(group: str, name: str) -> Any:
    """Return one plugin by name or raise PluginError naming the choices."""
    plugins = load_group(group)
    if name not in plugins:
        choices = ", ".join(sorted(plugins)) or "none"
        raise PluginError(
            f"unknown {group.rsplit('.', 1)[-1][:-1]} {name!r} (choose from {choices})"
        )
    return plugins[name]
