"""A summary of a project: tracks, clips, duration, layers and variants."""

from __future__ import annotations

from typing import Any

from timeline.model import Project
from timeline.plugins.track_kinds import track_kind


def summary(project: Project) -> dict[str, Any]:
    """A JSON-ready description of the project."""
    return {
        "axis": project.axis,
        "unit": project.unit,
        "rate": project.rate,
        "duration": project.duration,
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
                        "start": c.start,
                        "end": c.end,
                    }
                    for c in t.clips
                ],
            }
            for t in project.tracks
        ],
        "tiles": len(project.tiles),
        "palette": {tab.name: len(tab.tile_ids) for tab in project.palette},
        "variants": [v.name for v in project.variants],
        "active_variant": project.active_variant,
        "metadata": dict(project.metadata),
    }


def describe(project: Project) -> str:
    """The summary as text for a person."""
    s = summary(project)
    lines = [
        f"{s['axis']} axis, {s['rate']:g} samples/{s['unit']}, "
        f"duration {s['duration']:.6g} {s['unit']}",
        f"layers: {', '.join(s['layers']) or 'none'}",
    ]
    for t in s["tracks"]:
        flags = "".join([" [mute]" if t["mute"] else "", " [solo]" if t["solo"] else ""])
        lines.append(
            f"track {t['name']} ({t['kind']}, {t['unit']}, gain {t['gain']:g}){flags}: "
            f"{len(t['clips'])} clip(s)"
        )
        for c in t["clips"]:
            lines.append(f"  {c['id']}: {c['tile']} {c['start']:.6g} to {c['end']:.6g}")
    lines.append(f"variants: {', '.join(s['variants']) or 'none'}")
    return "\n".join(lines)
