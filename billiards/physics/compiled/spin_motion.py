"""The spin model's closed-form motion, compiled (spin.motion and spin.law, ball by
ball, in the same operations and order): a ball's motion state on anchoring (classify,
with NO_SLIP's snapping, then state_laws), its state at any time (spin_state), the
kinematics that start its next state (SpinLaw.state_changes), and the run's last stop.
"""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.compiled.airborne.bounces import bounce
from billiards.physics.compiled.airborne.flight import landing_time
from billiards.physics.compiled.arithmetic import np_maximum, np_minimum
from billiards.physics.compiled.jit import inline, kernel
from billiards.physics.compiled.state import Anchors, Table
from billiards.physics.spin.motion import FLYING, NO_SLIP, REST, ROLLING, SLIDING, SPINNING


@kernel
def classify(
    velocity: tuple[float, float], spin: tuple[float, float, float], radius: float
) -> tuple[int, float, float, float, float]:
    """A ball's motion state, velocity (zero at rest) and w_xy with a rounding-level slip
    removed (spin.motion.classify): (state, vx, vy, wx, wy)."""
    vx, vy = velocity
    wx, wy, wz = spin
    slip_x, slip_y = vx - radius * wy, vy + radius * wx
    slip_speed = math.sqrt(slip_x * slip_x + slip_y * slip_y)
    speed = math.sqrt(vx * vx + vy * vy)
    scale = speed + radius * math.sqrt(wx * wx + wy * wy)
    sliding = slip_speed > NO_SLIP * scale
    moving = speed > 0
    if sliding:
        return SLIDING, vx, vy, wx, wy
    if not moving:
        vx, vy = 0.0, 0.0
    state = ROLLING if moving else (SPINNING if wz != 0 else REST)
    # rolling_spin: z x v / R.
    return state, vx, vy, -vy / radius, vx / radius


@kernel
def state_laws(
    state: int,
    velocity: tuple[float, float],
    spin: tuple[float, float, float],
    decels: tuple[float, float, float, float],
) -> tuple[float, float, float, float, float]:
    """The acceleration, the angular acceleration of w_xy and the duration of a state
    entered with this velocity and spin (spin.motion.state_laws): (ax, ay, alpha_x,
    alpha_y, duration); w_z enters only a spinning ball's duration. decels: (R, mu_s g,
    mu_r g, 5 mu_sp g / (2R)), the radius first."""
    vx, vy = velocity
    wx, wy, wz = spin
    radius, slide_decel, roll_decel, spin_decel = decels
    if state == SLIDING:
        decel = slide_decel
        slip_x, slip_y = vx - radius * wy, vy + radius * wx
        slip_speed = math.sqrt(slip_x * slip_x + slip_y * slip_y)
        ax, ay = -decel * (slip_x / slip_speed), -decel * (slip_y / slip_speed)
        # The friction's torque over I = 2/5 m R^2: dw_xy/dt = -(5/2) (z x a) / R.
        duration = 2.0 * slip_speed / (7.0 * decel) if decel > 0 else math.inf
        return ax, ay, -2.5 * (-ay / radius), -2.5 * (ax / radius), duration
    if state == ROLLING:
        decel = roll_decel
        speed = math.sqrt(vx * vx + vy * vy)
        ax, ay = -decel * vx / speed, -decel * vy / speed
        duration = speed / decel if decel > 0 else math.inf
        return ax, ay, -ay / radius, ax / radius, duration
    if state == SPINNING:
        duration = abs(wz) / spin_decel if spin_decel > 0 else math.inf
        return 0.0, 0.0, 0.0, 0.0, duration
    return 0.0, 0.0, 0.0, 0.0, math.inf


@kernel
def spin_anchor(anchors: Anchors, ball: int, time: float, row: np.ndarray, table: Table) -> None:
    """Re-anchor one ball at `time` from row (9,): position, velocity, spin, height and
    vertical velocity (spin.law.SpinLaw.anchor; a ball above the cloth or leaving it,
    in a run that lets one fly, takes off: fly)."""
    if table.flies and (row[7] > table.radius or row[8] > 0):
        fly(anchors, ball, time, row, table)
        return
    anchors.lift[ball, 0], anchors.lift[ball, 1] = table.radius, 0.0
    wz = row[6]
    state, vx, vy, wx, wy = classify((row[2], row[3]), (row[4], row[5], wz), table.radius)
    decels = (table.radius, table.slide_decel, table.decel, table.spin_decel)
    ax, ay, alpha_x, alpha_y, duration = state_laws(state, (vx, vy), (wx, wy, wz), decels)
    anchors.t0[ball] = time
    anchors.p0[ball, 0], anchors.p0[ball, 1] = row[0], row[1]
    anchors.v0[ball, 0], anchors.v0[ball, 1] = vx, vy
    anchors.w0[ball, 0], anchors.w0[ball, 1], anchors.w0[ball, 2] = wx, wy, wz
    anchors.state[ball] = state
    anchors.acceleration[ball, 0], anchors.acceleration[ball, 1] = ax, ay
    anchors.angular[ball, 0], anchors.angular[ball, 1] = alpha_x, alpha_y
    anchors.duration[ball] = duration
    anchors.change_time[ball] = math.inf if state == REST else time + duration


@kernel
def fly(anchors: Anchors, ball: int, time: float, row: np.ndarray, table: Table) -> None:
    """Anchor a ball in the air (compiled.airborne.flight): its velocity and spin as
    given (no slip to remove: nothing touches it), no acceleration in the plane, and
    the state's end its landing, the later root of z(t) = R in closed form."""
    gravity = table.flight[0]
    anchors.t0[ball] = time
    anchors.p0[ball, 0], anchors.p0[ball, 1] = row[0], row[1]
    anchors.v0[ball, 0], anchors.v0[ball, 1] = row[2], row[3]
    anchors.w0[ball, 0], anchors.w0[ball, 1], anchors.w0[ball, 2] = row[4], row[5], row[6]
    anchors.state[ball] = FLYING
    anchors.acceleration[ball, 0] = anchors.acceleration[ball, 1] = 0.0
    anchors.angular[ball, 0] = anchors.angular[ball, 1] = 0.0
    anchors.lift[ball, 0], anchors.lift[ball, 1] = row[7], row[8]
    duration = landing_time(row[7] - table.radius, row[8], gravity)
    anchors.duration[ball] = duration
    anchors.change_time[ball] = time + duration


# The anchors' arrays the spin motion reads (t0, duration, p0, v0, acceleration, w0,
# angular): handed to a call made for every ball instead of all of Anchors (each array a
# compiled call takes costs it two atomic reference counts).
SpinAnchors = tuple[
    np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray
]


@inline
def spin_anchors(anchors: Anchors) -> SpinAnchors:
    return (
        anchors.t0,
        anchors.duration,
        anchors.p0,
        anchors.v0,
        anchors.acceleration,
        anchors.w0,
        anchors.angular,
    )


@inline
def spin_state_at(anchors: Anchors, ball: int, time: float, table: Table, out: np.ndarray) -> None:
    """out (STATE_WIDTH,) = position, velocity, acceleration, spin, height and vertical
    velocity of `ball` at `time` (spin_state; flight_height)."""
    spin_state(spin_anchors(anchors), ball, time, table.spin_decel, out)
    flight_height(anchors, ball, time, table, out)


@inline
def flight_height(anchors: Anchors, ball: int, time: float, table: Table, out: np.ndarray) -> None:
    """out[9], out[10] = the ball's height and vertical velocity at `time`: R and 0 on the
    cloth; in the air the parabola z0 + v_z t - g t^2 / 2 (flight.flight_position's
    order), its spin constant (out[8] = w_z, which the cloth alone would turn down)."""
    if anchors.state[ball] != FLYING:
        out[9], out[10] = table.radius, 0.0
        return
    gravity = table.flight[0]
    tau = np_minimum(np_maximum(time - anchors.t0[ball], 0.0), anchors.duration[ball])
    drop = 0.5 * gravity * (tau * tau)
    z0, vz0 = anchors.lift[ball, 0], anchors.lift[ball, 1]
    out[9] = (z0 + vz0 * tau) - drop
    out[10] = vz0 - gravity * tau
    out[8] = anchors.w0[ball, 2]


@kernel
def spin_state(
    anchors: SpinAnchors, ball: int, time: float, spin_decel: float, out: np.ndarray
) -> None:
    """out (9,) = position, velocity, acceleration (zero once the state has run out) and
    spin of `ball` at `time` (spin.motion.spin_state, spin.law.SpinLaw.state_at)."""
    t0s, durations, p0, v0s, accelerations, w0, angular = anchors
    t0, duration = t0s[ball], durations[ball]
    elapsed = np_maximum(time - t0, 0.0)
    tau = np_minimum(elapsed, duration)
    running = time - t0 < duration
    for axis in range(2):
        v0, acceleration = v0s[ball, axis], accelerations[ball, axis]
        out[axis] = p0[ball, axis] + v0 * tau + 0.5 * acceleration * (tau * tau)
        out[2 + axis] = v0 + acceleration * tau
        out[4 + axis] = acceleration if running else 0.0
        out[6 + axis] = w0[ball, axis] + angular[ball, axis] * tau
    w0z = w0[ball, 2]
    magnitude = np_maximum(abs(w0z) - spin_decel * elapsed, 0.0)
    sign = 1.0 if w0z > 0 else (-1.0 if w0z < 0 else (0.0 if w0z == 0 else w0z))  # np.sign
    out[8] = sign * magnitude


@kernel
def state_change(anchors: Anchors, ball: int, time: float, table: Table, out: np.ndarray) -> None:
    """out (STATE_WIDTH,) = spin_state_at, then the kinematics that start the ball's next
    state at its change_time (spin.law.SpinLaw.state_changes): a slide ends rolling (its
    slip zero by construction, rounding removed), a roll or a spin at rest (a roll keeps
    its w_z, spinning in place), a flight at the bed's bounce."""
    spin_state_at(anchors, ball, time, table, out)
    state = anchors.state[ball]
    if state == FLYING:  # a landing: the bed's bounce (bounces.bounce), then up or on
        gravity, restitution, friction, lowest_launch = table.flight
        velocity = (out[2], out[3], out[10])
        spin = (out[6], out[7], out[8])
        laws = (table.radius, restitution, friction)
        after, turned, _ = bounce(velocity, spin, laws, gravity, lowest_launch)
        out[2], out[3] = after[0], after[1]
        out[6], out[7], out[8] = turned
        out[9], out[10] = table.radius, after[2]  # on the cloth, exactly
        return
    if state == SLIDING:
        out[6], out[7] = -out[3] / table.radius, out[2] / table.radius
        return
    out[2] = out[3] = 0.0
    out[6] = out[7] = 0.0
    if state != ROLLING:
        out[8] = 0.0


@kernel
def spin_latest_stop(anchors: Anchors) -> float:
    """When the run's last ball came to rest, or the end of its latest state still
    running (spin.law.SpinLaw.latest_stop: ends.max(initial=0.0))."""
    stop = 0.0
    for ball in range(len(anchors.t0)):
        t0 = anchors.t0[ball]
        end = t0 if anchors.state[ball] == REST else t0 + anchors.duration[ball]
        stop = np_maximum(stop, end)
    return stop
