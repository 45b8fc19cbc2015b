"""`haptic-timeline devices`: the device plugins and what each one finds."""

from __future__ import annotations

import argparse
import warnings

from timeline import plugins
from timeline.plugins import discovery


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("devices", help="list the device plugins and the devices each one finds")
    p.set_defaults(func=run)


def describe_devices() -> list[str]:
    """One line per device plugin (and per unit found); a plugin that finds nothing says so,
    and why when a library it needs is missing."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        loaded = plugins.load_group(plugins.DEVICES)
    names = sorted(set(discovery.names(plugins.DEVICES)) | set(loaded))
    lines = []
    for name in names:
        if name not in loaded:
            why = next((str(w.message) for w in caught if f"{name!r}" in str(w.message)), "")
            lines.append(f"{name}: not available ({why or 'failed to load'})")
            continue
        try:
            found = list(loaded[name].discover())
        except Exception as exc:  # a plugin's search must not take the listing down
            lines.append(f"{name}: could not search ({exc})")
            continue
        if not found:
            why = loaded[name].missing()
            lines.append(f"{name}: nothing found" + (f" ({why})" if why else ""))
        lines += [f"{name}: {unit}" for unit in found]
    return lines


def run(args: argparse.Namespace) -> int:
    for line in describe_devices():
        print(line)
    return 0
