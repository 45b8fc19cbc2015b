"""A project's picture in a notebook: Project._repr_svg_ (timeline.model.picture)."""

import xml.etree.ElementTree as ET
from dataclasses import replace

from timeline import edits, generator
from timeline.model import Clip, Project, Track
from timeline.model.picture import LEFT, MAX_CLIPS, PLOT, SILENT, WIDTH

SVG = "{http://www.w3.org/2000/svg}"


def _rects(svg: str, cls: str) -> list[ET.Element]:
    return [r for r in ET.fromstring(svg).iter(f"{SVG}rect") if r.get("class") == cls]


def _layout() -> Project:
    """A 2 s project: a drive track with clips at 0 and 1.5 s (0.5 s each), and a muted
    stiffness track with one 1 s clip at 0.5 s."""
    p = edits.new_project(templates=False)
    p, drive = edits.add_track(p, "drive", "Buzz")
    p, spring = edits.add_track(p, "stiffness", "Spring")
    p, short = edits.add_tile(p, generator("sine", 0.5, frequency=175.0))
    p, long = edits.add_tile(p, generator("sine", 1.0, frequency=20.0))
    p, _ = edits.add_clip(p, drive, short, start=0.0)
    p, _ = edits.add_clip(p, drive, short, start=1.5)
    p, _ = edits.add_clip(p, spring, long, start=0.5)
    return edits.set_track(p, spring, mute=True)


def test_each_clip_is_a_rectangle_at_its_start_and_length():
    project = _layout()
    assert project.duration == 2.0
    svg = project._repr_svg_()
    root = ET.fromstring(svg)
    assert root.get("width") == str(WIDTH) == "720"
    assert len(_rects(svg, "lane")) == 2
    clips = _rects(svg, "clip")
    # 720 px wide, names in the first 150 px and 16 px to spare at the right: 2 s over 554 px
    assert (LEFT, PLOT) == (150, 554)
    xs = [(float(r.get("x", "")), float(r.get("width", ""))) for r in clips]
    assert xs == [(150.0, 138.5), (565.5, 138.5), (288.5, 277.0)]
    assert [r.findtext(f"{SVG}title") for r in clips] == ["sine", "sine", "sine"]
    # the muted track is grey, the sounding one is not; lanes are one under the other
    fills = [r.get("fill") for r in clips]
    assert fills[2] == SILENT and fills[0] == fills[1] != SILENT
    assert float(clips[2].get("y", "")) - float(clips[0].get("y", "")) == 30.0


def test_names_are_escaped():
    p = edits.new_project(templates=False)
    p, track = edits.add_track(p, "drive", "a <b> & c")
    p, tile = edits.add_tile(p, generator("sine", 1.0, '<&>"', frequency=5.0))
    p, _ = edits.add_clip(p, track, tile, start=0.0)
    svg = p._repr_svg_()
    assert "<&>" not in svg and "&lt;&amp;&gt;" in svg
    texts = [t.text for t in ET.fromstring(svg).iter(f"{SVG}text")]
    assert "a <b> & c" in texts and '<&>"' in texts
    assert _rects(svg, "clip")[0].findtext(f"{SVG}title") == '<&>"'


def test_a_name_too_long_for_its_clip_is_cut():
    p = edits.new_project(templates=False)
    p, track = edits.add_track(p, "drive", "Buzz")
    p, tile = edits.add_tile(p, generator("sine", 0.1, "x" * 40, frequency=5.0))
    p, _ = edits.add_clip(p, track, tile, start=0.0)
    p, _ = edits.add_clip(p, track, tile, start=0.9)  # 1 s: each clip is 55.4 px wide
    labels = [t.text or "" for t in ET.fromstring(p._repr_svg_()).iter(f"{SVG}text")]
    assert labels.count("xxxxxx…") == 2  # 7 characters of 6.2 px in 55.4 - 6 px
    assert "x" * 40 not in labels


def test_a_project_of_ten_thousand_clips_is_drawn_merged_and_says_so():
    p, tile = edits.add_tile(edits.new_project(templates=False), generator("sine", 0.05))
    tracks = []
    for k in range(4):
        # runs of 100 clips 0.1 s apart, 1.05 s between runs: 274 s over 554 px, so a run's
        # clips are 0.1 px apart (merged) and runs 2.1 px apart (not)
        clips = tuple(
            Clip(f"c{k}_{i}", tile, i * 0.1 + i // 100 * 1.0, 0.0, 0.05) for i in range(2_500)
        )
        tracks.append(Track(f"t{k}", "drive", f"lane {k}", clips))
    p = replace(p, tracks=tuple(tracks))
    assert sum(len(t.clips) for t in p.tracks) == 10_000 > MAX_CLIPS
    svg = p._repr_svg_()
    assert _rects(svg, "clip") == []
    merged = _rects(svg, "clips")
    assert len(merged) == 4 * 25  # each track: 25 runs of 100 clips
    assert {r.findtext(f"{SVG}title") for r in merged} == {"100 clips"}
    assert "10,000 clips: each lane's clips merged where they touch, no names" in svg


def test_an_empty_project_is_a_picture_too():
    svg = edits.new_project(templates=False)._repr_svg_()
    assert _rects(svg, "lane") == []
    assert "no tracks" in svg
