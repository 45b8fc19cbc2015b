"""The scene updates only the clip items an edit touched, and shows the same as a fresh scene."""

from __future__ import annotations

from PySide6.QtCore import QPoint

from timeline import edits
from timeline.gui.clip_item import ClipItem
from timeline.gui.snapping import EdgeIndex, snap
from timeline.tiles import generator

from .helpers import clip_point, drag


def _many_clips(tracks: int = 4, per_track: int = 12):
    project = edits.new_project(templates=False)
    project, tile = edits.add_tile(project, generator("sine", 0.2, frequency=20))
    for i in range(tracks):
        project, track = edits.add_track(project, ("drive", "stiffness", "damping")[i % 3])
        for j in range(per_track):
            project, _ = edits.add_clip(project, track, tile, 0.5 * j + 0.05 * i)
    return project


def _shown(win) -> dict[str, tuple[float, float, float, str]]:
    """Clip id -> (x, y, width, track) as the items show them."""
    return {
        cid: (item.pos().x(), item.pos().y(), item.boundingRect().width(), item.track_id)
        for cid, item in win.view.scene().items_by_clip.items()
    }


def _fresh(win, qtbot) -> dict[str, tuple[float, float, float, str]]:
    """What a window opened on the current project shows (every item built from scratch)."""
    from timeline.gui.main_window import MainWindow

    other = MainWindow(win.doc.project)
    qtbot.addWidget(other)
    other.resize(win.size())
    other.view.lane_geometry.px_per_unit = win.view.lane_geometry.px_per_unit
    other.view.refresh()
    shown = _shown(other)
    other.player.close()
    other.autosaver.discard()
    return shown


def test_a_drag_updates_only_the_dragged_clips_item(window, qtbot, monkeypatch):
    window.doc.replace("many clips", _many_clips())
    window.view.refresh()
    project = window.doc.project
    moved = project.tracks[1].clips[3]
    updated = []
    original = ClipItem.update_from

    def counting(item, clip, *args):
        updated.append(clip.id)
        return original(item, clip, *args)

    monkeypatch.setattr(ClipItem, "update_from", counting)
    start = clip_point(window, moved.id)
    drag(window, start, start + QPoint(40, 0))
    after = window.doc.project.find_clip(moved.id)[1]
    assert after.start == moved.start + 40 / 200.0
    assert set(updated) == {moved.id}  # press (selection) and each drag step: that item only
    assert _shown(window) == _fresh(window, qtbot)


def test_undo_redo_move_across_tracks_and_delete_show_what_a_fresh_scene_shows(window, qtbot):
    window.doc.replace("many clips", _many_clips())
    project = window.doc.project
    a, b = project.tracks[0].clips[2].id, project.tracks[2].clips[5].id
    window.doc.apply("move", edits.move_clip, a, 3.3, project.tracks[3].id)
    window.doc.apply("remove", edits.remove_clips, [b])
    assert set(_shown(window)) == {c.id for t in window.doc.project.tracks for c in t.clips}
    assert _shown(window) == _fresh(window, qtbot)
    window.doc.undo()
    window.doc.undo()
    assert _shown(window) == _fresh(window, qtbot)
    window.doc.redo()
    window.view.zoom(1.5)
    assert _shown(window) == _fresh(window, qtbot)


def test_replacing_a_tile_redraws_the_clips_that_use_it(window):
    window.doc.replace("many clips", _many_clips(2, 3))
    project = window.doc.project
    tile_id = project.tracks[0].clips[0].tile_id
    window.doc.apply("tile", edits.replace_tile, tile_id, generator("square", 0.2, frequency=9))
    new_tile = window.doc.project.tile(tile_id)
    assert all(item.tile is new_tile for item in window.view.scene().items_by_clip.values())


def test_selection_marks_exactly_the_selected_items(window):
    window.doc.replace("many clips", _many_clips(3, 4))
    ids = [c.id for t in window.doc.project.tracks for c in t.clips]
    for chosen in ([ids[1]], [ids[1], ids[7]], [ids[11]], []):
        window.doc.select_clips(chosen)
        items = window.view.scene().items_by_clip
        assert {cid for cid, item in items.items() if item.selected} == set(chosen)


def _brute_nearest(project, value, exclude):
    edges = [0.0] + [
        e for t in project.tracks for c in t.clips if c.id not in exclude for e in (c.start, c.end)
    ]
    return min(edges, key=lambda e: abs(e - value))


def test_edge_index_finds_the_nearest_edge_a_walk_over_all_clips_finds():
    project = _many_clips(5, 20)
    index = EdgeIndex()
    ids = [c.id for t in project.tracks for c in t.clips]
    for k, value in enumerate([-1.0, 0.0, 0.26, 3.33, 4.71, 9.86, 12.0, 100.0]):
        dragged = [ids[(7 * k) % len(ids)], ids[(11 * k + 3) % len(ids)]]
        want = _brute_nearest(project, value, dragged)
        assert abs(index.nearest(project, value, dragged) - value) == abs(want - value)
        project = edits.move_clip(project, dragged[0], 0.013 * k + 1.0)
    assert snap(3.31, [index.nearest(project, 3.31)], 0.0, 0.05) == _brute_nearest(
        project, 3.31, []
    )


def _lanes(win) -> dict[int, list[tuple[str, float, float, tuple]]]:
    """Lane -> its clips as the clip layer holds them: id, start, end, covered span, in order."""
    return {
        lane: [
            (i.clip.id, float(s), float(e), i.covered)
            for i, s, e in zip(clips.items, clips.starts, clips.ends, strict=True)
        ]
        for lane, clips in win.view.scene().layer.lanes.items()
    }


def test_a_drag_over_other_clips_hatches_and_orders_them_as_a_fresh_scene(window, qtbot):
    """A drag along a track updates the dragged clip's item and the items it comes to cover or
    leaves, without going over the lane's clips again: the result is what a new window shows."""
    window.doc.replace("many clips", _many_clips(2, 8))
    window.view.refresh()
    moved = window.doc.project.tracks[0].clips[2]
    start = clip_point(window, moved.id)
    for end in (QPoint(70, 0), QPoint(120, 0), QPoint(-190, 0)):  # onto, past, back over
        drag(window, start, start + end, steps=6)
        start = clip_point(window, moved.id)
        from timeline.gui.main_window import MainWindow

        other = MainWindow(window.doc.project)
        qtbot.addWidget(other)
        other.view.lane_geometry.px_per_unit = window.view.lane_geometry.px_per_unit
        other.view.refresh()
        assert _lanes(window) == _lanes(other)
        assert any(covered for lane in _lanes(window).values() for *_, covered in lane) == (
            end.x() > 0
        )
        other.player.close()
        other.autosaver.discard()
