"""Fitting a table: every shot's stroke, and the constants that all the shots share.

`score` keeps the table's constants and fits each shot's stroke alone. `calibrate`
fits the constants too: Nelder-Mead over the constants (scaled to their bounds), each
trial (a candidate set of constants) fitting every shot's stroke on the trial's table
from the same kinematic estimate (`kinematic_starts`: the speed and direction the cue
ball's first recorded positions show, with the few tips the stroke search always tries),
never from another candidate's fitted strokes: strokes fitted at one set of constants
carry its bias into the next (tailuge/billiards found its sweeps biased towards the
defaults its strokes were fitted at). A trial picks each shot's best start and polishes
it (a batch a polish round, every run with the trial's constants), and scores the mean
of the shots' whole-shot RMSE; then every shot's stroke is fitted afresh (differential
evolution, from the same estimate) at the best constants.

Why these optimizers (SciPy's): a stroke's error is discontinuous (a ball hit or just
missed changes the rest of the shot), so no gradient helps and a local start can sit in
the wrong basin; differential evolution searches the whole box, and with
`vectorized=True` a generation is one batch of runs with one table's constants, which
the engine simulates together. The table's constants move every run at once and their
error is smoother (a mean over many shots); there are few of them (6), so Nelder-Mead,
which needs no gradient and few evaluations, suffices.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from billiards.fit.outcomes import (
    Agreement,
    AgreementCounts,
    Outcome,
    agreement,
    count_agreements,
    shot_outcomes,
)
from billiards.fit.recordings import Recording
from billiards.fit.seeds import aimed_strokes, outcome_check
from billiards.fit.shots import (
    Budget,
    Errors,
    Shot,
    Stroke,
    fit_stroke,
    polish_strokes,
    prepare,
    simulate_strokes,
)
from billiards.scene.reader import Physics, Scene

# The [physics] constants a calibration fits, with their search bounds: the cloth's
# for every table, the cushion law's own by law. Each is a key of the scene's [physics].
CLOTH_CONSTANTS: dict[str, tuple[float, float]] = {
    "sliding_friction": (0.05, 0.5),
    "rolling_friction": (0.002, 0.03),
    "spinning_friction": (0.001, 0.08),
    "ball_restitution": (0.8, 1.0),
    # The ball-ball friction mu(v) = a + b exp(-c v) (Alciatore's a = 0.00995, b = 0.108):
    # it sets the throw, so the object ball's direction after every contact.
    "ball_friction_a": (0.0, 0.05),
    "ball_friction_b": (0.0, 0.3),
}
CUSHION_CONSTANTS: dict[str, dict[str, tuple[float, float]]] = {
    "han2005": {"cushion_restitution": (0.5, 1.0), "cushion_friction": (0.0, 0.6)},
    "mathavan2010": {"cushion_restitution": (0.6, 1.0), "cushion_friction": (0.0, 0.4)},
    "mathavan2010_ev": {
        "cushion_restitution": (0.6, 1.0),
        "cushion_friction": (0.0, 0.4),
        "cushion_restitution_speed": (1.0, 10.0),
    },
}


# The side and height offsets of START_TIPS, / R.
TIP_GRID = (-0.6, -0.3, 0.0, 0.3, 0.6)


class FitError(ValueError):
    """A fit that cannot start (a scene that cannot model the recordings); one line."""


def fitted_constants(scene: Scene) -> dict[str, tuple[float, float]]:
    """The constants a calibration of this scene fits, with their bounds."""
    physics = scene.physics
    if physics.model != "spin":
        raise FitError(
            f'{scene.source}: physics.model = "{physics.model}": expected "spin" (a '
            "recorded stroke has spin: the fit searches the cue tip's offset)"
        )
    return {**CLOTH_CONSTANTS, **CUSHION_CONSTANTS.get(physics.cushion_model, {})}


def with_constants(scene: Scene, constants: dict[str, float]) -> Scene:
    return replace(scene, physics=replace(scene.physics, **constants))  # type: ignore[arg-type]


@dataclass(frozen=True)
class ShotFit:
    """One shot's fitted stroke, its errors and (from `score`) its outcome, recorded and
    simulated (billiards.fit.outcomes)."""

    shot: Shot
    stroke: Stroke
    errors: Errors
    recorded: Outcome | None = None
    simulated: Outcome | None = None

    @property
    def agreement(self) -> Agreement | None:
        if self.recorded is None or self.simulated is None:
            return None
        return agreement(self.recorded, self.simulated)


@dataclass(frozen=True)
class Fit:
    """A table's fitted shots, and its [physics] (the scene's, or the calibrated)."""

    table: Scene
    shots: list[ShotFit]

    def median_rmse(self) -> tuple[float, float, float]:
        """Median over shots of the whole-shot, the first-4-s and the weighted
        first-4-s RMSE (tailuge/billiards' weights, Errors.rmse_early_weighted), m."""
        return (
            float(np.median([fit.errors.rmse for fit in self.shots])),
            float(np.median([fit.errors.rmse_early for fit in self.shots])),
            float(np.median([fit.errors.rmse_early_weighted for fit in self.shots])),
        )

    def outcome_agreement(self) -> AgreementCounts:
        """How many shots' fitted strokes give the recording's outcome (shots without an
        outcome left out)."""
        return count_agreements(fit.agreement for fit in self.shots if fit.agreement is not None)


Progress = Callable[[int], None]


def _no_progress(count: int) -> None:
    pass


def score(
    recordings: Sequence[Recording],
    table: Scene,
    budget: Budget | None = None,
    progress: Progress = _no_progress,
    starts: Sequence[Stroke | None] | None = None,
) -> Fit:
    """Each shot's stroke fitted on the table as it is (its constants kept), the search
    seeded by the recording's first contact (billiards.fit.seeds), and its outcome
    against the recording's."""
    fitted_constants(table)  # the checks: a table that can model a stroke
    budget = budget or Budget()
    fits = []
    for index, recording in enumerate(recordings):
        shot = prepare(recording)
        start = starts[index] if starts is not None else None
        stroke, errors = fit_stroke(
            table, shot, budget, start, aimed_strokes(table, shot), outcome_check(table, shot)
        )
        fits.append(ShotFit(shot, stroke, errors, *shot_outcomes(table, shot, stroke)))
        progress(1)
    return Fit(table, fits)


# The tips (side, height) / R a candidate's stroke fits start from, with the speed and
# direction the first frames show (which show no spin): a grid, because a short polish
# from the stroke search's five (GUESS_TIPS) misses a stroke with both side and height
# (a synthetic shot struck at (0.3, 0.3): 36 mm from its recording after 4 rounds,
# against 1.5 mm from this grid's nearest).
START_TIPS = tuple((side, height) for side in TIP_GRID for height in TIP_GRID)


def kinematic_starts(shot: Shot) -> list[Stroke]:
    """Where every candidate's fit of this shot's stroke starts: the cue ball's speed and
    direction as its first recorded positions show them (Shot.guess), with each of
    START_TIPS. The same whatever the table's constants."""
    guess = shot.guess
    return [Stroke.of((guess.speed, guess.direction, side, height)) for side, height in START_TIPS]


def fit_trial_strokes(
    table: Scene, shots: Sequence[Shot], starts: Sequence[Sequence[Stroke]], budget: Budget
) -> tuple[list[Stroke], list[Errors]]:
    """A candidate's strokes: for each shot the best budget.starts of its `starts` on
    this table (one batch for every shot), each polished budget.trial_polish rounds (one
    polish for all), and the best of those kept."""
    jobs = [
        (shot, stroke) for shot, options in zip(shots, starts, strict=True) for stroke in options
    ]
    errors, _ = simulate_strokes(table, jobs)
    keep = max(budget.starts, 1)
    chosen: list[tuple[int, Stroke]] = []
    at = 0
    for index, options in enumerate(starts):
        losses = [error.loss(budget) for error in errors[at : at + len(options)]]
        chosen += [(index, options[k]) for k in np.argsort(losses)[:keep]]
        at += len(options)
    polished, polished_errors = polish_strokes(
        table,
        [shots[index] for index, _ in chosen],
        [stroke for _, stroke in chosen],
        budget.trial_polish,
        budget,
    )
    best: dict[int, tuple[Stroke, Errors]] = {}
    for (index, _), stroke, error in zip(chosen, polished, polished_errors, strict=True):
        if index not in best or error.loss(budget) < best[index][1].loss(budget):
            best[index] = (stroke, error)
    return [best[k][0] for k in range(len(shots))], [best[k][1] for k in range(len(shots))]


def calibrate(
    recordings: Sequence[Recording],
    table: Scene,
    budget: Budget | None = None,
    progress: Progress = _no_progress,
    constants: Sequence[str] | None = None,
    refit: bool = True,
) -> Fit:
    """The table's constants (fitted_constants, or only the named ones) that, with
    every shot's stroke fitted, match the recordings best (least mean whole-shot RMSE);
    returns the shots' fits on the calibrated table (none unless `refit`: a
    cross-validation needs only the table). The trials use at most budget.trial_shots
    of the shots, each trial fitting their strokes from the same kinematic estimate
    (kinematic_starts). Progress counts shot fits and constant trials."""
    from scipy.optimize import minimize

    budget = budget or Budget()
    names, low, high = _fitted_ranges(table, constants)
    span = high - low

    def constants_at(unit: np.ndarray) -> dict[str, float]:
        values = low + span * np.clip(unit, 0.0, 1.0)
        # As table.toml writes them (6 digits): the file reproduces the fit exactly.
        return {name: float(f"{value:.6g}") for name, value in zip(names, values, strict=True)}

    shots = [prepare(recordings[k]) for k in _trial_shots(len(recordings), budget)]
    starts = [kinematic_starts(shot) for shot in shots]  # every candidate's, the same
    unit = np.clip(
        (np.array([getattr(table.physics, name) for name in names]) - low) / span, 0.0, 1.0
    )
    best = (math.inf, unit)

    def trial(unit: np.ndarray) -> float:
        nonlocal best
        trial_table = with_constants(table, constants_at(unit))
        strokes, errors = fit_trial_strokes(trial_table, shots, starts, budget)
        loss = _trial_loss(
            [
                ShotFit(shot, stroke, error)
                for shot, stroke, error in zip(shots, strokes, errors, strict=True)
            ],
            budget,
        )
        if loss < best[0]:
            best = (loss, np.clip(unit, 0.0, 1.0))
        progress(1)
        return loss

    passes = max(budget.passes, 1)
    for _ in range(passes):  # each pass a Nelder-Mead from the best so far, simplex anew
        start = best[1]
        simplex = np.vstack([start, *(_stepped(start, axis) for axis in range(len(names)))])
        minimize(
            trial,
            start,
            method="Nelder-Mead",
            bounds=[(0.0, 1.0)] * len(names),
            options={
                "maxfev": max(budget.evaluations // passes, len(names) + 1),
                "initial_simplex": simplex,
                "xatol": 1e-3,
                "fatol": 1e-5,
            },
        )
    table_now = with_constants(table, constants_at(best[1]))
    if not refit:
        return Fit(table_now, [])
    # Every shot's stroke fitted afresh on the calibrated table, from the first frames' estimate.
    return score(recordings, table_now, budget, progress)


def _fitted_ranges(
    table: Scene, constants: Sequence[str] | None
) -> tuple[list[str], np.ndarray, np.ndarray]:
    """The constants to fit (fitted_constants', or the named ones), their low and high bounds."""
    bounds = fitted_constants(table)
    for name in constants or ():
        if name not in bounds:
            raise FitError(f"{name}: not a constant this table fits ({', '.join(bounds)})")
    names = list(constants or bounds)
    return (
        names,
        np.array([bounds[name][0] for name in names]),
        np.array([bounds[name][1] for name in names]),
    )


def _trial_shots(count: int, budget: Budget) -> list[int]:
    """The trials' shots: at most budget.trial_shots, spread evenly over the recordings."""
    step = max(count / max(budget.trial_shots, 1), 1.0)
    return sorted({int(k * step) for k in range(min(count, budget.trial_shots))})


# A shot whose end chaos has taken says little about the constants: its whole-shot
# RMSE counts at most this much in a trial's loss.
TRIAL_CAP = 0.3  # m


def _trial_loss(fits: Sequence[ShotFit], budget: Budget) -> float:
    """A constants trial's loss: the mean over shots of the whole-shot RMSE, capped (in
    window "4s", of the weighted first-4-s RMSE)."""
    if budget.window == "4s":
        return float(np.mean([min(fit.errors.rmse_early_weighted, TRIAL_CAP) for fit in fits]))
    return float(np.mean([min(fit.errors.rmse, TRIAL_CAP) for fit in fits]))


def _stepped(unit: np.ndarray, axis: int) -> np.ndarray:
    """A simplex vertex: one constant moved a tenth of its range (inwards at a bound)."""
    moved = unit.copy()
    moved[axis] += 0.1 if unit[axis] <= 0.9 else -0.1
    return moved


def calibration_steps(count: int, budget: Budget) -> int:
    """How many progress steps calibrate takes (about: Nelder-Mead may pass its
    evaluations by a few): shot fits and trials."""
    passes = max(budget.passes, 1)
    return count + passes * max(budget.evaluations // passes, 7)


def physics_toml(physics: Physics) -> str:
    """A [physics] table of every constant (the fitted ones and the scene's own)."""
    lines = ["[physics]"]
    for name, value in vars(physics).items():
        lines.append(f"{name} = {_toml_value(value)}")
    return "\n".join(lines) + "\n"


def _toml_value(value: Any) -> str:
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(float(f"{value:.6g}")) if math.isfinite(value) else repr(value)
    return repr(value)
