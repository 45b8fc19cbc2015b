"""The .htl file: exact round trips, atomic saves, and one clear error for bad files."""

import base64
import json
import os
import zlib

import numpy as np
import pytest

from timeline import edits
from timeline.errors import ProjectFileError
from timeline.files import media, projectfile
from timeline.tiles import SampledTile, spline

from .helpers import one_clip


def rich_project():
    data = np.random.default_rng(3).normal(size=5000) * 1e-7
    data[0], data[1] = np.nextafter(0.0, 1.0), -np.pi  # a subnormal and an irrational survive
    p, clip = one_clip(SampledTile(data, 44_100.0, "rec", "rec.wav"), start=0.123456789)
    p = edits.set_fade(p, clip, "in", 0.01, "equal-power")
    p, t = edits.add_track(p, "damping", gain=0.3)
    p, tile = edits.add_tile(p, spline([(0, 1), (0.5, -2), (1, 0.1)], 1.2, "pchip"))
    p, c2 = edits.add_clip(p, t, tile, 1 / 3)
    p = edits.scale_clip(edits.stretch_clip(p, c2, 1.7, "repeat"), c2, 2.5, 0.1)
    p = edits.add_tab(p, "Mine")
    p = edits.place_tile(p, tile, "Mine")
    p = edits.save_variant(p, "A")
    return edits.reverse_clip(p, clip)


def test_round_trip_is_exact_and_samples_are_bit_identical(tmp_path):
    p = rich_project()
    path = tmp_path / "x.htl"
    projectfile.save(p, path)
    q = projectfile.load(path)
    assert q == p
    a = next(t for t in p.tiles.values() if isinstance(t, SampledTile))
    b = next(t for t in q.tiles.values() if isinstance(t, SampledTile))
    assert a.data.tobytes() == b.data.tobytes()
    projectfile.save(q, tmp_path / "y.htl")
    assert (tmp_path / "y.htl").read_bytes() == path.read_bytes()


def test_file_is_readable_json_with_a_schema_version(tmp_path):
    projectfile.save(rich_project(), tmp_path / "x.htl")
    text, _ = (tmp_path / "x.htl").read_bytes().split(b"\n" + media.SEPARATOR)  # then samples
    doc = json.loads(text)
    assert doc["format"] == "haptic-timeline" and doc["schema"] == projectfile.SCHEMA
    assert doc["project"]["tracks"][0]["kind"] == "drive"


def test_a_crash_mid_save_leaves_the_previous_file_intact(tmp_path, monkeypatch):
    path = tmp_path / "x.htl"
    projectfile.save(rich_project(), path)
    before = path.read_bytes()

    def crash(*_):
        raise OSError("disk unplugged")

    monkeypatch.setattr(os, "replace", crash)
    with pytest.raises(OSError):
        projectfile.save(edits.new_project(), path)
    assert path.read_bytes() == before
    assert [f.name for f in tmp_path.iterdir()] == ["x.htl"]  # no temporary left behind


def _saved_doc(tmp_path):
    """A project file as text, its samples as base64 (the clipboard's form and schema 3's)."""
    return json.loads(projectfile.dumps(rich_project()))


def _bad(tmp_path, doc_or_text, match):
    path = tmp_path / "bad.htl"
    text = doc_or_text if isinstance(doc_or_text, str) else json.dumps(doc_or_text)
    path.write_text(text)
    before = path.read_bytes()
    with pytest.raises(ProjectFileError, match=match) as info:
        projectfile.load(path)
    assert "\n" not in str(info.value)
    assert path.read_bytes() == before


def test_truncated_file(tmp_path):
    text = (tmp_path / "x.htl").write_text("") or None
    text = projectfile.dumps(rich_project())
    _bad(tmp_path, text[: len(text) // 2], "not a readable project file")


def test_future_schema_is_refused(tmp_path):
    doc = _saved_doc(tmp_path)
    doc["schema"] = 99
    _bad(tmp_path, doc, "newer haptic-timeline")


def test_not_a_project(tmp_path):
    _bad(tmp_path, {"hello": 1}, "not a haptic-timeline project")
    _bad(tmp_path, "[1, 2]", "not a haptic-timeline project")


def test_huge_declared_sample_count_is_refused_before_inflating(tmp_path):
    doc = _saved_doc(tmp_path)
    key = next(iter(doc["media"]))
    doc["media"][key]["count"] = 2**40
    _bad(tmp_path, doc, "outside the supported range")


def test_decompression_bomb_is_stopped_at_the_declared_size(tmp_path):
    doc = _saved_doc(tmp_path)
    key = next(iter(doc["media"]))
    bomb = zlib.compress(b"\0" * (64 * 2**20))  # 64 MiB of zeros in ~64 KiB
    doc["media"][key]["data"] = base64.b64encode(bomb).decode()
    _bad(tmp_path, doc, "declares 5000")


def test_wrong_types_and_missing_references(tmp_path):
    doc = _saved_doc(tmp_path)
    doc["project"]["tracks"][0]["clips"][0]["start"] = "soon"
    _bad(tmp_path, doc, "start should be a number, not text")
    doc = _saved_doc(tmp_path)
    doc["project"]["tracks"][0]["clips"][0]["tile"] = "nope"
    _bad(tmp_path, doc, "missing tile 'nope'")
    doc = _saved_doc(tmp_path)
    doc["project"]["tracks"][0]["kind"] = "laser"
    _bad(tmp_path, doc, "unknown track 'laser'|unknown track")
    doc = _saved_doc(tmp_path)
    doc["project"]["tracks"][0]["kind"] = "torque"  # a position kind on a time project
    _bad(tmp_path, doc, "torque track on the time axis")


def test_missing_path_and_directory(tmp_path):
    with pytest.raises(ProjectFileError, match="does not exist"):
        projectfile.load(tmp_path / "none.htl")
    with pytest.raises(ProjectFileError, match="is a folder"):
        projectfile.load(tmp_path)


def test_deeply_nested_json(tmp_path):
    _bad(tmp_path, "[" * 100_000 + "]" * 100_000, "nested too deeply|not a readable")


def test_a_registered_migration_upgrades_an_old_file(tmp_path, monkeypatch):
    doc = _saved_doc(tmp_path)
    # Pretend the next schema stores track gains as numbers and the current one in decibels.
    current = projectfile.SCHEMA
    for track in doc["project"]["tracks"]:
        track["gain_db"] = 20 * np.log10(track.pop("gain"))

    def upgrade(old):
        for track in old["project"]["tracks"]:
            track["gain"] = 10 ** (track.pop("gain_db") / 20)
        return {**old, "schema": current + 1}

    monkeypatch.setattr(projectfile, "SCHEMA", current + 1)
    monkeypatch.setitem(projectfile.MIGRATIONS, current, upgrade)
    (tmp_path / "old.htl").write_text(json.dumps(doc))
    p = projectfile.load(tmp_path / "old.htl")
    assert p.tracks[1].gain == pytest.approx(0.3)


def test_loading_runs_no_code():
    import ast

    with open(projectfile.__file__) as f:
        tree = ast.parse(f.read())
    imported = {a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names}
    imported |= {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}
    assert not imported & {"pickle", "marshal", "shelve", "dill", "yaml"}
    called = {
        n.func.id
        for n in ast.walk(tree)
        if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)
    }
    assert not called & {"eval", "exec", "compile", "__import__"}
