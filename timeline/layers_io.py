"""Write rendered layers to .csv, .npz or .wav (the `render` verb's outputs)."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from timeline.errors import HapticTimelineError

LAYER_SUFFIXES = (".csv", ".npz", ".wav")


def axis_column(axis: str) -> str:
    """The first column's name: time in seconds, or angle in radians."""
    return "time" if axis == "time" else "angle"


def write_layers(
    layers: dict[str, np.ndarray], path: str | os.PathLike, start: float, rate: float, axis: str
) -> None:
    """Write layers (kind id -> SI samples) with their axis to a CSV, NPZ or WAV file."""
    path = Path(path)
    suffix = path.suffix.lower()
    n = len(next(iter(layers.values()))) if layers else 0
    positions = start + np.arange(n) / rate
    if suffix == ".csv":
        columns = [axis_column(axis), *layers]
        table = np.column_stack([positions, *layers.values()]) if n else np.zeros((0, len(columns)))
        np.savetxt(path, table, delimiter=",", header=",".join(columns), comments="", fmt="%.17g")
    elif suffix == ".npz":
        np.savez(path, **{axis_column(axis): positions}, rate=np.float64(rate), **layers)
    elif suffix == ".wav":
        import soundfile

        if axis != "time":
            raise HapticTimelineError("a position-axis project cannot be written as audio")
        if not layers:
            raise HapticTimelineError("the project has no layers to write")
        data = np.column_stack(list(layers.values())).astype(np.float64)
        soundfile.write(path, data, int(round(rate)), subtype="DOUBLE")
    else:
        raise HapticTimelineError(
            f"cannot write {path.name}: the render output must end in {', '.join(LAYER_SUFFIXES)}"
        )
