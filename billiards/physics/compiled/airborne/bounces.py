"""The hops after a landing: each impact with the bed (bed.bed_frictional) sends the ball
up at e_t times the speed it came down at, so the heights fall by e_t^2 and the flights
(2 v_k / g each) by e_t:

    v_k = e_t^k v,   h_k = v_k^2 / (2 g),   total air time = sum_k 2 v_k / g
                                             = 2 v e_t (1 - e_t^n) / (g (1 - e_t)),

until a launch is slower than a stated vertical speed v_s, or (the same test) would rise
less than a stated height h, v_s = sqrt(2 g h) (pooltool's min_bounce_height, 5 mm:
SETTLE_HEIGHT); that impact's vertical speed is dropped and the ball slides on the cloth.
Rigid bouncing never ends by itself (Zeno: infinitely many hops in a finite time), so
the settling speed ends it after n hops, n the least k with e_t^(k+1) v below it: counted by repeated multiplication (no logarithm, which IEEE 754 leaves
to each library), the loop bounded by MAX_BOUNCES (more than e_t = 0.999 from 100 m/s
takes).
"""

from __future__ import annotations

import math

from billiards.physics.compiled.airborne.bed import bed_frictional
from billiards.physics.compiled.airborne.flight import Vector3
from billiards.physics.compiled.jit import kernel
from billiards.rules import seed

SETTLE_HEIGHT = seed.SETTLE_HEIGHT  # m: a launch rising less ends the hopping (pooltool's)
MAX_BOUNCES = 10_000  # a safeguard for e_t >= 1, never reached by e_t <= 0.999


@kernel
def settle_speed(settle_height: float, gravity: float) -> float:
    """The launch speed that rises `settle_height`: sqrt(2 g h) (v^2 / (2 g) = h)."""
    return math.sqrt(2.0 * gravity * settle_height)


@kernel
def settles(launch_speed: float, lowest_launch: float) -> bool:
    """Whether a ball leaving the bed at `launch_speed` settles: slower than `lowest_launch`, the
    settling speed (a launch of 0, or down, settles whatever `lowest_launch`)."""
    return not (launch_speed > 0 and launch_speed >= lowest_launch)


@kernel
def bounce_count(landing_speed: float, restitution: float, lowest_launch: float) -> int:
    """How many flights follow a landing at `landing_speed` (downward, > 0): the number
    of k >= 1 with e_t^k v at least the settling speed `lowest_launch`, counted by multiplying."""
    launch = landing_speed
    for count in range(MAX_BOUNCES):
        launch = restitution * launch
        if settles(launch, lowest_launch):
            return count
    return MAX_BOUNCES


@kernel
def bounce(
    velocity: Vector3,
    spin: Vector3,
    laws: tuple[float, float, float],
    gravity: float,
    lowest_launch: float,
) -> tuple[Vector3, Vector3, float]:
    """One landing (velocity with v_z < 0, the centre at height R): velocity and spin
    after the bed's impact (bed.bed_frictional; laws = (R, e_t, mu_t)) and the flight's
    time, 2 v_z' / g; 0, with v_z' = 0, when it settles on the cloth (slower than
    `lowest_launch`, the settling speed)."""
    radius, restitution, friction = laws
    after, turned = bed_frictional(velocity, spin, radius, restitution, friction)
    if settles(after[2], lowest_launch):
        return (after[0], after[1], 0.0), turned, 0.0
    return after, turned, 2.0 * after[2] / gravity


@kernel
def bounce_sequence(
    velocity: Vector3,
    spin: Vector3,
    laws: tuple[float, float, float],
    gravity: float,
    lowest_launch: float,
) -> tuple[int, float, tuple[float, float], Vector3, Vector3]:
    """Every hop after a landing, with nothing else met: (the number of flights, their
    total time, the way they carried the ball on the cloth's plane, and the velocity
    (v_z = 0) and spin it slides off with at the last landing). Each flight keeps its
    horizontal velocity; each impact's friction changes it (bounce)."""
    air_time = 0.0
    carried_x = 0.0
    carried_y = 0.0
    for count in range(MAX_BOUNCES + 1):
        velocity, spin, flight = bounce(velocity, spin, laws, gravity, lowest_launch)
        if flight == 0:
            return count, air_time, (carried_x, carried_y), velocity, spin
        air_time += flight
        carried_x += velocity[0] * flight
        carried_y += velocity[1] * flight
        velocity = (velocity[0], velocity[1], 0.0 - velocity[2])  # lands as it left
    return MAX_BOUNCES, air_time, (carried_x, carried_y), (velocity[0], velocity[1], 0.0), spin
