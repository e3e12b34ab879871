"""Mathavan, Jackson and Parkin 2010's cushion, compiled (laws.mathavan2010's
integration and laws.cushion's mathavan2010 and mathavan2010_ev): the same fixed
Runge-Kutta steps, split steps and Newton steps, operation for operation.

Where the Python floats of the numpy law raise (a division by zero: arithmetic.quotient),
this raises too; the written-out step's zero slip (a ZeroDivisionError the numpy law
catches) is asked before it divides. A step's state is (vx, vy, wx, wy, wz, work); the
split step's slip directions (`ways`) come with a flag saying whether they hold.

Cost: an impact takes about 450 written-out steps of 4 stages and 200 other slopes
(the seed's constants, 0.5-5 m/s), each stage a chain of two square roots and four
divisions that the next stage waits for: about 60 us a contact (scripts/bench_laws.py),
against 1.7 ms in numpy. Only fewer steps would make it faster, and they change the bits.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from billiards.physics.compiled.arithmetic import length, py_max, py_min, quotient
from billiards.physics.compiled.jit import kernel
from billiards.physics.compiled.laws import CushionNumbers, Spin, Vector
from billiards.physics.compiled.state import Flag
from billiards.physics.laws.mathavan2010 import NEWTON_STEPS, STEPS_PER_MOMENTUM, ZERO_SLIP

State = tuple[float, float, float, float, float, float]  # vx, vy, wx, wy, wz, work
Slopes = tuple[float, float, float, float, float]  # d(vx, vy, wx, wy, wz)/dP
Ways = tuple[float, float, float, float]  # a split step's slips at its start: I, then C
NO_WAYS: Ways = (0.0, 0.0, 0.0, 0.0)
NO_STATE: State = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
MOST_STEPS = 64 * STEPS_PER_MOMENTUM + 64  # a phase's
# Flags and counts are handed on as np.bool_ and np.int64 values, not constants: numba
# compiles a kernel once for each constant it is handed (twice the compile, same code).


class Impact(NamedTuple):
    """One ball's impact (mathavan2010._Impact) and the constants _slopes_of binds."""

    mass: float
    radius: float
    sin_t: float
    cos_t: float
    mu_w: float  # at the nose
    mu_s: float  # on the cloth
    turn: float  # dw per unit impulse arm: R / I
    minus_turn: float
    a: float
    b: float
    d: float
    held_f2: float  # both contacts held
    s_c: float
    a_mu_s: float
    d_mu_s_s: float
    d_mu_s_c: float


@kernel
def impact_of(
    mass: float, radius: float, sin_t: float, cos_t: float, mu_w: float, mu_s: float
) -> Impact:
    """The impact's constants, as mathavan2010._slopes_of computes them."""
    s, c = sin_t, cos_t
    turn = 5.0 / (2.0 * mass * radius)
    a, b, d = 2.5 * s - 1.0, s * s + 2.5, s - 2.5
    held_f2 = quotient(c * (s - 2.0 * d / 7.0), b - 2.0 * d * d / 7.0)
    return Impact(
        mass=mass,
        radius=radius,
        sin_t=s,
        cos_t=c,
        mu_w=mu_w,
        mu_s=mu_s,
        turn=turn,
        minus_turn=-turn,
        a=a,
        b=b,
        d=d,
        held_f2=held_f2,
        s_c=s * c,
        a_mu_s=a * mu_s,
        d_mu_s_s=d * mu_s * s,
        d_mu_s_c=d * mu_s * c,
    )


@kernel
def slopes(
    impact: Impact,
    velocity_spin: Slopes,
    cushion_at_rest: bool,
    table_at_rest: bool,
    has_ways: Flag,
    ways: Ways,
) -> Slopes:
    """The impact's d(velocity, spin)/dP at (vx, vy, wx, wy, wz), the contacts at rest
    or sliding (mathavan2010._slopes_of's slopes, the paper's eqs. 12a-e)."""
    vx, vy, wx, wy, wz = velocity_spin
    r, s, c = impact.radius, impact.sin_t, impact.cos_t
    mu_w, mu_s = impact.mu_w, impact.mu_s
    sx_i, sy_i = vx + r * (wy * s - wz * c), r * wx - vy * s  # the slip at I
    sx_c, sy_c = vx - r * wy, vy + r * wx  # at C
    if has_ways:  # a split step: a slip reversed by a rounding keeps its way
        if not sx_i * ways[0] + sy_i * ways[1] > 0.0:
            sx_i, sy_i = ways[0], ways[1]
        if not sx_c * ways[2] + sy_c * ways[3] > 0.0:
            sx_c, sy_c = ways[2], ways[3]
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
        f1, f2 = 0.0, impact.held_f2
    else:  # the cloth slides: its friction follows N_C, linear in f2
        ux, uy = sx_c / size_c, sy_c / size_c
        f2 = quotient(impact.s_c + impact.d_mu_s_s * uy, impact.b - impact.d_mu_s_c * uy)
        f1 = impact.a_mu_s * (s + c * f2) * ux / 3.5
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
        g1, g2 = impact.a * f1 / 3.5, (impact.d * f2 - c) / 3.5
        holding = math.sqrt(g1 * g1 + g2 * g2)
        limit = mu_s * normal_c
        if holding > limit:
            g1, g2 = limit * g1 / holding, limit * g2 / holding
    m, turn = impact.mass, impact.turn
    dvx, dvy = -(f1 + g1) / m, -(c - s * f2 + g2) / m
    return dvx, dvy, impact.minus_turn * (f2 + g2), impact.minus_turn * (f1 * s - g1), turn * f1 * c


@kernel
def step(
    impact: Impact,
    state: State,
    first: State,
    size: float,
    work_c: float,
    modes: tuple[bool, bool],
    has_ways: Flag,
    ways: Ways,
) -> State:
    """One classical Runge-Kutta step of `size` in P from `state`, its rate there
    `first`, the contacts' modes (cushion, table at rest) held (mathavan2010._step)."""
    vx, vy, wx, wy, wz, work = state
    k0, k1, k2, k3, k4, _ = first
    t0, t1, t2, t3, t4, t5 = first
    half = 0.5 * size
    for _ in range(2):  # the middle stages, each from the state along the one before
        y = vy + half * k1
        k0, k1, k2, k3, k4 = slopes(
            impact,
            (vx + half * k0, y, wx + half * k2, wy + half * k3, wz + half * k4),
            modes[0],
            modes[1],
            has_ways,
            ways,
        )
        t0, t1, t2 = t0 + 2.0 * k0, t1 + 2.0 * k1, t2 + 2.0 * k2
        t3, t4, t5 = t3 + 2.0 * k3, t4 + 2.0 * k4, t5 + 2.0 * (y * work_c)
    y = vy + size * k1  # the last stage, and the sum a + 2 b + 2 c + d
    k0, k1, k2, k3, k4 = slopes(
        impact,
        (vx + size * k0, y, wx + size * k2, wy + size * k3, wz + size * k4),
        modes[0],
        modes[1],
        has_ways,
        ways,
    )
    sixth = size / 6.0
    vx, vy, wx = vx + sixth * (t0 + k0), vy + sixth * (t1 + k1), wx + sixth * (t2 + k2)
    wy, wz, work = wy + sixth * (t3 + k3), wz + sixth * (t4 + k4), work + sixth * (t5 + y * work_c)
    return vx, vy, wx, wy, wz, work


@kernel
def phase(
    impact: Impact, state: State, size: float, scale: float, has_target: Flag, target: float
) -> State:
    """Integrate one phase from `state` in steps of `size` (mathavan2010._phase):
    compression (no target) until vy is zero, restitution until the work reaches
    `target`. Runs of plain steps go to `slide`; here the others, one at a time."""
    r, s, c = impact.radius, impact.sin_t, impact.cos_t
    work_c = -c if has_target else c  # d(work)/dP = +-vy cos(theta)
    at_rest = ZERO_SLIP * scale
    landed_i = landed_c = False  # a contact whose slip a split step just brought to zero
    sliding = True  # both contacts slid at the last step here: slide may take the next
    left = int(np.int64(MOST_STEPS))
    while left:
        tried, first, trial = False, NO_STATE, NO_STATE
        if sliding and not (landed_i or landed_c):
            taken, state, tried, first, trial = slide(
                impact, state, size, work_c, has_target, target, at_rest, left
            )
            left -= taken
            if not left:
                break
        left -= 1
        vx, vy, wx, wy, wz, _ = state
        slips = (vx + r * (wy * s - wz * c), r * wx - vy * s, vx - r * wy, vy + r * wx)
        square_i = slips[0] * slips[0] + slips[1] * slips[1]
        square_c = slips[2] * slips[2] + slips[3] * slips[3]
        cushion_at_rest = landed_i or math.sqrt(square_i) <= at_rest
        table_at_rest = landed_c or math.sqrt(square_c) <= at_rest
        sliding = not (cushion_at_rest or table_at_rest)
        modes = (cushion_at_rest, table_at_rest)
        if not tried:
            a0, a1, a2, a3, a4 = slopes(
                impact, (vx, vy, wx, wy, wz), modes[0], modes[1], np.bool_(False), NO_WAYS
            )
            first = (a0, a1, a2, a3, a4, vy * work_c)
            trial = step(impact, state, first, size, work_c, modes, np.bool_(False), NO_WAYS)
        share, event = passed_event(
            impact, state, first, trial, slips, modes, size, has_target, target
        )
        if event < 0:
            state, landed_i, landed_c = trial, False, False
            continue
        # The step split at the event; its first rate is k1, where each slip has its own way.
        split = py_min(py_max(share, 0.0), 1.0) * size
        state = step(impact, state, first, split, work_c, modes, np.bool_(True), slips)
        if event == 2:
            return onto_end(impact, state, work_c, modes, has_target, target)
        landed_i, landed_c = event == 0, event == 1
    raise ValueError("mathavan2010: the impact did not end (the frictions hold the ball)")


@kernel
def passed_event(
    impact: Impact,
    state: State,
    first: State,
    trial: State,
    slips: Ways,
    modes: tuple[bool, bool],
    size: float,
    has_target: Flag,
    target: float,
) -> tuple[float, int]:
    """The earliest event a trial step passed, as the share of the step that reaches it
    along the first slope, and which: the phase's end (2), a slip's zero at I (0) or at
    C (1); -1 for none (mathavan2010._phase's test of its trial)."""
    r, s, c = impact.radius, impact.sin_t, impact.cos_t
    vy, work = state[1], state[5]
    a0, a1, a2, a3, a4, a5 = first
    tvx, tvy, twx, twy, twz, twork = trial
    sx_i, sy_i, sx_c, sy_c = slips
    spun = r * twx
    tsx_i, tsy_i = tvx + r * (twy * s - twz * c), spun - tvy * s
    tsx_c, tsy_c = tvx - r * twy, tvy + spun
    share, event = 2.0, -1
    if not has_target:
        if tvy <= 0.0:
            share, event = quotient(vy, -a1 * size), 2
    elif twork >= target:
        share, event = quotient(to_work(work, a5, a1, target, c), size), 2
    if not modes[0]:  # M d(slip_I)/dP from the rates of v and w
        closing = -(sx_i * (a0 + r * (a3 * s - a4 * c)) + sy_i * (r * a2 - a1 * s))
        # (A stage of the trial may pass the zero that its end falls short of.)
        square = sx_i * sx_i + sy_i * sy_i
        reach = quotient(square, closing * size) if closing > 0.0 else 2.0
        if sx_i * tsx_i + sy_i * tsy_i <= 0.0 or not reach > 1.0:
            share, event = earlier(reach, 0, share, event)
    if not modes[1]:
        closing = -(sx_c * (a0 - r * a3) + sy_c * (a1 + r * a2))
        square = sx_c * sx_c + sy_c * sy_c
        reach = quotient(square, closing * size) if closing > 0.0 else 2.0
        if sx_c * tsx_c + sy_c * tsy_c <= 0.0 or not reach > 1.0:
            share, event = earlier(reach, 1, share, event)
    return share, event


@kernel
def slide(
    impact: Impact,
    state: State,
    size: float,
    work_c: float,
    has_target: Flag,
    target: float,
    at_rest: float,
    most: int,
) -> tuple[int, State, bool, State, State]:
    """phase's plain steps (both contacts sliding, no event: mathavan2010._slide), at
    most `most`. Returns how many it took, the state they reached, and whether it
    passed an event, with the next step's first rate and trial if so."""
    r, s, c = impact.radius, impact.sin_t, impact.cos_t
    vx, vy, wx, wy, wz, work = state
    slips = (vx + r * (wy * s - wz * c), r * wx - vy * s, vx - r * wy, vy + r * wx)
    for taken in range(most):
        sx_i, sy_i, sx_c, sy_c = slips
        square_i, square_c = sx_i * sx_i + sy_i * sy_i, sx_c * sx_c + sy_c * sy_c
        size_i, size_c = math.sqrt(square_i), math.sqrt(square_c)
        if size_i <= at_rest or size_c <= at_rest:
            return taken, (vx, vy, wx, wy, wz, work), False, NO_STATE, NO_STATE
        held, first, trial = sliding_step(impact, state, slips, (size_i, size_c), size, work_c)
        if held:  # a slip exactly zero at a stage: phase holds it there
            return taken, (vx, vy, wx, wy, wz, work), False, NO_STATE, NO_STATE
        a0, a1, a2, a3, a4, _ = first
        tvx, tvy, twx, twy, twz, twork = trial
        spun = r * twx
        tsx_i, tsy_i = tvx + r * (twy * s - twz * c), spun - tvy * s
        tsx_c, tsy_c = tvx - r * twy, tvy + spun
        # phase's slip events: a reversal, or a zero within the step along a0..a5.
        closing_i = -(sx_i * (a0 + r * (a3 * s - a4 * c)) + sy_i * (r * a2 - a1 * s))
        closing_c = -(sx_c * (a0 - r * a3) + sy_c * (a1 + r * a2))
        if (
            ((twork >= target) if has_target else (tvy <= 0.0))
            or sx_i * tsx_i + sy_i * tsy_i <= 0.0
            or sx_c * tsx_c + sy_c * tsy_c <= 0.0
            or (closing_i > 0.0 and not quotient(square_i, closing_i * size) > 1.0)
            or (closing_c > 0.0 and not quotient(square_c, closing_c * size) > 1.0)
        ):
            return taken, (vx, vy, wx, wy, wz, work), True, first, trial
        vx, vy, wx, wy, wz, work = state = trial
        slips = (tsx_i, tsy_i, tsx_c, tsy_c)
    return most, (vx, vy, wx, wy, wz, work), False, NO_STATE, NO_STATE


@kernel
def sliding_step(
    impact: Impact,
    state: State,
    slips: Ways,
    sizes: Vector,
    size: float,
    work_c: float,
) -> tuple[bool, State, State]:
    """One step with both contacts sliding: step written out, its stages' slopes as
    slopes computes them, its sum as a + 2 b + 2 c + d (mathavan2010._slide's inner
    loop). Returns (a slip was exactly zero at a stage, the first rate, the trial)."""
    m, r, s, c = impact.mass, impact.radius, impact.sin_t, impact.cos_t
    mu_w, mu_s, turn, minus_turn = impact.mu_w, impact.mu_s, impact.turn, impact.minus_turn
    vx, vy, wx, wy, wz, work = state
    half, sixth = 0.5 * size, size / 6.0
    reaches = (half, half, size, 0.0)  # after each stage, the next one's from the state
    ax_i, ay_i, ax_c, ay_c = slips
    size_i, size_c = sizes
    x1 = vy
    first = NO_STATE
    t0 = t1 = t2 = t3 = t4 = t5 = 0.0
    for index in range(4):
        if size_i == 0.0 or size_c == 0.0:  # where the numpy law divides by zero
            return True, NO_STATE, NO_STATE
        f1, f2 = mu_w * ax_i / size_i, mu_w * ay_i / size_i
        normal_c = s + c * f2
        if normal_c < 0.0:
            normal_c = 0.0
        push = mu_s * normal_c
        g1, g2 = push * ax_c / size_c, push * ay_c / size_c
        k0, k1 = -(f1 + g1) / m, -(c - s * f2 + g2) / m
        k2, k3, k4 = minus_turn * (f2 + g2), minus_turn * (f1 * s - g1), turn * f1 * c
        k5 = x1 * work_c
        reach = reaches[index]
        if index == 0:  # the step's first rate
            first = (k0, k1, k2, k3, k4, k5)
            t0, t1, t2, t3, t4, t5 = first
        elif reach != 0.0:
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
        size_i = math.sqrt(ax_i * ax_i + ay_i * ay_i)
        size_c = math.sqrt(ax_c * ax_c + ay_c * ay_c)
    trial = (
        vx + sixth * t0,
        vy + sixth * t1,
        wx + sixth * t2,
        wy + sixth * t3,
        wz + sixth * t4,
        work + sixth * t5,
    )
    return False, first, trial


@kernel
def onto_end(
    impact: Impact,
    state: State,
    work_c: float,
    modes: tuple[bool, bool],
    has_target: Flag,
    target: float,
) -> State:
    """Newton steps onto the phase's end: vy = 0, or the work at `target`."""
    for _ in range(NEWTON_STEPS):
        vx, vy, wx, wy, wz, work = state
        k0, k1, k2, k3, k4 = slopes(
            impact, (vx, vy, wx, wy, wz), modes[0], modes[1], np.bool_(False), NO_WAYS
        )
        rate = (k0, k1, k2, k3, k4, vy * work_c)
        if has_target:
            remaining = to_work(work, rate[5], rate[1], target, impact.cos_t)
        else:
            remaining = quotient(vy, -rate[1])
        state = step(impact, state, rate, remaining, work_c, modes, np.bool_(False), NO_WAYS)
    return state


@kernel
def earlier(reach: float, slip: int, share: float, event: int) -> tuple[float, int]:
    """A slip's zero at `reach` of the step if before the event found at `share`."""
    if reach > 1.0:
        reach = 1.0
    return (reach, slip) if reach < share else (share, event)


@kernel
def to_work(work: float, slope: float, vy_slope: float, target: float, cos_t: float) -> float:
    """The impulse that brings the work to `target` (mathavan2010._to_work)."""
    remaining = target - work
    bend = py_max(-cos_t * vy_slope, 0.0)
    root = math.sqrt(py_max(slope * slope + 2.0 * bend * remaining, 0.0))
    if slope + root <= 0.0:
        return 0.0
    return 2.0 * remaining / (slope + root)


@kernel
def rebound(
    velocity: Vector,
    spin: Spin,
    mass: float,
    radius: float,
    height: float,
    restitution: float,
    cushion_friction: float,
    table_friction: float,
) -> tuple[float, float, float, float, float]:
    """One ball's impact in the cushion frame (mathavan2010.rebound, its default steps):
    velocity (vx along the cushion, vy > 0 into it) and spin -> (vx, vy, wx, wy, wz)."""
    sin_t = quotient(height, radius) - 1.0
    cos_t = math.sqrt(py_max(1.0 - sin_t * sin_t, 0.0))
    impact = impact_of(mass, radius, sin_t, cos_t, cushion_friction, table_friction)
    vx, vy = velocity
    wx, wy, wz = spin
    if not vy > 0.0:  # not into the cushion: no impact
        return vx, vy, wx, wy, wz
    scale = length(vx, vy) + radius * math.sqrt(wx * wx + wy * wy + wz * wz)
    size = mass * vy / STEPS_PER_MOMENTUM
    state = phase(impact, (vx, vy, wx, wy, wz, 0.0), size, scale, np.bool_(False), 0.0)
    target = restitution * restitution * state[5]  # of the work compression absorbed
    state = (state[0], state[1], state[2], state[3], state[4], 0.0)
    if target > 0.0:
        state = phase(impact, state, size, scale, np.bool_(True), target)
    return state[0], py_min(state[1], 0.0), state[2], state[3], state[4]


@kernel
def cushion_impact(
    velocity: Vector,
    spin: Spin,
    into: Vector,
    mass: float,
    constants: CushionNumbers,
    speed_dependent: Flag,
) -> tuple[Vector, Spin, float]:
    """cushion.mathavan2010 on one ball: turned into the paper's frame (y `into` the
    cushion, x = into cross z), integrated, turned back; a ball not moving into the
    cushion passes, approach 0. With `speed_dependent`, e_e = e_0 / sqrt(1 + (v_n /
    v_c)^4)."""
    nx, ny = into
    ax, ay = ny, -nx  # the paper's x: into cross z
    v_x, v_y = velocity
    w_x, w_y, w_z = spin
    normal = v_x * nx + v_y * ny
    if not normal > 0.0:
        return velocity, spin, 0.0
    along, spin_along, spin_into = v_x * ax + v_y * ay, w_x * ax + w_y * ay, w_x * nx + w_y * ny
    e_e = constants.cushion_restitution
    if speed_dependent:
        share = quotient(normal, constants.cushion_restitution_speed)
        e_e = e_e / math.sqrt(1.0 + share * share * share * share)
    out = rebound(
        (along, normal),
        (spin_along, spin_into, w_z),
        mass,
        constants.radius,
        constants.cushion_height,
        e_e,
        constants.cushion_friction,
        constants.sliding_friction,
    )
    new_velocity = (out[0] * ax + out[1] * nx, out[0] * ay + out[1] * ny)
    new_spin = (out[2] * ax + out[3] * nx, out[2] * ay + out[3] * ny, out[4])
    return new_velocity, new_spin, normal


@kernel
def mathavan2010(
    velocity: Vector, spin: Spin, into: Vector, mass: float, constants: CushionNumbers
) -> tuple[Vector, Spin, float]:
    """The registry's mathavan2010, in the cushion laws' one signature."""
    return cushion_impact(velocity, spin, into, mass, constants, np.bool_(False))


@kernel
def mathavan2010_ev(
    velocity: Vector, spin: Spin, into: Vector, mass: float, constants: CushionNumbers
) -> tuple[Vector, Spin, float]:
    """The registry's mathavan2010_ev (e_e falling with the normal speed)."""
    return cushion_impact(velocity, spin, into, mass, constants, np.bool_(True))
