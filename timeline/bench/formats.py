"""Import and export speed of the vibration formats (.haptic, AHAP) on long designs.

Each time is also given as a ratio to parsing the same file with json.loads in the same process
(the least any reader must pay), so machines of different speed compare.
"""

from __future__ import annotations

import contextlib
import json
import tempfile
from pathlib import Path

import numpy as np

from timeline import edits
from timeline.bench.report import Table, best_time
from timeline.edits.vibration import Emphasis, VibrationDesign, place_design
from timeline.errors import FormatError
from timeline.files import exporting, importing
from timeline.model import Project
from timeline.plugins.file_formats import all_formats
from timeline.tiles import SampledTile

NAME = "formats"
SUMMARY = ".haptic and AHAP import/export time of long designs, as ratios to a JSON parse"
HAPTIC_SECONDS = 120.0
HAPTIC_BREAKPOINTS = 6_881  # amplitude and frequency together, as in a 120 s Studio export
RECORDING_RATE = 10_000.0  # Hz: a drive recording at the knob's servo rate
AHAP_EVENTS = 440_000  # issue 11's target: imported in <= 5 s, or refused by a documented limit
EMPHASIS = 10_000  # a minute of dense accents: emphasis between the envelope's breakpoints


def long_haptic(seconds: float = HAPTIC_SECONDS, breakpoints: int = HAPTIC_BREAKPOINTS) -> dict:
    """A seeded .haptic document: breakpoints split between the two envelopes, some emphasis."""
    rng = np.random.default_rng(14)
    n_amp = breakpoints // 2 + 1
    n_freq = breakpoints - n_amp

    def envelope(n: int, key: str) -> list[dict]:
        times = np.sort(rng.uniform(0.0, seconds, n))
        times[0], times[-1] = 0.0, seconds
        values = np.round(rng.uniform(0.0, 1.0, n), 6)
        return [{"time": float(t), key: float(v)} for t, v in zip(times, values, strict=True)]

    amplitude = envelope(n_amp, "amplitude")
    for bp in amplitude[:: max(1, n_amp // 50)]:
        bp["emphasis"] = {"amplitude": 1.0, "frequency": 0.7}
    return {
        "version": {"major": 1, "minor": 0, "patch": 0},
        "signals": {
            "continuous": {
                "envelopes": {"amplitude": amplitude, "frequency": envelope(n_freq, "frequency")}
            }
        },
    }


def drive_recording(seconds: float = HAPTIC_SECONDS, rate: float = RECORDING_RATE) -> Project:
    """A seeded drive recording on one clip: a wandering envelope on a wandering 20-140 Hz
    carrier (exporting it analyses the rendered waveform into breakpoints)."""
    rng = np.random.default_rng(11)
    t = np.arange(int(seconds * rate)) / rate
    knots = np.linspace(0.0, seconds, int(seconds * 4) + 1)
    envelope = np.interp(t, knots, rng.uniform(0.0, 1.0, len(knots)))
    hz = np.interp(t, knots, rng.uniform(20.0, 140.0, len(knots)))
    samples = envelope * np.sin(2.0 * np.pi * np.cumsum(hz) / rate)
    project, track = edits.add_track(edits.new_project(templates=False), "drive")
    project, tile = edits.add_tile(project, SampledTile(samples, rate, "recording"))
    return edits.add_clip(project, track, tile, 0.0)[0]


def accented_design(emphasis: int = EMPHASIS, seconds: float = 60.0) -> VibrationDesign:
    """A seeded design: a 700-breakpoint envelope and `emphasis` accents at off-grid times."""
    rng = np.random.default_rng(5)
    times = np.sort(rng.uniform(0.0, seconds, 700))
    times[0], times[-1] = 0.0, seconds
    levels = np.round(rng.uniform(0.0, 1.0, 700), 4)
    amplitude = tuple(zip(times.tolist(), levels.tolist(), strict=True))
    accents = tuple(
        Emphasis(t, a, f)
        for t, a, f in zip(
            rng.uniform(0.0, seconds, emphasis).tolist(),
            np.round(rng.uniform(0.2, 1.0, emphasis), 4).tolist(),
            np.round(rng.uniform(0.0, 1.0, emphasis), 4).tolist(),
            strict=True,
        )
    )
    return VibrationDesign(amplitude, (), accents, seconds)


def many_events_ahap(events: int = AHAP_EVENTS) -> dict:
    """A seeded AHAP of transients and short continuous events, half each, 1 ms apart."""
    rng = np.random.default_rng(14)
    pattern = []
    for k in range(events):
        kind = "HapticTransient" if k % 2 else "HapticContinuous"
        event = {
            "Time": round(k * 0.001, 6),
            "EventType": kind,
            "EventParameters": [
                {"ParameterID": "HapticIntensity", "ParameterValue": round(rng.uniform(), 4)},
                {"ParameterID": "HapticSharpness", "ParameterValue": round(rng.uniform(), 4)},
            ],
        }
        if kind == "HapticContinuous":
            event["EventDuration"] = 0.0008
        pattern.append({"Event": event})
    return {"Version": 1.0, "Pattern": pattern}


def _try(path: Path) -> None:
    with contextlib.suppress(FormatError):
        importing.read_file(path)


def _row(name: str, path: Path, work, repeat: int) -> list[object]:
    text = path.read_bytes()
    parse = best_time(lambda: json.loads(text), repeat)
    seconds = best_time(work, repeat)
    return [name, len(text) / 1e6, 1e3 * parse, 1e3 * seconds, seconds / parse]


def _export_rows(project: Project, label: str, stem: Path, repeat: int) -> list[list[object]]:
    """Rows timing the project's export to .haptic and to AHAP (the file written once first)."""
    rows = []
    for ext in (".haptic", ".ahap"):
        target = stem.with_suffix(ext)
        exporting.export_project(project, target)
        rows.append(
            _row(
                f"{label} export {ext}",
                target,
                lambda t=target: exporting.export_project(project, t),
                repeat,
            )  # fmt: skip
        )
    return rows


def run(quick: bool, out: Path) -> list[Table]:
    table = Table(
        "Vibration formats: import and export (best of runs)",
        ["case", "file MB", "json.loads ms", "ms", "ratio to json.loads"],
    )
    repeat = 1 if quick else 7
    breakpoints = HAPTIC_BREAKPOINTS // 10 if quick else HAPTIC_BREAKPOINTS
    events = AHAP_EVENTS // 20 if quick else AHAP_EVENTS
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        haptic = folder / "long.haptic"
        haptic.write_text(json.dumps(long_haptic(breakpoints=breakpoints), indent=2))
        table.rows.append(
            _row(
                f".haptic of {breakpoints:,} breakpoints import",
                haptic,
                lambda: importing.read_file(haptic),
                repeat,
            )
        )
        project, _ = importing.import_file(edits.new_project(templates=False), haptic)
        table.rows += _export_rows(project, "that design", folder / "out", repeat)
        seconds = HAPTIC_SECONDS / 10 if quick else HAPTIC_SECONDS
        recording = drive_recording(seconds)
        table.rows += _export_rows(
            recording, f"{seconds:g} s drive recording", folder / "recording", repeat
        )
        emphasis = EMPHASIS // 10 if quick else EMPHASIS
        accented = place_design(
            edits.new_project(templates=False), accented_design(emphasis), name="accents"
        )
        table.rows += _export_rows(
            accented, f"design of {emphasis:,} emphasis", folder / "accents", repeat
        )
        table.rows.append(
            _row(
                f"that AHAP ({emphasis:,} transients) import",
                folder / "accents.ahap",
                lambda: importing.import_file(
                    edits.new_project(templates=False), folder / "accents.ahap"
                ),
                repeat,
            )
        )
        # the AHAP plugin's own limit, no part of the Format protocol
        limit: int = getattr(all_formats()["ahap"], "max_events")  # noqa: B009
        sizes = [limit // 50] if quick else [limit, AHAP_EVENTS]
        for events in sizes:
            ahap = folder / f"many{events}.ahap"
            ahap.write_text(json.dumps(many_events_ahap(events), separators=(",", ":")))
            verdict = "refused" if events > limit else "import"
            table.rows.append(
                _row(f"AHAP of {events:,} events: {verdict}", ahap, lambda a=ahap: _try(a), 1)
            )
    table.notes.append(
        f"targets: the {HAPTIC_BREAKPOINTS:,}-breakpoint .haptic imports in <= 0.3 s and exports "
        f"in <= 0.5 s, and so does a {HAPTIC_SECONDS:g} s drive recording (rendered and "
        f"analysed into breakpoints; json.loads is of the file it writes); {AHAP_EVENTS:,} "
        f"AHAP events import in <= 5 s or are refused by a "
        f"documented limit (the AHAP reader's max_events)"
    )
    if quick:
        table.notes.append(
            "--quick: a tenth of the breakpoints, the recording and the emphasis, a fiftieth of "
            "the AHAP limit, no refusal case"
        )
    return [table]
