"""Exact edits of a tile's parameters: a generator's values and any tile's length (Qt-free).

Changing a length carries the clips that play the whole tile with it, so a clip of a 1 s sine
becomes a clip of the 2 s sine; clips that play a part keep that part when it still exists.
A tile in the Templates tab is never edited: `editable` puts a copy in Scratch first.
"""

from __future__ import annotations

import math
from dataclasses import replace

from timeline import edits
from timeline.edits.naming import unique_tile_name
from timeline.errors import EditError
from timeline.model import Project
from timeline.signal.generators import GENERATORS
from timeline.tiles import GeneratorTile, SampledTile, SplineTile, Tile

_EDGE = 1e-9


def set_param(project: Project, tile_id: str, name: str, value: float) -> Project:
    """Set one parameter of a generator tile."""
    tile = project.tile(tile_id)
    if not isinstance(tile, GeneratorTile):
        raise EditError(f"tile {tile.name!r} is not a generator, so it has no {name}")
    if name not in dict(tile.params):
        raise EditError(f"generator {tile.generator!r} has no parameter {name!r}")
    params = tuple((k, float(value) if k == name else v) for k, v in tile.params)
    if not math.isfinite(float(value)):
        raise EditError(f"{name} must be a finite number, not {value!r}")
    try:  # the tile refuses what its generator cannot render (GeneratorSpec.check)
        new = GeneratorTile(tile.generator, tile.duration, params, tile.name)
        new.evaluate(_probe(new))
    except (EditError, ValueError, ZeroDivisionError) as exc:
        raise EditError(f"{name} = {value:g} does not make a {tile.generator}: {exc}") from None
    project = edits.replace_tile(project, tile_id, new)
    natural = GENERATORS[tile.generator].length
    if natural is None:
        return project
    return set_length(project, tile_id, natural(dict(new.params)))  # its clips follow


def set_length(project: Project, tile_id: str, length: float) -> Project:
    """Give a tile a new length; clips that played all of it play all of the new one."""
    length = float(length)
    if not (math.isfinite(length) and length > 0):
        raise EditError(f"a tile's length must be a positive number, not {length:g}")
    tile = project.tile(tile_id)
    natural_length = GENERATORS[tile.generator].length if isinstance(tile, GeneratorTile) else None
    if isinstance(tile, GeneratorTile) and natural_length is not None:
        natural = natural_length(dict(tile.params))
        if abs(length - natural) > _EDGE * max(1.0, natural):
            raise EditError(
                f"a {tile.generator} lasts {natural:.6g} s, as its parameters say; "
                "change those instead"
            )
    old = tile.duration
    new = _with_length(tile, length)
    tracks = []
    for track in project.tracks:
        clips = []
        for c in track.clips:
            if c.tile_id == tile_id and c.source_in <= _EDGE and c.source_out >= old * (1 - _EDGE):
                c = replace(c, source_out=length)
                over = c.fade_in.length + c.fade_out.length - c.duration
                if over > 0:
                    scale = c.duration / (c.fade_in.length + c.fade_out.length)
                    c = replace(
                        c,
                        fade_in=replace(c.fade_in, length=c.fade_in.length * scale),
                        fade_out=replace(c.fade_out, length=c.fade_out.length * scale),
                    )
            clips.append(c)
        tracks.append(replace(track, clips=tuple(clips)))
    return edits.replace_tile(replace(project, tracks=tuple(tracks)), tile_id, new)


def editable(project: Project, tile_id: str, clip_ids: list[str]) -> tuple[Project, str]:
    """The tile to edit: itself, or for a template a copy in Scratch that the clips now play."""
    try:
        templates = project.tab("Templates").tile_ids
    except EditError:
        templates = ()
    if tile_id not in templates:
        return project, tile_id
    tile = project.tile(tile_id)
    name = unique_tile_name(project, f"{tile.name} copy")
    project, copy = edits.add_tile(project, tile.with_name(name), "Scratch")
    chosen = set(clip_ids)
    tracks = tuple(
        replace(
            t,
            clips=tuple(
                replace(c, tile_id=copy) if c.id in chosen and c.tile_id == tile_id else c
                for c in t.clips
            ),
        )
        for t in project.tracks
    )
    return replace(project, tracks=tracks), copy


def _with_length(tile: Tile, length: float) -> Tile:
    if isinstance(tile, GeneratorTile):
        return GeneratorTile(tile.generator, length, tile.params, tile.name)
    if isinstance(tile, SplineTile):
        factor = length / tile.duration
        points = tuple((t * factor, v) for t, v in tile.points)
        return SplineTile(points, length, tile.method, tile.name)
    if isinstance(tile, SampledTile):
        raise EditError("a recording's length is its samples'; trim or stretch its clips instead")
    raise EditError(f"tile {tile.name!r} has no length to set")


def _probe(tile: GeneratorTile):
    import numpy as np

    return np.linspace(0.0, tile.duration, 5)
