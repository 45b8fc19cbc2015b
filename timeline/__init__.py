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

from importlib import import_module
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # what pyright and IDEs see; at run time each name loads on first use
    from timeline import edits
    from timeline.edits.history import History
    from timeline.errors import EditError, HapticTimelineError, ProjectFileError, RenderError
    from timeline.files.projectfile import load, save
    from timeline.model import Clip, Fade, Project, Track
    from timeline.rendering.mixer import Mixer, render, render_chunks
    from timeline.tiles import GeneratorTile, SampledTile, SplineTile, generator, spline

# Public names -> the module that defines them. They load on first use, so the command line's
# --help and verbs that need little do not pay for numpy, scipy and the mixer.
_EXPORTS = {
    "edits": "timeline.edits",
    "EditError": "timeline.errors",
    "HapticTimelineError": "timeline.errors",
    "ProjectFileError": "timeline.errors",
    "RenderError": "timeline.errors",
    "History": "timeline.edits.history",
    "Mixer": "timeline.rendering.mixer",
    "render": "timeline.rendering.mixer",
    "render_chunks": "timeline.rendering.mixer",
    "Clip": "timeline.model",
    "Fade": "timeline.model",
    "Project": "timeline.model",
    "Track": "timeline.model",
    "load": "timeline.files.projectfile",
    "save": "timeline.files.projectfile",
    "GeneratorTile": "timeline.tiles",
    "SampledTile": "timeline.tiles",
    "SplineTile": "timeline.tiles",
    "generator": "timeline.tiles",
    "spline": "timeline.tiles",
}


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'timeline' has no attribute {name!r}")
    value = import_module(module)
    if name != "edits":
        value = getattr(value, name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    """The public names, loaded or not (what an IDE or a notebook completes)."""
    return sorted(__all__)


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
