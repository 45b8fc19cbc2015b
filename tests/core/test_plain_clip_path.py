"""The loader's fast path for plain clips gives exactly the clip the field-by-field reader gives,
and leaves every malformed clip to that reader (so its one-sentence refusals are unchanged)."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from timeline.errors import FieldError
from timeline.files import projectfile
from timeline.model import Clip, Fade

PLAIN = {
    "id": "clip7", "tile": "tile3", "start": 1.25, "source_in": 0.0, "source_out": 0.5,
    "stretch": 2.0, "stretch_mode": "squeeze", "loop_phase": 0.0, "gain": 0.8, "scale": -1.0,
    "offset": 0.1, "pivot": 0.0, "reverse": True,
    "fade_in": {"length": 0.0, "shape": "linear"}, "fade_out": {"length": 0.25, "shape": "s-curve"},
}  # fmt: skip

odd_values = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(min_value=-(2**70), max_value=2**70),
    st.booleans(),
    st.none(),
    st.sampled_from(["", "squeeze", "repeat", "linear", "tile3", "s-curve"]),
    st.fixed_dictionaries(
        {
            "length": st.floats(allow_nan=True) | st.integers() | st.none(),
            "shape": st.sampled_from(["linear", "exponential", "zigzag"]) | st.integers(),
        }  # fmt: skip
    ),
    st.lists(st.floats(), max_size=2),
)


def _slow(obj: dict) -> Clip | str:
    try:
        return projectfile.built_at(lambda: projectfile._clip(obj, "clip"), "clip")
    except FieldError as exc:
        return str(exc)


@given(
    st.dictionaries(st.sampled_from(sorted(PLAIN) + ["extra"]), odd_values, max_size=4),
    st.sets(st.sampled_from(sorted(PLAIN)), max_size=2),
)
def test_fast_path_agrees_with_the_field_by_field_reader(changes: dict, dropped: set):
    obj = {k: v for k, v in {**PLAIN, **changes}.items() if k not in dropped}
    fast = projectfile._plain_clip(obj)
    slow = _slow(obj)
    if fast is not None:
        assert fast == slow and isinstance(slow, Clip)
    if isinstance(slow, Clip):
        assert projectfile.clip_from_json(obj, "clip") == slow
    else:  # refused: the fast path took no part, the message names the field
        assert fast is None
        with pytest.raises(FieldError, match="clip"):
            projectfile.clip_from_json(obj, "clip")


def test_plain_clip_takes_the_fast_path_with_every_field():
    clip = projectfile._plain_clip(PLAIN)
    assert clip is not None and clip == _slow(PLAIN)
    assert clip.fade_out == Fade(0.25, "s-curve") and clip.fade_in == Fade()
    assert clip.end == pytest.approx(1.25 + 0.5 * 2.0)


@pytest.mark.parametrize(
    ("key", "value", "message"),
    [
        ("start", 1e308 * 10, "finite"),
        ("gain", 2**1100, "too large"),
        ("source_out", -1.0, "positive length"),
        ("stretch", 0.0, "stretch must be positive"),
        ("stretch_mode", "warp", "unknown stretch mode"),
        ("reverse", "yes", "reverse should be true or false"),
        ("fade_in", {"length": -0.5, "shape": "linear"}, "cannot be negative"),
        ("fade_out", {"length": 0.1, "shape": "zigzag"}, "unknown fade shape"),
    ],
)
def test_each_bad_field_is_refused_with_its_sentence(key: str, value: object, message: str):
    obj = {**PLAIN, key: value}
    assert projectfile._plain_clip(obj) is None
    with pytest.raises(FieldError, match=message):
        projectfile.clip_from_json(obj, "project.tracks[0].clips[3]")


def test_a_sum_that_overflows_only_takes_the_slow_path():
    obj = {**PLAIN, "start": 1.6e308, "gain": 1.6e308}
    assert not math.isfinite(obj["start"] + obj["gain"])
    assert projectfile._plain_clip(obj) is None
    slow = _slow(obj)
    assert isinstance(slow, Clip) and projectfile.clip_from_json(obj, "clip") == slow


@pytest.mark.parametrize("enabled", [True, False])
def test_loading_restores_the_garbage_collector_even_on_a_refusal(enabled: bool):
    import gc

    from timeline import edits
    from timeline.errors import ProjectFileError

    text = projectfile.dumps(edits.new_project())
    was = gc.isenabled()
    try:
        (gc.enable if enabled else gc.disable)()
        assert projectfile.loads(text) == edits.new_project()
        assert gc.isenabled() is enabled
        with pytest.raises(ProjectFileError):
            projectfile.loads(text.replace('"rate": 10000.0', '"rate": -1.0'))
        assert gc.isenabled() is enabled
    finally:
        (gc.enable if was else gc.disable)()


finite = st.floats(allow_nan=False, allow_infinity=False, min_value=-1e300, max_value=1e300)


@given(
    st.text(max_size=6),
    st.text(max_size=6),
    finite,
    st.floats(min_value=-1e6, max_value=1e6),
    st.floats(min_value=1e-3, max_value=1e6),
    st.floats(min_value=1e-6, max_value=1e3),
    st.sampled_from(["squeeze", "repeat"]),
    st.lists(finite, min_size=5, max_size=5),
    st.booleans(),
    st.floats(min_value=0.0, max_value=1e3),
    st.sampled_from(["linear", "equal-power", "exponential", "s-curve"]),
)
def test_a_clip_line_is_the_json_encoders_text_for_the_clip(
    clip_id, tile_id, start, source_in, length, stretch, mode, rest, reverse, fade, shape
):
    clip = Clip(
        clip_id, tile_id, start, source_in, source_in + length, stretch, mode, *rest,
        reverse=reverse, fade_in=Fade(fade, shape), fade_out=Fade(),
    )  # fmt: skip
    assert projectfile._clip_line(clip) == projectfile._COMPACT.encode(
        projectfile.clip_to_json(clip)
    )


def test_saving_through_clip_lines_gives_the_bytes_of_the_dict_encoder():
    from timeline.bench.scenes import LargeSpec, large_project
    from timeline.edits import save_variant

    project = save_variant(large_project(LargeSpec(4, 300, 20.0, 12)), "A")
    plain = projectfile._text(projectfile.to_json(project), projectfile._COMPACT.encode) + "\n"
    assert projectfile.dumps(project) == plain
    assert projectfile.loads(plain) == project and project.variants[0].tracks[0].clips
