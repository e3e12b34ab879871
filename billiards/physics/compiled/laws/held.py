"""Held contacts, compiled (laws.held, on one contact's numbers in its order): a ball
pressed by its own slip into what it touches is held (hold), a sliding front ball of a
pair pushes the other (push), a ball held twice at one instant is wedged (wedge), a
pressed pair with no slip driving it is parted (part, paid by payer_of's ball)."""

from __future__ import annotations

import math

from billiards.physics.compiled.arithmetic import length
from billiards.physics.compiled.jit import kernel
from billiards.physics.compiled.laws import Spin, Vector


@kernel
def hold(
    velocity: Vector, spin: Spin, into: Vector, holder_speed: float, radius: float
) -> tuple[Vector, Spin]:
    """A ball held by what it presses into along `into`, moving at `holder_speed` along
    it: (velocity', spin') with no normal slip (held.hold)."""
    along = (-into[1], into[0])
    normal = holder_speed - (velocity[0] * into[0] + velocity[1] * into[1])
    held_velocity = (velocity[0] + normal * into[0], velocity[1] + normal * into[1])
    turn = holder_speed / radius - (spin[0] * along[0] + spin[1] * along[1])
    return held_velocity, (spin[0] + turn * along[0], spin[1] + turn * along[1], spin[2])


@kernel
def wedge(velocity: Vector, spin: Spin, radius: float) -> Spin:
    """The spin of a ball with no slip left: w_xy = z x v / R (held.wedge)."""
    return (-velocity[1] / radius, velocity[0] / radius, spin[2])


@kernel
def push(
    velocities: tuple[Vector, Vector],
    spins: tuple[Spin, Spin],
    masses: Vector,
    into: Vector,
    radius: float,
) -> tuple[bool, tuple[Vector, Vector], tuple[Spin, Spin]]:
    """Two touching balls, the first pressed by its slip along `into` into the second:
    (pushed, velocities', spins') at one normal speed with no normal slip; pushed is
    False where the contact impulse would pull (held.push's None)."""
    along = (-into[1], into[0])
    (v1, v2), (w1, w2) = velocities, spins
    speed1 = v1[0] * into[0] + v1[1] * into[1]
    speed2 = v2[0] * into[0] + v2[1] * into[1]
    slip1 = -radius * (w1[0] * along[0] + w1[1] * along[1])
    slip2 = -radius * (w2[0] * along[0] + w2[1] * along[1])
    rolled1 = masses[0] * (speed1 - 0.4 * slip1)
    rolled2 = masses[1] * (speed2 - 0.4 * slip2)
    common = (rolled1 + rolled2) / (1.4 * (masses[0] + masses[1]))
    if rolled1 - 1.4 * masses[0] * common < 0:
        return False, velocities, spins
    pushed1 = (v1[0] + (common - speed1) * into[0], v1[1] + (common - speed1) * into[1])
    pushed2 = (v2[0] + (common - speed2) * into[0], v2[1] + (common - speed2) * into[1])
    turn1 = (common / radius) - (w1[0] * along[0] + w1[1] * along[1])
    turn2 = (common / radius) - (w2[0] * along[0] + w2[1] * along[1])
    turned1 = (w1[0] + turn1 * along[0], w1[1] + turn1 * along[1], w1[2])
    turned2 = (w2[0] + turn2 * along[0], w2[1] + turn2 * along[1], w2[2])
    return True, (pushed1, pushed2), (turned1, turned2)


@kernel
def slip_of(velocity: Vector, spin: Spin, radius: float) -> Vector:
    """A ball's slip, the velocity of its contact with the cloth: v + R (-w_y, w_x)."""
    return (velocity[0] - radius * spin[1], velocity[1] + radius * spin[0])


@kernel
def payer_of(
    velocities: tuple[Vector, Vector],
    spins: tuple[Spin, Spin],
    sliding: tuple[bool, bool],
    radius: float,
) -> int:
    """The ball (0 or 1) that pays for `part`: the sliding one, or the faster slipping."""
    if not (sliding[0] and sliding[1]):
        return 0 if sliding[0] else 1
    first = slip_of(velocities[0], spins[0], radius)
    second = slip_of(velocities[1], spins[1], radius)
    return 0 if length(first[0], first[1]) >= length(second[0], second[1]) else 1


@kernel
def part(
    velocities: tuple[Vector, Vector],
    spins: tuple[Spin, Spin],
    masses: Vector,
    normal: Vector,
    payer: int,
    constants: Vector,
) -> tuple[tuple[Vector, Vector], tuple[Spin, Spin]]:
    """Two touching balls moving together, pressed though no slip drives one into the
    other: parted at `apart` along the normal, paid by the cloth's friction on the
    sliding `payer` (held.part, whose docstring derives it). constants: (radius,
    apart). Returns (velocities', spins')."""
    radius, apart = constants
    mass = masses[payer]
    reduced = masses[0] * masses[1] / (masses[0] + masses[1])
    velocity, spin = velocities[payer], spins[payer]
    slip = slip_of(velocity, spin, radius)
    slip_speed = length(slip[0], slip[1])
    cost = 0.5 * reduced * apart * apart * (1.0 + 1e-9)
    discriminant = slip_speed * slip_speed - 7.0 * cost / mass
    if discriminant < 0:
        apart = math.sqrt(2.0 * mass * slip_speed * slip_speed / (7.0 * reduced)) / (1.0 + 1e-6)
        discriminant = 0.0
    paid = (slip_speed - math.sqrt(discriminant)) * mass / 3.5
    if slip_speed > 0:
        share = paid / mass / slip_speed
        change = (share * slip[0], share * slip[1])  # dv = c/m u_hat, taken away
        velocity = (velocity[0] - change[0], velocity[1] - change[1])
        # du = 7/2 dv: the spin's part of the slip, R (-w_y, w_x), takes 5/2 dv.
        spin = (spin[0] - 2.5 * change[1] / radius, spin[1] + 2.5 * change[0] / radius, spin[2])
    first, second = velocities
    turned = spins
    if payer == 0:
        first, turned = velocity, (spin, spins[1])
    else:
        second, turned = velocity, (spins[0], spin)
    parting = (first[0] - second[0]) * normal[0] + (first[1] - second[1]) * normal[1]
    if parting < apart:
        impulse = reduced * (apart - parting)
        first = (
            first[0] + (impulse / masses[0]) * normal[0],
            first[1] + (impulse / masses[0]) * normal[1],
        )
        second = (
            second[0] - (impulse / masses[1]) * normal[0],
            second[1] - (impulse / masses[1]) * normal[1],
        )
    return (first, second), turned
