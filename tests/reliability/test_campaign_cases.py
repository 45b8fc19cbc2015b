"""The smallest inputs of the hostile campaign's findings (tests/reliability/hostile_attack.py):
each verb ends in a result or one sentence, with nothing on stderr but that sentence."""

from __future__ import annotations

import contextlib
import io
import warnings

import pytest

from timeline import edits, generator
from timeline.cli import main as cli
from timeline.files import projectfile


def _run(argv: list[str]) -> tuple[int, str]:
    """Exit code and stderr, every warning written into it as a user would see it (pytest
    otherwise takes them before they reach stderr)."""
    err = io.StringIO()
    with (
        warnings.catch_warnings(record=True) as caught,
        contextlib.redirect_stderr(err),
        contextlib.redirect_stdout(io.StringIO()),
    ):
        warnings.simplefilter("always")
        code = cli.main(argv)
    return code, err.getvalue() + "".join(f"{w.category.__name__}: {w.message}\n" for w in caught)


def _project(tmp_path, name="p", full_scale=None, **clip):
    """A 1 kHz project of one 0.2 s sine clip (and the given clip fields)."""
    fields = {} if full_scale is None else {"full_scale": full_scale}
    project, track = edits.add_track(edits.new_project(rate=1000.0, templates=False), "drive",
                                     **fields)  # fmt: skip
    project, tile = edits.add_tile(project, generator("sine", 0.2, frequency=20.0))
    project, clip_id = edits.add_clip(project, track, tile, 0.0)
    if clip:
        project = edits.set_clip(project, clip_id, **clip)
    path = tmp_path / f"{name}.htl"
    projectfile.save(project, path)
    return path


def test_a_gain_of_1e308_is_refused_by_a_float32_table_and_warns_nowhere(tmp_path):
    """Its table held inf (numpy's 'overflow encountered in cast' on stderr); check and compare
    warned of a divide by zero in log10 and invalid values in multiply."""
    path = _project(tmp_path, gain=1e308)
    code, err = _run(["export", str(path), "-o", str(tmp_path / "t.h")])
    assert code == 1 and err.startswith("haptic-timeline: the drive layer reaches 1.8e+307, ")
    assert "Warning" not in err and not (tmp_path / "t.h").exists()
    code, err = _run(["export", str(path), "-o", str(tmp_path / "t.h"), "--fixed-point"])
    assert code == 0 and "Warning" not in err
    code, err = _run(["check", str(path)])
    assert code == 3 and "Warning" not in err
    assert _run(["compare", str(_project(tmp_path, "q")), str(path)]) == (0, "")


def test_a_full_scale_of_5e_324_compares_as_a_silent_icon(tmp_path):
    """Its drive is all below 1e-300: compare's events were none (an IndexError)."""
    path = _project(tmp_path, full_scale=5e-324)
    assert _run(["compare", str(_project(tmp_path, "q")), str(path)]) == (0, "")


@pytest.mark.parametrize("verb", [["play", "--duration", "0.2"], ["export", "-o", "t.h"]])
def test_a_clip_stretched_1e308_plays_its_start_and_exports(tmp_path, verb):
    """It lasts 2e307 s, more samples than a render counts: play of its first 0.2 s and the
    firmware table's grid converted infinity to an integer (OverflowError)."""
    path = _project(tmp_path, stretch=1e308)
    argv = [verb[0], str(path), *verb[1:]]
    argv[-1] = str(tmp_path / argv[-1]) if verb[0] == "export" else argv[-1]
    code, err = _run(argv)
    assert code == 0 and "Traceback" not in err and "Warning" not in err


def test_a_sine_under_detents_checks_without_a_warning(tmp_path):
    """Found with an OTIO import (reduced): somewhere the pair's frequency estimate is
    infinite, and the skin model multiplied infinity by zero (numpy's 'invalid value
    encountered in multiply' before check's findings)."""
    project, track = edits.add_track(edits.new_project(rate=1000.0, templates=False), "drive")
    project, sine = edits.add_tile(project, generator("sine", 0.5, frequency=5.0))
    project, _ = edits.add_clip(project, track, sine, 0.0)
    project, tile = edits.add_tile(project, generator("detents", 0.3, count=4))
    project, _ = edits.add_clip(project, track, tile, 0.1)
    path = tmp_path / "detents.htl"
    projectfile.save(project, path)
    code, err = _run(["check", str(path)])
    assert code in (0, 3) and "Warning" not in err and "Traceback" not in err
