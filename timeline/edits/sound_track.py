"""The source sound beside a design: a mono sound placed on an audio (context) track.

Context tracks are heard and seen but never felt: timeline.rendering.source_sound mixes them
alone; the haptic render and every export leave them out.
"""

from __future__ import annotations

import numpy as np

from timeline import edits
from timeline.errors import EditError
from timeline.model import Project
from timeline.plugins.track_kinds import track_kind
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
