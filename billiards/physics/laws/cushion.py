"""Cushion contact laws: what a cushion does to a ball's velocity (the README's model
section, "cushions"; the source report's eq. 2.7)."""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.arithmetic import dot, length
from billiards.physics.motion import FloatArray
from billiards.physics.setup import Setup


def mirror(
    velocities: FloatArray, spins: FloatArray, into: FloatArray, masses: FloatArray, setup: Setup
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The seed's cushion (eq. 2.7), about any normal: mirror each ball's velocity
    component along its unit normal `into` (k, 2, pointing into the cushion or jaw) and
    keep setup.retention of the kinetic energy; the spins pass unchanged.

    About a cushion's own normal (+-1, 0) this is exactly the component's sign flip: v.n
    is v_x to the bit, and v_x - 2 v_x is exact. Returns (velocities', spins, approach
    speeds (k,))."""
    approach = dot(velocities, into)
    bounced = velocities - 2.0 * approach[:, None] * into
    return bounced * math.sqrt(setup.retention), spins, approach


def han2005(
    velocities: FloatArray, spins: FloatArray, into: FloatArray, masses: FloatArray, setup: Setup
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Han 2005's cushion (han2005_one) on each of k balls: velocities (k, 2), spins
    (k, 3), unit normals `into` (k, 2), masses (k,); the nose height, restitution and
    friction from the setup. Returns (velocities', spins', approach speeds (k,))."""
    bounced = np.array(velocities, dtype=np.float64)
    turned = np.array(spins, dtype=np.float64)
    approach = np.zeros(len(velocities))
    for row in range(len(velocities)):
        bounced[row], turned[row], approach[row] = han2005_one(
            bounced[row],
            turned[row],
            into[row],
            setup.radius,
            float(masses[row]),
            setup.cushion_restitution,
            setup.cushion_friction,
            setup.cushion_height,
        )
    return bounced, turned, approach


def han2005_one(
    velocity: FloatArray,
    spin: FloatArray,
    into: FloatArray,
    radius: float,
    mass: float,
    restitution: float,
    friction: float,
    height: float,
) -> tuple[FloatArray, FloatArray, float]:
    """A cushion that grips a spinning ball: Han 2005, "Dynamics in carom and three
    cushion billiards" (J. Mech. Sci. Tech. 19(4)), eqs. 14-20, as pooltool applies it
    (the ball stays on the cloth: the vertical part of the impulse is dropped).

    velocity (2,), spin (3,) of one ball; `into` (2,) the unit normal pointing into the
    cushion; the cushion's nose touches the ball at `height` above the cloth, i.e. at
    theta = asin(height / R - 1) above the ball's equator. In the cushion frame (x into
    the cushion, y along it, z up) the normal n = (cos theta, 0, sin theta) takes the
    impulse (1 + e) m (v.n) and the contact point's slip s (in the tangent plane) a
    friction impulse opposing it: -2m/7 s if that stops it within mu of the normal
    impulse (sticking), else mu times the normal impulse along -s (sliding). Returns
    (velocity, spin, approach speed). Energy never rises: the normal impulse is a
    restitution e <= 1, friction only removes slip, and the dropped vertical part of the
    velocity only removes energy."""
    along = np.array([-into[1], into[0]])  # z x into: the cushion's direction
    normal_speed = float(dot(velocity, into))
    if normal_speed <= 0:
        return velocity, spin, 0.0
    sin_t = height / radius - 1.0
    cos_t = math.sqrt(max(1.0 - sin_t * sin_t, 0.0))
    # The cushion frame.
    v_x, v_y = normal_speed, float(dot(velocity, along))
    w_x, w_y, w_z = float(dot(spin[:2], into)), float(dot(spin[:2], along)), float(spin[2])
    normal_impulse = (1.0 + restitution) * mass * v_x * cos_t
    slip_1 = v_x * sin_t + radius * w_y  # along t1 = (sin, 0, -cos), in the tangent plane
    slip_2 = v_y + radius * (w_z * cos_t - w_x * sin_t)  # along y
    slip = length(slip_1, slip_2)
    sticking = 2.0 * mass / 7.0  # the impulse that stops the slip, per m/s of it
    if slip * sticking <= friction * normal_impulse:
        push_1, push_2 = -sticking * slip_1, -sticking * slip_2
    else:
        push_1 = -friction * normal_impulse * slip_1 / slip
        push_2 = -friction * normal_impulse * slip_2 / slip
    impulse = (
        -normal_impulse * cos_t + push_1 * sin_t,
        push_2,
        -normal_impulse * sin_t - push_1 * cos_t,
    )
    # Angular impulse R n x J over I = 2/5 m R^2.
    turn = radius / (0.4 * mass * radius * radius)
    w_x += turn * (-sin_t * impulse[1])
    w_y += turn * (sin_t * impulse[0] - cos_t * impulse[2])
    w_z += turn * (cos_t * impulse[1])
    # The ball stays on the cloth, and cannot be driven on into the cushion.
    v_x = min(v_x + impulse[0] / mass, 0.0)
    v_y = v_y + impulse[1] / mass
    new_velocity = v_x * into + v_y * along
    new_spin = np.array([*(w_x * into + w_y * along), w_z])
    return new_velocity, new_spin, normal_speed
