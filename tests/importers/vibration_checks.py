"""The .haptic and AHAP checks the corpus tests and the tests/data tests share (one file each)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from importers import ahap
from importers.ahap_playback import playback
from timeline import edits
from timeline.edits.vibration import VibrationDesign, design_of
from timeline.files import exporting, importing

AHAP_AMPLITUDE_BOUND = 0.03  # .haptic -> AHAP -> design, away from steps (measured 0.010)
TRANSIENT_BOUND = 0.05  # an exported transient's felt intensity, relative to its design
PLAYBACK_BOUND = 0.01 + 1e-9  # an exported AHAP's continuous amplitude and frequency vs design


def read_project(path: Path):
    """A new project holding the file's import."""
    project, _ = importing.import_file(edits.new_project(templates=False), path)
    return project


def export_doc(project, path: Path) -> dict:
    """Export the project to `path` and return the written JSON."""
    exporting.export_project(project, path)
    return json.loads(path.read_text())


def away_from_steps(design: VibrationDesign, grid: np.ndarray) -> np.ndarray:
    """Grid points more than 2 ms from a step (two amplitude breakpoints at one time)."""
    steps = [
        a for (a, _), (b, _) in zip(design.amplitude, design.amplitude[1:], strict=False) if a == b
    ]
    keep = np.ones(len(grid), dtype=bool)
    for s in steps:
        keep &= np.abs(grid - s) > 0.002
    return keep


def player(path: Path) -> tuple[dict, list, list]:
    """An AHAP's control curves as the player follows them, its control points and transients."""
    doc = json.loads(path.read_text())
    events, controls, _ = ahap._entries(doc["Pattern"], path.name)
    curves = {}
    for pid, default in (("HapticIntensityControl", 1.0), ("HapticSharpnessControl", 0.0)):
        control = ahap._Control(default)
        for _, start, points in sorted((c for c in controls if c[0] == pid), key=lambda c: c[1]):
            control.set_from(start, points)
        curves[pid] = control.freeze()
    transients = sorted(
        (e["time"], e["intensity"], e["sharpness"])
        for e in events
        if e["type"] == "HapticTransient"
    )
    return curves, controls, transients


def check_written_back_exactly(path: Path, tmp_path: Path) -> None:
    """An unedited .haptic import exported as .haptic: the same breakpoints and emphasis."""
    source = json.loads(path.read_text())["signals"]["continuous"]["envelopes"]
    written = export_doc(read_project(path), tmp_path / "out.haptic")["signals"]["continuous"]
    amp0, amp1 = source["amplitude"], written["envelopes"]["amplitude"]
    assert len(amp1) == len(amp0), path.name  # within 5 %: the same count
    for b0, b1 in zip(amp0, amp1, strict=True):
        assert b1["time"] == b0["time"] and abs(b1["amplitude"] - b0["amplitude"]) <= 0.005
        if "emphasis" in b0:
            e0, e1 = b0["emphasis"], b1["emphasis"]
            assert e1["frequency"] == e0["frequency"], path.name
            assert e1["amplitude"] == max(e0["amplitude"], b0["amplitude"]), path.name
    assert written["envelopes"].get("frequency", []) == [
        {"time": b["time"], "frequency": b["frequency"]} for b in source.get("frequency", [])
    ], path.name


def check_envelopes_kept_through_ahap(path: Path, tmp_path: Path) -> None:
    """A .haptic import exported as AHAP and read back: envelopes within the bound, the same
    emphasis."""
    design = design_of(read_project(path))
    export_doc(read_project(path), tmp_path / "out.ahap")
    back = design_of(read_project(tmp_path / "out.ahap"))
    grid = np.linspace(design.amplitude[0][0], design.amplitude[-1][0], 20_001)
    keep = away_from_steps(design, grid)
    amp_error = np.abs(design.amplitude_at(grid) - back.amplitude_at(grid))[keep].max()
    assert amp_error <= AHAP_AMPLITUDE_BOUND, path.name
    if design.frequency:
        f_error = np.abs(design.frequency_at(grid) - back.frequency_at(grid))[keep].max()
        assert f_error <= AHAP_AMPLITUDE_BOUND, path.name
    assert [(e.time, e.frequency) for e in back.emphasis] == [
        (e.time, e.frequency) for e in design.emphasis
    ]
    assert all(
        abs(a.amplitude - b.amplitude) < 1e-9
        for a, b in zip(design.emphasis, back.emphasis, strict=True)
    )


def playback_errors(design: VibrationDesign, doc: dict, convention: str) -> tuple[float, ...]:
    """How far an exported AHAP plays from its design, as Core Haptics documents playing it
    (importers.ahap_playback): the worst transient intensity error relative to its design, the
    worst transient sharpness error, the worst continuous amplitude (intensity squared) error
    and the worst frequency error where the envelope sounds (frequency = sharpness, or its
    square in Meta's convention)."""
    played = playback(doc)
    want = sorted((e.time, np.sqrt(e.amplitude), e.frequency) for e in design.emphasis)
    assert [t for t, _, _ in played.transients] == [t for t, _, _ in want]
    intensity = max(
        [abs(p[1] - w[1]) / w[1] for p, w in zip(played.transients, want, strict=True) if w[1]]
        + [0.0]
    )
    sharp = max([abs(p[2] - w[2]) for p, w in zip(played.transients, want, strict=True)] + [0.0])
    if len(design.amplitude) < 2:
        return intensity, sharp, 0.0, 0.0
    start, end = design.amplitude[0][0], design.amplitude[-1][0]
    n = 20_000
    grid = start + (end - start) * (np.arange(n) + 0.37) / n  # never on a breakpoint
    level, heard = played.continuous_at(grid)
    amplitude = float(np.abs(level**2 - design.amplitude_at(grid)).max())
    sounding = level > 0
    felt = heard**2 if convention == "sqrt" else heard
    frequency = np.abs(felt - design.frequency_at(grid))[sounding]
    return intensity, sharp, amplitude, float(frequency.max()) if len(frequency) else 0.0


def check_ahap_round_trip(path: Path, tmp_path: Path) -> None:
    """An AHAP imported and exported: the export plays the imported design (transients within
    TRANSIENT_BOUND, the continuous amplitude and frequency within PLAYBACK_BOUND) and keeps
    the transients' times."""
    exported = tmp_path / "out.ahap"
    project = read_project(path)
    doc = export_doc(project, exported)
    design = design_of(project)
    convention = "linear" if doc["Metadata"]["Description"] == ahap.LINEAR_NOTE else "sqrt"
    intensity, sharp, amplitude, frequency = playback_errors(design, doc, convention)
    assert intensity <= TRANSIENT_BOUND and sharp <= 1e-9, (path.name, intensity, sharp)
    assert amplitude <= PLAYBACK_BOUND and frequency <= PLAYBACK_BOUND, (path.name, amplitude)
