"""Clips that render differently from their design at a rate: one sentence each.

The band-limiting itself (timeline.signal.band_limit) removes content at or above Nyquist; this
module reads a project's generator clips and says, for the message bar and the CLI, which ones it
touched and how.
"""

from __future__ import annotations

import numpy as np

from timeline.model import Project
from timeline.signal.band_limit import HIGHEST_FREQUENCY
from timeline.signal.harmonic_waves import HARMONIC
from timeline.tiles import GeneratorTile


def aliasing_notes(project: Project, rate: float | None = None) -> list[str]:
    """One sentence per generator clip that renders differently from its design at `rate`.

    Names clips whose content is removed above Nyquist, square/saw/triangle clips whose
    third harmonic (at 1/3 or 1/9 of the level) is removed by band-limiting, and noise clips
    whose bandwidth is above Nyquist (rendered band-limited to it).
    """
    rate = float(project.rate if rate is None else rate)
    nyquist = 0.5 * rate
    unit = "Hz" if project.axis == "time" else "cycles/rad"
    notes = []
    for track in project.tracks:
        for clip in track.clips:
            tile = project.tiles.get(clip.tile_id)
            if not isinstance(tile, GeneratorTile):
                continue
            params = dict(tile.params)
            speed = clip.stretch if clip.stretch_mode == "squeeze" else 1.0
            where = f"clip {clip.id} ({tile.name}) on track {track.name!r}"
            if tile.generator in HARMONIC:
                f = abs(params["frequency"]) / speed
                if f >= nyquist:
                    notes.append(
                        f"{where} at {f:g} {unit} is above the {nyquist:g} {unit} Nyquist "
                        "frequency of this rate and was removed"
                    )
                elif 3 * f >= nyquist:
                    notes.append(
                        f"{where}: the harmonics of its {f:g} {unit} {tile.generator} wave at or "
                        f"above {nyquist:g} {unit} were removed, so it renders close to a sine; "
                        "render at a higher rate to keep its shape"
                    )
                continue
            if tile.generator == "noise":
                bandwidth = params["bandwidth"] / speed
                if bandwidth > nyquist:
                    notes.append(
                        f"{where} has a {bandwidth:g} {unit} bandwidth, above the {nyquist:g} "
                        f"{unit} Nyquist frequency of this rate: it renders as noise band-limited "
                        f"to {nyquist:g} {unit}, at the level of its part below that"
                    )
                continue
            highest = HIGHEST_FREQUENCY.get(tile.generator)
            if highest is None:
                continue
            u = np.linspace(clip.source_in, clip.source_out, 257)
            top = np.max(np.broadcast_to(highest(u, tile.duration, params), u.shape)) / speed
            if top >= nyquist:
                notes.append(
                    f"{where} reaches {top:g} {unit}, above the {nyquist:g} {unit} Nyquist "
                    "frequency of this rate: that part was removed"
                )
    return notes
