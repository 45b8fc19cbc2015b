"""A sound file read in blocks, mixed to mono: what `convert` and the editor analyse.

Any file soundfile (libsndfile) reads: WAV, FLAC, OGG, AIFF and others. The file is read twice
in blocks (once for its level, once for the analysis), so memory stays bounded for hours of
sound. A file that is not audio, or is truncated, is one clear sentence.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path

import numpy as np
import soundfile as sf

from timeline.analysis.settings import DEFAULTS, AnalysisSettings
from timeline.analysis.sound import Level, SoundAnalysis, analyse_blocks
from timeline.errors import AnalysisError

BLOCK_FRAMES = 1 << 16


def _open(path: Path) -> sf.SoundFile:
    try:
        return sf.SoundFile(path)
    except sf.LibsndfileError as exc:
        reason = str(exc.error_string).rstrip(".")
    except (RuntimeError, TypeError, ValueError) as exc:
        reason = str(exc)
    raise AnalysisError(f"{path.name} is not a sound file that can be read ({reason})")


def mono_blocks(path: Path) -> Iterator[np.ndarray]:
    """The file's samples as float32 mono blocks (channels mixed by their mean)."""
    with _open(path) as f:
        mix = np.full(f.channels, 1.0 / f.channels, dtype=np.float32)
        for block in f.blocks(BLOCK_FRAMES, dtype="float32", always_2d=True):
            yield block @ mix if f.channels > 1 else block[:, 0]


def mono_samples(path: Path) -> np.ndarray:
    """The file's mono mix as one read-only float32 array, filled block by block (no list of
    blocks, no second copy): a tile keeps it as it is."""
    with _open(path) as f:
        frames = f.frames
    out = np.empty(frames, dtype=np.float32)
    filled = 0
    for block in mono_blocks(path):
        if filled + len(block) > frames:
            raise AnalysisError(f"{path.name} holds more samples than it declares")
        out[filled : filled + len(block)] = block
        filled += len(block)
    if filled != frames:
        raise AnalysisError(f"{path.name} ended after {filled} of its {frames} samples")
    out.setflags(write=False)
    return out


def _level(path: Path, settings: AnalysisSettings) -> tuple[Level, int]:
    total, count, peak = 0.0, 0, 0.0
    for block in mono_blocks(path):
        if not np.all(np.isfinite(block)):
            raise AnalysisError(f"{path.name} holds samples that are not finite numbers")
        total += float(np.sum(block, dtype=np.float64))
        count += len(block)
        peak = max(peak, float(np.max(np.abs(block))) if len(block) else 0.0)
    if count == 0:
        raise AnalysisError(f"{path.name} holds no audio samples")
    return Level.of(total / count, peak, settings), count


def analyse_file(
    path: str | Path,
    settings: AnalysisSettings = DEFAULTS,
    progress: Callable[[float], None] | None = None,
) -> SoundAnalysis:
    """Analyse a sound file (see timeline.analysis.sound) in bounded memory.

    `progress` hears the fraction done (0..1) after each block; it may raise to stop.
    """
    path = Path(path)
    if not path.is_file():
        raise AnalysisError(f"there is no sound file {path}")
    with _open(path) as f:
        rate = float(f.samplerate)
    level, length = _level(path, settings)
    try:
        return analyse_blocks(mono_blocks(path), rate, length, level, settings, progress)
    except sf.LibsndfileError as exc:
        reason = exc.error_string
    raise AnalysisError(f"{path.name} could not be read to its end ({reason})")
