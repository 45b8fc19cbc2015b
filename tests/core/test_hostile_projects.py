"""Hostile project files: every malformed field is one sentence naming it, never a traceback."""

import json

import pytest

from timeline.cli import main as cli
from timeline.errors import ProjectFileError
from timeline.files import projectfile
from timeline.signal import memory

EXAMPLE = "projects/notification_buzz.htl"
OVERFLOW = "@1e999@"  # written as the bare literal 1e999, which JSON readers take as inf


def _doc():
    with open(EXAMPLE, encoding="utf-8") as f:
        return json.load(f)


def _clip(doc):
    return doc["project"]["tracks"][0]["clips"][0]


def _generator(doc):
    return next(t for t in doc["project"]["tiles"].values() if t["type"] == "generator")


def _spline(doc):
    return next(t for t in doc["project"]["tiles"].values() if t["type"] == "spline")


CASES = {
    "huge int clip start": (
        lambda d: _clip(d).update(start=10**400),
        "start is a number too large",
    ),
    "null gain": (lambda d: _clip(d).update(gain=None), "gain should be a number, not null"),
    "object gain": (
        lambda d: _clip(d).update(gain={"a": 1}),
        "gain should be a number, not an obj",
    ),
    "huge generator param": (
        lambda d: _generator(d)["params"].update(frequency=10**400),
        "params.frequency is a number too large",
    ),
    "null generator param": (
        lambda d: _generator(d)["params"].update(frequency=None),
        "params.frequency should be a number, not null",
    ),
    "text spline point": (
        lambda d: _spline(d)["points"][0].__setitem__(0, "x"),
        r"points\[0\] should be a number, not text",
    ),
    "huge spline point": (
        lambda d: _spline(d)["points"][0].__setitem__(1, 10**400),
        r"points\[0\] is a number too large",
    ),
    "track gain NaN": (
        lambda d: d["project"]["tracks"][0].update(gain=float("nan")),
        "holds NaN",
    ),
    "track gain inf": (
        lambda d: d["project"]["tracks"][0].update(gain=float("inf")),
        "holds Infinity",
    ),
    "negative full scale": (
        lambda d: d["project"]["tracks"][0].update(full_scale=-1.0),
        "full_scale should be above zero, not -1",
    ),
    "text full scale": (
        lambda d: d["project"]["tracks"][0].update(full_scale="big"),
        "full_scale should be a number, not text",
    ),
    "clip end overflows": (
        lambda d: _clip(d).update(start=1.7e308, stretch=1e308),
        "ends beyond any finite time",
    ),
    "huge next id": (lambda d: d["project"].update(next_id=10**400), "next_id is a 401-digit"),
    "huge project rate": (
        lambda d: d["project"].update(rate=10**400),
        "rate is a number too large",
    ),
    "zero project rate": (lambda d: d["project"].update(rate=0), "rate should be above zero"),
    "reverse as text": (lambda d: _clip(d).update(reverse="no"), "reverse should be true or false"),
    "mute as number": (lambda d: d["project"]["tracks"][0].update(mute=1), "mute should be true"),
    "fade as number": (lambda d: _clip(d).update(fade_in=5), "fade_in should be an object"),
    "negative fade": (
        lambda d: _clip(d).update(fade_in={"length": -1, "shape": "linear"}),
        r"clips\[0\].fade_in: a fade's length cannot be negative",
    ),
    "stretch mode as number": (lambda d: _clip(d).update(stretch_mode=3), "stretch_mode should"),
    "zero stretch": (lambda d: _clip(d).update(stretch=0), r"clips\[0\]: a clip's stretch must"),
    "palette id as number": (
        lambda d: d["project"]["palette"][0].update(tiles=[1]),
        "tiles should be tile ids",
    ),
    "metadata overflow": (
        lambda d: d["project"]["metadata"].update(x=OVERFLOW),
        "metadata holds a value that is not finite JSON",
    ),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_malformed_field_is_one_sentence(tmp_path, case):
    change, message = CASES[case]
    doc = _doc()
    change(doc)
    path = tmp_path / "bad.htl"
    path.write_text(json.dumps(doc).replace(f'"{OVERFLOW}"', "1e999"))
    before = path.read_bytes()
    with pytest.raises(ProjectFileError, match=message) as info:
        projectfile.load(path)
    assert "\n" not in str(info.value)
    assert path.read_bytes() == before


@pytest.mark.parametrize("verb", ["info", "render"])
def test_cli_reports_a_hostile_number_in_one_line(tmp_path, capsys, verb):
    doc = _doc()
    _clip(doc)["start"] = 10**400
    path = tmp_path / "bad.htl"
    path.write_text(json.dumps(doc))
    argv = [verb, str(path)] + (["-o", str(tmp_path / "o.csv")] if verb == "render" else [])
    assert cli.main(argv) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "start is a number too large to use" in err
    assert not (tmp_path / "o.csv").exists()


def test_a_clip_ending_far_away_is_refused_by_render_not_a_traceback(tmp_path, capsys):
    doc = _doc()
    _clip(doc).update(start=1e308, stretch=1e308)  # ends at 1.3e308 s: finite, uncountable
    path = tmp_path / "far.htl"
    path.write_text(json.dumps(doc))
    assert cli.main(["render", str(path), "-o", str(tmp_path / "o.csv")]) == 1
    assert "more samples than can be counted" in capsys.readouterr().err


def test_a_render_too_big_for_memory_says_the_size_it_needs(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(memory, "_free_memory", lambda: 8 * 2**30)  # a machine with 8 GiB free
    doc = _doc()
    _clip(doc)["stretch"] = 6e5  # 0.3 s * 6e5 = 180,000 s: 1.8e9 samples at 10 kHz, ~80 GiB
    path = tmp_path / "long.htl"
    path.write_text(json.dumps(doc))
    assert cli.main(["render", str(path), "-o", str(tmp_path / "o.csv")]) == 1
    err = capsys.readouterr().err
    assert "would need about 80.5 GiB of memory, but only 8.0 GiB is available" in err
    assert err.count("\n") == 1
    assert not (tmp_path / "o.csv").exists()
