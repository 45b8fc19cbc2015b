"""Context tracks: the source sound beside a design, heard and seen but never felt.

A context kind (TrackKind.context, e.g. `audio`) holds material to design against. The mixer
leaves such tracks out of every haptic render and export; `render_sound` mixes them alone, with
their own gain, mute and solo, at a sound card's rate.
"""

from __future__ import annotations

import numpy as np

from timeline import edits, mixer
from timeline.errors import EditError
from timeline.kinds import track_kind
from timeline.model import Project
from timeline.tiles import SampledTile

AUDIO = "audio"


def add_sound(
    project: Project,
    samples: np.ndarray,
    rate: float,
    *,
    name: str = "sound",
    source: str = "",
    at: float = 0.0,
    track_id: str | None = None,
) -> tuple[Project, str]:
    """Put a mono sound on an audio track (a new one unless `track_id`); returns the clip id."""
    if track_id is None:
        project, track_id = edits.add_track(project, AUDIO)
    elif not track_kind(project.track(track_id).kind).context:
        raise EditError("a sound for reference goes on an audio (context) track")
    project, tile_id = edits.add_tile(project, SampledTile(samples, rate, name, source))
    return edits.add_clip(project, track_id, tile_id, at)


def has_sound(project: Project) -> bool:
    """Whether any sounding context track has clips."""
    return any(t.clips and track_kind(t.kind).context for t in mixer.active_tracks(project))


def render_sound(
    project: Project, start: float, stop: float, rate: float, quality: str = "normal"
) -> np.ndarray | None:
    """The context tracks mixed on [start, stop) at `rate` (None if none sounds)."""
    layers = mixer.render(project, start, stop, rate, quality, context=True)
    if not layers:
        return None
    return np.sum([np.asarray(v, dtype=np.float64) for v in layers.values()], axis=0)
