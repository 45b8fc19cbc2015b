"""An import never poisons a good project: the project every verb still uses, or one sentence.

Random valid-looking files (CSV with odd rate headers and time columns, .haptic designs with
tiny and extreme times) are imported into a good project file; afterwards render, check, export
and info all succeed, or the import was refused with one line and the file is byte for byte
what it was (issue 25: a `# rate=1e-300` CSV made every verb a traceback).
"""

from __future__ import annotations

import contextlib
import io
import json

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from timeline import edits, generator
from timeline.cli import main as cli
from timeline.cli.check_cmd import FOUND
from timeline.files import projectfile

from .conftest import count

RATES = ["1e-300", "1e-310", "5e-3", "1e-3", "0.5", "1", "1e4", "1e9", "1e12", "1e300", "nan",
         "inf", "-1", "0", "1e400", "1" * 60]  # fmt: skip
VALUES = st.floats(-1e6, 1e6) | st.sampled_from([0.0, 1e-300, -1e-300, 5e-324])


@st.composite
def csv_files(draw) -> tuple[str, str]:
    values = draw(st.lists(VALUES, min_size=1, max_size=3))
    if draw(st.booleans()):
        mark = draw(st.sampled_from(["#", "%"]))
        key = draw(st.sampled_from(["rate", "fs", "RATE"]))
        header = f"{mark} {key}={draw(st.sampled_from(RATES))}\n"
        return "design.csv", header + "".join(f"{v!r}\n" for v in values)
    start = draw(st.sampled_from([0.0, -1.0, 1e-300, 5.0, 1e300]))
    step = draw(st.sampled_from([1e-300, 1e-3, 0.25, 1e3, 1e300]))
    rows = "".join(f"{start + i * step!r},{v!r}\n" for i, v in enumerate(values))
    return "design.csv", "time,value\n" + rows


@st.composite
def haptic_files(draw) -> tuple[str, str]:
    times = sorted(draw(st.lists(st.sampled_from([0.0, 1e-300, 1e-9, 0.5, 600.0]), min_size=2,
                                 max_size=4)))  # fmt: skip
    amplitude = [{"time": t, "amplitude": draw(st.sampled_from([0.0, 1e-300, 1.0]))} for t in times]
    if draw(st.booleans()):
        amplitude[0]["emphasis"] = {
            "amplitude": draw(st.sampled_from([1e-300, 1.0])),
            "frequency": draw(st.sampled_from([0.0, 1e-300, 1.0])),
        }
    doc = {"version": {"major": 1, "minor": 0, "patch": 0},
           "signals": {"continuous": {"envelopes": {"amplitude": amplitude}}}}  # fmt: skip
    return "design.haptic", json.dumps(doc)


def _run(argv: list[str]) -> tuple[int, str]:
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        code = cli.main(argv)
    return code, err.getvalue()


SLOW_OK = [HealthCheck.function_scoped_fixture, HealthCheck.too_slow]


@settings(max_examples=count(8), deadline=None, suppress_health_check=SLOW_OK)
@given(st.one_of(csv_files(), haptic_files()))
def test_an_import_leaves_a_project_every_verb_uses_or_is_refused(tmp_path, file) -> None:
    name, text = file
    source = tmp_path / name
    source.write_text(text)
    project = edits.new_project(rate=10.0)  # renders of a long import stay small
    project, track = edits.add_track(project, "drive")
    project, tile = edits.add_tile(project, generator("sine", 0.5, frequency=5))
    project, _ = edits.add_clip(project, track, tile, start=0.0)
    design = tmp_path / "good.htl"
    projectfile.save(project, design)
    before = design.read_bytes()
    code, err = _run(["import", str(source), "--into", str(design)])
    if code != 0:
        last = err.strip().splitlines()[-1]  # after the progress line: one sentence
        assert last.startswith("haptic-timeline: ") and "Traceback" not in err, err
        assert design.read_bytes() == before
        return
    assert _run(["info", str(design)])[0] == 0
    assert _run(["render", str(design), "-o", str(tmp_path / "r.csv")])[0] == 0
    assert _run(["export", str(design), "-o", str(tmp_path / "e.csv")])[0] == 0
    assert _run(["check", str(design)])[0] in (0, FOUND)
