"""What the ball laws' callers share, compiled (laws.ball_ball): the line of centres
and a pressed pair's separation."""

from __future__ import annotations

import math

from billiards.physics.compiled.arithmetic import length, py_max, py_min
from billiards.physics.compiled.jit import kernel
from billiards.physics.compiled.laws import Vector
from billiards.physics.laws.ball_ball import ELASTIC_BELOW


@kernel
def pressed_separation(
    normal: Vector, v1: Vector, m1: float, v2: Vector, m2: float
) -> tuple[Vector, Vector]:
    """Velocities after a pressed contact (ball_ball.pressed_separation): w = v1 - v2
    turned, its length kept, until its normal part is min(ELASTIC_BELOW, |w|) apart."""
    nx, ny = normal
    rx, ry = v1[0] - v2[0], v1[1] - v2[1]
    speed = length(rx, ry)
    apart = py_min(ELASTIC_BELOW, speed)
    tx, ty = -ny, nx
    along = rx * tx + ry * ty
    sliding = math.copysign(math.sqrt(py_max(speed * speed - apart * apart, 0.0)), along)
    change_x = apart * nx + sliding * tx - rx
    change_y = apart * ny + sliding * ty - ry
    reduced = m1 * m2 / (m1 + m2)
    first = (v1[0] + (reduced / m1) * change_x, v1[1] + (reduced / m1) * change_y)
    second = (v2[0] - (reduced / m2) * change_x, v2[1] - (reduced / m2) * change_y)
    return first, second


@kernel
def line_of_centres(first: Vector, second: Vector) -> Vector:
    """The unit normal from ball 2's centre to ball 1's (ball_ball.line_of_centres)."""
    x, y = first[0] - second[0], first[1] - second[1]
    distance = length(x, y)
    return (x / distance, y / distance)
