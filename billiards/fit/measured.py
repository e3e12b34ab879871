"""The model's laws against measured sets, one contact at a time (docs/validation.md,
"Measured sets"; scripts/validation_measured.py prints the report):

- rebounds (Mathavan 2010): a rolling ball (natural roll, no side spin) square into the
  cushion; the rebound speed is the ball's speed as the cushion law leaves it;
- cut shots (Mathavan 2009) and a head-on shot (Derby and Fuller 1999): the ball law
  at the contact, then each ball's slide on the cloth to rolling in closed form: sliding
  friction keeps v - (2/5) R z x w (its angular momentum about the contact point), so a
  ball rolls on at (5/7) of it, whatever mu_s (the spin model's slide, docs/spin.md); the
  slide lasts |u| / ((7/2) mu_s g), u the slip of the contact point.

The sets travel with the package (billiards/fit/data, whose SOURCES.md names each
paper and the licence): `MEASURED` is their folder.
"""

from __future__ import annotations

import csv
import importlib.resources
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from billiards.physics.engine.setup import Setup
from billiards.physics.laws import CUSHION_LAWS
from billiards.physics.laws.cushion import CushionConstants, CushionContact
from billiards.rules.seed import (
    CUSHION_FRICTION,
    CUSHION_RESTITUTION,
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
# The measured sets' folder, inside the package (a wheel holds it too).
MEASURED = Path(str(importlib.resources.files("billiards.fit") / "data"))
# Its files, by the set each holds.
MEASURED_SETS = {
    "rebounds": "mathavan2010_cushion_rebounds.csv",
    "cut shots": "mathavan2009_cut_shots.csv",
    "head-on": "derby_fuller1999_head_on.csv",
}


class MissingData(FileNotFoundError):
    """A data file that is not where it was looked for; str() is one line naming it,
    where it was looked for and how to get it."""


def measured_file(name: str, folder: Path = MEASURED) -> Path:
    """A measured set's file in `folder` (MissingData, one line, if it is not there)."""
    path = folder / name
    if not path.is_file():
        raise MissingData(
            f"--data {folder}: no {name}; expected the measured sets' folder "
            f"({', '.join(MEASURED_SETS.values())}), as the package holds it: {MEASURED}"
        )
    return path


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
