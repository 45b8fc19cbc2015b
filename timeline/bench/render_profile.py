"""Where a full render of distinct clips spends its CPU: per tile kind and per stage, and the
libm calls it cannot do without.

The stages are timed inside the mixer's own render by wrapping the functions that do each one
(the exclusive CPU time of each, a wrapped call inside another counted once, in the inner one):
evaluation per tile kind (the generator, spline or recording's render; within it the square's
Fourier sum, soxr's whole-recording resampling and the recordings' fractional delay), the
amplitude and fades, each piece's peak, the scaled add into the output, placing the clips, the
cancellation check and the finite check. Bookkeeping is the rest of the same render's CPU
(each clip's calls, grid and cache, allocating and first touching the pieces). The floor is the
time of exactly the `sin` and `cos` calls that the scene's numpy forms make (timed around each
np.sin / np.cos call of a numpy-form render), plus the Fourier sum: no bit-identical render can
make fewer of them.
"""

from __future__ import annotations

import time
from collections import defaultdict
from collections.abc import Callable, Iterator
from contextlib import ExitStack, contextmanager
from typing import Any
from unittest import mock

import numpy as np

from timeline.model import Project
from timeline.rendering import clip_render, mixer
from timeline.signal import compiled, resample
from timeline.tiles import GeneratorTile, SampledTile, SplineTile, VibrationTile

BOOKKEEPING = "bookkeeping (the rest: calls, grids, caches, allocations)"


class _Clock:
    """Exclusive CPU seconds per stage name, for wrapped functions that may nest."""

    def __init__(self) -> None:
        self.seconds: dict[str, float] = defaultdict(float)
        self.calls: dict[str, int] = defaultdict(int)
        self._inner: list[float] = []

    def wrap(self, fn: Callable, name: str | Callable[..., str]) -> Callable:
        def timed(*args: Any, **kwargs: Any) -> Any:
            stage = name if isinstance(name, str) else name(*args)
            self._inner.append(0.0)
            start = time.process_time()
            try:
                return fn(*args, **kwargs)
            finally:
                spent = time.process_time() - start
                inner = self._inner.pop()
                self.seconds[stage] += spent - inner
                self.calls[stage] += 1
                if self._inner:
                    self._inner[-1] += spent

        return timed


def _kind(tile: Any, *_: Any) -> str:
    return tile.generator if isinstance(tile, GeneratorTile) else "spline"


@contextmanager
def _stages(clock: _Clock) -> Iterator[None]:
    """Every stage's function wrapped for the duration."""
    from timeline.signal import render_kernels

    with ExitStack() as stack:

        def patch(owner: Any, attr: str, name: str | Callable[..., str]) -> None:
            stack.enter_context(
                mock.patch.object(owner, attr, clock.wrap(getattr(owner, attr), name))
            )

        for cls in (GeneratorTile, SplineTile):
            patch(cls, "render", _kind)
        patch(SampledTile, "render", "recording (taking samples)")
        patch(VibrationTile, "render", "vibration")
        patch(resample, "_fractional_delay", "recording: fractional delay")
        patch(resample, "_whole", "recording: soxr, whole recordings")
        patch(render_kernels, "fourier_real", "square: Fourier sum")
        patch(clip_render, "_apply_fades", "fades")
        patch(mixer, "peak_of", "peak of each piece")
        patch(mixer.Mixer, "_place", "placing the clips")
        patch(mixer.Mixer, "_resum_cancelled", "cancellation check")
        patch(mixer, "_check_finite", "finite check")
        adder = mixer._adder

        def timed_adder(starts: np.ndarray, ends: np.ndarray) -> Callable:
            return clock.wrap(adder(starts, ends), "scaled add into the output")

        stack.enter_context(mock.patch.object(mixer, "_adder", timed_adder))
        yield


def _clock_cost(calls: int = 20_000) -> float:
    """CPU seconds that timing one call adds to its stage (the clock is read twice a call, a
    system call of a few microseconds here): measured on a call that does nothing."""
    clock = _Clock()
    nothing = clock.wrap(lambda: None, "nothing")
    for _ in range(calls):
        nothing()
    return clock.seconds["nothing"] / calls


def stage_seconds(render: Callable[[], object]) -> dict[str, float]:
    """CPU seconds of each stage in one call of `render` (a full render from scratch), less
    what timing its calls added, and under BOOKKEEPING the rest of that same render's CPU."""
    clock = _Clock()
    with _stages(clock):
        start = time.process_time()
        render()
        whole = time.process_time() - start
    cost = _clock_cost()
    stages = {stage: max(0.0, t - cost * clock.calls[stage]) for stage, t in clock.seconds.items()}
    stages[BOOKKEEPING] = whole - cost * sum(clock.calls.values()) - sum(stages.values())
    return stages


def libm_seconds(project: Project, stop: float) -> tuple[float, int]:
    """CPU seconds and count of the sin/cos evaluations in the numpy forms' render of the scene
    (each np.sin / np.cos call timed alone; the Fourier sum, compiled, is timed by the stages)."""
    spent = [0.0, 0]

    def timed(ufunc: np.ufunc) -> Callable:
        def call(x: Any, *args: Any, **kwargs: Any) -> Any:
            start = time.process_time()
            out = ufunc(x, *args, **kwargs)
            spent[0] += time.process_time() - start
            spent[1] += int(np.size(x))
            return out

        return call

    resample.forget_resampled()
    with (
        mock.patch.object(compiled, "compiled_wanted", lambda n: False),
        mock.patch.object(np, "sin", timed(np.sin)),
        mock.patch.object(np, "cos", timed(np.cos)),
    ):
        mixer.Mixer().render(project, 0.0, stop)
    return spent[0], int(spent[1])
