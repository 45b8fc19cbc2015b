"""The plugin table discovery reads without importing importlib.metadata gives what
importlib.metadata.entry_points() gives for sys.path's folders, and its entries load the objects
they name."""

from __future__ import annotations

import importlib.metadata
import sys

import pytest

from timeline.plugins import discovery


def _table() -> list[tuple[str, str, str]]:
    discovery._table.cache_clear()
    return [(e.group, e.name, e.value) for e in discovery._table()]


def _by_group(table: list[tuple[str, str, str]]) -> dict[str, list[tuple[str, str]]]:
    """Each group's (name, value) pairs in order, as importlib.metadata selects them."""
    groups = {group: [] for group, _, _ in table} | {"haptic_timeline.tracks": []}
    for group, name, value in table:
        groups[group].append((name, value))
    return groups


def _metadata_groups(groups) -> dict[str, list[tuple[str, str]]]:  # noqa: ANN001
    return {
        group: [(e.name, e.value) for e in importlib.metadata.entry_points(group=group)]
        for group in groups
    }


@pytest.fixture
def fresh(monkeypatch):
    monkeypatch.setattr(sys, "path", list(sys.path))
    yield
    discovery._table.cache_clear()


def test_the_installed_table_is_importlib_metadatas(fresh):
    groups = _by_group(_table())
    assert groups == _metadata_groups(groups)
    assert ("drive", "tracks.time_kinds:DRIVE") in groups["haptic_timeline.tracks"]


def test_first_distribution_of_a_name_wins_and_comments_are_skipped(tmp_path, fresh):
    first, second = tmp_path / "a", tmp_path / "b"
    for folder, stem, text in (
        (first, "My_Plugin-1.0.dist-info", "# note\n[demo.group]\n one = json:dumps \n\n"),
        (first, "other.egg-info", "[demo.group]\ntwo = json.decoder:JSONDecoder.decode\n"),
        (second, "my.plugin-2.0.dist-info", "[demo.group]\none = os:getcwd\n"),
        (second, "third-1.dist-info", "[demo.group]\nthree = json\n[x]\na=b=c\n"),
        (second, "nothing-1.dist-info", None),
    ):
        (folder / stem).mkdir(parents=True)
        if text is not None:
            (folder / stem / "entry_points.txt").write_text(text)
    sys.path[:] = [str(first), str(tmp_path / "missing"), str(second)]
    table = _table()
    groups = _by_group(table)
    assert groups == _metadata_groups(groups)
    assert sorted(table) == [  # the folder's order is the file system's
        ("demo.group", "one", "json:dumps"),  # my-plugin 2.0 on the later path is hidden
        ("demo.group", "three", "json"),
        ("demo.group", "two", "json.decoder:JSONDecoder.decode"),
        ("x", "a", "b=c"),
    ]
    import json

    loaded = {e.name: e.load() for e in discovery._table() if e.group == "demo.group"}
    assert loaded == {"one": json.dumps, "two": json.decoder.JSONDecoder.decode, "three": json}


def test_a_zip_on_the_path_is_passed_over(tmp_path, fresh):
    archive = tmp_path / "plugins.zip"
    archive.write_bytes(b"PK\x05\x06" + bytes(18))  # an empty zip
    sys.path[:] = [str(archive)]
    assert _table() == []
