"""MPEG-I haptics interchange format (ISO/IEC 23090-31 .hjif): vibration designs and force layers.

Reading (module hjif_read) turns each vibration or force channel of the file into tracks: its
vectorial and transient bands into one vibration design (envelopes and emphasis, as .haptic and
AHAP imports place them), its curve bands into sampled force layers on a drive track. Writing
(module hjif_write) takes the sounding drive tracks: vibration designs as a Vibrotactile
perception, the other drive clips as a Force perception's curve. Bounds of the round trips are in
docs/formats.md ("MPEG-I haptics").
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from importers import _vibration as vib
from importers.hjif_read import CURVE_RATE, ChannelContent, read_channels
from importers.hjif_write import document
from timeline.edits.vibration import (
    DRIVE,
    EMPHASIS_TRACK,
    VibrationDesign,
    design_placements,
    emphasis_tile,
)
from timeline.errors import EditError
from timeline.model import Project
from timeline.plugins.file_formats import FormatError, Imported, Placement, Progress, TrackInfo
from timeline.tiles import SampledTile, VibrationTile


def _design(channel: ChannelContent) -> VibrationDesign:
    amplitude = channel.amplitude if len(channel.amplitude) >= 2 else []
    return VibrationDesign(
        tuple(amplitude), tuple(channel.frequency), tuple(channel.emphasis), channel.duration
    )


def _convention(channel: ChannelContent) -> str:
    return "linear" if channel.linear else "sqrt"


def placements(channels: list[ChannelContent], name: str, source: str, notes: list[str]):
    """The channels as placements: one design alone as .haptic imports place it; otherwise a
    drive track per design (with its emphasis track) and per force channel."""
    designs = [c for c in channels if c.has_design]
    forces = [c for c in channels if c.curves]
    if len(designs) == 1 and not forces:
        only = designs[0]
        return design_placements(_design(only), name, source, _convention(only), tuple(notes))
    placed: list[Placement] = []
    tracks: list[TrackInfo] = []
    for k, c in enumerate(designs):
        key, accents = f"design {k + 1}", f"emphasis {k + 1}"
        design = _design(c)
        envelopes = VibrationDesign(design.amplitude, design.frequency, (), design.duration)
        tracks.append(TrackInfo(key, c.name, DRIVE))
        placed.append(
            Placement(VibrationTile(envelopes, name, source, _convention(c)), 0.0, DRIVE, key)
        )
        if design.emphasis:
            tracks.append(TrackInfo(accents, EMPHASIS_TRACK, DRIVE))
            placed += [Placement(emphasis_tile(e), e.time, DRIVE, accents) for e in design.emphasis]
    for k, c in enumerate(forces):
        key = f"force {k + 1}"
        tracks.append(TrackInfo(key, f"{c.name} (force)", DRIVE))
        for start, samples in c.curves:
            tile = SampledTile(samples, CURVE_RATE, f"{name} force", source)
            placed.append(Placement(tile, start, DRIVE, key))
    return Imported(tuple(placed), tuple(tracks), tuple(notes))


class HjifFormat:
    """MPEG-I haptics .hjif: vibrotactile designs and force curves, read and written."""

    name = "hjif"
    extensions = (".hjif",)
    reads = "design"
    writes = "project"
    options: tuple[str, ...] = ()

    def read(self, path: Path, *, progress: Progress | None = None, **options: Any) -> Imported:
        """The file's vibration and force channels as clips on drive tracks."""
        path = Path(path)
        channels, notes = read_channels(path)
        try:
            result = placements(channels, path.stem, str(path), notes)
        except EditError as exc:  # a value the design or a tile refuses
            raise FormatError(f"{path.name}: {exc}") from None
        if progress is not None:
            progress(1.0)
        return result

    def write(self, source: Project, path: Path, rate: float | None = None, **options: Any) -> None:
        """Write the project's sounding drive tracks as an .hjif file."""
        title = Path(options.get("target") or path).stem
        vib.write_json(document(source, rate, title), path)


FORMAT = HjifFormat()
