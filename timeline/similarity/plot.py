"""The similarity map as a PNG (matplotlib, no Qt)."""

from __future__ import annotations

from timeline.files.atomic import write_atomically
from timeline.similarity.compare import Comparison
from timeline.similarity.distance import ALIKE
from timeline.similarity.labels import label_groups


def draw_map(ax, comparison: Comparison) -> None:  # noqa: ANN001 - a matplotlib Axes
    """Points for icons, red lines between pairs too alike, axes in JNDs."""
    xy = comparison.coords
    index = {name: i for i, name in enumerate(comparison.names)}
    for a, b, d in comparison.too_alike():
        i, j = index[a], index[b]
        ax.plot(xy[[i, j], 0], xy[[i, j], 1], color="#c0392b", lw=1.5, zorder=1)
        ax.annotate(f"{d:.2f}", xy[[i, j]].mean(axis=0), color="#c0392b", fontsize=8)
    ax.scatter(xy[:, 0], xy[:, 1], s=50, color="#2c3e50", zorder=2)
    groups = label_groups(comparison.names, xy)
    for n, (names, (x, y)) in enumerate(groups):  # neighbours in x label above, then below
        ax.annotate(" / ".join(names), (x, y), xytext=(5, 5 if n % 2 == 0 else -13),
                    textcoords="offset points", fontsize=9)  # fmt: skip
    ax.set_xlabel("MDS 1 [JND]")
    ax.set_ylabel("MDS 2 [JND]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    ax.set_title(
        f"{len(comparison.names)} icons; map keeps {100 * comparison.explained:.0f} % of the "
        f"variance; red: closer than {ALIKE:g} JND",
        fontsize=9,
    )


def plot_map(comparison: Comparison, path: str) -> None:
    """Write the map to a PNG."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib import pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 6))
    draw_map(ax, comparison)
    fig.tight_layout()
    write_atomically(path, lambda tmp: fig.savefig(tmp, dpi=110, format="png"))
    plt.close(fig)
