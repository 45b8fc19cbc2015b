"""Variants outlive undo, redo and history jumps: only a variant's own deletion removes it."""

from __future__ import annotations

from timeline import edits
from timeline.files import projectfile


def saved_variants(win, tmp_path) -> dict[str, float]:
    """Save, reload, and give each variant's first clip start (what the variant holds)."""
    path = tmp_path / "design.htl"
    assert win.save_to(path)
    loaded = projectfile.load(path)
    return {v.name: v.tracks[0].clips[0].start for v in loaded.variants}


def test_every_variant_survives_undo_redo_and_jumps_across_saves(window, tmp_path):
    win, c1 = window, window.ids["c1"]
    win.save_variant()  # A: the clip at 0.5
    win.doc.apply("move clip", edits.move_clip, c1, 1.25)
    win.save_variant()  # B: the clip at 1.25
    win.doc.apply("move clip", edits.move_clip, c1, 2.0)
    win.save_variant()  # C: the clip at 2.0
    assert saved_variants(win, tmp_path) == {"A": 0.5, "B": 1.25, "C": 2.0}
    history = win.doc.history
    walk = [
        win.doc.undo,
        win.doc.undo,
        win.doc.redo,
        lambda: win.doc.go_to(0),  # before any variant was saved
        lambda: win.doc.go_to(len(history) - 1),
        lambda: win.doc.go_to(1),  # just after A was saved
        win.next_variant,  # a new step from the past: the redo steps are gone
        win.doc.undo,
        lambda: win.doc.go_to(0),
    ]
    for step in walk:
        step()
        assert saved_variants(win, tmp_path) == {"A": 0.5, "B": 1.25, "C": 2.0}, history.labels


def test_only_its_own_deletion_removes_a_variant(window, tmp_path):
    win, c1 = window, window.ids["c1"]
    win.save_variant()  # A
    win.doc.apply("move clip", edits.move_clip, c1, 1.5)
    win.save_variant()  # B, active
    win.delete_variant()
    assert saved_variants(win, tmp_path) == {"A": 0.5}
    win.doc.undo()  # the deletion undone
    assert saved_variants(win, tmp_path) == {"A": 0.5, "B": 1.5}
    win.doc.redo()  # and done again
    assert saved_variants(win, tmp_path) == {"A": 0.5}
    win.doc.go_to(0)  # jumping back before the deletion brings B back
    assert saved_variants(win, tmp_path) == {"A": 0.5, "B": 1.5}
    win.doc.go_to(len(win.doc.history) - 1)  # and forward past it deletes it again
    assert saved_variants(win, tmp_path) == {"A": 0.5}


def test_a_jump_that_adds_a_variant_to_the_saved_step_marks_the_project_unsaved(window, tmp_path):
    win = window
    assert win.save_to(tmp_path / "design.htl")  # saved with no variant
    win.save_variant()
    win.doc.undo()  # back at the saved step, with variant A carried
    assert [v.name for v in win.doc.project.variants] == ["A"]
    assert win.doc.modified
