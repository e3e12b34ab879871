"""Ball-ball contact laws: what a contact between two balls does to their velocities
(the README's model section, "ball-ball contacts")."""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.arithmetic import dot, length, total
from billiards.physics.motion import FloatArray
from billiards.physics.setup import Setup

# Restitution rises to 1 at low impact speeds: a contact always leaves its pair
# separating at least this fast (or as fast as it closed, if slower). Real balls do
# the same, and without it low restitution goes wrong in two ways: a chain of
# touching balls collapses into infinitely many ever-softer contacts in finite time
# (inelastic collapse), and a pair left touching at zero closing speed is pressed
# into overlap by its two decelerations.
ELASTIC_BELOW = 1e-3  # m/s


def frictionless(
    normal: FloatArray,
    velocities: FloatArray,
    spins: FloatArray,
    masses: FloatArray,
    restitution: float,
    setup: Setup,
) -> tuple[FloatArray, FloatArray, float]:
    """The seed's contact (frictionless_impulse) in the registry's form: the spins pass."""
    v1, v2, approach = frictionless_impulse(
        normal, velocities[0], float(masses[0]), velocities[1], float(masses[1]), restitution
    )
    return np.array([v1, v2]), spins, approach


def frictionless_impulse(
    normal: FloatArray,
    v1: FloatArray,
    m1: float,
    v2: FloatArray,
    m2: float,
    restitution: float,
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
