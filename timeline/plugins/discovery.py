"""Plugin discovery through entry points; timeline/ never imports a particular plugin."""

from __future__ import annotations

import importlib
import os
import re
import sys
import warnings
from collections.abc import Iterator
from dataclasses import dataclass
from functools import cache, reduce
from typing import Any

from timeline.errors import PluginError

TRACKS = "haptic_timeline.tracks"
IMPORTERS = "haptic_timeline.importers"
DEVICES = "haptic_timeline.devices"
BENCHMARKS = "haptic_timeline.benchmarks"  # modules with NAME, SUMMARY and run(quick, out)


_VALUE = re.compile(r"(?P<module>[\w.]+)\s*(:\s*(?P<attr>[\w.]+)\s*)?((?P<extras>\[.*\])\s*)?$")


@dataclass(frozen=True)
class Entry:
    """One entry point (what importlib.metadata.EntryPoint gives: name, value, group, load)."""

    name: str
    value: str
    group: str

    def load(self) -> Any:
        """The object the value names: "module" or "module:attr.attr"."""
        found = _VALUE.match(self.value)
        if found is None:
            raise ValueError(f"malformed entry point value {self.value!r}")
        module = importlib.import_module(found["module"])
        return reduce(getattr, filter(None, (found["attr"] or "").split(".")), module)


@cache
def _entry_points(group: str) -> tuple[Entry, ...]:
    """The group's entry points in name order (read once)."""
    return tuple(sorted((e for e in _table() if e.group == group), key=lambda e: e.name))


@cache
def _table() -> tuple[Entry, ...]:
    """Every entry point of the distributions installed in sys.path's folders, as
    importlib.metadata.entry_points() gives them there: each `.dist-info` or `.egg-info` folder's
    entry_points.txt in file order, the first distribution of a name on sys.path winning.

    Read here rather than by importlib.metadata, whose import (with the email package) cost the
    editor's launch 25-50 ms of CPU (docs/performance.md). What pip writes is read; a zip or an
    .egg on sys.path, which pip never installs, is not (importlib.metadata would look inside).
    """
    seen: set[str] = set()
    found: list[Entry] = []
    for root in sys.path:
        try:
            children = os.listdir(root or ".")
        except OSError:  # missing, or a file (a zip)
            continue
        for stem in _distributions(children):
            name = _normalized(stem)
            if name not in seen:
                seen.add(name)
                found += _parse(_read(os.path.join(root or ".", stem, "entry_points.txt")))
    return tuple(found)


def _distributions(children: list[str]) -> list[str]:
    """A folder's .dist-info and .egg-info entries, grouped by name as importlib.metadata's
    Lookup groups them (first appearance of each name, then each of its entries)."""
    groups: dict[str, list[str]] = {}
    for child in children:
        if child.lower().endswith((".dist-info", ".egg-info")):
            groups.setdefault(_normalized(child), []).append(child)
    return [child for members in groups.values() for child in members]


def _normalized(stem: str) -> str:
    """The distribution's name in a folder name ("Foo_Bar-1.0.dist-info" -> "foo_bar")."""
    name = stem.lower().rpartition(".")[0].partition("-")[0]
    return re.sub(r"[-_.]+", "_", name)


def _read(path: str) -> str:
    try:
        with open(path, encoding="utf-8") as file:
            return file.read()
    except OSError:  # no entry points, or not a folder
        return ""


def _parse(text: str) -> list[Entry]:
    """entry_points.txt: [group] headers and name = value lines; blank and # lines skipped."""
    entries: list[Entry] = []
    group = ""
    for line in map(str.strip, text.splitlines()):
        if not line or line.startswith("#"):
            continue
        if line.startswith("[") and line.endswith("]"):
            group = line.strip("[]")
            continue
        name, value = line.split("=", 1)
        entries.append(Entry(name.strip(), value.strip(), group))
    return entries


_loaded: dict[tuple[str, str], Any] = {}  # (group, name) -> plugin, or None if it failed
_FAILED = object()


def _load(group: str, ep: Entry) -> Any:
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
