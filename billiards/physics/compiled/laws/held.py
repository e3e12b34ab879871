"""A ball held against a rubber, compiled for the rolling model (laws.held.hold)."""

from __future__ import annotations

from billiards.physics.compiled.jit import kernel

Vector = tuple[float, float]


@kernel
def hold(velocity: Vector, into: Vector) -> Vector:
    """A ball held by the rubber it presses into (held.hold, holder at rest): its normal
    velocity gone. (The rolling model has no spin to turn, so a wedge changes nothing.)"""
    normal_speed = 0.0 - (velocity[0] * into[0] + velocity[1] * into[1])
    return (velocity[0] + normal_speed * into[0], velocity[1] + normal_speed * into[1])
