"""Stability limits of a sampled knob's servo loop: stiffness, damping and virtual mass.

The loop a kinesthetic device runs each period T: read the encoder, estimate velocity (backward
difference, first-order low-pass) and acceleration (the difference of the velocity estimate,
low-passed, or an observer: predict with the acceleration held, correct with the reading, as the
device declares), compute tau = -k*theta - b*theta_dot - m*theta_ddot, apply it `delay` periods
later and hold it over a period on a rotor of inertia J and viscous damping b_dev. With an ideal
sensor and no friction that loop is linear, so its period-to-period map is a matrix and it is
stable exactly when every eigenvalue lies inside the unit circle (`spectral_radius` < 1). The
single-layer limits below are found on that map with the knob free (no hand) and the other
layers at zero. They do not bound the layers together, and a hand does not always steady the
knob (a pinch's stiff, light grip makes a mass of -0.95 J unstable that the free knob renders):
`whole_loop` judges all three layers at once, with each load a hand puts on the knob, on the
loop's characteristic polynomial.

* stiffness: passivity (Colgate & Schenkel 1997): b_dev > K*T/2 + |B|; with a computation delay
  of D periods the held torque is older by D*T and the bound becomes b_dev > K*T*(1/2 + D) + |B|
  (the same energy-leak argument; Diolaiti et al. 2006 treat delay this way).
* damping: the largest B with the free knob's loop stable (about 2*J/T with a raw backward
  difference and no delay).
* mass: the band of m (negative to positive) with the loop stable; J + m <= 0 is never allowed.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.linalg import expm

from timeline.errors import DeviceError
from timeline.plugins.device_protocol import Dynamics, Hand
from timeline.plugins.device_protocol.hand_models import HAND_MODELS

UNSTABLE = 1.0 + 1e-9  # spectral radius above this grows; the free knob's angle mode sits at 1


def passive_stiffness(device_damping: float, virtual_damping, period: float, delay: int = 0):
    """K_pass = (b_dev - |B|) / (T*(1/2 + D)) in N*m/rad; scalars or arrays.

    An absurd virtual damping gives -inf (nothing is passive), which is the right answer.
    """
    with np.errstate(over="ignore"):
        return (device_damping - np.abs(virtual_damping)) / (period * (0.5 + delay))


def smoothing(cutoff: float, rate: float) -> float:
    """Gain of a first-order low-pass at a cut-off (1.0 = no filtering)."""
    return 1.0 if cutoff <= 0 else 1.0 - math.exp(-2.0 * math.pi * cutoff / rate)


def _plant(dynamics: Dynamics, period: float) -> np.ndarray:
    """The rotor's exact zero-order-hold map [theta, omega, u] -> [theta, omega] over a period."""
    a = np.zeros((3, 3))
    a[0, 1], a[1, 1], a[1, 2] = 1.0, -dynamics.damping / dynamics.inertia, 1.0 / dynamics.inertia
    return expm(a * period)[:2]


def _velocity_rows(dynamics: Dynamics, period: float, e: np.ndarray):  # noqa: ANN202
    """The next [meas, vel] over the loop's state [theta, omega, meas, vel, ...]: the backward
    difference of the reading through its low-pass."""
    rate = 1.0 / period
    av = smoothing(dynamics.velocity_cutoff, rate)
    return [e[0], (1.0 - av) * e[3] + av * rate * (e[0] - e[2])]


def _filter_rows(dynamics: Dynamics, period: float, e: np.ndarray, vel: np.ndarray):  # noqa: ANN202
    """The acceleration filter's next [prev_vel, acc] over the state [..., prev_vel, acc, ...]
    at 4 and 5 (the difference of the velocity estimate `vel`, low-passed)."""
    aa = smoothing(dynamics.acceleration_cutoff, 1.0 / period)
    return [vel, (1.0 - aa) * e[5] + aa * (vel - e[4]) / period]


def _observer_rows(dynamics: Dynamics, period: float, e: np.ndarray, vel: np.ndarray):  # noqa: ANN202, ARG001
    """The observer's next [angle, velocity, acceleration] over the state [..., o0, o1, o2, ...]
    at 4 to 6: predict with the acceleration held, correct by L times the reading's miss, as the
    firmware does."""
    t = period
    a = np.array([[1.0, t, t * t / 2.0], [0.0, 1.0, t], [0.0, 0.0, 1.0]])
    predicted = a @ e[4:7]
    miss = e[0] - predicted[0]
    return [predicted[i] + dynamics.observer_gains[i] * miss for i in range(3)]


def loop_matrix(
    dynamics: Dynamics, period: float, k: float = 0.0, b: float = 0.0, m: float = 0.0
) -> np.ndarray:
    """The free knob's closed loop over one period: state [theta, omega, meas, vel, the
    acceleration estimator's state (filter: prev_vel, acc; an observer: its angle, velocity and
    acceleration), tau(n-1) ... tau(n-D)]."""
    if not dynamics.estimator_declared:
        raise DeviceError("the servo loop cannot be modelled: the device does not declare its "
                          "velocity and acceleration estimator")  # fmt: skip
    observed = bool(dynamics.observer_gains)
    first_delay = 7 if observed else 6  # index of tau(n-1) in the state
    delay = int(dynamics.delay)
    e = np.eye(first_delay + delay)
    velocity = _velocity_rows(dynamics, period, e)
    acceleration = (_observer_rows if observed else _filter_rows)(dynamics, period, e, velocity[1])
    tau = -k * e[0] - b * velocity[1] - m * acceleration[-1]
    applied = e[first_delay + delay - 1] if delay else tau
    plant = _plant(dynamics, period)
    rows = [p[0] * e[0] + p[1] * e[1] + p[2] * applied for p in plant]
    rows += velocity + acceleration
    if delay:  # tau(n) is remembered, the older ones shift by one
        rows += [tau, *e[first_delay : first_delay + delay - 1]]
    return np.array(rows)


def spectral_radius(matrix: np.ndarray) -> float:
    """Largest eigenvalue magnitude (above 1: the loop grows)."""
    return float(np.abs(np.linalg.eigvals(matrix)).max())


def _edge(dynamics: Dynamics, period: float, layer: str, sign: float) -> float:
    """The magnitude of k, b or m (with the others zero) at which the loop turns unstable."""

    def stable(x: float) -> bool:
        return spectral_radius(loop_matrix(dynamics, period, **{layer: sign * x})) <= UNSTABLE

    scale = {"k": 1.0, "b": dynamics.inertia / period, "m": dynamics.inertia}[layer]
    if sign < 0 and layer == "m":
        hi = dynamics.inertia  # J + m <= 0 is never stable
    else:
        hi = scale
        while stable(hi):
            hi *= 2.0
            if hi > 1e12 * scale:
                return math.inf
    lo = 0.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    return lo


@lru_cache(maxsize=64)
def damping_limit(dynamics: Dynamics, period: float) -> float:
    """Largest virtual damping B (N*m*s/rad) the free knob's loop renders stably."""
    return _edge(dynamics, period, "b", 1.0)


@lru_cache(maxsize=64)
def mass_limits(dynamics: Dynamics, period: float) -> tuple[float, float]:
    """(lowest, highest) virtual mass m (kg*m^2) the free knob's loop renders stably."""
    return -_edge(dynamics, period, "m", -1.0), _edge(dynamics, period, "m", 1.0)


@lru_cache(maxsize=64)
def stable_stiffness(dynamics: Dynamics, period: float) -> float:
    """Largest stiffness K (N*m/rad) with the free knob's loop stable (B = m = 0)."""
    return _edge(dynamics, period, "k", 1.0)


# --- the whole loop: stiffness, damping and mass together, with a hand on the knob -----------


@dataclass(frozen=True)
class Load:
    """What a hand puts on the knob as the loop sees it: inertia (kg*m^2), and a grip's
    stiffness (N*m/rad) and damping (N*m*s/rad) to its target angle (0 when it does not grip)."""

    name: str
    inertia: float = 0.0
    stiffness: float = 0.0
    damping: float = 0.0


FREE = Load("free knob")


def load_of(hand: Hand) -> Load:
    """The load a hand (mode and model) puts on the knob."""
    if not hand.touches:
        return FREE
    grip = (hand.grip_stiffness, hand.grip_damping) if hand.grips else (0.0, 0.0)
    name = f"{hand.model} hand {'holding' if hand.grips else 'pushing'}"
    return Load(name, hand.inertia, *grip)


def hand_loads() -> tuple[Load, ...]:
    """Every load the docs' hands make: the free knob, each named hand holding (or turning) and
    pushing (its inertia without a grip); loads with the same numbers are kept once (a pinch
    pushing, with no inertia, is the free knob)."""
    found = {(0.0, 0.0, 0.0): FREE}
    for model in HAND_MODELS:
        for mode in ("hold", "push"):
            load = load_of(Hand(mode, 0.0, model=model))
            found.setdefault((load.inertia, load.stiffness, load.damping), load)
    return tuple(found.values())


def _poly(*factors: np.ndarray) -> np.ndarray:
    out = np.array([1.0])
    for f in factors:
        out = np.polymul(out, f)
    return out


@lru_cache(maxsize=256)
def characteristic(dynamics: Dynamics, period: float, load: Load = FREE) -> np.ndarray:
    """The closed loop's characteristic polynomial as rows c0, ck, cb, cm (coefficients of z,
    highest power first): chi(z) = c0 + k*ck + b*cb + m*cm, monic, affine in (k, b, m).

    The plant G = Np/Dp is the rotor (with the load) from the held torque to the angle over one
    period (zero-order hold, exact); the estimators are filters of the reading: velocity
    V = Nv/Dv (backward difference, low-pass), acceleration A = Na/Da (the filter chain, or an
    observer's acceleration row); the law is tau = -(k + b*V + m*A) * theta, applied D periods
    later. So chi = z^D * Dp * De + Np * (k*De + b*Nv*De/Dv + m*Na*De/Da), De = lcm(Dv, Da).
    """
    if not dynamics.estimator_declared:
        raise DeviceError("the servo loop cannot be modelled: the device does not declare its "
                          "velocity and acceleration estimator")  # fmt: skip
    inertia = dynamics.inertia + load.inertia
    a = np.zeros((3, 3))
    a[0, 1] = 1.0
    a[1] = [-load.stiffness, -(dynamics.damping + load.damping), 1.0]
    a[1] /= inertia
    step = expm(a * period)
    phi, gamma = step[:2, :2], step[:2, 2]
    dp = np.array([1.0, -np.trace(phi), np.linalg.det(phi)])
    np_ = np.array([gamma[0], phi[0, 1] * gamma[1] - phi[1, 1] * gamma[0]])
    rate = 1.0 / period
    av = smoothing(dynamics.velocity_cutoff, rate)
    nv, dv = av * rate * np.array([1.0, -1.0]), np.array([1.0, av - 1.0])
    if dynamics.observer_gains:
        gains = np.array(dynamics.observer_gains)
        t = period
        kin = np.array([[1.0, t, t * t / 2.0], [0.0, 1.0, t], [0.0, 0.0, 1.0]])
        m_obs = (np.eye(3) - np.outer(gains, [1.0, 0.0, 0.0])) @ kin
        da = np.poly(m_obs)  # Faddeev-LeVerrier: adj(zI - M) = I z^2 + B1 z + B2
        b1 = m_obs + da[1] * np.eye(3)
        b2 = m_obs @ b1 + da[2] * np.eye(3)
        na = np.array([gains[2], (b1 @ gains)[2], (b2 @ gains)[2], 0.0])  # times z
        de, cb, cm = _poly(dv, da), _poly(np_, nv, da), _poly(np_, na, dv)
    else:
        aa = smoothing(dynamics.acceleration_cutoff, rate)
        na, da = aa * rate * np.array([1.0, -1.0]), np.array([1.0, aa - 1.0])
        de, cb, cm = _poly(dv, da), _poly(np_, nv, da), _poly(np_, nv, na)
    delay = np.zeros(int(dynamics.delay) + 1)
    delay[0] = 1.0
    c0 = _poly(delay, dp, de)
    rows = [c0, _poly(np_, de), cb, cm]
    return np.array([np.concatenate([np.zeros(c0.size - r.size), r]) for r in rows])


@lru_cache(maxsize=256)
def _deflated(dynamics: Dynamics, period: float, load: Load) -> np.ndarray:
    """The rows c0, cb, cm divided by (z - 1) (ck set to 0): the loop at k = 0 on a knob no
    spring holds, whose angle mode sits exactly at z = 1 (a kicked knob rests where it stops)."""
    rows = characteristic(dynamics, period, load)
    out = np.zeros((4, rows.shape[1] - 1))
    for i in (0, 2, 3):
        out[i] = np.polydiv(rows[i], [1.0, -1.0])[0]
    return out


PIECE = 1 << 16  # unstable samples judged at a time by whole_loop (each piece's roots found apart)
BATCH = 64  # samples tested side by side (independent chains: the compiler vectorises them)


def unstable_samples(
    rows: np.ndarray, flat: np.ndarray, k: np.ndarray, b: np.ndarray, m: np.ndarray, deflate: bool
) -> np.ndarray:
    """Whether the polynomial rows[:, 0] + k*rows[:, 1] + b*rows[:, 2] + m*rows[:, 3] (rows by
    power, highest first) of each sample has a root outside the unit circle (compiled by
    `_compiled`; a run of equal samples is tested once).

    The Schur-Cohn test (Jury's table) by reflection coefficients: p has every root inside the
    unit circle iff |p_n / p_0| < 1 and p - (p_n/p_0) * reversed(p), less its last term, has
    too. With `deflate` (a knob no spring holds) a sample with k = 0 is tested on `flat`, the
    rows divided by (z - 1): its angle mode sits exactly at z = 1 (a kicked knob rests where it
    stops). `_judged` scales z so that a root on the circle passes.
    """
    n = k.size
    out = np.zeros(n, dtype=np.bool_)
    picks = np.empty((2, n), dtype=np.int64)  # the first sample of each run: spring, no spring
    count = np.zeros(2, dtype=np.int64)
    for i in range(n):
        if i > 0 and k[i] == k[i - 1] and b[i] == b[i - 1] and m[i] == m[i - 1]:
            continue
        g = 1 if deflate and k[i] == 0.0 else 0
        picks[g, count[g]] = i
        count[g] += 1
    a = np.empty((rows.shape[0], BATCH))
    ok = np.empty(BATCH, dtype=np.bool_)
    gamma = np.empty(BATCH)
    for g in range(2):
        src = flat if g == 1 else rows
        width = src.shape[0]
        for first in range(0, count[g], BATCH):
            size_b = min(BATCH, count[g] - first)
            for j in range(width):
                c0, c1, c2, c3 = src[j, 0], src[j, 1], src[j, 2], src[j, 3]
                for s in range(size_b):
                    i = picks[g, first + s]
                    a[j, s] = c0 + k[i] * c1 + b[i] * c2 + m[i] * c3
            ok[:size_b] = True
            for size in range(width, 1, -1):
                for s in range(size_b):
                    gamma[s] = a[size - 1, s] / a[0, s]
                    ok[s] &= abs(gamma[s]) < 1.0  # NaN (absurd layers) is unstable too
                for j in range((size + 1) // 2):
                    top, bottom = a[j], a[size - 1 - j]
                    for s in range(size_b):
                        lo, hi = top[s], bottom[s]
                        top[s], bottom[s] = lo - gamma[s] * hi, hi - gamma[s] * lo
            for s in range(size_b):
                out[picks[g, first + s]] = not ok[s]
    for i in range(1, n):  # the rest of each run
        if k[i] == k[i - 1] and b[i] == b[i - 1] and m[i] == m[i - 1]:
            out[i] = out[i - 1]
    return out


@lru_cache(maxsize=256)
def _judged(dynamics: Dynamics, period: float, load: Load) -> tuple[np.ndarray, np.ndarray]:
    """The rows as unstable_samples reads them (by power, z scaled by UNSTABLE so a root on the
    circle passes), whole and (for a load with no spring) divided by (z - 1)."""
    rows = characteristic(dynamics, period, load)
    flat = _deflated(dynamics, period, load) if load.stiffness == 0.0 else rows

    def scaled(r: np.ndarray) -> np.ndarray:
        return np.ascontiguousarray((r * UNSTABLE ** -np.arange(r.shape[1])).T)

    return scaled(rows), scaled(flat)


@lru_cache(maxsize=1)
def _compiled():  # noqa: ANN202 - a numba dispatcher
    """unstable_samples compiled with numba (imported here: `check` pays for it only when a
    design has stiffness, damping or mass)."""
    from numba import njit

    return njit(cache=True, error_model="numpy")(unstable_samples)


def loop_radius(
    polys: np.ndarray, interrupt: Callable[[], None] = lambda: None, rows: int = 8192
) -> np.ndarray:
    """The largest root magnitude of each row's polynomial (eigenvalues of its companion), found
    `rows` at a time with `interrupt` called between them (a stale check stops there)."""
    if polys.shape[0] > rows:
        parts = []
        for first in range(0, polys.shape[0], rows):
            interrupt()
            parts.append(loop_radius(polys[first : first + rows]))
        return np.concatenate(parts)
    n = polys.shape[1] - 1
    comp = np.zeros((polys.shape[0], n, n))
    comp[:, 0, :] = -polys[:, 1:] / polys[:, :1]
    comp[:, np.arange(1, n), np.arange(n - 1)] = 1.0
    return np.abs(np.linalg.eigvals(comp)).max(axis=1)


@dataclass(frozen=True)
class WholeLoop:
    """The loop judged at each sample: growth per period (largest root magnitude; NaN where the
    loop is stable with every load, or where it was not asked for) and, per load, where that
    load makes it unstable."""

    radius: np.ndarray
    unstable: dict[str, np.ndarray]

    @property
    def any(self) -> np.ndarray:
        return np.isfinite(self.radius)


def whole_loop(
    dynamics: Dynamics,
    period: float,
    k: np.ndarray,
    b: np.ndarray,
    m: np.ndarray | None,
    loads: tuple[Load, ...] = (FREE,),
    interrupt: Callable[[], None] = lambda: None,
    where: np.ndarray | None = None,
) -> WholeLoop:
    """Judge the linear loop (ideal sensor, no friction, no clamp) at every sample's (k, b, m)
    with each load. A negative stiffness is judged as 0: it pulls the knob away from rest, a
    slide the designer asked for (a detent's far side), not an oscillation; the clamp bounds it.
    Only the samples where (k, b, m) changes are tested (a run of equal samples is one test);
    the growth is found (eigenvalues) only where the loop is unstable and `where` asks (default
    everywhere), once per distinct (k, b, m), with `interrupt` called between pieces."""
    n = k.size
    m = np.zeros(n) if m is None else m
    spring = np.maximum(k, 0.0)
    worst = np.full(n, np.nan)
    unstable = {}
    if not (spring.any() or b.any() or m.any()):  # no virtual layer: rotor and filters only
        return WholeLoop(worst, unstable)
    test = _compiled()
    for load in loads:
        rows = characteristic(dynamics, period, load)
        whole, flat = _judged(dynamics, period, load)
        bad = test(whole, flat, spring, b, m, load.stiffness == 0.0)
        if not bad.any():
            continue
        unstable[load.name] = bad
        at = np.flatnonzero(bad if where is None else bad & where)
        if not at.size:
            continue
        radius = np.full(at.size, np.inf)
        for lo in range(0, at.size, PIECE):  # pieces: a stale check stops between them
            interrupt()
            part = at[lo : lo + PIECE]
            radius[lo : lo + part.size] = _radius(rows, spring, b, m, part, interrupt)
        worst[at] = np.fmax(worst[at], radius)
    return WholeLoop(worst, unstable)


def _radius(
    rows: np.ndarray,
    k: np.ndarray,
    b: np.ndarray,
    m: np.ndarray,
    at: np.ndarray,
    interrupt: Callable[[], None],
) -> np.ndarray:
    """The growth per period of the loop at the samples `at` (ascending; inf where the
    polynomial is not finite): a run of equal (k, b, m) is one polynomial, found at its first
    sample, and each distinct (k, b, m) (the same numbers: the same polynomial) is found once."""
    same = (at[1:] == at[:-1] + 1) & (k[at[1:]] == k[at[:-1]])
    same &= (b[at[1:]] == b[at[:-1]]) & (m[at[1:]] == m[at[:-1]])
    first = np.concatenate([[True], ~same])
    starts = at[first]
    triples = np.column_stack([k[starts], b[starts], m[starts]])
    keys = triples.view(np.dtype((np.void, triples.itemsize * 3))).reshape(-1)
    _, index, which = np.unique(keys, return_index=True, return_inverse=True)
    k, b, m = triples[index].T
    with np.errstate(over="ignore", invalid="ignore"):  # absurd layers: not finite
        polys = rows[0] + np.outer(k, rows[1]) + np.outer(b, rows[2])
        polys += np.outer(m, rows[3])
    finite = np.isfinite(polys).all(axis=1)
    radius = np.full(k.size, np.inf)
    radius[finite] = loop_radius(polys[finite], interrupt)
    return radius[which.reshape(-1)][np.cumsum(first) - 1]


def layers_inside(
    dynamics: Dynamics, period: float, k: np.ndarray, b: np.ndarray, m: np.ndarray | None
) -> np.ndarray:
    """Samples where every layer is inside its own (free knob, one layer at a time) limit:
    k <= K_pass at B = 0, 0 <= b <= the damping limit, m in the mass band with J + m > 0."""
    inside = (k <= passive_stiffness(dynamics.damping, 0.0, period, dynamics.delay)) & (b >= 0)
    inside &= b <= damping_limit(dynamics, period)
    if m is not None:
        low, high = mass_limits(dynamics, period)
        inside &= (m >= low) & (m <= high) & (dynamics.inertia + m > 0)
    return inside
