"""Labels for map points that would print on top of each other (shared by the PNG and the GUI)."""

from __future__ import annotations

import numpy as np


def label_groups(names: list[str], xy: np.ndarray) -> list[tuple[list[str], tuple[float, float]]]:
    """Points closer than 3 % of the map's span share one label; groups sorted left to right.

    Draw the n-th group's label above its point for even n and below for odd n, so neighbours
    in x do not overwrite each other.
    """
    span = float(max(xy.max(axis=0) - xy.min(axis=0))) if len(names) else 0.0
    near = 0.03 * span if span > 0 else 1e-9
    groups: list[tuple[list[str], tuple[float, float]]] = []
    for name, (x, y) in zip(names, xy, strict=True):
        for members, (gx, gy) in groups:
            if abs(x - gx) < near and abs(y - gy) < near:
                members.append(name)
                break
        else:
            groups.append(([name], (float(x), float(y))))
    return sorted(groups, key=lambda g: g[1])
