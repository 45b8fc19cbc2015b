"""Render time of the example projects in projects/ (fresh mixer, and again from its caches)."""

from __future__ import annotations

from pathlib import Path

from timeline.bench.report import Table, best_time
from timeline.files.projectfile import load
from timeline.rendering.mixer import Mixer

NAME = "examples"
SUMMARY = "render time of the example projects (needs the source tree's projects/)"
PROJECTS = Path(__file__).resolve().parents[2] / "projects"


def run(quick: bool, out: Path) -> list[Table]:
    table = Table(
        "Example projects: full render at the project's rate, normal quality",
        ["project", "axis", "samples", "fresh mixer ms", "cached ms"],
    )
    repeat = 3 if quick else 9
    paths = sorted(PROJECTS.glob("*.htl"))
    for path in paths:
        project = load(path)
        fresh = best_time(lambda p=project: Mixer().render(p), repeat)
        mixer = Mixer()
        layers = mixer.render(project)
        cached = best_time(lambda p=project, m=mixer: m.render(p), repeat)
        samples = sum(len(v) for v in layers.values())
        table.rows.append([path.name, project.axis, samples, 1e3 * fresh, 1e3 * cached])
    if not paths:
        table.notes.append(f"no example projects found in {PROJECTS} (an installed copy)")
    table.notes.append("cached: the same project again, every clip and block from the caches")
    return [table]
