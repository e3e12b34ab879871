"""The contact laws, compiled (laws.ball_ball, laws.cushion), each on one contact's
numbers in the numpy law's order: the frictionless impulse, the pressed separation and
the mirror cushion, and the dispatch that picks a run's law by its number (the held
laws: compiled.held)."""

from __future__ import annotations

import math

from billiards.physics.compiled.arithmetic import length, py_max, py_min
from billiards.physics.compiled.jit import kernel
from billiards.physics.laws.ball_ball import ELASTIC_BELOW

Vector = tuple[float, float]


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
def mirror(velocity: Vector, into: Vector, retention: float) -> tuple[Vector, float]:
    """The seed's cushion (cushion.mirror): the velocity mirrored about the rubber's
    normal `into`, keeping `retention` of the kinetic energy; and the approach speed."""
    approach = velocity[0] * into[0] + velocity[1] * into[1]
    keep = math.sqrt(retention)
    bounced_x = (velocity[0] - 2.0 * approach * into[0]) * keep
    bounced_y = (velocity[1] - 2.0 * approach * into[1]) * keep
    return (bounced_x, bounced_y), approach


@kernel
def line_of_centres(first: Vector, second: Vector) -> Vector:
    """The unit normal from ball 2's centre to ball 1's (ball_ball.line_of_centres)."""
    x, y = first[0] - second[0], first[1] - second[1]
    distance = length(x, y)
    return (x / distance, y / distance)


# The laws by number (Table.ball_law, Table.cushion_law): laws.BALL_LAWS' and
# laws.CUSHION_LAWS' names, each a kernel on one contact's numbers. A law compiled later
# is a kernel here, a name in its tuple and a branch in its kind's dispatch.
BALL_LAWS = ("frictionless",)
CUSHION_LAWS = ("mirror",)
FRICTIONLESS = BALL_LAWS.index("frictionless")
MIRROR = CUSHION_LAWS.index("mirror")
Spin = tuple[float, float, float]


@kernel
def ball_contact(
    law: int,
    normal: Vector,
    velocities: tuple[Vector, Vector],
    spins: tuple[Spin, Spin],
    masses: Vector,
    restitution: float,
) -> tuple[Vector, Vector, Spin, Spin, float]:
    """Two balls at a contact by the run's ball law (laws.BALL_LAWS): velocities' and
    spins' after, and the approach speed."""
    (v1, v2), (w1, w2) = velocities, spins
    # FRICTIONLESS (the only law compiled yet): the spins pass.
    after1, after2, approach = frictionless_impulse(
        normal, v1, masses[0], v2, masses[1], restitution
    )
    return after1, after2, w1, w2, approach


@kernel
def cushion_contact(
    law: int, velocity: Vector, spin: Spin, into: Vector, retention: float
) -> tuple[Vector, Spin, float]:
    """A ball at a cushion or jaw by the run's cushion law (laws.CUSHION_LAWS): its
    velocity and spin after, and the approach speed."""
    # MIRROR (the only law compiled yet): the spin passes.
    bounced, approach = mirror(velocity, into, retention)
    return bounced, spin, approach
