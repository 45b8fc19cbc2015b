"""haptic-timeline: design haptic icons on a multitrack timeline.

The Python API the CLI and the editor use::

    from timeline import edits, generator, render, load, save
    p = edits.new_project()
    p, track = edits.add_track(p, "drive")
    p, tile = edits.add_tile(p, generator("sine", 0.5, frequency=175))
    p, clip = edits.add_clip(p, track, tile, start=0.0)
    layers = render(p)            # {"drive": float64 array in N*m at 10 kHz}
    save(p, "buzz.htl")
"""

from timeline import edits
from timeline.errors import EditError, HapticTimelineError, ProjectFileError, RenderError
from timeline.history import History
from timeline.mixer import Mixer, render, render_chunks
from timeline.model import Clip, Fade, Project, Track
from timeline.projectfile import load, save
from timeline.tiles import GeneratorTile, SampledTile, SplineTile, generator, spline

__all__ = [
    "Clip",
    "EditError",
    "Fade",
    "GeneratorTile",
    "HapticTimelineError",
    "History",
    "Mixer",
    "Project",
    "ProjectFileError",
    "RenderError",
    "SampledTile",
    "SplineTile",
    "Track",
    "edits",
    "generator",
    "load",
    "render",
    "render_chunks",
    "save",
    "spline",
]
