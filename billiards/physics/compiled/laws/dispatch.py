"""The compiled laws by id (the package's registry): one kernel per kind of contact,
one signature each, so that a loop calls `cushion_law(law_id, ...)` and
`ball_law(law_id, ...)` and never knows which law it holds."""

from __future__ import annotations

from billiards.physics.compiled.jit import kernel
from billiards.physics.compiled.laws import (
    FRICTIONAL,
    FRICTIONLESS,
    HAN2005,
    MATHAVAN2010,
    MATHAVAN2010_EV,
    MIRROR,
    BallConstants,
    BallMotion,
    CushionNumbers,
    Spin,
    Vector,
)
from billiards.physics.compiled.laws.frictional import frictional
from billiards.physics.compiled.laws.frictionless import frictionless
from billiards.physics.compiled.laws.han2005 import han2005
from billiards.physics.compiled.laws.mathavan2010 import mathavan2010, mathavan2010_ev
from billiards.physics.compiled.laws.mirror import mirror


@kernel
def cushion_law(
    law_id: int,
    velocity: Vector,
    spin: Spin,
    into: Vector,
    mass: float,
    constants: CushionNumbers,
) -> tuple[Vector, Spin, float]:
    """The cushion law `law_id` names (CUSHION_LAW_IDS) on one ball at a cushion or a
    jaw, `into` the unit normal into the rubber: (velocity', spin', approach speed)."""
    if law_id == MIRROR:
        return mirror(velocity, spin, into, mass, constants)
    if law_id == HAN2005:
        return han2005(velocity, spin, into, mass, constants)
    if law_id == MATHAVAN2010:
        return mathavan2010(velocity, spin, into, mass, constants)
    if law_id == MATHAVAN2010_EV:
        return mathavan2010_ev(velocity, spin, into, mass, constants)
    raise ValueError("no cushion law has this id (laws.CUSHION_LAW_IDS)")


@kernel
def ball_law(
    law_id: int, normal: Vector, motion: BallMotion, constants: BallConstants
) -> tuple[Vector, Vector, Spin, Spin, float]:
    """The ball law `law_id` names (BALL_LAW_IDS) on two balls in contact, `normal` the
    unit line of centres from ball 2 to ball 1, the pair's motion (v1, v2, w1, w2) and
    constants (m1, m2, e, R, ball friction): (v1', v2', w1', w2', approach speed)."""
    if law_id == FRICTIONLESS:
        return frictionless(normal, motion, constants)
    if law_id == FRICTIONAL:
        return frictional(normal, motion, constants)
    raise ValueError("no ball law has this id (laws.BALL_LAW_IDS)")
