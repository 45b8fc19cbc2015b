"""Issue 25's smallest hostile inputs: each is refused with one sentence or handled in bounds."""

from __future__ import annotations

import json
import tracemalloc

import numpy as np
import pytest

from timeline import edits, generator
from timeline.errors import EditError, FormatError
from timeline.files import projectfile
from timeline.files.importing import import_file, import_into_project_file, read_file
from timeline.limits.device_checks import _factor
from timeline.signal import memory
from timeline.signal.render_presets import preset
from timeline.signal.resample import sample_grid
from timeline.tiles import SampledTile


def _good_project(tmp_path):
    p = edits.new_project()
    p, track = edits.add_track(p, "drive")
    p, tile = edits.add_tile(p, generator("sine", 0.5, frequency=5))
    p, _ = edits.add_clip(p, track, tile, start=0.0)
    path = tmp_path / "good.htl"
    projectfile.save(p, path)
    return path


RATE = "a sampled tile's rate must be from 0.001"


@pytest.mark.parametrize(
    "text, words",
    [
        (
            "# rate=1e-300\n0.1\n0.2\n0.3\n",
            r"a sampled tile's rate must be from 0.001 to 1e\+09 .* not 1e-300",
        ),
        (
            "# rate=1e-310\n0.1\n0.2\n",
            "a sampled tile's rate must be from 0.001",
        ),  # was "source out ... inf"
        ("t,v\n-1,0.1\n-0.5,0.2\n0,0.3\n", "a clip would start at -1 s, before the timeline's 0"),
    ],
)
def test_a_poisoning_csv_is_refused_and_the_project_is_untouched(tmp_path, text, words):
    design = _good_project(tmp_path)
    before = design.read_bytes()
    source = tmp_path / "bad.csv"
    source.write_text(text)
    with pytest.raises(FormatError, match=f"^bad.csv cannot be imported: {words}") as err:
        import_into_project_file(source, design)
    assert "\n" not in str(err.value) and "source out" not in str(err.value)
    assert design.read_bytes() == before


def test_a_project_file_holding_a_sampled_rate_of_1e_300_is_refused_at_open(tmp_path):
    p = edits.new_project()
    p, _ = edits.add_tile(p, SampledTile(np.array([0.1, 0.2]), 10.0))
    text = projectfile.dumps(p).replace('"rate": 10.0', '"rate": 1e-300')
    with pytest.raises(projectfile.ProjectFileError, match="rate must be from 0.001"):
        projectfile.loads(text)


def test_a_slow_csv_renders_in_memory_bounded_by_the_output(tmp_path):
    """`% rate=5e-3` and two values: soxr's margins were 2,000,000x upsampled (8.2 GB)."""
    source = tmp_path / "slow.csv"
    source.write_text("% rate=5e-3\n0.1\n0.2\n")
    tile = read_file(source).placements[0].tile
    tracemalloc.start()
    try:
        values = sample_grid(tile.data, tile.rate, 0.0, 1e-4, 100, preset("exact"))
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 2**25  # 32 MiB (mostly the sinc table, made once), not gigabytes
    assert values[0] == pytest.approx(0.1, abs=1e-12)  # sample 0 on the grid: the sinc is 1 there
    assert 0.1 <= values[-1] < 0.1 + 1e-5  # 10 ms into a 200 s sample step: hardly moved


def test_a_haptic_file_of_many_weak_emphases_is_noted_in_four_lines(tmp_path):
    amplitude = [
        {
            "time": i / 1000,
            "amplitude": 0.5,
            "emphasis": {"amplitude": 0.1 + i / 1e6, "frequency": 0.5},
        }
        for i in range(20)
    ]
    doc = {"version": {"major": 1, "minor": 0, "patch": 0},
           "signals": {"continuous": {"envelopes": {"amplitude": amplitude}}}}  # fmt: skip
    path = tmp_path / "weak.haptic"
    path.write_text(json.dumps(doc))
    notes = read_file(path).notes
    weak = [n for n in notes if "weaker" in n]
    assert weak[0].startswith("the emphasis at 0 s (0.1) is weaker than its breakpoint (0.5)")
    assert len(weak) == 4 and weak[3].startswith("17 more emphases are weaker")


def test_equal_emphases_share_one_tile(tmp_path):
    amplitude = [
        {"time": i / 100, "amplitude": 0.5, "emphasis": {"amplitude": 0.9, "frequency": 0.5}}
        for i in range(50)
    ]
    amplitude.append({"time": 1.0, "amplitude": 0.0})
    doc = {"version": {"major": 1, "minor": 0, "patch": 0},
           "signals": {"continuous": {"envelopes": {"amplitude": amplitude}}}}  # fmt: skip
    path = tmp_path / "accents.haptic"
    path.write_text(json.dumps(doc))
    p, clips = import_file(edits.new_project(templates=False), path)
    assert len(clips) == 51 and len(p.tiles) == 2  # the envelopes and one emphasis


def test_huge_counts_are_written_short_and_name_no_python_function():
    assert memory.count_text(1800000000) == "1800000000"
    assert memory.count_text(3 * 10**303) == "3e+303"
    from timeline.rendering.mixer import Mixer

    p = edits.new_project()
    p, track = edits.add_track(p, "drive")
    p, tile = edits.add_tile(p, generator("sine", 0.5))
    p, clip = edits.add_clip(p, track, tile, start=0.0)
    p = edits.stretch_clip(p, clip, 1e300)
    with pytest.raises(Exception, match=r"^5e\+303 samples is too many for one render") as err:
        Mixer().render(p)
    assert "render_chunks" not in str(err.value)


def test_check_advises_a_tiny_factor_in_significant_digits():
    assert _factor(0.5) == "0.50"
    assert _factor(1.8e-300) == "1.8e-300"  # was "0.00"


def test_an_edit_error_from_placing_stays_an_edit_error(tmp_path):
    source = tmp_path / "ok.csv"
    source.write_text("# rate=100\n0.1\n0.2\n")
    with pytest.raises(EditError, match="cannot start at -1"):
        import_file(edits.new_project(), source, at=-1.0)


def _damaged_sounds(folder):
    """A WAV cut in half (its header promises 8,000 frames) and a FLAC with flipped bytes."""
    import soundfile as sf

    x = np.sin(np.arange(8000) / 5) * 0.5
    sf.write(folder / "whole.wav", x, 8000)
    whole = (folder / "whole.wav").read_bytes()
    (folder / "cut.wav").write_bytes(whole[: len(whole) // 2])
    sf.write(folder / "whole.flac", x, 8000)
    flac = bytearray((folder / "whole.flac").read_bytes())
    for i in range(200, len(flac), 97):
        flac[i] ^= 0x55
    (folder / "bad.flac").write_bytes(bytes(flac))


@pytest.mark.parametrize(
    "name, words",
    [("cut.wav", "cut.wav is truncated: its header promises more audio than the file holds"),
     ("bad.flac", r"bad.flac could not be read to the end \(Error : flac decoder lost sync\)")],
)  # fmt: skip
def test_convert_refuses_a_damaged_sound_as_import_does(tmp_path, name, words):
    from timeline.errors import ConvertError
    from timeline.files.convert import convert_file

    _damaged_sounds(tmp_path)
    with pytest.raises(ConvertError, match=f"^{words}$"):
        convert_file(tmp_path / name, tmp_path / "out.haptic")
    assert not (tmp_path / "out.haptic").exists()


def test_a_lone_surrogate_in_a_name_is_refused_at_open():
    p, _ = edits.add_track(edits.new_project(), "drive", "knob")
    text = projectfile.dumps(p).replace('"name": "knob"', '"name": "a\\ud800b"')
    with pytest.raises(projectfile.ProjectFileError, match=r"name is not text \(it holds a lone"):
        projectfile.loads(text)
