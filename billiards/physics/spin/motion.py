"""Closed-form motion of the spin model: sliding, rolling, spinning in place, rest.

A ball has position p, velocity v (on the cloth) and angular velocity w (3-D, z up);
its contact with the cloth, at (0, 0, -R), slips at u = v + w x (0, 0, -R) = (v_x -
R w_y, v_y + R w_x). Each state has a constant acceleration, so paths are quadratic
in time and w linear (Alciatore's TP A.4 and neighbours; Leckie & Greenspan 2005;
pooltool's evolve step):

- sliding: dv/dt = -mu_s g u_hat and, from the torque with I = 2/5 m R^2, dw_xy/dt =
  5 mu_s g / (2R) (-u_y, u_x)_hat, so du/dt = -(7/2) mu_s g u_hat: the slip keeps its
  direction and vanishes after 2 |u0| / (7 mu_s g); the ball then rolls;
- rolling: v slows at mu_r g and w_xy = z x v / R; it stops after |v| / (mu_r g);
- spinning in place and rest: v = 0, w_xy = 0.

In every state w_z decays at 5 mu_sp g / (2R) (pooltool's spinning friction) to zero,
never coupled to the motion on the cloth. Nothing here changes its inputs.
"""

from __future__ import annotations

import numpy as np

from billiards.physics.numerics.arithmetic import at_rows, column, norm
from billiards.physics.numerics.arrays import Constant, FloatArray, IntArray

SLIDING, ROLLING, SPINNING, REST = 0, 1, 2, 3
# Off the cloth (issue 45): a ball in the air, its centre a parabola, its spin constant.
# Only the compiled loop's runs whose setup lets a ball leave the cloth (Setup.drives)
# enter it; the numpy engine never does (its state_laws give it no acceleration).
FLYING = 4
STATE_NAMES = ("sliding", "rolling", "spinning", "rest", "flying")

# A slip below this share of the ball's own speeds (|v| + R |w_xy|) is rounding: the
# ball rolls (a natural-roll tip, 0.4 R, gives w = v / R only to a few ulps).
NO_SLIP = 1e-12


def slip_velocity(velocities: FloatArray, spins: FloatArray, radius: Constant) -> FloatArray:
    """Velocity (..., 2) of the contact with the cloth: v + w x (0, 0, -R)."""
    return np.stack(
        (velocities[..., 0] - radius * spins[..., 1], velocities[..., 1] + radius * spins[..., 0]),
        axis=-1,
    )


def rolling_spin(velocities: FloatArray, radius: Constant) -> FloatArray:
    """w_xy (..., 2) of a ball rolling without slip at `velocities`: z x v / R."""
    return np.stack((-velocities[..., 1], velocities[..., 0]), axis=-1) / column(radius)


def tip_spin(velocities: FloatArray, tips: FloatArray, radius: float) -> FloatArray:
    """Angular velocity (N, 3) after a horizontal cue struck at `tips` = (side, height),
    fractions of R, giving the ball `velocities` (N, 2): the impulse m v at R (side s_hat
    + height z), s_hat = d x z, gives w = 5 |v| / (2 R) (height (z x d) + side z)
    (Alciatore's cue-tip offset law; height 0.4 is natural roll)."""
    speed = norm(velocities)
    scale = 5.0 / (2.0 * radius) * np.asarray(tips, dtype=np.float64)  # (N, 2)
    spins = np.zeros((len(velocities), 3))
    spins[:, 0] = -velocities[:, 1] * scale[:, 1]
    spins[:, 1] = velocities[:, 0] * scale[:, 1]
    spins[:, 2] = speed * scale[:, 0]
    return spins


def classify(
    velocities: FloatArray, spins: FloatArray, radius: Constant
) -> tuple[IntArray, FloatArray, FloatArray]:
    """Each ball's motion state, velocity (zero at rest) and spins with a rounding-level
    slip removed (a rolling ball gets exactly w_xy = z x v / R)."""
    slip_speed = norm(slip_velocity(velocities, spins, radius))
    speed = norm(velocities)
    scale = speed + radius * norm(spins[:, :2])
    sliding = slip_speed > NO_SLIP * scale
    # Moving means a speed the state laws can divide by (a 1e-170 m/s velocity is rest).
    moving = speed > 0
    states = np.where(
        sliding, SLIDING, np.where(moving, ROLLING, np.where(spins[:, 2] != 0, SPINNING, REST))
    ).astype(np.intp)
    still = ~sliding & ~moving
    kept = np.where(still[:, None], 0.0, velocities)
    snapped = np.array(spins, dtype=np.float64)
    snapped[~sliding, :2] = rolling_spin(kept[~sliding], at_rows(radius, ~sliding))
    return states, kept, snapped


def state_laws(
    states: IntArray,
    velocities: FloatArray,
    spins: FloatArray,
    radius: Constant,
    slide_decel: Constant,
    roll_decel: Constant,
    spin_decel: Constant,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """For balls entering `states` with these velocities and spins: the acceleration
    (N, 2), the angular acceleration of w_xy (N, 2) and the state's duration (N,) (inf:
    no end). slide_decel = mu_s g, roll_decel = mu_r g, spin_decel = 5 mu_sp g / (2R)."""
    count = len(states)
    acceleration = np.zeros((count, 2))
    angular = np.zeros((count, 2))
    duration = np.full(count, np.inf)
    with np.errstate(divide="ignore", invalid="ignore"):
        sliding = states == SLIDING
        if sliding.any():
            radius_of = at_rows(radius, sliding)
            decel = at_rows(slide_decel, sliding)
            slip = slip_velocity(velocities[sliding], spins[sliding], radius_of)
            slip_speed = norm(slip)
            slip_hat = slip / slip_speed[:, None]
            acceleration[sliding] = column(-decel) * slip_hat
            # The friction's torque over I = 2/5 m R^2: dw_xy/dt = -(5/2) (z x a) / R.
            angular[sliding] = -2.5 * rolling_spin(acceleration[sliding], radius_of)
            duration[sliding] = np.where(decel > 0, 2.0 * slip_speed / (7.0 * decel), np.inf)
        rolling = states == ROLLING
        if rolling.any():
            decel = at_rows(roll_decel, rolling)
            speed = norm(velocities[rolling])
            acceleration[rolling] = column(-decel) * velocities[rolling] / speed[:, None]
            angular[rolling] = rolling_spin(acceleration[rolling], at_rows(radius, rolling))
            duration[rolling] = np.where(decel > 0, speed / decel, np.inf)
        spinning = states == SPINNING
        if spinning.any():
            decel = at_rows(spin_decel, spinning)
            duration[spinning] = np.where(decel > 0, np.abs(spins[spinning, 2]) / decel, np.inf)
    return acceleration, angular, duration


def spin_state(
    p0: FloatArray,
    v0: FloatArray,
    w0: FloatArray,
    acceleration: FloatArray,
    angular: FloatArray,
    t0: FloatArray,
    duration: FloatArray,
    spin_decel: Constant,
    times: FloatArray | float,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The spin model's one closed-form evaluator: positions, velocities and spins at
    `times` (broadcasting), each acceleration held for at most `duration` seconds."""
    elapsed = np.maximum(times - t0, 0.0)
    tau = np.minimum(elapsed, duration)
    positions = p0 + v0 * tau[..., None] + 0.5 * acceleration * (tau * tau)[..., None]
    velocities = v0 + acceleration * tau[..., None]
    spins_xy = w0[..., :2] + angular * tau[..., None]
    magnitude = np.maximum(np.abs(w0[..., 2]) - spin_decel * elapsed, 0.0)
    spins = np.concatenate((spins_xy, (np.sign(w0[..., 2]) * magnitude)[..., None]), axis=-1)
    return positions, velocities, spins
