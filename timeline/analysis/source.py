"""A sound file read in blocks, mixed to mono: what `convert` and the editor analyse.

Any file soundfile (libsndfile) reads: WAV, FLAC, OGG, AIFF and others. A file of up to
HELD_FRAMES frames is read once, its mono blocks held for both passes (its level, then the
analysis); a longer one is read twice in blocks, so memory stays bounded for hours of sound.
A file that is not audio, or is truncated, is one clear sentence.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from pathlib import Path

import numpy as np
import soundfile as sf
from numba import njit

from timeline.analysis.settings import DEFAULTS, AnalysisSettings
from timeline.analysis.sound import Level, SoundAnalysis, analyse_blocks
from timeline.errors import AnalysisError

BLOCK_FRAMES = 1 << 16
# a file this long or shorter is read once, its mono blocks held: 2 MB of float32, about the
# analysis's own working memory (10.9 s at 48 kHz)
HELD_FRAMES = 1 << 19


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


@njit(cache=True)
def _peak(block: np.ndarray) -> tuple[float, bool]:
    """The block's largest magnitude, and whether every sample is a finite number."""
    peak = np.float32(0.0)
    finite = True
    for i in range(block.shape[0]):
        finite &= np.isfinite(block[i])
        peak = max(peak, abs(block[i]))
    return float(peak), finite


def _level(
    path: Path, blocks: Iterable[np.ndarray], settings: AnalysisSettings
) -> tuple[Level, int]:
    total, count, peak = 0.0, 0, 0.0
    for block in blocks:
        top, finite = _peak(np.ascontiguousarray(block))
        if not finite:
            raise AnalysisError(f"{path.name} holds samples that are not finite numbers")
        total += float(np.sum(block, dtype=np.float64))
        count += len(block)
        peak = max(peak, top)
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
        rate, frames = float(f.samplerate), f.frames
    held = list(mono_blocks(path)) if frames <= HELD_FRAMES else None
    level, length = _level(path, mono_blocks(path) if held is None else held, settings)
    try:
        blocks = mono_blocks(path) if held is None else held
        return analyse_blocks(blocks, rate, length, level, settings, progress)
    except sf.LibsndfileError as exc:
        reason = exc.error_string
    raise AnalysisError(f"{path.name} could not be read to its end ({reason})")
