"""Mathavan, Jackson and Parkin 2010's cushion: the impact integrated over its impulse.

S. Mathavan, M. R. Jackson, R. M. Parkin, "A theoretical analysis of billiard ball
dynamics under cushion impacts", Proc. IMechE C 224(9), 1863-1873 (2010), eqs. 12-17.
The nose touches the ball at I, theta above its equator (sin theta = h / R - 1), the
table at C. Both contacts slip, each friction opposing its slip with mu_w (cushion) or
mu_s (cloth) times its normal force (the table's: the cushion's push downwards). In the
normal impulse P at I every velocity is linear, with coefficients set by the two slip
directions. Compression runs until the normal speed at I is zero, restitution until
the normal force has done back e_e^2 of the work it absorbed.

Frame (pooltool's): y into the cushion, x = y cross z along it, z up. Slip directions
come from sqrt (never atan2/sin/cos), and P is taken in fixed classical Runge-Kutta
steps of 1/STEPS_PER_MOMENTUM of the normal momentum. A slip reaching zero inside a
step (a rolling ball's at the cushion) splits the step there; a contact at zero slip
sticks if its holding friction lies within its cone, else slides along it. Phase ends
are found by Newton steps. Python floats and `math.sqrt` only: the same bits everywhere.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

from billiards.physics.numerics.arithmetic import length

# Converged: halving the step changes the rebound by under 1e-9 m/s (2.1e-10, and 9.0e-10
# in R w, at a 1.56 m/s oblique shot with every spin), the paper's rolling shots only by
# roundings (tests/physics/test_mathavan2010.py).
STEPS_PER_MOMENTUM = 256
# A slip this small against the ball's own speed is at rest (rounding, or a split).
ZERO_SLIP = 1e-10
NEWTON_STEPS = 3  # a phase's end: its first guess is already within rounding in 1D

State = tuple[float, float, float, float, float, float]  # vx, vy, wx, wy, wz, work
Slopes = tuple[float, float, float, float, float]  # d(vx, vy, wx, wy, wz)/dP
# For a step split at a slip's zero, the slips at its start (the ways the slips had).
Ways = tuple[float, float, float, float] | None
# The slopes of the velocity and spin at a state, the contacts at rest (or sliding).
SlopesAt = Callable[[float, float, float, float, float, bool, bool, Ways], Slopes]

# Speed (issue 31): an impact takes about 500 steps of 4 stages, so the common step (both
# contacts sliding) is written out on local names in _slide; slopes() and _step() take the
# rest, by the same operations in the same order (tests/physics/test_mathavan2010.py).


class _Impact(NamedTuple):
    """One ball's impact: its mass and radius, the nose's angle, the two frictions."""

    mass: float
    radius: float
    sin_t: float
    cos_t: float
    mu_w: float  # at the nose
    mu_s: float  # on the cloth


def _slopes_of(impact: _Impact) -> SlopesAt:
    """The impact's d(velocity, spin)/dP (the paper's eqs. 12a-e), constants bound."""
    m, r, s, c, mu_w, mu_s = impact
    turn = 5.0 / (2.0 * m * r)  # dw per unit impulse arm: R / I
    minus_turn = -turn
    # M d(slip)/dP, linear in the frictions (the paper's eq. 12 at the contacts):
    #   I: x: -7/2 f1 + a g1,   y: s c - b f2 + d g2
    #   C: x:  a f1 - 7/2 g1,   y: -c + d f2 - 7/2 g2
    a, b, d = 2.5 * s - 1.0, s * s + 2.5, s - 2.5
    held_f2 = c * (s - 2.0 * d / 7.0) / (b - 2.0 * d * d / 7.0)  # both contacts held
    s_c, a_mu_s = s * c, a * mu_s
    d_mu_s_s, d_mu_s_c = d * mu_s * s, d * mu_s * c

    def slopes(
        vx: float,
        vy: float,
        wx: float,
        wy: float,
        wz: float,
        cushion_at_rest: bool,
        table_at_rest: bool,
        ways: Ways,
    ) -> Slopes:
        # The friction impulses (f1, f2) at I and (g1, g2) at C per unit normal impulse,
        # each along its slip (the ball is pushed against it): mu_w and mu_s N_C, N_C =
        # sin theta + f2 cos theta the table's normal impulse; at a contact at rest, the
        # friction that keeps it at rest, clipped to its cone.
        sx_i, sy_i = vx + r * (wy * s - wz * c), r * wx - vy * s  # the slip at I
        sx_c, sy_c = vx - r * wy, vy + r * wx  # at C
        if ways is not None:  # a split step: a slip reversed by a rounding keeps its way
            if not sx_i * ways[0] + sy_i * ways[1] > 0.0:
                sx_i, sy_i = ways[0], ways[1]
            if not sx_c * ways[2] + sy_c * ways[3] > 0.0:
                sx_c, sy_c = ways[2], ways[3]
        # A slip exactly zero at a stage (a split step's end lands on it) is at rest too.
        size_i = size_c = 0.0
        if not cushion_at_rest:
            size_i = math.sqrt(sx_i * sx_i + sy_i * sy_i)
            cushion_at_rest = size_i == 0.0
        if not table_at_rest:
            size_c = math.sqrt(sx_c * sx_c + sy_c * sy_c)
            table_at_rest = size_c == 0.0
        if not cushion_at_rest:
            f1, f2 = mu_w * sx_i / size_i, mu_w * sy_i / size_i
        elif table_at_rest:  # both held: the four equations at zero slip rate
            f1, f2 = 0.0, held_f2
        else:  # the cloth slides: its friction follows N_C, linear in f2
            ux, uy = sx_c / size_c, sy_c / size_c
            f2 = (s_c + d_mu_s_s * uy) / (b - d_mu_s_c * uy)
            f1 = a_mu_s * (s + c * f2) * ux / 3.5
        if cushion_at_rest:
            holding = math.sqrt(f1 * f1 + f2 * f2)
            if holding > mu_w:
                f1, f2 = mu_w * f1 / holding, mu_w * f2 / holding
        normal_c = s + c * f2
        if normal_c < 0.0:  # max(normal_c, 0.0)
            normal_c = 0.0
        if not table_at_rest:
            push = mu_s * normal_c
            g1, g2 = push * sx_c / size_c, push * sy_c / size_c
        else:
            g1, g2 = a * f1 / 3.5, (d * f2 - c) / 3.5
            holding = math.sqrt(g1 * g1 + g2 * g2)
            limit = mu_s * normal_c
            if holding > limit:
                g1, g2 = limit * g1 / holding, limit * g2 / holding
        dvx, dvy = -(f1 + g1) / m, -(c - s * f2 + g2) / m
        return dvx, dvy, minus_turn * (f2 + g2), minus_turn * (f1 * s - g1), turn * f1 * c

    return slopes


def _step(
    slopes: SlopesAt,
    state: State,
    first: State,
    size: float,
    work_c: float,
    cushion_at_rest: bool,
    table_at_rest: bool,
    ways: Ways,
) -> State:
    """One classical Runge-Kutta step of `size` in P from `state`, its rate there
    `first`, the contacts' modes held. The work's rate is work_c times vy (c, or -c
    while the ball is pushed back out); no rate depends on the work."""
    vx, vy, wx, wy, wz, work = state
    k0, k1, k2, k3, k4, _ = t0, t1, t2, t3, t4, t5 = first
    half = 0.5 * size
    for _ in range(2):  # the middle stages, each from the state along the one before
        y = vy + half * k1
        k0, k1, k2, k3, k4 = slopes(
            vx + half * k0,
            y,
            wx + half * k2,
            wy + half * k3,
            wz + half * k4,
            cushion_at_rest,
            table_at_rest,
            ways,
        )
        t0, t1, t2 = t0 + 2.0 * k0, t1 + 2.0 * k1, t2 + 2.0 * k2
        t3, t4, t5 = t3 + 2.0 * k3, t4 + 2.0 * k4, t5 + 2.0 * (y * work_c)
    y = vy + size * k1  # the last stage, and the sum a + 2 b + 2 c + d
    k0, k1, k2, k3, k4 = slopes(
        vx + size * k0,
        y,
        wx + size * k2,
        wy + size * k3,
        wz + size * k4,
        cushion_at_rest,
        table_at_rest,
        ways,
    )
    sixth = size / 6.0
    vx, vy, wx = vx + sixth * (t0 + k0), vy + sixth * (t1 + k1), wx + sixth * (t2 + k2)
    wy, wz, work = wy + sixth * (t3 + k3), wz + sixth * (t4 + k4), work + sixth * (t5 + y * work_c)
    return vx, vy, wx, wy, wz, work


def _phase(
    impact: _Impact, slopes: SlopesAt, state: State, step: float, scale: float, target: float | None
) -> State:
    """Integrate one phase from `state` in steps of `step`: compression (target None)
    until the normal speed vy is zero, restitution until the work reaches `target`.
    Runs of plain steps go to _slide; here the others, one at a time."""
    r, s, c = impact.radius, impact.sin_t, impact.cos_t
    work_c = c if target is None else -c  # d(work)/dP = +-vy cos(theta)
    at_rest = ZERO_SLIP * scale
    landed_i = landed_c = False  # a contact whose slip a split step just brought to zero
    sliding = True  # both contacts slid at the last step here: _slide may take the next
    left = 64 * STEPS_PER_MOMENTUM + 64  # steps
    while left:
        tried = None  # the step's first rate and trial, if _slide stopped at its events
        if sliding and not (landed_i or landed_c):
            taken, state, tried = _slide(impact, state, step, work_c, target, at_rest, left)
            left -= taken
            if not left:
                break
        left -= 1
        vx, vy, wx, wy, wz, work = state
        sx_i, sy_i = vx + r * (wy * s - wz * c), r * wx - vy * s  # the slips at I and at C
        sx_c, sy_c = vx - r * wy, vy + r * wx
        square_i, square_c = sx_i * sx_i + sy_i * sy_i, sx_c * sx_c + sy_c * sy_c
        cushion_at_rest = landed_i or math.sqrt(square_i) <= at_rest
        table_at_rest = landed_c or math.sqrt(square_c) <= at_rest
        sliding = not (cushion_at_rest or table_at_rest)
        if tried is None:
            a0, a1, a2, a3, a4 = slopes(vx, vy, wx, wy, wz, cushion_at_rest, table_at_rest, None)
            a5 = vy * work_c
            first = (a0, a1, a2, a3, a4, a5)
            trial = _step(slopes, state, first, step, work_c, cushion_at_rest, table_at_rest, None)
        else:
            first, trial = tried
            a0, a1, a2, a3, a4, a5 = first
        tvx, tvy, twx, twy, twz, twork = trial
        spun = r * twx
        tsx_i, tsy_i = tvx + r * (twy * s - twz * c), spun - tvy * s
        tsx_c, tsy_c = tvx - r * twy, tvy + spun
        # The events the trial passed (the phase's end, a slip's zero), each as the share
        # of the step that reaches it along the first slope.
        share, event = 2.0, -1
        if target is None:
            if tvy <= 0.0:
                share, event = vy / (-a1 * step), 2
        elif twork >= target:
            share, event = _to_work(work, a5, a1, target, c) / step, 2
        if not cushion_at_rest:  # M d(slip_I)/dP from the rates of v and w
            closing = -(sx_i * (a0 + r * (a3 * s - a4 * c)) + sy_i * (r * a2 - a1 * s))
            # (A stage of the trial may pass the zero that its end falls short of.)
            reach = square_i / (closing * step) if closing > 0.0 else 2.0
            if sx_i * tsx_i + sy_i * tsy_i <= 0.0 or not reach > 1.0:
                share, event = _earlier(reach, 0, share, event)
        if not table_at_rest:
            closing = -(sx_c * (a0 - r * a3) + sy_c * (a1 + r * a2))
            reach = square_c / (closing * step) if closing > 0.0 else 2.0
            if sx_c * tsx_c + sy_c * tsy_c <= 0.0 or not reach > 1.0:
                share, event = _earlier(reach, 1, share, event)
        if event < 0:
            state, landed_i, landed_c = trial, False, False
            continue
        # The step split at the event; its first rate is k1, where each slip has its own way.
        modes = (cushion_at_rest, table_at_rest)
        state = _step(
            slopes,
            state,
            first,
            min(max(share, 0.0), 1.0) * step,
            work_c,
            *modes,
            (sx_i, sy_i, sx_c, sy_c),
        )
        if event == 2:
            return _onto_end(slopes, state, work_c, modes, target, c)
        landed_i, landed_c = event == 0, event == 1
    raise ValueError("mathavan2010: the impact did not end (the frictions hold the ball)")


def _slide(
    impact: _Impact,
    state: State,
    step: float,
    work_c: float,
    target: float | None,
    at_rest: float,
    most: int,
) -> tuple[int, State, tuple[State, State] | None]:
    """_phase's plain steps (both contacts sliding, no event: most), at most `most`:
    _step written out on local names, its stages' slopes as slopes() computes them, its
    sum as a + 2 b + 2 c + d. Returns how many it took, the state they reached, and the
    next step's first rate and trial if it passed an event."""
    m, r, s, c, mu_w, mu_s = impact
    turn = 5.0 / (2.0 * m * r)  # as _slopes_of's
    minus_turn = -turn
    half, sixth = 0.5 * step, step / 6.0
    sqrt = math.sqrt
    reaches = (half, half, step, 0.0)  # after each stage, the next one's from the state
    vx, vy, wx, wy, wz, work = state
    sx_i, sy_i = vx + r * (wy * s - wz * c), r * wx - vy * s  # the slips at I and at C
    sx_c, sy_c = vx - r * wy, vy + r * wx
    for taken in range(most):
        square_i, square_c = sx_i * sx_i + sy_i * sy_i, sx_c * sx_c + sy_c * sy_c
        size_i, size_c = sqrt(square_i), sqrt(square_c)
        if size_i <= at_rest or size_c <= at_rest:
            return taken, (vx, vy, wx, wy, wz, work), None
        ax_i, ay_i, ax_c, ay_c = sx_i, sy_i, sx_c, sy_c
        x1, first = vy, True
        try:
            for reach in reaches:
                f1, f2 = mu_w * ax_i / size_i, mu_w * ay_i / size_i
                normal_c = s + c * f2
                if normal_c < 0.0:
                    normal_c = 0.0
                push = mu_s * normal_c
                g1, g2 = push * ax_c / size_c, push * ay_c / size_c
                k0, k1 = -(f1 + g1) / m, -(c - s * f2 + g2) / m
                k2, k3, k4 = minus_turn * (f2 + g2), minus_turn * (f1 * s - g1), turn * f1 * c
                k5 = x1 * work_c
                if first:  # the step's first rate
                    a0, a1, a2, a3, a4, a5 = t0, t1, t2, t3, t4, t5 = k0, k1, k2, k3, k4, k5
                    first = False
                elif reach:
                    t0, t1, t2 = t0 + 2.0 * k0, t1 + 2.0 * k1, t2 + 2.0 * k2
                    t3, t4, t5 = t3 + 2.0 * k3, t4 + 2.0 * k4, t5 + 2.0 * k5
                else:
                    t0, t1, t2 = t0 + k0, t1 + k1, t2 + k2
                    t3, t4, t5 = t3 + k3, t4 + k4, t5 + k5
                    break
                x0, x1, x2 = vx + reach * k0, vy + reach * k1, wx + reach * k2
                x3, x4 = wy + reach * k3, wz + reach * k4
                spun = r * x2  # R w_x, in both slips
                ax_i, ay_i = x0 + r * (x3 * s - x4 * c), spun - x1 * s
                ax_c, ay_c = x0 - r * x3, x1 + spun
                size_i = sqrt(ax_i * ax_i + ay_i * ay_i)
                size_c = sqrt(ax_c * ax_c + ay_c * ay_c)
        except ZeroDivisionError:  # a slip exactly zero at a stage: _phase holds it there
            return taken, (vx, vy, wx, wy, wz, work), None
        tvx, tvy, twx = vx + sixth * t0, vy + sixth * t1, wx + sixth * t2
        twy, twz, twork = wy + sixth * t3, wz + sixth * t4, work + sixth * t5
        spun = r * twx
        tsx_i, tsy_i = tvx + r * (twy * s - twz * c), spun - tvy * s
        tsx_c, tsy_c = tvx - r * twy, tvy + spun
        # _phase's slip events: a reversal, or a zero within the step along a0..a5.
        closing_i = -(sx_i * (a0 + r * (a3 * s - a4 * c)) + sy_i * (r * a2 - a1 * s))
        closing_c = -(sx_c * (a0 - r * a3) + sy_c * (a1 + r * a2))
        if (
            ((tvy <= 0.0) if target is None else (twork >= target))
            or sx_i * tsx_i + sy_i * tsy_i <= 0.0
            or sx_c * tsx_c + sy_c * tsy_c <= 0.0
            or (closing_i > 0.0 and not square_i / (closing_i * step) > 1.0)
            or (closing_c > 0.0 and not square_c / (closing_c * step) > 1.0)
        ):
            tried = (a0, a1, a2, a3, a4, a5), (tvx, tvy, twx, twy, twz, twork)
            return taken, (vx, vy, wx, wy, wz, work), tried
        vx, vy, wx = tvx, tvy, twx
        wy, wz, work = twy, twz, twork
        sx_i, sy_i, sx_c, sy_c = tsx_i, tsy_i, tsx_c, tsy_c
    return most, (vx, vy, wx, wy, wz, work), None


def _onto_end(
    slopes: SlopesAt,
    state: State,
    work_c: float,
    modes: tuple[bool, bool],
    target: float | None,
    cos_t: float,
) -> State:
    """Newton steps onto the phase's end: vy = 0, or the work at `target`."""
    for _ in range(NEWTON_STEPS):
        vx, vy, wx, wy, wz, work = state
        rate = (*slopes(vx, vy, wx, wy, wz, *modes, None), vy * work_c)
        remaining = (
            vy / -rate[1] if target is None else _to_work(work, rate[5], rate[1], target, cos_t)
        )
        state = _step(slopes, state, rate, remaining, work_c, *modes, None)
    return state


def _earlier(reach: float, slip: int, share: float, event: int) -> tuple[float, int]:
    """A slip's zero at `reach` of the step if before the event found at `share`."""
    if reach > 1.0:
        reach = 1.0
    return (reach, slip) if reach < share else (share, event)


def _to_work(work: float, slope: float, vy_slope: float, target: float, cos_t: float) -> float:
    """The impulse that brings the work to `target`: W + a x + b x^2 / 2 = target, with
    a = dW/dP and b = -cos(theta) dvy/dP (vy falls linearly at first), in the stable
    form 2 D / (a + sqrt(a^2 + 2 b D)); D may be a rounding below zero near the end."""
    remaining = target - work
    bend = max(-cos_t * vy_slope, 0.0)
    root = math.sqrt(max(slope * slope + 2.0 * bend * remaining, 0.0))
    if slope + root <= 0.0:
        return 0.0
    return 2.0 * remaining / (slope + root)


def rebound(
    velocity: tuple[float, float],
    spin: tuple[float, float, float],
    mass: float,
    radius: float,
    height: float,
    restitution: float,
    cushion_friction: float,
    table_friction: float,
    steps: int = STEPS_PER_MOMENTUM,
) -> tuple[float, float, float, float, float]:
    """One ball's impact in the cushion frame: velocity (vx along the cushion, vy > 0
    into it) and spin (wx, wy, wz) in m/s and rad/s, the nose at `height` above the
    cloth, e_e = `restitution`, mu_w = `cushion_friction`, mu_s = `table_friction`.
    Returns (vx, vy, wx, wy, wz) after it; vy <= 0 (the ball leaves, or slides along)."""
    sin_t = height / radius - 1.0
    cos_t = math.sqrt(max(1.0 - sin_t * sin_t, 0.0))
    impact = _Impact(mass, radius, sin_t, cos_t, cushion_friction, table_friction)
    slopes = _slopes_of(impact)
    vx, vy = velocity
    wx, wy, wz = spin
    if not vy > 0.0:  # not into the cushion: no impact
        return vx, vy, wx, wy, wz
    scale = length(vx, vy) + radius * math.sqrt(wx * wx + wy * wy + wz * wz)
    step = mass * vy / steps
    state = _phase(impact, slopes, (vx, vy, wx, wy, wz, 0.0), step, scale, None)
    target = restitution * restitution * state[5]  # of the work compression absorbed
    state = (state[0], state[1], state[2], state[3], state[4], 0.0)
    if target > 0.0:
        state = _phase(impact, slopes, state, step, scale, target)
    return state[0], min(state[1], 0.0), state[2], state[3], state[4]
