"""A summary of a project: tracks, clips, duration, markers, layers and variants.

Places and lengths on the axis are given as a designer reads them: seconds, or degrees on a
position project (radians inside); `unit` names which. The JSON rate is in samples per second
or per radian (`rate_unit`), the unit files and firmware tables use; the text says it per degree
on a position project, as `--rate` takes it.
"""

from __future__ import annotations

from typing import Any

from timeline.edits.naming import display_unit, displayed
from timeline.model import Project
from timeline.plugins.track_kinds import track_kind


def summary(project: Project) -> dict[str, Any]:
    """A JSON-ready description of the project."""
    axis = project.axis

    def shown(x: float) -> float:
        return displayed(x, axis)

    loop = project.loop
    return {
        "axis": axis,
        "unit": display_unit(axis),
        "rate": project.rate,
        "rate_unit": f"samples/{project.unit}",
        "duration": shown(project.duration),
        "layers": sorted({t.kind for t in project.tracks if t.clips}),
        "tracks": [
            {
                "id": t.id,
                "name": t.name,
                "kind": t.kind,
                "unit": track_kind(t.kind).si_unit,
                "gain": t.gain,
                "mute": t.mute,
                "solo": t.solo,
                "clips": [
                    {
                        "id": c.id,
                        "tile": project.tiles[c.tile_id].name,
                        "start": shown(c.start),
                        "end": shown(c.end),
                        "length": shown(c.duration),
                    }
                    for c in t.clips
                ],
            }
            for t in project.tracks
        ],
        "markers": [{"name": m.name, "at": shown(m.at)} for m in project.markers],
        "loop": None if loop is None else [shown(loop.start), shown(loop.stop)],
        "tiles": len(project.tiles),
        "palette": {tab.name: len(tab.tile_ids) for tab in project.palette},
        "variants": [v.name for v in project.variants],
        "active_variant": project.active_variant,
        "metadata": dict(project.metadata),
    }


def describe(project: Project) -> str:
    """The summary as text for a person."""
    s = summary(project)
    unit = s["unit"]
    rate = f"{s['rate']:g} {s['rate_unit']}"
    if s["axis"] == "position":  # per degree, as --rate takes it; the files' own unit after
        rate = f"{s['rate'] / displayed(1.0, 'position'):.6g} samples/deg ({rate})"
    lines = [
        f"{s['axis']} axis, {rate}, duration {s['duration']:.6g} {unit}",
        f"layers: {', '.join(s['layers']) or 'none'}",
    ]
    for t in s["tracks"]:
        flags = "".join([" [mute]" if t["mute"] else "", " [solo]" if t["solo"] else ""])
        lines.append(
            f"track {t['name']} ({t['kind']}, {t['unit']}, gain {t['gain']:g}){flags}: "
            f"{len(t['clips'])} clip(s)"
        )
        for c in t["clips"]:
            lines.append(
                f"  {c['id']}: {c['tile']} {c['start']:.6g} to {c['end']:.6g} {unit} "
                f"({c['length']:.6g} {unit})"
            )
    if s["markers"]:
        lines.append(
            "markers: " + ", ".join(f"{m['name']} {m['at']:.6g} {unit}" for m in s["markers"])
        )
    if s["loop"]:
        lines.append(f"loop: {s['loop'][0]:.6g} to {s['loop'][1]:.6g} {unit}")
    lines.append(f"variants: {', '.join(s['variants']) or 'none'}")
    return "\n".join(lines)
