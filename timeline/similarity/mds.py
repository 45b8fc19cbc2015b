"""Classical multidimensional scaling (Torgerson): points whose distances match a matrix."""

from __future__ import annotations

import numpy as np


def classical_mds(distance: np.ndarray, dimensions: int = 2) -> tuple[np.ndarray, float]:
    """Coordinates (n x dimensions) and the share of the variance they keep (0..1).

    Double-centre the squared distances, B = -1/2 J D^2 J, and take the eigenvectors of the
    largest eigenvalues scaled by their square roots. Negative eigenvalues (a matrix that no
    Euclidean layout fits exactly) count as lost variance.
    """
    d = np.asarray(distance, dtype=np.float64)
    n = d.shape[0]
    if n == 0:
        return np.zeros((0, dimensions)), 1.0
    centre = np.eye(n) - np.full((n, n), 1.0 / n)
    b = -0.5 * centre @ (d * d) @ centre
    values, vectors = np.linalg.eigh((b + b.T) / 2.0)
    order = np.argsort(values)[::-1]
    values, vectors = values[order], vectors[:, order]
    kept = np.clip(values[:dimensions], 0.0, None)
    coords = vectors[:, :dimensions] * np.sqrt(kept)
    if coords.shape[1] < dimensions:
        coords = np.pad(coords, ((0, 0), (0, dimensions - coords.shape[1])))
    total = float(np.abs(values).sum())
    return coords, float(kept.sum() / total) if total > 0 else 1.0
