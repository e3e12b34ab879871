"""What a contact does to velocities (MODEL.md, "Ball-ball contact", "Ball-cushion contact")."""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.motion import FloatArray


def ball_impulse(
    p1: FloatArray,
    v1: FloatArray,
    m1: float,
    p2: FloatArray,
    v2: FloatArray,
    m2: float,
    restitution: float,
) -> tuple[FloatArray, FloatArray, float]:
    """Velocities after a frictionless contact along the line of centres.

    J = (1 + e) ((v1 - v2).n) / (1/m1 + 1/m2);  v1' = v1 - J n / m1,  v2' = v2 + J n / m2.
    Returns (v1', v2', approach speed); a pair that is not approaching is left as is
    (approach speed 0).
    """
    separation = p1 - p2
    normal = separation / math.hypot(separation[0], separation[1])
    closing = float((v1 - v2) @ normal)
    if closing >= 0:
        return v1, v2, 0.0
    impulse = (1.0 + restitution) * closing / (1.0 / m1 + 1.0 / m2)
    return v1 - (impulse / m1) * normal, v2 + (impulse / m2) * normal, -closing


def cushion_bounce(velocity: FloatArray, axis: int, retention: float) -> tuple[FloatArray, float]:
    """Mirror the normal component and keep `retention` of the kinetic energy (eq. 2.7).

    Returns (new velocity, approach speed into the cushion)."""
    bounced = velocity.copy()
    approach = abs(float(velocity[axis]))
    bounced[axis] = -bounced[axis]
    return bounced * math.sqrt(retention), approach


def kinetic_energy(masses: FloatArray, velocities: FloatArray) -> float:
    return float(0.5 * np.sum(masses * np.sum(velocities * velocities, axis=1)))
