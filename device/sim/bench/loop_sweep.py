"""Simulated knob: the whole-loop stability flag against simulation, over random layer mixes.

Random (k, b, m), each inside its own single-layer limit (0 <= k <= K_pass at B = 0,
0 <= b <= the damping limit, m in the mass band), for every estimator, delay 0 and 1 and every
load the docs' hands put on the knob. Each mix is played on the linear knob (ideal sensor, no
Coulomb friction, the 180 mNm clamp kept) after a 1 mNm kick, and called unstable when the
torque grows (the simulation: an independent method from the flag's root test): its peak over
the last quarter of the run is above its peak over the quarter before (and above rounding
noise, `FLOOR`), or it reached the clamp.
A run is flagged when the sim raised a flag that claims the loop grows (`GROWS`); passivity and
negative damping are not stability claims (a passive bound is stricter than stability).

Run by `python benchmarks/loop_sweep.py` (20 minutes on a loaded 2-core machine: not one of the
`bench` verb's benchmarks, whose `--quick` run CI takes); tests/device/test_whole_loop.py runs a
small sweep.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from device.sim import KnobParams, KnobPhysics
from timeline.bench.report import Table
from timeline.limits import servo
from timeline.plugins.device_protocol import ESTIMATORS, CoefficientBlock, Hand

GROWS = {"unstable-loop", "damping-limit", "mass-limit", "mass-cancels-inertia", "blow-up"}
LINEAR = {"quantum": 0.0, "coulomb": 0.0}
# one hand per load the docs' hands make (servo.hand_loads): free, each model holding, pushing
HANDS = (
    Hand("free"),
    Hand("hold"),
    Hand("hold", model="pinch"),
    Hand("hold", model="grasp"),
    Hand("push", 0.0),
    Hand("push", 0.0, model="grasp"),
)
KICK = 1e-3  # N*m over the first 5 periods
FLOOR = 1e-12  # N*m: below this a torque is rounding noise (a decayed ring sits near 1e-18)


@dataclass
class Tally:
    """Runs counted by (flagged, unstable in the simulation)."""

    runs: int = 0
    unstable: int = 0
    flagged: int = 0
    missed: int = 0  # unstable, not flagged
    false_alarms: int = 0  # flagged, stable

    def add(self, flagged: bool, unstable: bool) -> None:
        self.runs += 1
        self.unstable += unstable
        self.flagged += flagged
        self.missed += unstable and not flagged
        self.false_alarms += flagged and not unstable

    @property
    def false_alarm_share(self) -> float:
        return self.false_alarms / self.flagged if self.flagged else 0.0


def mixes(params: KnobParams, count: int, rng: np.random.Generator) -> np.ndarray:
    """count random (k, b, m) rows, each layer uniform inside its own single-layer limit."""
    dyn, period = params.dynamics, params.period
    k_top = servo.passive_stiffness(dyn.damping, 0.0, period, dyn.delay)
    low, high = servo.mass_limits(dyn, period)
    return np.column_stack(
        [
            rng.uniform(0.0, k_top, count),
            rng.uniform(0.0, servo.damping_limit(dyn, period), count),
            rng.uniform(low, high, count),
        ]
    )


def play(params: KnobParams, hand: Hand, mix: np.ndarray, seconds: float) -> tuple[bool, bool]:
    """(flagged, unstable) for one mix held constant after a kick."""
    knob = KnobPhysics(params)
    knob.start(hand)
    n = int(seconds * params.rate)
    d = np.zeros(n)
    d[:5] = KICK
    k, b, m = (np.full(n, x) for x in mix)
    tel = knob.run_block(CoefficientBlock(d, k, b, m))
    flagged = any(f.kind in GROWS for f in tel.flags)
    torque = np.abs(tel.torque)
    quarter = n // 4
    clamped = torque[5:].max() >= params.max_torque if torque.size > 5 else False
    late = torque[-quarter:].max() if torque.size == n else np.inf
    grows = late > max(torque[-2 * quarter : -quarter].max(), FLOOR)
    return flagged, bool(clamped or grows)


def sweep(count: int, seconds: float, seed: int = 20) -> dict[tuple[str, int, str], Tally]:
    """Tallies per (estimator, delay, hand) over `count` mixes each."""
    rng = np.random.default_rng(seed)
    out: dict[tuple[str, int, str], Tally] = {}
    for estimator in ESTIMATORS:
        for delay in (0, 1):
            params = KnobParams(**LINEAR, estimator=estimator, delay=delay)
            rows = mixes(params, count, rng)
            for hand in HANDS:
                tally = out.setdefault((estimator, delay, servo.load_of(hand).name), Tally())
                for mix in rows:
                    tally.add(*play(params, hand, mix, seconds))
    return out


def run(quick: bool, out: Path) -> list[Table]:  # noqa: ARG001 - no plot
    count, seconds = (30, 1.0) if quick else (300, 2.0)
    tallies = sweep(count, seconds)
    table = Table(
        f"Whole-loop stability flags against simulation: {count} random (k, b, m) per row, each "
        f"layer inside its own limit, {seconds:g} s runs on the linear knob after a 1 mNm kick",
        ["estimator", "delay", "hand", "runs", "unstable (sim)", "flagged", "unstable unflagged",
         "flagged stable", "flagged stable %"],
    )  # fmt: skip
    total = Tally()
    for (estimator, delay, hand), t in tallies.items():
        table.rows.append([estimator, delay, hand, t.runs, t.unstable, t.flagged, t.missed,
                           t.false_alarms, 100.0 * t.false_alarm_share])  # fmt: skip
        for name in ("runs", "unstable", "flagged", "missed", "false_alarms"):
            setattr(total, name, getattr(total, name) + getattr(t, name))
    table.rows.append(["all", "", "", total.runs, total.unstable, total.flagged, total.missed,
                       total.false_alarms, 100.0 * total.false_alarm_share])  # fmt: skip
    table.notes.append(
        "unstable (sim): the torque's peak over the last quarter of the run is above the quarter "
        "before (and above 1e-12 N*m), or reaches the 180 mNm clamp; flagged: unstable-loop, "
        "damping-limit, mass-limit, mass-cancels-inertia or blow-up"
    )
    return [table]
