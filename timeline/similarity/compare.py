"""Compare icons: features, the distance matrix, the 2-D map and the pairs too alike."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from timeline.errors import HapticTimelineError
from timeline.limits.design import sample
from timeline.model import Project
from timeline.similarity.distance import ALIKE, Parts, distances
from timeline.similarity.features import Features, features
from timeline.similarity.mds import classical_mds


@dataclass(frozen=True, eq=False)
class Comparison:
    """Icons by name, their distances (JNDs), each pair's parts, and the MDS map."""

    names: list[str]
    features: list[Features]
    matrix: np.ndarray
    parts: Parts  # parts[i][j]: the pair's {feature: JNDs}
    coords: np.ndarray  # n x 2
    explained: float  # share of the variance the map keeps

    def too_alike(self) -> list[tuple[str, str, float]]:
        """Pairs closer than ALIKE JNDs, closest first."""
        n = len(self.names)
        pairs = [
            (self.names[i], self.names[j], float(self.matrix[i, j]))
            for i in range(n)
            for j in range(i + 1, n)
            if self.matrix[i, j] < ALIKE
        ]
        return sorted(pairs, key=lambda p: p[2])

    def as_dict(self) -> dict[str, object]:
        """A JSON-ready mapping."""
        return {
            "icons": self.names,
            "distance": self.matrix.round(6).tolist(),
            "parts": {
                f"{self.names[i]} | {self.names[j]}": self.parts[i][j]
                for i in range(len(self.names))
                for j in range(i + 1, len(self.names))
            },
            "map": self.coords.round(6).tolist(),
            "map_explains": self.explained,
            "too_alike": [list(p) for p in self.too_alike()],
            "alike_below": ALIKE,
            "unit": "JND",
        }


def compare(icons: list[tuple[str, Project]], quality: str = "normal") -> Comparison:
    """Measure each icon, the distances between them and the map that shows them."""
    if len(icons) < 2:
        raise HapticTimelineError(
            "compare needs two icons: give two projects, or one with two saved variants"
        )
    names = [name for name, _ in icons]
    if len(set(names)) < len(names):
        raise HapticTimelineError(f"two icons share a name ({', '.join(names)}): rename one")
    measured = [features(name, sample(project, None, quality)) for name, project in icons]
    matrix, parts = distances(measured)
    coords, explained = classical_mds(matrix, 2)
    return Comparison([f.name for f in measured], measured, matrix, parts, coords, explained)
