"""Snapping's edge index against a walk over every clip, with the lanes' arrays or without."""

import numpy as np

from timeline import edits
from timeline.gui.snapping import EdgeIndex
from timeline.tiles import generator


def _touching_clips():
    """Two tracks of 0.5 s clips that touch end to start, so most edges come twice."""
    project = edits.new_project(templates=False)
    project, tile = edits.add_tile(project, generator("sine", 0.5, frequency=5))
    for offset in (0.0, 0.25):
        project, track = edits.add_track(project, "drive")
        for k in range(6):
            project, _ = edits.add_clip(project, track, tile, offset + 0.5 * k)
    return project


def _brute(project, value, exclude):
    edges = [0.0] + [
        e for t in project.tracks for c in t.clips if c.id not in exclude for e in (c.start, c.end)
    ]
    return min(edges, key=lambda e: (abs(e - value), e))


def _lane_arrays(track):
    """What the scene's lane holds: starts and ends in start order, as arrays."""
    clips = sorted(track.clips, key=lambda c: c.start)
    return np.array([c.start for c in clips]), np.array([c.end for c in clips])


def test_the_lanes_arrays_and_shared_edges_of_excluded_clips_find_what_a_walk_finds():
    project = _touching_clips()
    ids = [c.id for t in project.tracks for c in t.clips]
    asked = []
    index = EdgeIndex(lambda track: asked.append(track.id) or _lane_arrays(track))
    for k, value in enumerate([0.49, 0.51, 1.0, 1.26, 2.74, 3.1, 9.0]):
        dragged = [ids[k], ids[k + 1], ids[-1 - k]]  # neighbours: an edge each shares
        got = index.nearest(project, value, dragged)
        assert abs(got - value) == abs(_brute(project, value, dragged) - value)
        project = edits.move_clip(project, ids[k], 0.37 * k + 0.1)
    assert asked  # the arrays were used, not the clips
    first = project.tracks[0]  # its lane out of step with it: its dragged clip's edges not there
    lying = EdgeIndex(lambda t: (np.array([5.0]), np.array([6.0])) if t is first else None)
    dragged = [first.clips[2].id]
    for value in (1.26, 1.49, 5.1):
        assert lying.nearest(project, value, dragged) == _brute(project, value, dragged)
