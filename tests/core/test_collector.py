"""Reading files pauses the cyclic garbage collector and always restores it as it was."""

import gc
import json

import pytest

from timeline.bench.formats import long_haptic
from timeline.files import gc_pause, importing
from timeline.plugins.file_formats import FormatError


@pytest.fixture(params=[True, False], ids=["enabled", "disabled"])
def collector_state(request):
    was = gc.isenabled()
    (gc.enable if request.param else gc.disable)()
    yield request.param
    (gc.enable if was else gc.disable)()


@pytest.fixture
def collections():
    """The collections the cyclic collector starts while the test runs."""
    started = []

    def note(phase, info):
        if phase == "start":
            started.append(info["generation"])

    gc.callbacks.append(note)
    yield started
    gc.callbacks.remove(note)


def test_paused_restores_the_state_even_when_the_body_raises(collector_state):
    with pytest.raises(ZeroDivisionError), gc_pause.paused():
        assert not gc.isenabled()
        1 / 0  # noqa: B018
    assert gc.isenabled() is collector_state


def test_reading_a_design_runs_no_collection_and_restores_the_collector(
    collector_state, collections, tmp_path
):
    design = tmp_path / "long.haptic"
    design.write_text(json.dumps(long_haptic(breakpoints=2_000)))
    first = importing.read_file(design)  # loads the format plugins
    collections.clear()
    again = importing.read_file(design)
    # thousands of new dicts and lists: no collection while reading, at most the one that the
    # first allocation after it starts over what the read kept (the design)
    assert len(collections) <= 1
    assert again.placements == first.placements and len(again.placements) > 1
    assert gc.isenabled() is collector_state
    with gc_pause.paused():
        pass
    assert gc.isenabled() is collector_state
    bad = tmp_path / "b.ahap"
    bad.write_text('{"Version": 1.0, "Pattern": [{"Event": {"Time": "soon"}}]}')
    with pytest.raises(FormatError):
        importing.read_file(bad)
    assert gc.isenabled() is collector_state


def test_the_same_reading_unpaused_would_collect(collections, tmp_path):
    """The check above can fail: the same format's reader, called with the collector on, collects
    again and again."""
    design = tmp_path / "long.haptic"
    design.write_text(json.dumps(long_haptic(breakpoints=2_000)))
    was = gc.isenabled()
    gc.enable()
    try:
        importing.readers_for(design)[0].read(design)
    finally:
        (gc.enable if was else gc.disable)()
    assert len(collections) > 1
