"""Han 2005's gripping cushion, compiled (laws.cushion.han2005, one ball): the same
operations in the same order, numpy's where and maximum as numpy computes them."""

from __future__ import annotations

import math

from billiards.physics.compiled.arithmetic import np_maximum
from billiards.physics.compiled.jit import kernel
from billiards.physics.compiled.laws import CushionNumbers, Spin, Vector


@kernel
def han2005(
    velocity: Vector, spin: Spin, into: Vector, mass: float, constants: CushionNumbers
) -> tuple[Vector, Spin, float]:
    """cushion.han2005 on one ball (its docstring has the model): (velocity', spin',
    approach); a ball not moving into the cushion passes, approach 0. In the cushion
    frame x is `into`, y = z x into along the cushion."""
    radius, restitution = constants.radius, constants.cushion_restitution
    friction, height = constants.cushion_friction, constants.cushion_height
    into_x, into_y = into
    along_x, along_y = -into_y, into_x
    normal_speed = velocity[0] * into_x + velocity[1] * into_y
    if not normal_speed > 0:  # numpy's where keeps such a row as it came
        return velocity, spin, 0.0
    sin_t = height / radius - 1.0
    cos_t = math.sqrt(np_maximum(1.0 - sin_t * sin_t, 0.0))
    v_x, v_y = normal_speed, velocity[0] * along_x + velocity[1] * along_y
    w_x = spin[0] * into_x + spin[1] * into_y
    w_y = spin[0] * along_x + spin[1] * along_y
    w_z = spin[2]
    normal_impulse = (1.0 + restitution) * mass * v_x * cos_t
    slip_1 = v_x * sin_t + radius * w_y  # along t1 = (sin, 0, -cos)
    slip_2 = v_y + radius * (w_z * cos_t - w_x * sin_t)  # along y
    slip = math.sqrt(slip_1 * slip_1 + slip_2 * slip_2)
    sticking = 2.0 * mass / 7.0
    if slip * sticking <= friction * normal_impulse:  # sticks
        push_1, push_2 = -sticking * slip_1, -sticking * slip_2
    else:
        push_1 = -friction * normal_impulse * slip_1 / slip
        push_2 = -friction * normal_impulse * slip_2 / slip
    impulse_x = -normal_impulse * cos_t + push_1 * sin_t
    impulse_y = push_2
    impulse_z = -normal_impulse * sin_t - push_1 * cos_t
    turn = radius / (0.4 * mass * radius * radius)
    w_x = w_x + turn * (-sin_t * impulse_y)
    w_y = w_y + turn * (sin_t * impulse_x - cos_t * impulse_z)
    w_z = w_z + turn * (cos_t * impulse_y)
    v_x = v_x + impulse_x / mass
    if v_x > 0.0:  # the ball leaves the cushion (NaN stays, as numpy's where keeps it)
        v_x = 0.0
    v_y = v_y + impulse_y / mass
    new_velocity = (v_x * into_x + v_y * along_x, v_x * into_y + v_y * along_y)
    new_spin = (w_x * into_x + w_y * along_x, w_x * into_y + w_y * along_y, w_z)
    return new_velocity, new_spin, normal_speed
