"""Context tracks: the source sound beside a design, heard and seen but never felt.

A context kind (TrackKind.context, e.g. `audio`) holds material to design against. The mixer
leaves such tracks out of every haptic render and export; `render_sound` mixes them alone, with
their own gain, mute and solo, at a sound card's rate.
"""

from __future__ import annotations

import numpy as np

from timeline.model import Project
from timeline.plugins.track_kinds import track_kind
from timeline.rendering import mixer


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
