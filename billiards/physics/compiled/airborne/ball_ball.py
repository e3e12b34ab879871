"""Two balls meeting in 3D (a flying ball over another, or on its upper half): the
frictionless contact along the line of centres, now a 3D unit normal n from ball 2 to
ball 1, written as the plane's law (compiled.laws.frictionless_impulse, the README's
ball-ball contact; its elastic floor ELASTIC_BELOW) with z's terms added last:

    J = (1 + e) ((v1 - v2).n) / (1/m1 + 1/m2),   v1' = v1 - J n / m1,   v2' = v2 + J n / m2.

Momentum is kept in all three axes and, with e <= 1, energy never rises. A ball on the
cloth that the impulse pushes down (v_z' < 0) meets the bed at that instant (bed.
bed_frictional: the cloth takes the downward momentum, as pooltool resolves a ball-table
event at once after a ball-ball one); one pushed up leaves the cloth.
"""

from __future__ import annotations

import math

from billiards.physics.compiled.airborne.flight import Vector3
from billiards.physics.compiled.arithmetic import py_max, py_min
from billiards.physics.compiled.jit import kernel
from billiards.physics.laws.ball_ball import ELASTIC_BELOW


@kernel
def line_of_centres_3d(first: Vector3, second: Vector3) -> Vector3:
    """The unit normal from ball 2's centre to ball 1's."""
    x, y, z = first[0] - second[0], first[1] - second[1], first[2] - second[2]
    distance = math.sqrt((x * x + y * y) + z * z)
    return (x / distance, y / distance, z / distance)


@kernel
def frictionless_impulse_3d(
    normal: Vector3, v1: Vector3, m1: float, v2: Vector3, m2: float, restitution: float
) -> tuple[Vector3, Vector3, float]:
    """Velocities after a frictionless contact along the unit 3D `normal` (from ball 2 to
    ball 1) and the approach speed; a pair not approaching is left as is (0)."""
    nx, ny, nz = normal
    closing = ((v1[0] - v2[0]) * nx + (v1[1] - v2[1]) * ny) + (v1[2] - v2[2]) * nz
    if closing >= 0:
        return v1, v2, 0.0
    restitution = py_max(restitution, py_min(1.0, ELASTIC_BELOW / -closing))
    impulse = (1.0 + restitution) * closing / (1.0 / m1 + 1.0 / m2)
    first = (
        v1[0] - (impulse / m1) * nx,
        v1[1] - (impulse / m1) * ny,
        v1[2] - (impulse / m1) * nz,
    )
    second = (
        v2[0] + (impulse / m2) * nx,
        v2[1] + (impulse / m2) * ny,
        v2[2] + (impulse / m2) * nz,
    )
    return first, second, -closing
