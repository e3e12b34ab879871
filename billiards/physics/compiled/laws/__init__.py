"""The contact laws, compiled: one module per law (billiards.physics.laws' laws, each
in the numpy law's order, the same bits), and here their registry.

A law is chosen by an integer id, its name's place in billiards.physics.laws'
CUSHION_LAWS or BALL_LAWS (the one place the order is kept); dispatch.cushion_law and
dispatch.ball_law call the law an id names, with one signature per kind of contact, so
a loop never knows which law it holds. What a cushion law reads of a run comes as
CushionNumbers, laws.cushion.CushionConstants' fields as one run's floats.

This module imports no numba (the kernels' modules do).
"""

from __future__ import annotations

from typing import NamedTuple

from billiards.physics.laws import BALL_LAWS, CUSHION_LAWS
from billiards.physics.laws.cushion import CushionConstants

CUSHION_LAW_IDS: dict[str, int] = {name: index for index, name in enumerate(CUSHION_LAWS)}
BALL_LAW_IDS: dict[str, int] = {name: index for index, name in enumerate(BALL_LAWS)}

# The ids the dispatch compares with (numba reads them as constants).
MIRROR = CUSHION_LAW_IDS["mirror"]
HAN2005 = CUSHION_LAW_IDS["han2005"]
MATHAVAN2010 = CUSHION_LAW_IDS["mathavan2010"]
MATHAVAN2010_EV = CUSHION_LAW_IDS["mathavan2010_ev"]
FRICTIONLESS = BALL_LAW_IDS["frictionless"]
FRICTIONAL = BALL_LAW_IDS["frictional"]

Vector = tuple[float, float]
Spin = tuple[float, float, float]
# The ball laws' one signature (dispatch.ball_law): the unit normal from ball 2 to ball 1,
# the pair's motion (v1, v2, w1, w2) and its constants (m1, m2, e, R, the ball friction's
# a, b, c).
BallMotion = tuple[Vector, Vector, Spin, Spin]
BallConstants = tuple[float, float, float, float, Spin]


class CushionNumbers(NamedTuple):
    """One run's cushion constants (laws.cushion.CushionConstants' fields, in its order,
    as floats): what every compiled cushion law reads of the run."""

    radius: float
    retention: float  # mirror: the share of kinetic energy kept
    cushion_restitution: float  # han2005's e, mathavan2010's e_e (or e_0)
    cushion_friction: float  # han2005's mu, mathavan2010's mu_w
    cushion_height: float  # the cushion nose's, above the cloth
    sliding_friction: float  # mathavan2010's mu_s
    cushion_restitution_speed: float  # mathavan2010_ev's v_c

    @classmethod
    def of(cls, constants: CushionConstants) -> CushionNumbers:
        """A run's CushionConstants (each one number) as floats, field by field."""
        return cls(**{name: float(getattr(constants, name)) for name in cls._fields})
