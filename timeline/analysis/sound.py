"""A sound in, envelopes out: the analysis pipeline, run block by block in bounded memory.

The sound (mixed to mono) has its DC offset removed and is normalised (or given a gain); the
amplitude envelope is sampled every `update` seconds from the follower (envelope.py), its tail
below `tail_db` under the sound's peak expanded, and reduced (reduce.py); the frequency envelope
is the mapped spectral centroid of each frame (spectrum.py), reduced the same way; emphasis is
picked from the reduced amplitude envelope (onsets.py). Both envelopes start at 0 s and end
together at the end of the sound.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass

import numpy as np
from numba import njit

from timeline.analysis.envelope import EnvelopeFollower, expand_tail
from timeline.analysis.onsets import Frames, emphasis
from timeline.analysis.reduce import RegionReducer
from timeline.analysis.settings import DEFAULTS, AnalysisSettings
from timeline.analysis.spectrum import Features, SpectrumFrames, frequency_values
from timeline.errors import AnalysisError


@dataclass(frozen=True)
class SoundAnalysis:
    """The analysed design: breakpoints as (n, 2) arrays of (seconds, 0..1) and emphasis."""

    amplitude: np.ndarray  # (n, 2): time, amplitude
    frequency: np.ndarray  # (m, 2): time, normalised frequency
    emphasis: np.ndarray  # (k, 3): time, amplitude, frequency
    duration: float  # s: length of the sound
    rate: float  # Hz: the sound's sample rate
    peak: float  # the sound's peak level (less DC) before normalisation


@dataclass(frozen=True)
class Level:
    """What preprocessing does to every sample: subtract `offset`, then multiply by `gain`."""

    offset: float
    gain: float
    peak: float

    @classmethod
    def of(cls, mean: float, peak: float, settings: AnalysisSettings) -> Level:
        """DC removal and normalisation (or fixed gain) for a sound of this mean and peak."""
        headroom = peak - abs(mean)
        if settings.normalize:
            target = 10.0 ** (settings.level_db / 20.0)
            gain = target / headroom if headroom > 1e-9 else 0.0
        else:
            gain = 10.0 ** (settings.gain_db / 20.0)
        return cls(mean, gain, headroom)


def level_of(samples: np.ndarray, settings: AnalysisSettings) -> Level:
    """The preprocessing level of a whole mono sound held in memory."""
    if len(samples) == 0:
        return Level(0.0, 0.0, 0.0)
    return Level.of(float(np.mean(samples)), float(np.max(np.abs(samples))), settings)


def _check_rate(rate: float) -> float:
    if not (math.isfinite(rate) and rate > 0):
        raise AnalysisError(f"the sound's sample rate must be above zero, not {rate!r}")
    return float(rate)


class _AmplitudeEvents:
    """Samples the follower every `update` seconds (the output after the sample before).

    Event k (from 1) comes once ceil(k * update * rate) samples are processed; the last is the
    first to reach the end of the sound. Events are found block by block, never all at once.
    """

    def __init__(self, rate: float, update: float, length: int) -> None:
        self.step = update * rate  # samples between events
        self.rate = rate
        self.seen = 0
        k = max(1, math.ceil(length / self.step) - 1)
        while self._index(k) < length:
            k += 1
        while k > 1 and self._index(k - 1) >= length:
            k -= 1
        self.last = k
        self.needed = int(self._index(k))  # samples that must be processed to reach it

    def _index(self, k: np.ndarray | int) -> np.ndarray:
        return np.ceil(np.asarray(k) * self.step - 1e-9).astype(np.int64)

    def take(self, envelope: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.seen, self.seen + len(envelope)
        self.seen = hi
        first = max(1, int(lo / self.step))
        ks = np.arange(first, min(self.last, int(hi / self.step) + 1) + 1)
        index = self._index(ks)
        picked = index[(index > lo) & (index <= hi)]
        return picked / self.rate, np.minimum(envelope[picked - 1 - lo], 1.0)


class _FrameStore:
    """The spectrum frames' times and features, written into arrays sized once for the whole
    sound (pages never reached are never resident): hours of frames are held once, not as an
    array per block and then their concatenation."""

    def __init__(self, capacity: int) -> None:
        self.times = np.empty(capacity)
        self.features = Features(*(np.empty(capacity, np.float32) for _ in range(3)))
        self.count = 0

    def add(self, times: np.ndarray, features: Features) -> None:
        lo, hi = self.count, self.count + len(times)
        self.times[lo:hi] = times
        for name in ("flux", "strength", "power"):  # cast to float32 as they are written
            getattr(self.features, name)[lo:hi] = getattr(features, name)
        self.count = hi

    def frames(self) -> Frames:
        n = self.count
        f = self.features
        return Frames(self.times[:n], Features(f.flux[:n], f.strength[:n], f.power[:n]))


@njit(cache=True)
def _preprocess(block: np.ndarray, offset: float, gain: float, out: np.ndarray) -> bool:
    """out = (block - offset) * gain in float64; whether every sample is a finite number."""
    finite = True
    for i in range(block.shape[0]):
        v = (np.float64(block[i]) - offset) * gain
        out[i] = v
        finite &= np.isfinite(v)
    return finite


class _Scratch:
    """Float64 buffers reused from block to block (fresh pages for every block cost more than
    the arithmetic on them)."""

    def __init__(self) -> None:
        self._samples = np.empty(0)
        self._envelope = np.empty(0)

    def samples(self, n: int) -> np.ndarray:
        if len(self._samples) < n:
            self._samples = np.empty(n)
        return self._samples[:n]

    def envelope(self, n: int) -> np.ndarray:
        if len(self._envelope) < n:
            self._envelope = np.empty(n)
        return self._envelope[:n]


def analyse_blocks(
    blocks: Iterable[np.ndarray],
    rate: float,
    length: int,
    level: Level,
    settings: AnalysisSettings = DEFAULTS,
    progress: Callable[[float], None] | None = None,
) -> SoundAnalysis:
    """Analyse a mono sound of `length` samples arriving as blocks, preprocessed by `level`.

    `progress` hears the fraction of the sound analysed after each block (it may raise to stop).
    """
    rate = _check_rate(rate)
    if length <= 0:
        raise AnalysisError("the sound has no samples")
    follower = EnvelopeFollower.create(
        rate, settings.rms_window, settings.attack, settings.hold, settings.release
    )
    spectrum = SpectrumFrames.create(rate, settings, level.peak * level.gain)
    events = _AmplitudeEvents(rate, settings.update, length)
    tail = level.peak * level.gain * 10.0 ** (-settings.tail_db / 20.0)

    scratch = _Scratch()

    def envelope(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        times, values = events.take(follower.process(x, scratch.envelope(len(x))))
        return times, expand_tail(values, tail, settings.tail_ratio)

    # the resolution's error is relative to the sound's peak: a quiet sound keeps its shape too
    amp = RegionReducer(
        settings.amplitude_points_per_second, settings.minimum_score, settings.tolerance,
        settings.slack * min(1.0, level.peak * level.gain),
    )  # fmt: skip
    freq = RegionReducer(
        settings.frequency_points_per_second, settings.minimum_score, settings.tolerance,
        settings.slack,
    )  # fmt: skip
    store = _FrameStore((length + spectrum.size) // spectrum.hop + 2)  # at most one a hop

    def spectral(times: np.ndarray, centroid: np.ndarray, features: Features) -> None:
        store.add(times, features)
        ahead = times >= 0.0
        freq.add(times[ahead], frequency_values(centroid[ahead], rate, settings))

    fed = 0
    for block in blocks:
        x = scratch.samples(len(block))
        if not _preprocess(np.ascontiguousarray(block), level.offset, level.gain, x):
            raise AnalysisError("the sound holds samples that are not finite numbers")
        fed += len(x)
        amp.add(*envelope(x))
        spectral(*spectrum.process(x))
        if progress is not None:
            progress(min(fed / length, 1.0))
    if fed != length:
        raise AnalysisError(f"the sound ended after {fed} of its {length} samples")
    rest = np.zeros(max(0, events.needed - length))
    if len(rest):
        amp.add(*envelope(rest))
    spectral(*spectrum.finish())
    return _assemble(
        amp.finish(), freq.finish(), store.frames(), length / rate, rate, level, settings
    )


def _assemble(
    amp: tuple[np.ndarray, np.ndarray],
    freq: tuple[np.ndarray, np.ndarray],
    frames: Frames,
    duration: float,
    rate: float,
    level: Level,
    settings: AnalysisSettings,
) -> SoundAnalysis:
    at, av = amp
    if len(at) == 0 or at[0] != 0.0:
        at = np.concatenate([[0.0], at])
        av = np.concatenate([[av[0] if len(av) else 0.0], av])
    ft, fv = freq
    at, av, peaks, e_amp, e_freq = emphasis(at, av, frames, rate, settings)
    end = max(duration, float(at[-1]), float(ft[-1]) if len(ft) else 0.0)
    if at[-1] < end:
        at, av = np.append(at, end), np.append(av, av[-1])
    if len(ft) and ft[-1] < end:
        ft, fv = np.append(ft, end), np.append(fv, fv[-1])
    if len(ft) == 0:
        ft, fv = np.array([0.0, end]), np.zeros(2)
    return SoundAnalysis(
        amplitude=np.column_stack([at, av]),
        frequency=np.column_stack([ft, fv]),
        emphasis=np.column_stack([at[peaks], e_amp, e_freq]),
        duration=end,
        rate=rate,
        peak=level.peak,
    )


def analyse(
    samples: np.ndarray, rate: float, settings: AnalysisSettings = DEFAULTS
) -> SoundAnalysis:
    """Analyse a sound held in memory: mono (n,) or (n, channels), mixed down by the mean."""
    x = np.asarray(samples, dtype=np.float64)
    if x.ndim == 2:
        x = x.mean(axis=1)
    if x.ndim != 1:
        raise AnalysisError("a sound is a 1-D array of samples or a 2-D array (samples, channels)")
    if not np.all(np.isfinite(x)):
        raise AnalysisError("the sound holds samples that are not finite numbers")
    return analyse_blocks([x], rate, len(x), level_of(x, settings), settings)
