"""A hostile-input campaign over every reader and verb: `python -m tests.reliability.hostile_attack
OUT [--only CATEGORY,...]`.

Writes new hostile files by code (issue 25 items 1-6 and 8: every leaf of every JSON format given
each hostile value, lying audio and .mat headers, odd CSV headers and encodings, .otioz bombs and
paths, deep nesting, duplicate keys, lone surrogates, hostile import options), imports each into a
good project and runs every verb on the result (info, render, play on the sim, export to each
format, check, compare; convert for sounds) in this process. OTIO leaves are parsed without their
child interpreter, for speed, with the child's outcomes reproduced; structural JSON, .mat and
.otioz keep it. A run is clean when it ends with exit 0 and finite output, or with one sentence,
within 10 s of CPU time and with no warning; anything else goes to OUT/findings.jsonl (its input
to OUT/kept/). Writes the count per category (inputs, runs, clean) to OUT/counts.md.
"""

from __future__ import annotations

import contextlib
import io
import json
import shutil
import signal
import sys
import time
import traceback
import warnings
from collections import Counter
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from tests.reliability import hostile_inputs as inputs
from timeline.cli import main as cli
from timeline.cli.check_cmd import FOUND
from timeline.errors import HapticTimelineError, SandboxError
from timeline.files import crash_isolation

HANG_SECONDS = 10  # of CPU time: at load 12 a 2-second render took 20 s of wall time
ISOLATED = ("json-structure", "mat", "otioz")  # categories parsed in the child, as by users
EXPORTS = (".ahap", ".haptic", ".hjif", ".otio", ".otioz", ".wav", ".mat", ".csv", ".h")
LEAKS = ("Error:", "Error(", "numpy", "usecols", "sys.", "render_chunks", "NoneType",
         "has no attribute", "passed back", "index out of range", "object of type", "unhashable",
         "takes ", "positional argument", "not subscriptable", "<class", "dtype", "errno",
         "0x7f")  # fmt: skip


class Hang(Exception):
    """A run passed HANG_SECONDS."""


def _in_process(fn, *args, what: str, **_: object):
    """crash_isolation.run without the child: its outcomes, as the child would give them."""
    try:
        return fn(*args)
    except HapticTimelineError:
        raise
    except MemoryError:
        raise SandboxError(f"{what} could not be read: its parser needed more memory") from None
    except Exception as exc:  # noqa: BLE001 - what the child reports
        text = str(exc).splitlines()[0][:160] if str(exc) else ""
        raise SandboxError(f"{what} could not be read: {type(exc).__name__}: {text}") from None


def _alarm(*_: object) -> None:
    raise Hang


def run(argv: list[str]) -> dict:
    """One CLI run in this process: exit code, stderr, seconds and what was wrong with it."""
    err, out = io.StringIO(), io.StringIO()
    problems: list[str] = []
    start = time.perf_counter()
    signal.signal(signal.SIGPROF, _alarm)
    signal.setitimer(signal.ITIMER_PROF, HANG_SECONDS)
    with (
        warnings.catch_warnings(),
        contextlib.redirect_stderr(err),
        contextlib.redirect_stdout(out),
    ):
        warnings.simplefilter("default")
        try:
            code = cli.main(argv)
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else 2
        except Hang:
            code, problems = -1, ["hang"]
        except BaseException:  # noqa: BLE001 - the finding
            code = -2
            problems.append("traceback")
            err.write(traceback.format_exc())
        finally:
            signal.setitimer(signal.ITIMER_PROF, 0)
    text = err.getvalue()
    if "Traceback" in text and "traceback" not in problems:
        problems.append("traceback")
    if "Warning" in text:
        problems.append("warning")
    if code not in (0, -1, -2) and not (argv[0] == "check" and code == FOUND):
        said = [line for line in text.strip().splitlines() if _sentence(line, code)]
        if not said:
            problems.append("no sentence")
        elif any(word in said[-1] for word in LEAKS):
            problems.append("leak")
    return {"argv": argv, "code": code, "seconds": round(time.perf_counter() - start, 3),
            "problems": problems, "err": text[-2000:]}  # fmt: skip


def _sentence(line: str, code: int) -> bool:
    """A refusal's line: ours, or argparse's usage error (exit 2, after the usage lines)."""
    return line.startswith("haptic-timeline:") or (
        code == 2 and line.startswith("haptic-timeline ") and ": error: " in line
    )


def _finite_output(path: Path) -> bool:
    with np.load(path) as data:
        return all(np.all(np.isfinite(data[k])) for k in data.files if data[k].dtype.kind == "f")


def verbs(project: Path, good: Path, work: Path) -> Iterator[list[str]]:
    """Every verb on a project file."""
    yield ["info", str(project)]
    yield ["info", "--json", str(project)]
    yield ["render", str(project), "-o", str(work / "r.npz")]
    yield ["play", str(project), "--duration", "0.2", "-o", str(work / "t.csv")]
    for ext in EXPORTS:
        yield ["export", str(project), "-o", str(work / f"e{ext}")]
    yield ["check", str(project)]
    yield ["compare", str(good), str(project)]


def attack(source: Path, extra: list[str], good: Path, work: Path, record) -> None:
    """Import source into a copy of the good project and run every verb; or, for a project
    file, run every verb on it."""
    if source.suffix == ".htl":
        project = source
    else:
        project = work / "p.htl"
        shutil.copy(good, project)
        before = project.read_bytes()
        done = record(["import", str(source), "--into", str(project), *extra])
        if done["code"] != 0:
            if project.read_bytes() != before:
                done["problems"].append("poisoned (refused but changed)")
            return
        if inputs.is_sound(source):
            record(["convert", str(source), "-o", str(work / "c.haptic")])
    for argv in verbs(project, good, work):
        done = record(argv)
        if argv[0] == "render" and done["code"] == 0 and not _finite_output(work / "r.npz"):
            done["problems"].append("non-finite output")


def main(argv: list[str]) -> int:
    out = Path(argv[0])
    only = argv[argv.index("--only") + 1] if "--only" in argv else None
    out.mkdir(parents=True, exist_ok=True)
    isolated = crash_isolation.run
    good = out / "good.htl"
    inputs.good_project(good)
    counts: Counter = Counter()
    findings = (out / "findings.jsonl").open("w")
    for category, name, data, extra in inputs.everything(out):
        if only and category not in only.split(","):
            continue
        work = out / "work"
        shutil.rmtree(work, ignore_errors=True)
        work.mkdir()
        source = work / name
        source.write_bytes(data)
        counts[category, "inputs"] += 1
        # the child interpreter kept where a parser may crash (deep nesting segfaults OTIO's)
        crash_isolation.run = isolated if category in ISOLATED else _in_process
        runs: list[dict] = []

        def record(cli_argv: list[str], runs=runs) -> dict:
            done = run(cli_argv)
            runs.append(done)
            return done

        attack(source, extra, good, work, record)
        for done in runs:
            counts[category, "runs"] += 1
            if done["problems"]:
                finding = {"category": category, "input": name, **done}
                findings.write(json.dumps(finding) + "\n")
                findings.flush()
                keep = out / "kept" / f"{counts[category, 'inputs']}-{name}"
                keep.parent.mkdir(exist_ok=True)
                keep.write_bytes(data)
            else:
                counts[category, "clean"] += 1
        (out / "counts.md").write_text(_table(counts))
    print(_table(counts))
    return 0


def _table(counts: Counter) -> str:
    lines = ["| category | inputs | runs | clean |", "|---|---|---|---|"]
    for category in dict.fromkeys(c for c, _ in counts):
        row = [counts[category, k] for k in ("inputs", "runs", "clean")]
        lines.append(f"| {category} | {row[0]:,} | {row[1]:,} | {row[2]:,} |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
