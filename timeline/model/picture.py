"""A picture of a project as SVG text: what a notebook shows for `Project._repr_svg_`.

One lane per track (its name and kind at the left), each clip a rectangle at its start and length
on a shared axis, labelled with its tile's name; tracks that do not sound (muted, or not soloed
while another track is) are greyed. Pure string building from the model: nothing is rendered, so
a clip is drawn as its extent, not its shape.

A big project stays quick to draw: past MAX_CLIPS clips a lane's clips are merged where they
touch at the picture's resolution (no names), past MAX_TRACKS tracks the rest are left out, and
the picture says so.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from timeline.model.project import Clip, Project, Track

WIDTH = 720  # px
LEFT = 150  # px: the column of track names
RIGHT = 16  # px
PLOT = WIDTH - LEFT - RIGHT  # px: the width of the project's duration
TOP = 24  # px: the axis
LANE = 30  # px: one track
FOOT = 20  # px: the note under the lanes
MAX_CLIPS = 1_000  # each drawn and named up to this many; above, merged per lane
MAX_TRACKS = 40
CHAR = 6.2  # px: a character's width at 11 px, for fitting names into clips
COLOURS = ("#4c78a8", "#f58518", "#54a24b", "#e45756", "#72b7b2", "#b279a2", "#9d755d")
SILENT = "#b8b8b8"


def project_svg(project: Project) -> str:
    """The project's timeline as an SVG document (WIDTH px wide)."""
    span = project.duration if project.duration > 0 else 1.0
    scale = PLOT / span
    tracks = project.tracks[:MAX_TRACKS]
    clips = sum(len(t.clips) for t in project.tracks)
    merged = clips > MAX_CLIPS
    notes = []
    if merged:
        notes.append(f"{clips:,} clips: each lane's clips merged where they touch, no names")
    if len(project.tracks) > MAX_TRACKS:
        notes.append(f"{len(project.tracks) - MAX_TRACKS} more tracks not drawn")
    if not project.tracks:
        notes.append("no tracks")
    height = TOP + LANE * len(tracks) + (FOOT if notes else 4)
    soloed = any(t.solo for t in project.tracks)
    kinds = list(dict.fromkeys(t.kind for t in project.tracks))
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{height}" '
        f'viewBox="0 0 {WIDTH} {height}" font-family="sans-serif" font-size="11">',
        f'<rect width="{WIDTH}" height="{height}" fill="white"/>',
    ]
    silent = [t.mute or (soloed and not t.solo) for t in tracks]
    for row, track in enumerate(tracks):
        out += _lane(track, TOP + row * LANE, silent[row])
    out += _axis(span, scale, project.unit, TOP + LANE * len(tracks))
    for row, track in enumerate(tracks):
        colour = SILENT if silent[row] else COLOURS[kinds.index(track.kind) % len(COLOURS)]
        out += _clips(project, track, TOP + row * LANE, scale, colour, merged)
    if notes:
        out.append(
            f'<text x="{LEFT}" y="{height - 6}" fill="#666">{escape("; ".join(notes))}</text>'
        )
    out.append("</svg>")
    return "\n".join(out)


def _axis(span: float, scale: float, unit: str, bottom: int) -> list[str]:
    """Ticks at round positions along the top, with faint lines down through the lanes."""
    step = _tick_step(span)
    out = []
    for i in range(int(span / step + 1e-9) + 1):
        x = LEFT + i * step * scale
        label = f"{i * step:.10g}" + (f" {unit}" if i == 0 else "")
        out.append(
            f'<line x1="{x:.2f}" y1="{TOP - 4}" x2="{x:.2f}" y2="{bottom}" stroke="#e4e4e4"/>'
        )
        out.append(
            f'<text x="{x:.2f}" y="{TOP - 8}" text-anchor="middle" fill="#666">{label}</text>'
        )
    return out


def _tick_step(span: float) -> float:
    """A 1, 2 or 5 times a power of ten that puts about six ticks on the span."""
    power = 10.0 ** math.floor(math.log10(span / 6))
    return next(m * power for m in (1, 2, 5, 10) if span / (m * power) <= 7)


def _lane(track: Track, y: int, silent: bool) -> list[str]:
    """A track's background, name and kind."""
    text = "#999" if silent else "#222"
    kind = track.kind + (" · muted" if track.mute else " · not soloed" if silent else "")
    return [
        f'<rect class="lane" x="0" y="{y}" width="{WIDTH}" height="{LANE}" fill="#f6f6f6" '
        f'stroke="white"/>',
        f'<text x="6" y="{y + 13}" fill="{text}" font-weight="bold">'
        f"{escape(_fit(track.name, LEFT - 10))}</text>",
        f'<text x="6" y="{y + 25}" fill="#888" font-size="9">'
        f"{escape(_fit(kind, LEFT - 10))}</text>",
    ]


def _clips(
    project: Project, track: Track, y: int, scale: float, colour: str, merged: bool
) -> list[str]:
    """A track's clips: each named, or merged runs of them."""
    if merged:
        spans = _merged_spans(track.clips, scale)
        return [_rect("clips", x0, x1 - x0, y, colour, f"{n} clips") for x0, x1, n in spans]
    out = []
    for clip in track.clips:
        x, width = LEFT + clip.start * scale, clip.duration * scale
        tile = project.tiles.get(clip.tile_id)
        name = clip.tile_id if tile is None else tile.name
        out.append(_rect("clip", x, width, y, colour, name))
        label = _fit(name, width - 6)
        if label:
            out.append(
                f'<text x="{x + 3:.2f}" y="{y + LANE / 2 + 4}" fill="white">{escape(label)}</text>'
            )
    return out


def _rect(cls: str, x: float, width: float, y: int, colour: str, title: str) -> str:
    return (
        f'<rect class="{cls}" x="{x:.2f}" y="{y + 3}" width="{width:.2f}" height="{LANE - 6}" '
        f'rx="2" fill="{colour}" stroke="white" stroke-width="0.5"><title>{escape(title)}</title>'
        "</rect>"
    )


def _merged_spans(clips: tuple[Clip, ...], scale: float) -> list[tuple[float, float, int]]:
    """(x0, x1, clip count) of runs of clips less than a pixel apart, in start order."""
    spans: list[tuple[float, float, int]] = []
    for clip in sorted(clips, key=lambda c: c.start):
        x0, x1 = LEFT + clip.start * scale, LEFT + clip.end * scale
        if spans and x0 <= spans[-1][1] + 1.0:
            a, b, n = spans[-1]
            spans[-1] = (a, max(b, x1), n + 1)
        else:
            spans.append((x0, x1, 1))
    return spans


def _fit(text: str, width: float) -> str:
    """The text, cut with an ellipsis to fit the width; empty if not even two characters fit."""
    chars = int(width / CHAR)
    if len(text) <= chars:
        return text
    return text[: chars - 1] + "…" if chars >= 2 else ""


def escape(text: str) -> str:
    """Text safe inside an SVG element: &, < and > as entities (what xml.sax.saxutils.escape
    does; importing it pulls in urllib and http, a tenth of the editor's launch)."""
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
