"""Cushion contact laws (the README's model section, "cushions"). Each takes k balls
(CushionContact: velocities (k, 2), spins (k, 3), unit normals `into` (k, 2) pointing
into the rubber, masses (k,)) and returns (velocities', spins', approach speeds (k,))."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, fields
from functools import partial
from typing import NamedTuple

import numpy as np

from billiards.physics.laws.mathavan2010 import rebound
from billiards.physics.numerics.arithmetic import column, dot
from billiards.physics.numerics.arrays import Constant, FloatArray


@dataclass(frozen=True)
class CushionConstants:
    """What a cushion law reads: a run's constants, or a batch's rows (one, or one a row),
    each field named as the Setup names it."""

    radius: Constant
    retention: Constant  # mirror: the share of kinetic energy kept
    cushion_restitution: Constant  # han2005's e, mathavan2010's e_e (or e_0)
    cushion_friction: Constant  # ball on cushion: han2005's mu, mathavan2010's mu_w
    cushion_height: Constant  # the cushion nose's, above the cloth
    sliding_friction: Constant  # ball on cloth during an impact: mathavan2010's mu_s
    cushion_restitution_speed: Constant  # mathavan2010_ev's v_c

    @classmethod
    def of(cls, setup: object) -> CushionConstants:
        """A Setup's cushion constants, or a batch's (engine.batch.RunConstants): the
        fields of the same names."""
        return cls(**{field.name: getattr(setup, field.name) for field in fields(cls)})


class CushionContact(NamedTuple):
    """k balls, each at a cushion or a jaw (the module's docstring)."""

    velocities: FloatArray
    spins: FloatArray
    into: FloatArray
    masses: FloatArray


def mirror(
    balls: CushionContact, constants: CushionConstants
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The seed's cushion (eq. 2.7), about any normal: mirror each ball's velocity
    component along `into` and keep `retention` of the kinetic energy; spins pass.
    About a cushion's own normal (+-1, 0) this is exactly the component's sign flip."""
    velocities, spins, into, _ = balls
    approach = dot(velocities, into)
    bounced = velocities - 2.0 * approach[:, None] * into
    return bounced * column(np.sqrt(constants.retention)), spins, approach


def han2005(
    balls: CushionContact, constants: CushionConstants
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """A cushion that grips a spinning ball: Han 2005, "Dynamics in carom and three
    cushion billiards" (J. Mech. Sci. Tech. 19(4)), eqs. 14-20, as pooltool applies it
    (the ball stays on the cloth: the impulse's vertical part is dropped).

    The nose touches the ball at `height`, theta = asin(height / R - 1) above its
    equator. In the cushion frame (x into it, y along it, z up) the normal n = (cos
    theta, 0, sin theta) takes the impulse (1 + e) m (v.n), and the contact's slip s a
    friction impulse against it: -2m/7 s if that stops it within mu of the normal
    impulse (sticking), else mu times it along -s (sliding). A ball not moving into the
    cushion passes, approach 0. Energy never rises (e <= 1, friction only removes slip,
    the dropped vertical velocity only removes energy)."""
    velocities, spins, into, masses = balls
    radius, restitution = constants.radius, constants.cushion_restitution
    friction = constants.cushion_friction
    masses, height = np.asarray(masses, dtype=np.float64), constants.cushion_height
    along = np.stack((-into[:, 1], into[:, 0]), axis=1)  # z x into: the cushion's direction
    normal_speed = dot(velocities, into)
    sin_t = height / radius - 1.0
    cos_t = np.sqrt(np.maximum(1.0 - sin_t * sin_t, 0.0))
    v_x, v_y = normal_speed, dot(velocities, along)
    w_x, w_y, w_z = dot(spins[:, :2], into), dot(spins[:, :2], along), spins[:, 2]
    normal_impulse = (1.0 + restitution) * masses * v_x * cos_t
    slip_1 = v_x * sin_t + radius * w_y  # along t1 = (sin, 0, -cos), in the tangent plane
    slip_2 = v_y + radius * (w_z * cos_t - w_x * sin_t)  # along y
    slip = np.sqrt(slip_1 * slip_1 + slip_2 * slip_2)
    sticking = 2.0 * masses / 7.0  # the impulse that stops the slip, per m/s of it
    sticks = slip * sticking <= friction * normal_impulse
    with np.errstate(divide="ignore", invalid="ignore"):  # no slip: it sticks
        push_1 = np.where(sticks, -sticking * slip_1, -friction * normal_impulse * slip_1 / slip)
        push_2 = np.where(sticks, -sticking * slip_2, -friction * normal_impulse * slip_2 / slip)
    impulse_x = -normal_impulse * cos_t + push_1 * sin_t
    impulse_y = push_2
    impulse_z = -normal_impulse * sin_t - push_1 * cos_t
    turn = radius / (0.4 * masses * radius * radius)
    w_x = w_x + turn * (-sin_t * impulse_y)
    w_y = w_y + turn * (sin_t * impulse_x - cos_t * impulse_z)
    w_z = w_z + turn * (cos_t * impulse_y)
    v_x = v_x + impulse_x / masses
    v_x = np.where(v_x > 0.0, 0.0, v_x)  # min(v_x, 0.0): the ball leaves the cushion
    v_y = v_y + impulse_y / masses
    new_velocities = v_x[:, None] * into + v_y[:, None] * along
    new_spins = np.empty((len(spins), 3))
    new_spins[:, :2] = w_x[:, None] * into + w_y[:, None] * along
    new_spins[:, 2] = w_z
    into_it = normal_speed > 0
    return (
        np.where(into_it[:, None], new_velocities, velocities),
        np.where(into_it[:, None], new_spins, spins),
        np.where(into_it, normal_speed, 0.0),
    )


def mathavan2010(
    balls: CushionContact, constants: CushionConstants, speed_dependent: bool = False
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """A cushion whose impact is integrated over its impulse: Mathavan, Jackson and
    Parkin 2010 (laws.mathavan2010), e_e, mu_w and mu_s the constants' restitution,
    friction and table_friction. Each row is turned into the paper's frame (y into the
    cushion, x = y cross z), integrated, and turned back; a ball not moving into the
    cushion passes, approach 0. With `speed_dependent` (mathavan2010_ev), e_e =
    restitution / sqrt(1 + (v_n / restitution_speed)^4)."""
    velocities, spins, into, masses = balls
    c, masses = constants, np.asarray(masses, dtype=np.float64)
    new_velocities = np.array(velocities, dtype=np.float64)
    new_spins = np.array(spins, dtype=np.float64)
    approaches = np.zeros(len(velocities))
    for row in range(len(velocities)):
        nx, ny = float(into[row, 0]), float(into[row, 1])
        ax, ay = ny, -nx  # the paper's x: into cross z
        v_x, v_y = float(velocities[row, 0]), float(velocities[row, 1])
        w_x, w_y, w_z = (float(part) for part in spins[row])
        normal = v_x * nx + v_y * ny
        if not normal > 0.0:
            continue
        along, spin_along, spin_into = v_x * ax + v_y * ay, w_x * ax + w_y * ay, w_x * nx + w_y * ny
        e_e = _of_row(c.cushion_restitution, row)
        if speed_dependent:
            share = normal / _of_row(c.cushion_restitution_speed, row)
            e_e = e_e / math.sqrt(1.0 + share * share * share * share)
        out = rebound(
            (along, normal),
            (spin_along, spin_into, w_z),
            float(masses[row]),
            _of_row(c.radius, row),
            _of_row(c.cushion_height, row),
            e_e,
            _of_row(c.cushion_friction, row),
            _of_row(c.sliding_friction, row),
        )
        new_velocities[row] = (out[0] * ax + out[1] * nx, out[0] * ay + out[1] * ny)
        new_spins[row] = (out[2] * ax + out[3] * nx, out[2] * ay + out[3] * ny, out[4])
        approaches[row] = normal
    return new_velocities, new_spins, approaches


def _of_row(value: Constant, row: int) -> float:
    """A constant's value at one row, as a Python float."""
    return value if isinstance(value, float) else float(value[row])


CushionLaw = Callable[[CushionContact, CushionConstants], tuple[FloatArray, FloatArray, FloatArray]]


# mathavan2010 with a restitution that falls with the normal speed: e_e = e_0 /
# sqrt(1 + (v_n / v_c)^4), the cushion giving more at speed than the paper's rigid one
# (which it says fails above about 2.5 m/s); fitted to all of the paper's rebounds
# (docs/validation.md).
mathavan2010_ev: CushionLaw = partial(mathavan2010, speed_dependent=True)
