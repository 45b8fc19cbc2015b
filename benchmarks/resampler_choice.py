"""Which resampler should bring imported recordings to the project rate? Speed and quality.

Compares soxr (HQ, VHQ), scipy.signal.resample_poly (default Kaiser window) and linear
interpolation (np.interp) converting 10 s of 44.1 kHz and 48 kHz audio to the 10 kHz knob rate:
  - time: median of repeated runs;
  - passband: gain of a sine at 0.9 x the output Nyquist (dB, 0 is ideal);
  - stop-band rejection: level of a full-scale sine above the output Nyquist that aliases back
    (dB below full scale; more negative is better);
  - SNR: a band-limited multi-tone signal against its exact values at the output rate (dB).

Run: python benchmarks/resampler_choice.py
"""

from __future__ import annotations

import time
from fractions import Fraction

import numpy as np
import soxr
from scipy.signal import resample_poly

OUT_RATE = 10_000
SECONDS = 10.0


def _linear(x: np.ndarray, rate_in: int, rate_out: int) -> np.ndarray:
    n = int(len(x) * rate_out / rate_in)
    return np.interp(np.arange(n) * rate_in / rate_out, np.arange(len(x)), x)


def _poly(x: np.ndarray, rate_in: int, rate_out: int) -> np.ndarray:
    f = Fraction(rate_out, rate_in)
    return resample_poly(x, f.numerator, f.denominator)


METHODS = {
    "soxr HQ": lambda x, a, b: soxr.resample(x, a, b, quality="HQ"),
    "soxr VHQ": lambda x, a, b: soxr.resample(x, a, b, quality="VHQ"),
    "resample_poly": _poly,
    "linear (np.interp)": _linear,
}


def _tone(freq: float, rate: float, n: int) -> np.ndarray:
    return np.sin(2 * np.pi * freq * np.arange(n) / rate)


def _level_at(y: np.ndarray, freq: float, rate: float) -> float:
    """Amplitude of the component at freq (least squares on the middle of the signal)."""
    core = slice(len(y) // 4, 3 * len(y) // 4)
    t = np.arange(len(y))[core] / rate
    basis = np.column_stack([np.sin(2 * np.pi * freq * t), np.cos(2 * np.pi * freq * t)])
    coef, *_ = np.linalg.lstsq(basis, y[core], rcond=None)
    return float(np.hypot(*coef))


def _db(x: float) -> float:
    return 20 * np.log10(max(x, 1e-12))


def measure(rate_in: int) -> list[tuple[str, float, float, float, float]]:
    n = int(SECONDS * rate_in)
    nyq = OUT_RATE / 2
    rows = []
    rng = np.random.default_rng(0)
    freqs = rng.uniform(20, 0.8 * nyq, 12)
    phases = rng.uniform(0, 2 * np.pi, 12)

    def tones(rate: float, count: int) -> np.ndarray:
        t = np.arange(count) / rate
        return sum(np.sin(2 * np.pi * f * t + p) for f, p in zip(freqs, phases, strict=True)) / 12

    music = tones(rate_in, n)
    for name, fn in METHODS.items():
        times = []
        for _ in range(5):
            t0 = time.perf_counter()
            fn(music, rate_in, OUT_RATE)
            times.append(time.perf_counter() - t0)
        y = fn(music, rate_in, OUT_RATE)
        exact = tones(OUT_RATE, len(y))
        core = slice(len(y) // 10, 9 * len(y) // 10)
        snr = 10 * np.log10(np.mean(exact[core] ** 2) / np.mean((y[core] - exact[core]) ** 2))
        passband = _db(
            _level_at(fn(_tone(0.9 * nyq, rate_in, n), rate_in, OUT_RATE), 0.9 * nyq, OUT_RATE)
        )
        above = 1.3 * nyq  # aliases to 0.7 x Nyquist
        alias = OUT_RATE - above
        rejection = _db(_level_at(fn(_tone(above, rate_in, n), rate_in, OUT_RATE), alias, OUT_RATE))
        rows.append((name, 1e3 * float(np.median(times)), passband, rejection, float(snr)))
    return rows


def main() -> None:
    for rate_in in (44_100, 48_000):
        print(f"\n{SECONDS:g} s at {rate_in} Hz -> {OUT_RATE} Hz")
        print(f"{'method':20} {'time ms':>8} {'0.9 Nyq dB':>11} {'alias dB':>9} {'SNR dB':>7}")
        for name, ms, passband, rejection, snr in measure(rate_in):
            print(f"{name:20} {ms:8.2f} {passband:11.2f} {rejection:9.1f} {snr:7.1f}")


if __name__ == "__main__":
    main()
