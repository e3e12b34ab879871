"""The seed's cushion, compiled (laws.cushion.mirror): the velocity mirrored about the
rubber's normal, keeping `retention` of the kinetic energy; the spin passes."""

from __future__ import annotations

import math

from billiards.physics.compiled.jit import kernel
from billiards.physics.compiled.laws import CushionNumbers, Spin, Vector


@kernel
def mirror_velocity(velocity: Vector, into: Vector, retention: float) -> tuple[Vector, float]:
    """The velocity mirrored about the rubber's normal `into`, keeping `retention` of the
    kinetic energy; and the approach speed (the rolling model's loop, which has no spin)."""
    approach = velocity[0] * into[0] + velocity[1] * into[1]
    keep = math.sqrt(retention)
    bounced_x = (velocity[0] - 2.0 * approach * into[0]) * keep
    bounced_y = (velocity[1] - 2.0 * approach * into[1]) * keep
    return (bounced_x, bounced_y), approach


@kernel
def mirror(
    velocity: Vector, spin: Spin, into: Vector, mass: float, constants: CushionNumbers
) -> tuple[Vector, Spin, float]:
    """The registry's mirror (cushion.mirror) in the cushion laws' one signature
    (dispatch.cushion_law): (velocity', spin, approach), the approach as it comes (a
    ball moving away is mirrored too, as the numpy law does)."""
    bounced, approach = mirror_velocity(velocity, into, constants.retention)
    return bounced, spin, approach
