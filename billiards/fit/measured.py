"""The model's laws against measured sets, one contact at a time (docs/validation.md,
"Measured sets"; scripts/validation_measured.py prints the report):

- rebounds (Mathavan 2010): a rolling ball (natural roll, no side spin) square into the
  cushion; the rebound speed is the ball's speed as the cushion law leaves it;
- cut shots (Mathavan 2009) and a head-on shot (Derby and Fuller 1999): the ball law
  at the contact, then each ball's slide on the cloth to rolling in closed form: sliding
  friction keeps v - (2/5) R z x w (its angular momentum about the contact point), so a
  ball rolls on at (5/7) of it, whatever mu_s (the spin model's slide, docs/spin.md); the
  slide lasts |u| / ((7/2) mu_s g), u the slip of the contact point.
"""

from __future__ import annotations

import csv
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from billiards.physics.engine.setup import Setup
from billiards.physics.laws import BALL_LAWS, CUSHION_LAWS
from billiards.physics.laws.ball_ball import PairContact
from billiards.physics.laws.cushion import CushionConstants, CushionContact
from billiards.rules.seed import (
    BALL_FRICTION_A,
    BALL_FRICTION_B,
    BALL_FRICTION_C,
    CUSHION_FRICTION,
    CUSHION_RESTITUTION,
    GRAVITY,
    MATHAVAN_EV_RESTITUTION,
    MATHAVAN_EV_SPEED,
    MATHAVAN_FRICTION,
    MATHAVAN_RESTITUTION,
    RETENTION,
    SLIDING_FRICTION,
)

FloatArray = npt.NDArray[np.float64]

# Mathavan's snooker ball (both papers), the cushion nose at 7R/5 (the 2010 paper).
SNOOKER_R, SNOOKER_M = 0.02625, 0.1406
NOSE = 7 * SNOOKER_R / 5
# Derby and Fuller's ball: 0.1703 kg, 52.4 mm.
DERBY_R, DERBY_M = 0.0524 / 2, 0.1703
RIGID_BELOW = 2.5  # m/s: the paper's rigid-cushion domain


def read_rows(path: Path) -> list[dict[str, str]]:
    """A measured set: '#' lines are its source and notes, then a CSV with a header."""
    with path.open(newline="") as handle:
        return list(csv.DictReader(line for line in handle if not line.startswith("#")))


@dataclass(frozen=True)
class CushionModel:
    name: str  # the table's label
    law: str  # a name in CUSHION_LAWS
    constants: dict[str, float]  # Setup fields
    note: str


CUSHION_MODELS = (
    CushionModel("mirror", "mirror", {"retention": RETENTION}, f"keeps {RETENTION} of the energy"),
    CushionModel(
        "han2005",
        "han2005",
        {"cushion_restitution": CUSHION_RESTITUTION, "cushion_friction": CUSHION_FRICTION},
        f"e = {CUSHION_RESTITUTION}, mu = {CUSHION_FRICTION} (pooltool's)",
    ),
    CushionModel(
        "mathavan2010",
        "mathavan2010",
        {"cushion_restitution": MATHAVAN_RESTITUTION, "cushion_friction": MATHAVAN_FRICTION},
        f"e_e = {MATHAVAN_RESTITUTION}, mu_w = {MATHAVAN_FRICTION} (the paper's fit), "
        f"mu_s = {SLIDING_FRICTION}",
    ),
    CushionModel(
        "mathavan2010_ev",
        "mathavan2010_ev",
        {
            "cushion_restitution": MATHAVAN_EV_RESTITUTION,
            "cushion_friction": MATHAVAN_FRICTION,
            "cushion_restitution_speed": MATHAVAN_EV_SPEED,
        },
        f"e_0 = {MATHAVAN_EV_RESTITUTION}, v_c = {MATHAVAN_EV_SPEED} m/s (fitted to all 19), "
        f"mu_w = {MATHAVAN_FRICTION}, mu_s = {SLIDING_FRICTION}",
    ),
)


def rebound_speed(model: CushionModel, speed: float) -> float:
    """A rolling ball square into the +y cushion at `speed`: its speed as it leaves."""
    setup = Setup.of(
        [[0.5, 0.5]],
        model="spin",
        radius=SNOOKER_R,
        cushion_law=model.law,
        cushion_height=NOSE,
        sliding_friction=SLIDING_FRICTION,
        **model.constants,
    )
    velocities, _, _ = CUSHION_LAWS[model.law](
        CushionContact(
            np.array([[0.0, speed]]),
            np.array([[-speed / SNOOKER_R, 0.0, 0.0]]),  # natural roll along +y
            np.array([[0.0, 1.0]]),
            np.array([SNOOKER_M]),
        ),
        CushionConstants.of(setup),
    )
    return math.hypot(float(velocities[0, 0]), float(velocities[0, 1]))


def errors(predicted: Sequence[float], measured: Sequence[float]) -> FloatArray:
    return np.array([abs(p - m) / m for p, m in zip(predicted, measured, strict=True)])


@dataclass(frozen=True)
class BallModel:
    name: str
    law: str  # a name in BALL_LAWS
    restitution: float
    friction: tuple[float, float, float]  # mu = a + b exp(-c s)
    note: str


ALCIATORE = (BALL_FRICTION_A, BALL_FRICTION_B, BALL_FRICTION_C)


def contact(
    model: BallModel,
    radius: float,
    mass: float,
    normal: FloatArray,
    velocities: FloatArray,
    spins: FloatArray,
) -> tuple[FloatArray, FloatArray]:
    setup = Setup.of(
        [[0.5, 0.5], [1.0, 0.5]],
        model="spin",
        radius=radius,
        ball_law=model.law,
        ball_friction=model.friction,
    )
    pair = PairContact(normal, velocities, spins, np.array([mass, mass]))
    after_v, after_w, _ = BALL_LAWS[model.law](pair, model.restitution, setup)
    return after_v, after_w


def rolling_on(velocity: FloatArray, spin: FloatArray, radius: float) -> tuple[float, float]:
    """A ball's speed once its slide has ended, and how long the slide lasts (s)."""
    # v - (2/5) R z x w is kept while the cloth's friction works; z x w = (-w_y, w_x).
    kept_x = velocity[0] + 0.4 * radius * spin[1]
    kept_y = velocity[1] - 0.4 * radius * spin[0]
    # The contact point's slip: v + w x (-R z) = (v_x - R w_y, v_y + R w_x).
    slip = math.hypot(velocity[0] - radius * spin[1], velocity[1] + radius * spin[0])
    return 5.0 / 7.0 * math.hypot(kept_x, kept_y), slip / (3.5 * SLIDING_FRICTION * GRAVITY)


def cut_shot(model: BallModel, speed: float, cut_degrees: float) -> tuple[float, float]:
    """A rolling cue ball along +x meets an object ball at rest, cut_degrees off its line
    of centres: both balls' speeds once they roll."""
    angle = math.radians(cut_degrees)  # the report's own trigonometry, not the physics'
    normal = -np.array([math.cos(angle), math.sin(angle)])  # from the object ball to the cue
    velocities = np.array([[speed, 0.0], [0.0, 0.0]])
    spins = np.array([[0.0, speed / SNOOKER_R, 0.0], [0.0, 0.0, 0.0]])  # natural roll
    after_v, after_w = contact(model, SNOOKER_R, SNOOKER_M, normal, velocities, spins)
    cue, _ = rolling_on(after_v[0], after_w[0], SNOOKER_R)
    target, _ = rolling_on(after_v[1], after_w[1], SNOOKER_R)
    return cue, target


def cut_errors(model: BallModel, rows: list[dict[str, str]]) -> tuple[FloatArray, list[str]]:
    predicted, measured, cells = [], [], []
    for row in rows:
        cue, target = cut_shot(model, float(row["incoming_speed_m_s"]), float(row["cut_angle_deg"]))
        predicted += [cue, target]
        measured += [
            float(row["cue_post_slip_speed_m_s"]),
            float(row["object_post_slip_speed_m_s"]),
        ]
        cells.append(f"{cue:.3f} / {target:.3f}")
    return errors(predicted, measured), cells
