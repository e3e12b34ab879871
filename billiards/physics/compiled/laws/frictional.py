"""The ball-ball contact with friction at the contact point, compiled
(laws.ball_ball.frictional: throw), in the numpy law's order."""

from __future__ import annotations

import math

from billiards.physics.compiled.arithmetic import exp, py_max, py_min
from billiards.physics.compiled.jit import kernel
from billiards.physics.compiled.laws import BallConstants, BallMotion, Spin, Vector
from billiards.physics.compiled.laws.frictionless import frictionless
from billiards.physics.laws.ball_ball import ELASTIC_BELOW


@kernel
def frictional(
    normal: Vector, motion: BallMotion, constants: BallConstants
) -> tuple[Vector, Vector, Spin, Spin, float]:
    """ball_ball.frictional (its docstring has the model) in the ball laws' one
    signature: (v1', v2', w1', w2', approach); a pair not approaching is left as is (0)."""
    v1, v2, w1, w2 = motion
    m1, m2, restitution, radius, ball_friction = constants
    nx, ny = normal
    rx, ry = v1[0] - v2[0], v1[1] - v2[1]
    closing = rx * nx + ry * ny
    if closing >= 0:
        return v1, v2, w1, w2, 0.0
    restitution = py_max(restitution, py_min(1.0, ELASTIC_BELOW / -closing))
    impulse = (1.0 + restitution) * closing / (1.0 / m1 + 1.0 / m2)  # ball 1 takes -impulse n
    wx, wy, wz = w1[0] + w2[0], w1[1] + w2[1], w1[2] + w2[2]
    # u - (u.n) n: (w x n) = (-wz ny, wz nx, wx ny - wy nx) has no part along n.
    tx = rx + radius * wz * ny - closing * nx
    ty = ry - radius * wz * nx - closing * ny
    tz = -radius * (wx * ny - wy * nx)
    slip = math.sqrt(tx * tx + ty * ty + tz * tz)
    a, b, c = ball_friction
    mu = a + b * exp(-c * slip) if c * slip < 700.0 else a
    bound = mu * -impulse
    if not (slip > 0 and bound > 0):
        # No friction impulse: the frictionless law, to the bit (with the raised e).
        return frictionless(normal, motion, (m1, m2, restitution, radius, ball_friction))
    compliance = 3.5 * (1.0 / m1 + 1.0 / m2)
    scale = -py_min(bound, slip / compliance) / slip
    fx, fy, fz = scale * tx, scale * ty, scale * tz
    first = (v1[0] - (impulse / m1) * nx + fx / m1, v1[1] - (impulse / m1) * ny + fy / m1)
    second = (v2[0] + (impulse / m2) * nx - fx / m2, v2[1] + (impulse / m2) * ny - fy / m2)
    # dw = (arm x impulse) / I; both arms' torques are -R n x F: n x F / (2/5 m R).
    cx, cy, cz = ny * fz, -nx * fz, nx * fy - ny * fx
    turn1, turn2 = -2.5 / (m1 * radius), -2.5 / (m2 * radius)
    turned1 = (w1[0] + turn1 * cx, w1[1] + turn1 * cy, w1[2] + turn1 * cz)
    turned2 = (w2[0] + turn2 * cx, w2[1] + turn2 * cy, w2[2] + turn2 * cz)
    return first, second, turned1, turned2, -closing
