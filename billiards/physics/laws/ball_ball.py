"""Ball-ball contact laws: what a contact between two balls does to their velocities
(the README's model section, "ball-ball contacts")."""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from billiards.physics.engine.setup import Setup
from billiards.physics.numerics.arithmetic import dot, exp, length, total
from billiards.physics.numerics.arrays import FloatArray

# Restitution rises to 1 at low impact speeds: a contact always leaves its pair
# separating at least this fast (or as fast as it closed, if slower). Real balls do
# the same, and without it low restitution goes wrong in two ways: a chain of
# touching balls collapses into infinitely many ever-softer contacts in finite time
# (inelastic collapse), and a pair left touching at zero closing speed is pressed
# into overlap by its two decelerations.
ELASTIC_BELOW = 1e-3  # m/s


class PairContact(NamedTuple):
    """Two balls at a contact: the unit normal from ball 2 to ball 1, and their
    velocities (2, 2), spins (2, 3) and masses (2,)."""

    normal: FloatArray
    velocities: FloatArray
    spins: FloatArray
    masses: FloatArray


def frictionless(
    pair: PairContact, restitution: float, setup: Setup
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
    (from ball 2 to ball 1).

    J = (1 + e) ((v1 - v2).n) / (1/m1 + 1/m2);  v1' = v1 - J n / m1,  v2' = v2 + J n / m2,
    with e raised where needed to max(e, min(1, ELASTIC_BELOW / approach speed)). Returns
    (v1', v2', approach speed); a pair that is not approaching is left as is (0).
    """
    closing = float(dot(v1 - v2, normal))
    if closing >= 0:
        return v1, v2, 0.0
    restitution = max(restitution, min(1.0, ELASTIC_BELOW / -closing))
    impulse = (1.0 + restitution) * closing / (1.0 / m1 + 1.0 / m2)
    return v1 - (impulse / m1) * normal, v2 + (impulse / m2) * normal, -closing


def frictional(
    pair: PairContact, restitution: float, setup: Setup
) -> tuple[FloatArray, FloatArray, float]:
    """A contact with Coulomb friction at the contact point (docs/collisions.md): throw.

    The normal impulse is the frictionless law's (restitution along the line of centres,
    raised by ELASTIC_BELOW as there). Its partner is a friction impulse F at the
    contact point against the slip of ball 1's surface over ball 2's,

        u = (v1 - v2) - R (w1 + w2) x n,  u_t = u - (u.n) n   (3-D; n from 2 to 1)

    Both balls are solid spheres (I = 2/5 m R^2), so an impulse F (perpendicular to n)
    changes u_t by (7/2)(1/m1 + 1/m2) F whatever its direction: the slip keeps its
    direction while the balls are pressed together, and friction either slides
    throughout (|F| = mu J_n) or stops the slip part way (|F| = |u_t| / k_t):

        F = -min(mu(|u_t|) J_n, |u_t| / k_t) u_t / |u_t|,  k_t = (7/2)(1/m1 + 1/m2),
        mu(s) = a + b exp(-c s)   (Alciatore's fit, TP A-14 and A-28; setup.ball_friction)

    (Alciatore's TP A-14 in vector form, both balls free: his throw formula is its
    special case.) Ball 1 takes +F, ball 2 -F, each with the torque of its contact arm
    (-R n and +R n). F's vertical part (from top or bottom spin) turns the spins but moves
    neither ball: the cloth takes it, so no ball leaves the table (the cloth's own
    friction during that impulse is left out, as pooltool and TP A-14 leave it out).
    Momentum in the table's plane is kept exactly (one impulse, given and taken), and the
    energy never rises (friction works against a slip it never reverses; the vertical
    motion it would have made is dropped). Returns (velocities', spins', approach speed).
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
    radius = setup.radius
    # u - (u.n) n: (w x n) = (-wz ny, wz nx, wx ny - wy nx) has no part along n.
    tx = rx + radius * wz * ny - closing * nx
    ty = ry - radius * wz * nx - closing * ny
    tz = -radius * (wx * ny - wy * nx)
    slip = math.sqrt(tx * tx + ty * ty + tz * tz)
    a, b, c = setup.ball_friction
    # exp(-c s) below 1e-304 is 0 to every digit that mu keeps.
    mu = a + b * exp(-c * slip) if c * slip < 700.0 else a
    bound = mu * -impulse
    if not (slip > 0 and bound > 0):
        # No friction impulse (no slip, or mu = 0): the frictionless law, to the bit.
        # Adding the zero impulse would turn a -0.0 velocity or spin into +0.0.
        return frictionless(pair, restitution, setup)
    compliance = 3.5 * (1.0 / m1 + 1.0 / m2)
    scale = -min(bound, slip / compliance) / slip
    fx, fy, fz = scale * tx, scale * ty, scale * tz
    after = np.array(
        [
            [v1x - (impulse / m1) * nx + fx / m1, v1y - (impulse / m1) * ny + fy / m1],
            [v2x + (impulse / m2) * nx - fx / m2, v2y + (impulse / m2) * ny - fy / m2],
        ]
    )
    # dw = (arm x impulse) / I; both arms' torques are -R n x F: n x F / (2/5 m R).
    cx, cy, cz = ny * fz, -nx * fz, nx * fy - ny * fx
    turn1 = -2.5 / (m1 * radius)
    turn2 = -2.5 / (m2 * radius)
    turned = np.array(
        [
            [a1 + turn1 * cx, b1 + turn1 * cy, c1 + turn1 * cz],
            [a2 + turn2 * cx, b2 + turn2 * cy, c2 + turn2 * cz],
        ]
    )
    return after, turned, -closing


def pressed_separation(
    normal: FloatArray, v1: FloatArray, m1: float, v2: FloatArray, m2: float
) -> tuple[FloatArray, FloatArray]:
    """Velocities after a pressed contact: two touching balls with no closing speed
    (below rounding) whose decelerations press them together.

    Rigid balls would need a sustained normal force here, which is not closed form.
    Instead the pair's relative velocity w = v1 - v2 is turned, keeping its length,
    until its normal part is s = min(ELASTIC_BELOW, |w|) apart: an equal and opposite
    impulse J = mu (w' - w) (mu = m1 m2 / (m1 + m2)), as ball-ball friction would give.
    Momentum is kept exactly, and so is the kinetic energy (the centre-of-mass motion
    and |w| are unchanged), so the energy never rises; the pair leaves apart, and its
    decelerations can close it again only after about 2 s / (2 mu_r g) seconds.
    """
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


def kinetic_energy(masses: FloatArray, velocities: FloatArray) -> float:
    return 0.5 * total(masses * dot(velocities, velocities))
