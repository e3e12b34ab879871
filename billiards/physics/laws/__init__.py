"""The contact laws by kind of contact and name (pooltool's physics/resolve registry is
the model): a new law is a function in its kind's module and an entry here, where every
method looks it up. Each kind has one signature: a caller never knows which law it holds.
"""

from __future__ import annotations

from collections.abc import Callable

from billiards.physics.laws import ball_ball, cushion
from billiards.physics.numerics.arrays import FloatArray

# Two balls in contact (ball_ball.PairContact), restitution, what the law reads of the
# run (ball_ball.BallConstants, a Setup) -> (velocities', spins', approach speed). A law
# that ignores spin passes it on.
BallLaw = Callable[
    [ball_ball.PairContact, float, ball_ball.BallConstants], tuple[FloatArray, FloatArray, float]
]
# A cushion or a jaw (the same rubber, met along the line of centres): see laws.cushion.
# A law that ignores spin passes it on, so every law serves both motion models.
CushionLaw = cushion.CushionLaw

BALL_LAWS: dict[str, BallLaw] = {
    "frictionless": ball_ball.frictionless,
    "frictional": ball_ball.frictional,
}
CUSHION_LAWS: dict[str, CushionLaw] = {
    "mirror": cushion.mirror,
    "han2005": cushion.han2005,
    "mathavan2010": cushion.mathavan2010,
    "mathavan2010_ev": cushion.mathavan2010_ev,
}
# The seed's laws, the defaults of every run.
DEFAULT_BALL_LAW = "frictionless"
DEFAULT_CUSHION_LAW = "mirror"
