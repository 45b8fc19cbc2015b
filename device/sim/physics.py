"""The simulated knob stepped servo period by servo period, the way its firmware would run.

Each period: read the encoder (quantised, relative to the anchor), estimate velocity (backward
difference, low-passed) and, only when a mass layer exists, acceleration (by default a Kalman
observer, observer.py; or the difference of the velocity estimate, low-passed); compute tau =
d - k*theta - b*theta_dot - m*theta_ddot (or the position tables' T - B*theta_dot - M*theta_ddot);
replace NaN by 0 and clamp to the maximum; hold it over the period while the mechanics (rotor,
viscous and Coulomb friction, the hand) advance by a precomputed linear map (plant.py); that
loop is compiled (loop.py). State persists between blocks, so a USB emulation can feed blocks as
they arrive and call `run_idle` when none arrive (watchdog).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from device.sim.loop import State, servo_loop
from device.sim.observer import OFF, observer_tuple
from device.sim.params import KnobParams
from device.sim.plant import held_plant, step_matrix, viscous_loss
from device.sim.readings import blow_up_index, readings
from device.sim.stability import stability_flags
from timeline.limits.servo import load_of
from timeline.plugins.device_protocol import (
    CoefficientBlock,
    DeviceError,
    Hand,
    PositionProgram,
    PositionTable,
    StabilityFlag,
    Telemetry,
)

BLOW_UP_SPEED = 1e6  # rad/s: beyond this the simulation is numerically broken, not physical
NO_COEFFS = np.zeros((4, 0))  # the loop's coefficient rows when it plays tables
NO_TABLES = np.zeros((3, 0))  # the loop's tables when it plays coefficients


class KnobPhysics:
    """The knob, its firmware and a hand; advance it with run_block / run_table / run_idle."""

    def __init__(
        self, params: KnobParams | None = None, integrator: str = "zoh", substeps: int = 1
    ) -> None:
        self.params = params or KnobParams()
        self.integrator = integrator
        self.substeps = substeps
        self.theta = 0.0  # true absolute angle (rad)
        self.omega = 0.0  # true speed (rad/s)
        self._maps: dict[tuple[float, ...], tuple[tuple[float, ...], np.ndarray]] = {}
        self._tables: tuple[PositionTable | None, np.ndarray] = (None, NO_TABLES)
        self.start(Hand("hold"))

    @property
    def params(self) -> KnobParams:
        """The knob's constants; setting them (e.g. a lower torque limit) takes effect at once."""
        return self._params

    @params.setter
    def params(self, p: KnobParams) -> None:
        self._params = p
        filters = p.smoothing(p.velocity_cutoff), p.smoothing(p.acceleration_cutoff)
        self._firmware = _floats(
            p.rate, p.period, p.quantum, p.max_torque, p.coulomb, *filters, p.delay, p.slew
        )  # the loop's firmware tuple (loop.py), made once; index 5 is the velocity filter gain
        gains = p.observer_gains
        self._observer = OFF if gains is None else observer_tuple(p.period, gains)

    # --- set-up ---------------------------------------------------------------------------

    def _step_map(self, hand: Hand) -> tuple[tuple[float, ...], np.ndarray]:
        """The plant's theta and omega rows over a period, and the viscous loss's matrix W."""
        p = self.params
        key, a = held_plant(p.inertia, p.viscous, hand)
        if key not in self._maps:
            m = step_matrix(a, p.period, self.integrator, self.substeps)
            rows = tuple(float(x) for x in m[:2].ravel())
            self._maps[key] = (rows, viscous_loss(a, p.period, p.viscous))
        return self._maps[key]

    def _quantise(self, angle: float) -> float:
        q = self.params.quantum
        return math.floor(angle * (1.0 / q) + 0.5) * q if q else angle

    def start(self, hand: Hand | None = None) -> None:
        """Begin a play: the current angle becomes the anchor (theta = 0); estimators reset."""
        self.hand = hand or Hand("hold")
        self._map, self._loss = self._step_map(self.hand)
        self._loads = (load_of(self.hand),)  # the whole loop's stability is judged with it
        self.anchor = self._quantise(self.theta)
        self.grip_target = self.theta
        self.samples = 0  # samples since start
        self.energy = 0.0
        self.prev_meas = 0.0
        self.vel = 0.0
        self.prev_vel = 0.0
        self.acc = 0.0
        self.pending = 0.0  # the torque computed last period (applied now, with a delay)
        self.observed = (0.0, 0.0, 0.0)  # the observer's angle and velocity, last motor torque
        self.idle = 0  # samples since the last block arrived
        # what the watchdog keeps rendering: the last coefficients (rows d, k, b(, m)) or program
        self.last: np.ndarray | PositionProgram | None = None
        self.failed: str | None = None

    # --- public stepping -----------------------------------------------------------------

    def run_block(self, block: CoefficientBlock, judged: bool = True) -> Telemetry:
        """Render one block of coefficients (one value per servo period).

        NaN or infinite coefficients are played as zero (no force), never silently: they are
        flagged ("non-finite", at each such sample) and named in a warning. `judged`: flag the
        samples beyond the loop's stability limits (about 1 ms a block at 20,000 clips, most of
        it the whole loop's eigenvalues).
        """
        rows = (
            (block.d, block.k, block.b) if block.m is None else (block.d, block.k, block.b, block.m)
        )
        coeffs = np.array(rows, dtype=np.float64)
        finite, refused = np.isfinite(coeffs), None
        if not finite.all():
            refused = _nonfinite_flag(block, self.samples, self.params.period)
            coeffs = np.where(finite, coeffs, 0.0)  # as block.safe()
        self.idle = 0
        self.last = coeffs[:, -1:] if len(block) else self.last
        tel = self._run(len(block), coeffs=coeffs)
        n = len(tel)
        layers = dict(zip("dkbm", coeffs[:, :n], strict=False))
        p = self.params
        k, b, m = layers["k"], layers["b"], layers.get("m")
        flags = (
            stability_flags(tel.time, k, b, m, p.dynamics, p.period, self._loads) if judged else []
        )
        if refused is not None:
            flags.append(refused)
            tel = replace(tel, warnings=(*tel.warnings, refused.message))
        return _with(tel, layers, flags)

    def run_table(self, program: PositionProgram, n: int) -> Telemetry:
        """Render n servo periods of a position program (tables looked up at the knob's angle)."""
        self.idle = 0
        self.last = program
        return self._run_table(program, n)

    def run_idle(self, n: int) -> Telemetry:
        """n servo periods with no block arriving: the watchdog ramps the torque to zero.

        The last coefficients keep rendering for `watchdog_timeout`, then the torque is scaled
        down linearly to zero over `watchdog_ramp`; from then on it is exactly zero.
        """
        p = self.params
        t = (self.idle + np.arange(n)) * p.period
        ramp = p.watchdog_ramp
        if ramp > 0:
            gain = np.clip(1.0 - (t - p.watchdog_timeout) / ramp, 0.0, 1.0)
        else:
            gain = (t < p.watchdog_timeout).astype(float)
        self.idle += n
        last = self.last
        if isinstance(last, PositionProgram):
            return self._run_table(last, n, gain)
        coeffs = np.repeat(np.zeros((3, 1)) if last is None else last, n, axis=1)
        tel = self._run(n, coeffs=coeffs, gain=gain)
        return _with(tel, {"d": coeffs[0] * gain[: len(tel)]}, [])

    def _table_rows(self, table: PositionTable) -> np.ndarray:
        """The tables T, B, M as rows of one array (absent B and M are zeros), made once."""
        if self._tables[0] is not table:
            zeros = np.zeros_like(table.torque)
            rows = [table.torque, table.damping, table.mass]
            self._tables = (table, np.array([zeros if a is None else a for a in rows], np.float64))
        return self._tables[1]

    # --- the loop ------------------------------------------------------------------------

    def _run_table(
        self, program: PositionProgram, n: int, gain: np.ndarray | None = None
    ) -> Telemetry:
        table = program.table_now()
        tel = self._run(n, table=(table, program.origin), gain=gain)
        where = program.origin + tel.angle
        grid = table.angles()
        layers = {"d": np.interp(where, grid, table.torque)}
        damping = np.interp(where, grid, table.damping) if table.damping is not None else 0 * where
        mass = np.interp(where, grid, table.mass) if table.mass is not None else None
        if table.damping is not None:
            layers["b"] = damping
        if mass is not None:
            layers["m"] = mass
        stiffness = local_stiffness(table, where)
        p = self.params
        flags = stability_flags(
            tel.time, stiffness, damping, mass, p.dynamics, p.period, self._loads
        )
        return _with(tel, layers, flags)

    def _run(
        self,
        n: int,
        coeffs: np.ndarray | None = None,
        table: tuple[PositionTable, float] | None = None,
        gain: np.ndarray | None = None,
    ) -> Telemetry:
        """n servo periods of coefficient rows d, k, b(, m) or of a table at an origin."""
        if self.failed:
            raise DeviceError(f"the simulated knob stopped earlier: {self.failed}")
        p, hand = self.params, self.hand
        if table is None:
            tables, lookup, use_mass = NO_TABLES, (0.0, 0.0, 0.0), coeffs.shape[0] > 3
        else:
            tab, origin = table
            coeffs, tables, use_mass = NO_COEFFS, self._table_rows(tab), tab.mass is not None
            lookup = _floats(origin, tab.start, tab.rate)
        motion = _floats(hand.push_torque, hand.push_ramp, hand.turn_speed, self.samples * p.period)
        state = _floats(self.theta, self.omega, self.grip_target, self.anchor, self.prev_meas,
                        self.vel, self.prev_vel, self.acc, self.pending,
                        *self.observed)  # fmt: skip
        gain = np.ones(n) if gain is None else gain
        thetas, taus, frictions, losses, nonfinite, state = servo_loop(
            coeffs,
            tables,
            gain,
            use_mass,
            lookup,
            self._firmware,
            self._map,
            motion,
            state,
            self._observer,
            self._loss,
        )
        return self._finish(thetas, taus, frictions, losses, state, nonfinite)

    def _finish(
        self,
        thetas: np.ndarray,
        taus: np.ndarray,
        frictions: np.ndarray,
        losses: np.ndarray,
        state: State,
        nonfinite: int,
    ) -> Telemetry:
        """Turn the loop's record (true angle before each period, torque) into telemetry.

        Energy is what the device (motor with its own viscous and Coulomb friction, Colgate's
        "device") put into the rotor and hand: motor work minus the friction's dissipation (the
        viscous part integrated exactly over each held period, plant.viscous_loss).
        """
        p = self.params
        theta, omega, grip_target, _, *estimators = state
        done = blow_up_index(thetas, theta, p.rate, BLOW_UP_SPEED)
        flags: list[StabilityFlag] = []
        warnings: list[str] = []
        at = (self.samples + done) * p.period
        if done < thetas.size:
            self.failed = (
                f"the simulation blew up at {at:.6g} s (speed beyond {BLOW_UP_SPEED:g} rad/s "
                "or not a number); results end there"
            )
            flags.append(StabilityFlag("blow-up", self.failed, np.array([at]), np.array([0.0])))
            warnings.append(self.failed)
            theta, omega = float(thetas[done]), 0.0
            thetas, taus, frictions = thetas[:done], taus[:done], frictions[:done]
            losses = losses[:done]
        if nonfinite:
            warnings.append(f"{nonfinite} non-finite torque samples were replaced by zero")
        meas, velocity, energy = readings(
            thetas,
            theta,
            taus,
            frictions,
            losses,
            _floats(p.quantum, self.anchor, p.rate),
            _floats(self._firmware[5], self.prev_meas, self.vel),
            self.energy,
        )
        self.theta, self.omega, self.grip_target = theta, omega, grip_target
        self.prev_meas, self.vel, self.prev_vel, self.acc, self.pending, *observed = estimators
        self.observed = tuple(observed)
        self.energy = float(energy[-1]) if energy.size else self.energy
        time = (self.samples + np.arange(done)) * p.period
        self.samples += done
        saturated = np.abs(taus) >= p.max_torque
        return Telemetry(p.rate, time, meas, velocity, taus, energy, saturated, {},
                         tuple(flags), tuple(warnings))  # fmt: skip


def local_stiffness(table: PositionTable, where: np.ndarray) -> np.ndarray:
    """-dT/dtheta of the torque table at table angles (0 beyond its ends)."""
    if table.torque.size < 2:
        return np.zeros_like(where)
    slope = -np.diff(table.torque) * table.rate
    x = (where - table.start) * table.rate
    inside = (x > 0) & (x < table.torque.size - 1)
    j = np.clip(np.floor(x).astype(np.int64), 0, slope.size - 1)
    return np.where(inside, slope[j], 0.0)


def _floats(*values: float) -> tuple[float, ...]:
    """Plain floats for the compiled loop (one type signature, so one compilation)."""
    return tuple(float(v) for v in values)


def _nonfinite_flag(block: CoefficientBlock, first: int, period: float) -> StabilityFlag | None:
    """A flag at every sample of the block where a coefficient is NaN or infinite, or None."""
    if not block.nonfinite:
        return None
    named = {"d": block.d, "k": block.k, "b": block.b, "m": block.m}
    bad = {name: ~np.isfinite(a) for name, a in named.items() if a is not None}
    where = np.flatnonzero(np.logical_or.reduce(list(bad.values())))
    i = int(where[0])
    name = next(n for n, mask in bad.items() if mask[i])
    at = (first + i) * period
    message = (
        f"{where.size} sample(s) held NaN or infinite coefficients (first: {name} = "
        f"{named[name][i]} at {at:.6g} s) and were played as zero"
    )
    return StabilityFlag("non-finite", message, (first + where) * period, np.zeros(where.size))


def _with(tel: Telemetry, layers: dict[str, np.ndarray], flags: list[StabilityFlag]) -> Telemetry:
    n = len(tel)
    return replace(
        tel,
        layers={k: np.asarray(v, dtype=np.float64)[:n] for k, v in layers.items()},
        flags=tel.flags + tuple(flags),
    )
