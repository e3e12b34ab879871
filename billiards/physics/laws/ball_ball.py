"""Ball-ball contact laws (the README's model section, "ball-ball contacts")."""

from __future__ import annotations

import math
from typing import NamedTuple, Protocol

import numpy as np

from billiards.physics.numerics.arithmetic import dot, exp, length
from billiards.physics.numerics.arrays import FloatArray

# Restitution rises to 1 at low impact speeds: a contact leaves its pair separating at
# least this fast (or as fast as it closed). Real balls do; without it a touching chain
# collapses into infinitely many ever-softer contacts (inelastic collapse), and a pair
# left touching at no closing speed is pressed into overlap by its decelerations.
ELASTIC_BELOW = 1e-3  # m/s


class BallConstants(Protocol):
    """What a ball law reads of a run (a Setup has both): the balls' radius and the
    ball-ball friction fit (a, b, c) of mu(s) = a + b exp(-c s)."""

    @property
    def radius(self) -> float: ...

    @property
    def ball_friction(self) -> tuple[float, float, float]: ...


class PairContact(NamedTuple):
    """Two balls at a contact: the unit normal from ball 2 to ball 1, and their
    velocities (2, 2), spins (2, 3) and masses (2,)."""

    normal: FloatArray
    velocities: FloatArray
    spins: FloatArray
    masses: FloatArray


def frictionless(
    pair: PairContact, restitution: float, constants: BallConstants
) -> tuple[FloatArray, FloatArray, float]:
    """The seed's contact (frictionless_impulse) in the registry's form: the spins pass."""
    normal, velocities, spins, masses = pair
    v1, v2, approach = frictionless_impulse(
        normal, velocities[0], float(masses[0]), velocities[1], float(masses[1]), restitution
    )
    return np.array([v1, v2]), spins, approach


def frictionless_impulse(
    normal: FloatArray, v1: FloatArray, m1: float, v2: FloatArray, m2: float, restitution: float
) -> tuple[FloatArray, FloatArray, float]:
    """Velocities after a frictionless contact along the unit line of centres `normal`
    (from ball 2 to ball 1): J = (1 + e) ((v1 - v2).n) / (1/m1 + 1/m2), v1' = v1 - J n /
    m1, v2' = v2 + J n / m2, e raised to min(1, ELASTIC_BELOW / approach) where lower.
    Returns (v1', v2', approach speed); a pair not approaching is left as is (0)."""
    closing = float(dot(v1 - v2, normal))
    if closing >= 0:
        return v1, v2, 0.0
    restitution = max(restitution, min(1.0, ELASTIC_BELOW / -closing))
    impulse = (1.0 + restitution) * closing / (1.0 / m1 + 1.0 / m2)
    return v1 - (impulse / m1) * normal, v2 + (impulse / m2) * normal, -closing


def frictional(
    pair: PairContact, restitution: float, constants: BallConstants
) -> tuple[FloatArray, FloatArray, float]:
    """A contact with Coulomb friction at the contact point (docs/collisions.md): throw.

    The normal impulse J_n is the frictionless law's; a friction impulse F opposes the
    slip of ball 1's surface over ball 2's, u = (v1 - v2) - R (w1 + w2) x n, u_t = u -
    (u.n) n (3-D; n from 2 to 1). For solid spheres an F perpendicular to n changes u_t
    by k_t F, k_t = (7/2)(1/m1 + 1/m2), so the slip keeps its direction and

        F = -min(mu(|u_t|) J_n, |u_t| / k_t) u_t / |u_t|,  mu(s) = a + b exp(-c s)

    (Alciatore's TP A-14 in vector form, his fit of TP A-28: constants.ball_friction). Ball
    1 takes +F, ball 2 -F, with the torques of their arms (-R n, +R n). F's vertical
    part turns the spins but moves neither ball (the cloth takes it; its own friction is
    left out, as in pooltool and TP A-14). Momentum in the plane is kept exactly and the
    energy never rises (friction never reverses the slip; the vertical motion is dropped).
    """
    normal, velocities, spins, masses = pair
    nx, ny = float(normal[0]), float(normal[1])
    (v1x, v1y), (v2x, v2y) = velocities.tolist()
    m1, m2 = float(masses[0]), float(masses[1])
    rx, ry = v1x - v2x, v1y - v2y
    closing = rx * nx + ry * ny
    if closing >= 0:
        return velocities, spins, 0.0
    restitution = max(restitution, min(1.0, ELASTIC_BELOW / -closing))
    impulse = (1.0 + restitution) * closing / (1.0 / m1 + 1.0 / m2)  # ball 1 takes -impulse n
    (a1, b1, c1), (a2, b2, c2) = spins.tolist()
    wx, wy, wz = a1 + a2, b1 + b2, c1 + c2
    radius = constants.radius
    # u - (u.n) n: (w x n) = (-wz ny, wz nx, wx ny - wy nx) has no part along n.
    tx = rx + radius * wz * ny - closing * nx
    ty = ry - radius * wz * nx - closing * ny
    tz = -radius * (wx * ny - wy * nx)
    slip = math.sqrt(tx * tx + ty * ty + tz * tz)
    a, b, c = constants.ball_friction
    # exp(-c s) below 1e-304 is 0 to every digit that mu keeps.
    mu = a + b * exp(-c * slip) if c * slip < 700.0 else a
    bound = mu * -impulse
    if not (slip > 0 and bound > 0):
        # No friction impulse (no slip, or mu = 0): the frictionless law, to the bit.
        # Adding the zero impulse would turn a -0.0 velocity or spin into +0.0.
        return frictionless(pair, restitution, constants)
    compliance = 3.5 * (1.0 / m1 + 1.0 / m2)
    scale = -min(bound, slip / compliance) / slip
    fx, fy, fz = scale * tx, scale * ty, scale * tz
    after = np.array([
        [v1x - (impulse / m1) * nx + fx / m1, v1y - (impulse / m1) * ny + fy / m1],
        [v2x + (impulse / m2) * nx - fx / m2, v2y + (impulse / m2) * ny - fy / m2],
    ])  # fmt: skip
    # dw = (arm x impulse) / I; both arms' torques are -R n x F: n x F / (2/5 m R).
    cx, cy, cz = ny * fz, -nx * fz, nx * fy - ny * fx
    turn1, turn2 = -2.5 / (m1 * radius), -2.5 / (m2 * radius)
    turned = np.array([
        [a1 + turn1 * cx, b1 + turn1 * cy, c1 + turn1 * cz],
        [a2 + turn2 * cx, b2 + turn2 * cy, c2 + turn2 * cz],
    ])  # fmt: skip
    return after, turned, -closing


def pressed_separation(
    normal: FloatArray, v1: FloatArray, m1: float, v2: FloatArray, m2: float
) -> tuple[FloatArray, FloatArray]:
    """Velocities after a pressed contact: two touching balls with no closing speed whose
    decelerations press them together. Rigid balls would need a sustained normal force
    (not closed form); instead w = v1 - v2 is turned, keeping its length, until its
    normal part is min(ELASTIC_BELOW, |w|) apart: an impulse mu (w' - w), mu = m1 m2 /
    (m1 + m2). Momentum and kinetic energy are kept; the pair leaves apart."""
    relative = v1 - v2
    speed = length(relative[0], relative[1])
    apart = min(ELASTIC_BELOW, speed)
    tangent = np.array([-normal[1], normal[0]])
    along = float(dot(relative, tangent))
    sliding = math.copysign(math.sqrt(max(speed * speed - apart * apart, 0.0)), along)
    change = apart * normal + sliding * tangent - relative
    reduced = m1 * m2 / (m1 + m2)
    return v1 + (reduced / m1) * change, v2 - (reduced / m2) * change


def line_of_centres(p1: FloatArray, p2: FloatArray) -> FloatArray:
    """The unit normal from ball 2's centre to ball 1's."""
    separation = p1 - p2
    return np.asarray(separation / length(separation[0], separation[1]))
