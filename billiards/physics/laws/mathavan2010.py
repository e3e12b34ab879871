"""Mathavan, Jackson and Parkin 2010's cushion: the impact integrated over its impulse.

S. Mathavan, M. R. Jackson, R. M. Parkin, "A theoretical analysis of billiard ball
dynamics under cushion impacts", Proc. IMechE C 224(9), 1863-1873 (2010), eqs. 12-17.
The cushion's nose touches the ball at I, theta above its equator (sin theta =
h / R - 1); the table touches it at C. Both contacts slip; the cushion pushes along its
normal, and each contact's friction opposes its slip with mu_w (cushion) and mu_s (cloth)
times its normal force, the table's normal force being the cushion's push downwards.
The independent variable is the normal impulse P at I: every velocity is linear in dP
with coefficients set by the two slip directions alone. Compression runs until the
normal speed at I is zero, restitution until the normal force has done back e_e^2 of
the work it absorbed (energy-based restitution).

Frame (pooltool's): y into the cushion, x along it (x = y cross z), z up. The slip
directions are unit vectors from sqrt, never atan2/sin/cos, and the impulse is taken in
fixed classical Runge-Kutta steps of `STEPS_PER_MOMENTUM`-ths of the ball's normal
momentum, so a row's result does not depend on its speed's scale beyond rounding. A
slip that reaches zero inside a step (the cushion's slip reverses for a rolling ball)
is met by splitting the step there; a contact at zero slip sticks if the friction that
holds it lies within its cone, else slides along that friction (its direction is then
the slip's own, exactly so at the table, whose response is isotropic). Phase ends are
located by Newton steps on the normal speed and on the work. Python floats (IEEE 754
doubles) and `math.sqrt` only: the same bits on every machine.
"""

from __future__ import annotations

import math

# The impulse step: 1/STEPS_PER_MOMENTUM of the ball's incoming normal momentum m v_n.
# Converged: the rebound changes by under 1e-9 m/s when it halves (2.1e-10, and 9.0e-10
# in R w, at a 1.56 m/s oblique shot with every spin: fourth order), the paper's rolling
# shots only by roundings at any step (tests/physics/test_mathavan2010.py).
STEPS_PER_MOMENTUM = 256
# A slip this small against the ball's own speed is a slip at rest: rounding, or a
# step split where it reached zero.
ZERO_SLIP = 1e-10
NEWTON_STEPS = 3  # a phase's end: its first guess is already within rounding in 1D

State = tuple[float, float, float, float, float, float]  # vx, vy, wx, wy, wz, work
# Each contact at rest (or sliding), and for a step split at a slip's zero the slips
# at its start (the ways the slips had), else None.
Modes = tuple[bool, bool, tuple[float, float, float, float] | None]


class _Impact:
    """One ball's impact: its constants, and the derivative of its state along P."""

    def __init__(
        self,
        mass: float,
        radius: float,
        sin_t: float,
        cos_t: float,
        cushion_friction: float,
        table_friction: float,
    ) -> None:
        self.mass, self.radius = mass, radius
        self.sin_t, self.cos_t = sin_t, cos_t
        self.mu_w, self.mu_s = cushion_friction, table_friction
        self.turn = 5.0 / (2.0 * mass * radius)  # dw per unit impulse arm: R / I

    def slips(self, state: State) -> tuple[float, float, float, float]:
        """(x, y) slip of the ball against the cushion at I, then against the cloth at C."""
        vx, vy, wx, wy, wz, _ = state
        r, s, c = self.radius, self.sin_t, self.cos_t
        return vx + r * (wy * s - wz * c), r * wx - vy * s, vx - r * wy, vy + r * wx

    def frictions(self, state: State, modes: Modes) -> tuple[float, float, float, float]:
        """The friction impulses (f1, f2) at I and (g1, g2) at C per unit normal impulse,
        each along its slip (the ball is pushed against it): mu_w and mu_s N_C, N_C =
        sin theta + f2 cos theta the table's normal impulse; at a contact at rest, the
        friction that keeps it at rest, clipped to its cone."""
        s, c, mu_w, mu_s = self.sin_t, self.cos_t, self.mu_w, self.mu_s
        cushion_at_rest, table_at_rest, ways = modes
        sx_i, sy_i, sx_c, sy_c = self.slips(state)
        if ways is not None:  # a split step: a slip reversed by a rounding keeps its way
            sx_i, sy_i = _held(sx_i, sy_i, ways[0], ways[1])
            sx_c, sy_c = _held(sx_c, sy_c, ways[2], ways[3])
        size_i = math.sqrt(sx_i * sx_i + sy_i * sy_i)
        size_c = math.sqrt(sx_c * sx_c + sy_c * sy_c)
        # A slip exactly zero at a stage (a split step's end lands on it) is at rest too.
        cushion_at_rest = cushion_at_rest or size_i == 0.0
        table_at_rest = table_at_rest or size_c == 0.0
        # M d(slip)/dP, linear in the frictions (the paper's eq. 12 at the contacts):
        #   I: x: -7/2 f1 + a g1,   y: s c - b f2 + d g2
        #   C: x:  a f1 - 7/2 g1,   y: -c + d f2 - 7/2 g2
        a, b, d = 2.5 * s - 1.0, s * s + 2.5, s - 2.5
        if not cushion_at_rest:
            f1, f2 = mu_w * sx_i / size_i, mu_w * sy_i / size_i
        else:
            if table_at_rest:  # both held: the four equations at zero slip rate
                f1, f2 = 0.0, c * (s - 2.0 * d / 7.0) / (b - 2.0 * d * d / 7.0)
            else:  # the cloth slides: its friction follows N_C, linear in f2
                ux, uy = sx_c / size_c, sy_c / size_c
                f2 = (s * c + d * mu_s * s * uy) / (b - d * mu_s * c * uy)
                f1 = a * mu_s * (s + c * f2) * ux / 3.5
            holding = math.sqrt(f1 * f1 + f2 * f2)
            if holding > mu_w:
                f1, f2 = mu_w * f1 / holding, mu_w * f2 / holding
        normal_c = max(s + c * f2, 0.0)
        if not table_at_rest:
            g1, g2 = mu_s * normal_c * sx_c / size_c, mu_s * normal_c * sy_c / size_c
        else:
            g1, g2 = a * f1 / 3.5, (d * f2 - c) / 3.5
            holding = math.sqrt(g1 * g1 + g2 * g2)
            limit = mu_s * normal_c
            if holding > limit:
                g1, g2 = limit * g1 / holding, limit * g2 / holding
        return f1, f2, g1, g2

    def rate(self, state: State, modes: Modes, restoring: bool) -> State:
        """d(state)/dP: the paper's eqs. 12a-e, and the normal force's work rate."""
        f1, f2, g1, g2 = self.frictions(state, modes)
        m, k, s, c = self.mass, self.turn, self.sin_t, self.cos_t
        vy = state[1]
        return (
            -(f1 + g1) / m,
            -(c - s * f2 + g2) / m,
            -k * (f2 + g2),
            -k * (f1 * s - g1),
            k * f1 * c,
            (-vy if restoring else vy) * c,
        )

    def step(
        self,
        state: State,
        size: float,
        modes: Modes,
        restoring: bool,
        first: State | None = None,
    ) -> State:
        """One classical Runge-Kutta step of `size` in P, the contacts' modes held;
        `first`, the rate at `state` if known."""
        k1 = self.rate(state, modes, restoring) if first is None else first
        k2 = self.rate(_ahead(state, k1, 0.5 * size), modes, restoring)
        k3 = self.rate(_ahead(state, k2, 0.5 * size), modes, restoring)
        k4 = self.rate(_ahead(state, k3, size), modes, restoring)
        sixth = size / 6.0
        return (
            state[0] + sixth * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]),
            state[1] + sixth * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]),
            state[2] + sixth * (k1[2] + 2.0 * k2[2] + 2.0 * k3[2] + k4[2]),
            state[3] + sixth * (k1[3] + 2.0 * k2[3] + 2.0 * k3[3] + k4[3]),
            state[4] + sixth * (k1[4] + 2.0 * k2[4] + 2.0 * k3[4] + k4[4]),
            state[5] + sixth * (k1[5] + 2.0 * k2[5] + 2.0 * k3[5] + k4[5]),
        )


def _ahead(state: State, rate: State, size: float) -> State:
    return (
        state[0] + size * rate[0],
        state[1] + size * rate[1],
        state[2] + size * rate[2],
        state[3] + size * rate[3],
        state[4] + size * rate[4],
        state[5] + size * rate[5],
    )


def _phase(impact: _Impact, state: State, step: float, scale: float, target: float | None) -> State:
    """Integrate one phase from `state` in steps of `step`: compression (target None)
    until the normal speed vy is zero, restitution until the work reaches `target`."""
    restoring = target is not None
    landed = [False, False]  # a contact whose slip a split step has just brought to zero
    limit = 64 * STEPS_PER_MOMENTUM + 64
    for _ in range(limit):
        slips = impact.slips(state)
        at_rest = (
            landed[0] or _length(slips[0], slips[1]) <= ZERO_SLIP * scale,
            landed[1] or _length(slips[2], slips[3]) <= ZERO_SLIP * scale,
        )
        modes: Modes = (at_rest[0], at_rest[1], None)
        landed = [False, False]
        rate = impact.rate(state, modes, restoring)
        trial = impact.step(state, step, modes, restoring, rate)
        # The events the trial step passed, each as the share of the step that reaches
        # it along the step's first slope: the phase's end, a slip reaching zero.
        share, event = 2.0, -1
        if not restoring and trial[1] <= 0.0:
            share, event = state[1] / (-rate[1] * step), 2
        if restoring and target is not None and trial[5] >= target:
            share, event = _to_work(state, rate, target, impact.cos_t) / step, 2
        trial_slips = impact.slips(trial)
        for contact in (0, 1):
            if modes[contact]:
                continue
            x, y = slips[2 * contact], slips[2 * contact + 1]
            passed = x * trial_slips[2 * contact] + y * trial_slips[2 * contact + 1] <= 0.0
            if contact == 0:  # M d(slip_I)/dP from the rates of v and w
                r, s, c = impact.radius, impact.sin_t, impact.cos_t
                dx = rate[0] + r * (rate[3] * s - rate[4] * c)
                dy = r * rate[2] - rate[1] * s
            else:
                dx = rate[0] - impact.radius * rate[3]
                dy = rate[1] + impact.radius * rate[2]
            closing = -(x * dx + y * dy)
            # (A stage of the trial may pass the zero that its end falls short of.)
            reach = (x * x + y * y) / (closing * step) if closing > 0.0 else 2.0
            if not passed and reach > 1.0:
                continue
            reach = min(reach, 1.0)
            if reach < share:
                share, event = reach, contact
        if event < 0:
            state = trial
            continue
        split: Modes = (modes[0], modes[1], slips)
        state = impact.step(state, min(max(share, 0.0), 1.0) * step, split, restoring)
        if event < 2:
            landed[event] = True
            continue
        for _ in range(NEWTON_STEPS):  # onto the phase's end
            rate = impact.rate(state, modes, restoring)
            if restoring and target is not None:
                remaining = _to_work(state, rate, target, impact.cos_t)
            else:
                remaining = state[1] / -rate[1]
            state = impact.step(state, remaining, modes, restoring)
        return state
    raise ValueError("mathavan2010: the impact did not end (the frictions hold the ball)")


def _to_work(state: State, rate: State, target: float, cos_t: float) -> float:
    """The impulse that brings the work to `target`: W + a x + b x^2 / 2 = target, with
    a = dW/dP and b = -cos(theta) dvy/dP (vy falls linearly at first), in the stable
    form 2 D / (a + sqrt(a^2 + 2 b D)); D may be a rounding below zero near the end."""
    remaining = target - state[5]
    slope = rate[5]
    bend = max(-cos_t * rate[1], 0.0)
    root = math.sqrt(max(slope * slope + 2.0 * bend * remaining, 0.0))
    if slope + root <= 0.0:
        return 0.0
    return 2.0 * remaining / (slope + root)


def _held(x: float, y: float, way_x: float, way_y: float) -> tuple[float, float]:
    """The slip (x, y), or the way it had if it points against that (it passed zero)."""
    if x * way_x + y * way_y > 0.0:
        return x, y
    return way_x, way_y


def _length(x: float, y: float) -> float:
    return math.sqrt(x * x + y * y)


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
    vx, vy = velocity
    wx, wy, wz = spin
    if not vy > 0.0:  # not into the cushion: no impact
        return vx, vy, wx, wy, wz
    scale = _length(vx, vy) + radius * math.sqrt(wx * wx + wy * wy + wz * wz)
    step = mass * vy / steps
    state = _phase(impact, (vx, vy, wx, wy, wz, 0.0), step, scale, None)
    absorbed = state[5]
    target = restitution * restitution * absorbed
    state = (state[0], state[1], state[2], state[3], state[4], 0.0)
    if target > 0.0:
        state = _phase(impact, state, step, scale, target)
    return state[0], min(state[1], 0.0), state[2], state[3], state[4]
