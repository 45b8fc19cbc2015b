"""Benchmark results: tables that print as text and plots saved as PNG (matplotlib, Agg)."""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Literal, overload

if TYPE_CHECKING:  # matplotlib loads when a figure is drawn
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure


@dataclass
class Table:
    """A titled table of rows; cells are numbers or text."""

    title: str
    columns: Sequence[str]
    rows: list[Sequence[object]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    def text(self) -> str:
        """The table as aligned plain text (also valid as a Markdown table)."""
        cells = [[_cell(v) for v in row] for row in self.rows]
        widths = [max([len(c)] + [len(r[i]) for r in cells]) for i, c in enumerate(self.columns)]
        out = [f"## {self.title}", "", _line(self.columns, widths)]
        out.append("|" + "|".join("-" * (w + 2) for w in widths) + "|")
        out += [_line(r, widths) for r in cells]
        out += [""] + [f"- {n}" for n in self.notes] if self.notes else []
        return "\n".join(out)


def _line(cells: Sequence[str], widths: list[int]) -> str:
    return "| " + " | ".join(v.rjust(w) for v, w in zip(cells, widths, strict=True)) + " |"


def _cell(value: object) -> str:
    if isinstance(value, float):
        if value == 0 or not math.isfinite(value):
            return f"{value:g}"
        if abs(value) >= 1e5 or abs(value) < 1e-3:
            return f"{value:.3g}"
        return f"{value:.4g}"
    return str(value)


def _best(fn: Callable[[], object], repeat: int, clock: Callable[[], float]) -> float:
    best = math.inf
    for _ in range(repeat):
        start = clock()
        fn()
        best = min(best, clock() - start)
    return best


def best_time(fn: Callable[[], object], repeat: int) -> float:
    """Smallest wall time of `repeat` calls (seconds): the least disturbed run."""
    return _best(fn, repeat, time.perf_counter)


def best_cpu_time(fn: Callable[[], object], repeat: int) -> float:
    """Smallest CPU time of this process (all its threads) over `repeat` calls (seconds): what a
    call costs, whatever else the machine runs meanwhile."""
    return _best(fn, repeat, time.process_time)


@overload
def figure(
    width: float = 7.0, height: float = 4.5, ncols: Literal[1] = 1
) -> tuple[Figure, Axes]: ...
@overload
def figure(width: float, height: float, ncols: int) -> tuple[Figure, list[Axes]]: ...


def figure(
    width: float = 7.0, height: float = 4.5, ncols: int = 1
) -> tuple[Figure, Axes | list[Axes]]:
    """A new matplotlib figure and axes (one, or a list of ncols) drawn with the Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, ncols, figsize=(width, height), dpi=110, squeeze=False)
    for ax in axes[0]:
        ax.grid(True, which="both", alpha=0.3)
    return fig, (axes[0][0] if ncols == 1 else list(axes[0]))


def plain_log_axis(axis) -> None:
    """Label a log axis with plain numbers (2, 5, 10) instead of powers of ten."""
    from matplotlib.ticker import FuncFormatter

    fmt = FuncFormatter(lambda v, _: f"{v:g}")
    axis.set_major_formatter(fmt)
    axis.set_minor_formatter(fmt)


def save(fig, out: Path, name: str) -> Path:
    """Write the figure as out/name.png and close it."""
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    path = out / f"{name}.png"
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return path
