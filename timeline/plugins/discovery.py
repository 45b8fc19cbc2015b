"""Plugin discovery through entry points; timeline/ never imports a particular plugin."""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from functools import cache
from typing import Any

from timeline.errors import PluginError

TRACKS = "haptic_timeline.tracks"
IMPORTERS = "haptic_timeline.importers"
DEVICES = "haptic_timeline.devices"
BENCHMARKS = "haptic_timeline.benchmarks"  # modules with NAME, SUMMARY and run(quick, out)


@cache
def _entry_points(group: str) -> tuple:
    """The group's entry points in name order (read once)."""
    from importlib.metadata import entry_points  # 30 ms: only when a plugin is first needed

    return tuple(sorted(entry_points(group=group), key=lambda e: e.name))


_loaded: dict[tuple[str, str], Any] = {}  # (group, name) -> plugin, or None if it failed
_FAILED = object()


def _load(group: str, ep: Any) -> Any:
    """One plugin, loaded once; a broken one warns once and gives _FAILED."""
    key = (group, ep.name)
    if key not in _loaded:
        try:
            _loaded[key] = ep.load()
        except Exception as exc:  # a broken third-party plugin must not take the host down
            warnings.warn(f"plugin {ep.name!r} in {group} failed to load: {exc}", stacklevel=3)
            _loaded[key] = _FAILED
    return _loaded[key]


def iter_group(group: str, first: str = "") -> Iterator[tuple[str, Any]]:
    """(name, plugin) in name order (the one named `first`, if any, before the rest), each
    loaded only when the iteration reaches it.

    A caller that stops at the first plugin it wants (the writer for an extension) leaves the
    rest, and the libraries they import, unloaded.
    """
    for ep in sorted(_entry_points(group), key=lambda e: e.name != first):
        plugin = _load(group, ep)
        if plugin is not _FAILED:
            yield ep.name, plugin


def names(group: str) -> dict[str, str]:
    """The group's plugin names -> their entry point values ("module" or "module:attr"), nothing
    loaded."""
    return {ep.name: ep.value for ep in _entry_points(group)}


def load_group(group: str) -> dict[str, Any]:
    """Load every plugin of an entry-point group, skipping broken ones with a warning."""
    return dict(iter_group(group))


def get(group: str, name: str) -> Any:
    """Return one plugin by name (loading only it) or raise PluginError naming the choices."""
    for ep in _entry_points(group):
        if ep.name == name:
            plugin = _load(group, ep)
            if plugin is not _FAILED:
                return plugin
    choices = ", ".join(sorted(load_group(group))) or "none"
    raise PluginError(f"unknown {group.rsplit('.', 1)[-1][:-1]} {name!r} (choose from {choices})")
