"""Which resampler should bring imported recordings to the knob's rate? Speed and quality.

soxr (HQ, VHQ), scipy.signal.resample_poly (default Kaiser window) and linear interpolation
(np.interp, the floor) converting 44.1 kHz and 48 kHz audio to 10 kHz:
  - time: median of repeated runs;
  - passband: gain of a sine at 0.9 x the output Nyquist (dB, 0 is ideal);
  - stop-band rejection: level of a full-scale sine at 1.3 x the output Nyquist that aliases
    back (dB below full scale; more negative is better);
  - SNR: a band-limited multi-tone signal against its exact values at the output rate (dB).
Then the direct windowed sinc that upsamples slow recordings by huge ratios (where soxr's margins
would outnumber the output): a 2,000 s render at 10 kHz of a recording at 0.001 and 0.1 Hz, CPU
time, and its error against the windowed sincs summed exactly.
"""

from __future__ import annotations

import time
from fractions import Fraction
from functools import partial
from pathlib import Path

import numpy as np
import soxr
from scipy.signal import resample_poly

from timeline.bench.report import Table, best_cpu_time, figure, plain_log_axis, save
from timeline.signal.render_presets import preset
from timeline.signal.resample import sample_grid

NAME = "resampler"
SUMMARY = "resampler choice: soxr vs resample_poly vs linear, speed and quality"
OUT_RATE = 10_000


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
    return float(20 * np.log10(max(x, 1e-12)))


def measure(
    rate_in: int, seconds: float, repeat: int
) -> list[tuple[str, float, float, float, float]]:
    """Rows: method, time ms, passband dB, alias dB, SNR dB."""
    n = int(seconds * rate_in)
    nyq = OUT_RATE / 2
    rng = np.random.default_rng(0)
    freqs = rng.uniform(20, 0.8 * nyq, 12)
    phases = rng.uniform(0, 2 * np.pi, 12)

    def tones(rate: float, count: int) -> np.ndarray:
        t = np.arange(count) / rate
        waves = (np.sin(2 * np.pi * f * t + p) for f, p in zip(freqs, phases, strict=True))
        return sum(waves, np.zeros(count)) / 12

    music = tones(rate_in, n)
    rows = []
    for name, fn in METHODS.items():
        times = []
        for _ in range(repeat):
            start = time.perf_counter()
            fn(music, rate_in, OUT_RATE)
            times.append(time.perf_counter() - start)
        y = fn(music, rate_in, OUT_RATE)
        exact = tones(OUT_RATE, len(y))
        core = slice(len(y) // 10, 9 * len(y) // 10)
        snr = 10 * np.log10(np.mean(exact[core] ** 2) / np.mean((y[core] - exact[core]) ** 2))
        passband = _level_at(
            fn(_tone(0.9 * nyq, rate_in, n), rate_in, OUT_RATE), 0.9 * nyq, OUT_RATE
        )
        above = 1.3 * nyq  # aliases to 0.7 x Nyquist
        alias = _level_at(
            fn(_tone(above, rate_in, n), rate_in, OUT_RATE), OUT_RATE - above, OUT_RATE
        )
        rows.append((name, 1e3 * float(np.median(times)), _db(passband), _db(alias), float(snr)))
    return rows


def run(quick: bool, out: Path) -> list[Table]:
    seconds = 2.0 if quick else 10.0
    tables = []
    points: dict[str, list[tuple[float, float]]] = {}
    for rate_in in (44_100, 48_000):
        table = Table(
            f"Resamplers: {seconds:g} s at {rate_in} Hz -> {OUT_RATE} Hz (median of 5)",
            ["method", "time ms", "0.9 Nyquist dB", "alias dB", "SNR dB"],
        )
        rows = measure(rate_in, seconds, 5)
        table.rows.extend(rows)
        for name, ms, _, _, snr in rows:
            points.setdefault(name, []).append((ms, snr))
        tables.append(table)
    tables[-1].notes.append(
        "normal and exact use soxr (HQ, VHQ); draft interpolates linearly (no anti-aliasing)"
    )
    plot(points, seconds, out)
    tables.append(long_upsampling(200.0 if quick else 2_000.0))
    return tables


def _windowed_sincs(data: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The band-limited reconstruction at source positions x with exact taps: the sinc in a
    Kaiser window (beta 9) over +-32 samples, as timeline.signal.resample tabulates it."""
    d = x[:, None] - np.arange(len(data))[None, :]
    r = d / 32
    window = np.i0(9.0 * np.sqrt(np.clip(1.0 - r * r, 0.0, None))) / np.i0(9.0)
    return np.where((d >= -32) & (d < 32), np.sinc(d) * window, 0.0) @ data


def long_upsampling(seconds: float) -> Table:
    """A render of `seconds` at OUT_RATE of slow recordings (normal preset): CPU time (best of
    3) and the error of 2,001 outputs around the middle sample against exact taps."""
    table = Table(
        f"Resamplers: long upsampling, {seconds:g} s rendered at {OUT_RATE} Hz (CPU, best of 3)",
        ["recording", "ratio", "outputs", "CPU s", "ns per output", "max error"],
    )
    n = round(seconds * OUT_RATE)
    for rate in (0.001, 0.1):
        data = np.random.default_rng(0).uniform(-1.0, 1.0, max(2, round(seconds * rate)))
        render = partial(sample_grid, data, rate, 0.0, 1 / OUT_RATE, n, preset("normal"))
        cpu = best_cpu_time(render, 3)
        middle = (len(data) // 2) / rate - 0.1  # s: 0.1 s either side of a sample
        part = sample_grid(data, rate, middle, 1 / OUT_RATE, 2_001, preset("normal"))
        exact = _windowed_sincs(data, (middle + np.arange(2_001) / OUT_RATE) * rate)
        error = float(np.abs(part - exact).max() / np.abs(data).max())
        name = f"{len(data)} values at {rate:g} Hz"
        table.rows.append((name, f"{OUT_RATE / rate:g}x", n, cpu, 1e9 * cpu / n, error))
    table.notes.append(
        "the direct windowed sinc (timeline/signal/resample.py): the table's knots summed once, "
        "each output interpolated between two; error relative to full scale"
    )
    return table


def plot(points: dict[str, list[tuple[float, float]]], seconds: float, out: Path) -> None:
    fig, ax = figure(6.5, 4.2)
    for i, (name, values) in enumerate(points.items()):
        xs, ys = zip(*values, strict=True)
        ax.scatter(xs, ys, s=45, color=f"C{i}", label=name)
    ax.set_xscale("log")
    plain_log_axis(ax.xaxis)
    ax.set_xlabel(f"ms to resample {seconds:g} s (44.1 and 48 kHz -> 10 kHz)")
    ax.set_ylabel("SNR against the exact signal (dB)")
    ax.set_title("Resamplers: speed against quality", fontsize=10)
    ax.legend(fontsize=8)
    save(fig, out, "resampler")
