"""Spectral features per frame: the centroid (for the frequency envelope) and the flux (emphasis).

Frames are `fft_size` samples under a periodic Hann window, one every `hop` samples; the first
frames reach back before the sound (as zeros) and the last are centred on its end. A frame's
time is its centre. The centroid is taken over the bins below `centroid_lowpass` and reported as
a fraction of the Nyquist frequency; where those bins hold too little energy it is 0. The flux is
the summed rise of each bin's magnitude since the previous frame (it scores an emphasis's
sharpness); the onset strength is the same sum over bands of BAND bins, log-compressed as
log(1 + C m) with m relative to the sound's peak, so the same sound louder or softer gives the
same onsets (emphasis times, onsets.py); it is taken only when the adaptive emphasis uses it.
Frames are windowed, transformed and measured FRAME_CHUNK at a time in buffers kept from chunk to
chunk (fresh memory for every block's frames cost more than the arithmetic on them).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import cast

import numpy as np
import scipy.fft
from numba import njit

from timeline.analysis.settings import AnalysisSettings

QUIET_BIN_MAGNITUDE = 0.3  # mean magnitude per kept bin below which the centroid is 0
# Frames are windowed and transformed in float32 (magnitudes summed in float64): measured twice as
# fast as float64, and the frequency envelope and flux it gives differ by under 1e-5 (tested).
FRAME_DTYPE = np.float32
COMPRESSION = 1.0  # C in log(1 + C * magnitude / peak) of the onset strength
BAND = 8  # bins summed into one band of the onset strength (a log per band, not per bin)
FRAME_CHUNK = 64  # frames windowed, transformed and measured at once (their buffers stay in cache)


@njit(cache=True)
def _windowed(data: np.ndarray, ends: np.ndarray, window: np.ndarray, out: np.ndarray) -> None:
    """out[j] = data[e : e + len(window)] times the window, for each e = ends[j]."""
    size = window.shape[0]
    for j in range(ends.shape[0]):
        e = ends[j]
        for k in range(size):
            out[j, k] = data[e + k] * window[k]


@njit(cache=True, fastmath=True)
def _features(
    spectra: np.ndarray,
    half: int,
    lowpass: int,
    compression: float,
    previous: np.ndarray,
    flux: np.ndarray,
    strength: np.ndarray,
    power: np.ndarray,
    energy: np.ndarray,
    weighted: np.ndarray,
    logs: bool,
) -> None:
    """Per frame of complex spectra, into the arrays given: flux (summed magnitude rise), onset
    strength (summed rise of the log of each BAND bins' magnitude), power (summed squared
    magnitude), and the magnitude sum and bin-weighted sum below `lowpass`; `previous` (the
    last frame's magnitudes, then its bands' logs) is updated in place. Without `logs` the
    onset strength (a log per band, the costliest part) is left as it is. Loops without
    branches, so they compile to vector code."""
    n = spectra.shape[0]
    bands = (half + BAND - 1) // BAND
    row = np.empty(half, dtype=previous.dtype)
    for j in range(n):
        for k in range(half):
            c = spectra[j, k]
            row[k] = np.sqrt(c.real * c.real + c.imag * c.imag)
        rise = 0.0
        squares = 0.0
        for k in range(half):
            m = row[k]
            squares += m * m
            rise += max(m - previous[0, k], 0.0)
            previous[0, k] = m
        total = 0.0
        moment = 0.0
        for k in range(lowpass):
            total += row[k]
            moment += k * row[k]
        flux[j], power[j], energy[j], weighted[j] = rise, squares, total, moment
        if not logs:
            continue
        log_rise = 0.0
        for b in range(bands):
            band = 0.0
            for k in range(b * BAND, min(half, (b + 1) * BAND)):
                band += row[k]
            level = np.log1p(compression * band)
            log_rise += max(level - previous[1, b], 0.0)
            previous[1, b] = level
        strength[j] = log_rise


@dataclass(frozen=True)
class Features:
    """Per-frame onset features: flux, onset strength and power (float32, 12 bytes a frame)."""

    flux: np.ndarray
    strength: np.ndarray
    power: np.ndarray

    @classmethod
    def empty(cls) -> Features:
        return cls(np.empty(0, np.float32), np.empty(0, np.float32), np.empty(0, np.float32))


@dataclass
class SpectrumFrames:
    """Frame-by-frame spectral analysis carried from block to block."""

    rate: float
    size: int
    hop: int
    lowpass_bin: int
    compression: float  # C / the sound's peak
    window: np.ndarray
    history: np.ndarray  # the last `size` samples seen (zeros before the sound)
    previous: np.ndarray  # the last frame's magnitudes (row 0) and their logs (row 1)
    pending: int  # samples seen since the last frame ended
    onsets: bool  # whether the onset strength is used (adaptive emphasis): 0 when not
    frames: np.ndarray  # FRAME_CHUNK windowed frames, reused from chunk to chunk
    buffer: np.ndarray  # the history and a block as frame samples, reused from block to block
    seen: int = 0  # samples fed so far

    @classmethod
    def create(cls, rate: float, settings: AnalysisSettings, peak: float = 1.0) -> SpectrumFrames:
        """Frames for a sound at `rate` whose samples reach `peak` (after preprocessing)."""
        size, half = settings.fft_size, settings.fft_size // 2
        lowpass = min(half, max(2, math.ceil(half * settings.centroid_lowpass / (rate / 2.0))))
        n = np.arange(size)
        window = (0.5 - 0.5 * np.cos(2.0 * np.pi * n / size)).astype(FRAME_DTYPE)
        history, previous = np.zeros(size, FRAME_DTYPE), np.zeros((2, half), FRAME_DTYPE)
        compression = COMPRESSION / peak if peak > 1e-12 else COMPRESSION
        frames = np.empty((FRAME_CHUNK, size), FRAME_DTYPE)
        return cls(
            rate, size, settings.hop, lowpass, compression, window, history, previous, 0,
            settings.emphasis and settings.adaptive and settings.sensitivity > 0, frames,
            np.empty(0, FRAME_DTYPE),
        )  # fmt: skip

    def process(self, block: np.ndarray) -> tuple[np.ndarray, np.ndarray, Features]:
        """Times (s), centroids (fraction of Nyquist) and onset features of the frames that end
        in block."""
        data = self._data(block)  # the history, then the block
        first = self.hop - self.pending  # samples into the block where the next frame ends
        ends = np.arange(first, len(block) + 1, self.hop)  # frame j covers data[e : e + size]
        self.pending = (self.pending + len(block)) % self.hop
        self.history[:] = data[len(block) :]
        if len(ends) == 0:
            self.seen += len(block)
            return np.empty(0), np.empty(0), Features.empty()
        times = (self.seen + ends - self.size / 2.0) / self.rate
        self.seen += len(block)
        half = self.size // 2
        n = len(ends)
        flux, strength, power = np.zeros(n), np.zeros(n), np.zeros(n)
        energy, weighted = np.zeros(n), np.zeros(n)
        for lo in range(0, n, FRAME_CHUNK):
            hi = min(n, lo + FRAME_CHUNK)
            frames = self.frames[: hi - lo]
            _windowed(data, ends[lo:hi], self.window, frames)
            # scipy.fft is unannotated: pyright sees its dispatcher's tuple, not the array
            spectra = cast(np.ndarray, scipy.fft.rfft(frames, axis=1, workers=1))
            _features(spectra, half, self.lowpass_bin, self.compression, self.previous,
                      flux[lo:hi], strength[lo:hi], power[lo:hi], energy[lo:hi],
                      weighted[lo:hi], self.onsets)  # fmt: skip
        loud = energy >= QUIET_BIN_MAGNITUDE * (self.lowpass_bin - 1)
        centroid = np.where(loud, weighted / np.maximum(energy, 1e-300) / half, 0.0)
        return times, centroid, Features(flux, strength, power)

    def _data(self, block: np.ndarray) -> np.ndarray:
        """The history followed by the block as frame samples, in a buffer kept for the next."""
        n = self.size + len(block)
        if len(self.buffer) < n:
            self.buffer = np.empty(n, FRAME_DTYPE)
        data = self.buffer[:n]
        data[: self.size] = self.history
        data[self.size :] = block
        return data

    def finish(self) -> tuple[np.ndarray, np.ndarray, Features]:
        """The frames that reach past the end of the sound, up to one centred on its end."""
        return self.process(np.zeros(self.size // 2))


def frequency_values(centroid: np.ndarray, rate: float, settings: AnalysisSettings) -> np.ndarray:
    """Map centroids (fraction of Nyquist) from the Hz range to the output range, clipped 0..1."""
    nyquist = rate / 2.0
    lo, hi = settings.frequency_min / nyquist, settings.frequency_max / nyquist
    scaled = (centroid - lo) / (hi - lo)
    out = settings.output_min + scaled * (settings.output_max - settings.output_min)
    return np.clip(out, 0.0, 1.0)
