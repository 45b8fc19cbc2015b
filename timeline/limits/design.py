"""A design as the checks see it: the torque-law terms sampled along the project's axis."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from timeline.model import Project
from timeline.rendering.mixer import grid_length, render
from timeline.rendering.playback import layer_terms


@dataclass(frozen=True, eq=False)
class Sampled:
    """Terms d, k, b, m (those present) on a grid start + i/rate of the project's axis."""

    terms: dict[str, np.ndarray]
    names: dict[str, str]  # term -> kind id(s)
    rate: float
    start: float
    axis: str

    @property
    def length(self) -> int:
        return next((v.size for v in self.terms.values()), 0)

    def position(self, index: int) -> float:
        return self.start + index / self.rate


def sample(project: Project, rate: float | None = None, quality: str = "normal") -> Sampled:
    """Render a project's terms at a rate (time: the device's; position: the project's)."""
    rate = project.rate if rate is None or project.axis == "position" else float(rate)
    clips = [c for t in project.tracks for c in t.clips]
    start = min(0.0, min((c.start for c in clips), default=0.0))
    stop = project.duration
    if stop <= start:
        return Sampled({}, {}, rate, start, project.axis)
    sums, names = layer_terms(render(project, start, stop, rate, quality))
    n = grid_length(start, stop, rate)
    return Sampled({k: v[:n] for k, v in sums.items()}, names, rate, start, project.axis)


def variant_project(project: Project, name: str) -> Project:
    """The project as a saved variant left it."""
    v = project.variant(name)
    return replace(project, tracks=v.tracks, tiles=v.tiles)
