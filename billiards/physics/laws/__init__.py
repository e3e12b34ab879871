"""The contact laws, by kind of contact and name: one module per kind of contact.

A new law is a new function in its kind's module and a new entry in its registry here
(pooltool's physics/resolve registry is the model); the calendar and every method
(exact, event, naive) look their laws up here rather than branching on them. Each kind
has one signature, so a caller never knows which law it holds.
"""

from __future__ import annotations

from collections.abc import Callable

from billiards.physics.engine.setup import Setup
from billiards.physics.laws import ball_ball, cushion
from billiards.physics.numerics.arrays import FloatArray

# Two balls in contact (ball_ball.PairContact), restitution, setup -> (velocities',
# spins', approach speed). A law that ignores spin passes it on.
BallLaw = Callable[[ball_ball.PairContact, float, Setup], tuple[FloatArray, FloatArray, float]]
# A cushion, or a cushion's rounded end at a pocket (a jaw: the same rubber met along
# the line of centres): (k balls there (cushion.CushionContact), the constants of a run,
# or a batch's rows of runs (cushion.CushionConstants)) -> (velocities', spins',
# approach speeds (k,)). A law that ignores spin passes it on, so every law serves both
# motion models.
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
