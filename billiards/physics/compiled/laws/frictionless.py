"""The seed's ball-ball contact, compiled (laws.ball_ball.frictionless and
frictionless_impulse): the impulse along the line of centres; the spins pass."""

from __future__ import annotations

from billiards.physics.compiled.arithmetic import py_max, py_min
from billiards.physics.compiled.jit import kernel
from billiards.physics.compiled.laws import BallConstants, BallMotion, Spin, Vector
from billiards.physics.laws.ball_ball import ELASTIC_BELOW


@kernel
def frictionless_impulse(
    normal: Vector, v1: Vector, m1: float, v2: Vector, m2: float, restitution: float
) -> tuple[Vector, Vector, float]:
    """Velocities after a frictionless contact along the unit `normal` from ball 2 to ball
    1, and the approach speed (ball_ball.frictionless_impulse): a pair not approaching
    is left as is (0)."""
    nx, ny = normal
    closing = (v1[0] - v2[0]) * nx + (v1[1] - v2[1]) * ny
    if closing >= 0:
        return v1, v2, 0.0
    restitution = py_max(restitution, py_min(1.0, ELASTIC_BELOW / -closing))
    impulse = (1.0 + restitution) * closing / (1.0 / m1 + 1.0 / m2)
    first = (v1[0] - (impulse / m1) * nx, v1[1] - (impulse / m1) * ny)
    second = (v2[0] + (impulse / m2) * nx, v2[1] + (impulse / m2) * ny)
    return first, second, -closing


@kernel
def frictionless(
    normal: Vector, motion: BallMotion, constants: BallConstants
) -> tuple[Vector, Vector, Spin, Spin, float]:
    """The registry's frictionless law (ball_ball.frictionless), in the ball laws' one
    signature (dispatch.ball_law): (v1', v2', w1', w2', approach), the spins passed on."""
    v1, v2, w1, w2 = motion
    m1, m2, restitution, _, _ = constants
    first, second, approach = frictionless_impulse(normal, v1, m1, v2, m2, restitution)
    return first, second, w1, w2, approach
