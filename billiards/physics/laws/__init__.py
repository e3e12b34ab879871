"""The contact laws, by kind of contact and name: one module per kind of contact.

A new law is a new function in its kind's module and a new entry in its registry here
(pooltool's physics/resolve registry is the model); the calendar and every method
(exact, event, naive) look their laws up here rather than branching on them.
"""

from __future__ import annotations

from collections.abc import Callable

from billiards.physics.laws import ball_ball, cushion, jaw
from billiards.physics.motion import FloatArray, IntArray

# (unit normal, v1, m1, v2, m2, restitution) -> (v1', v2', approach speed)
BallLaw = Callable[
    [FloatArray, FloatArray, float, FloatArray, float, float], tuple[FloatArray, FloatArray, float]
]
# (velocities (k, 2), cushion axes (k,), retention) -> (velocities', approach speeds (k,))
CushionLaw = Callable[[FloatArray, IntArray, float], tuple[FloatArray, FloatArray]]

BALL_LAWS: dict[str, BallLaw] = {"frictionless": ball_ball.frictionless_impulse}
CUSHION_LAWS: dict[str, CushionLaw] = {"mirror": cushion.mirror}
# (velocities (k, 2), unit normals into the jaws (k, 2), retention) -> (velocities',
# approach speeds (k,)): each cushion law's form at a pocket's jaw, under its name.
JawLaw = Callable[[FloatArray, FloatArray, float], tuple[FloatArray, FloatArray]]
JAW_LAWS: dict[str, JawLaw] = {"mirror": jaw.mirror}
# The spin model's cushion laws that act on the spin too: (velocity (2,), spin (3,), unit
# normal into the cushion (2,), radius, mass, restitution, friction, nose height) ->
# (velocity', spin', approach speed). Any law of CUSHION_LAWS also serves the spin
# model, keeping the spin.
SpinCushionLaw = Callable[
    [FloatArray, FloatArray, FloatArray, float, float, float, float, float],
    tuple[FloatArray, FloatArray, float],
]
SPIN_CUSHION_LAWS: dict[str, SpinCushionLaw] = {"han2005": cushion.han2005}
# The seed's laws, the defaults of every run.
DEFAULT_BALL_LAW = "frictionless"
DEFAULT_CUSHION_LAW = "mirror"
