"""The fitter judged on shots it never saw: k-fold cross-validation (issue 31).

For each cushion law and each fold, calibrate the table's constants on the other
folds' shots (calibrate), then fit only the strokes of the fold's shots on that table
(score) and keep their errors: every shot is scored by the one fold that never saw it.
Beside the median over every shot, `fold_spread` gives each fold's own median and their
spread: how much the figure depends on the split. scripts/validation_tracks.py runs the
folds in parallel and prints the report.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from billiards.fit.recordings import Recording
from billiards.fit.shots import Budget, Window
from billiards.fit.table import Fit, ShotFit, calibrate, fitted_constants, score
from billiards.scene.reader import Scene, read_scene_tables, scene_from_dict

# Where every calibration starts: tailuge/billiards' champion cloth and Han 2005
# cushion, not the shipped scene's constants (those were calibrated on every shot, the
# held-out ones included). Other laws start from their own defaults.
START = {
    "sliding_friction": 0.13,
    "rolling_friction": 0.0055,
    "spinning_friction": 0.0127,
    "ball_restitution": 0.94,
}
START_CUSHION = {"han2005": {"cushion_restitution": 0.86, "cushion_friction": 0.17}}


@dataclass(frozen=True)
class FoldSpread:
    """A held-out figure's median over each fold's shots, by fold, and their spread."""

    medians: dict[int, float]

    @property
    def low(self) -> float:
        return min(self.medians.values())

    @property
    def high(self) -> float:
        return max(self.medians.values())

    def quartiles(self) -> tuple[float, float]:
        """The folds' medians' first and third quartiles (numpy's linear interpolation)."""
        first, third = np.percentile(list(self.medians.values()), [25, 75])
        return float(first), float(third)

    def line(self) -> str:
        """`11.2 | 12.0 | 13.1 (min 11.2, max 13.1, IQR 11.6-12.6)`: fold 0's first."""
        first, third = self.quartiles()
        each = " | ".join(f"{self.medians[fold]:.2f}" for fold in sorted(self.medians))
        return f"{each} (min {self.low:.2f}, max {self.high:.2f}, IQR {first:.2f}-{third:.2f})"


def fold_spread(rows: list[dict[str, Any]], model: str, window: str, column: str) -> FoldSpread:
    """Each fold's median of `column` (a held-out row's figure, such as rmse_cm) over
    its shots of this law and window."""
    by_fold: dict[int, list[float]] = {}
    for row in rows:
        if row["model"] == model and row["window"] == window and int(row["fold"]) >= 0:
            by_fold.setdefault(int(row["fold"]), []).append(float(row[column]))
    return FoldSpread({fold: float(np.median(values)) for fold, values in by_fold.items()})


def folds_of(recordings: list[Recording], folds: int, seed: int = 31) -> list[int]:
    """Each shot's fold: a seeded shuffle dealt round (the same split every run)."""
    order = np.random.default_rng(seed).permutation(len(recordings))
    fold = [0] * len(recordings)
    for place, index in enumerate(order):
        fold[int(index)] = place % folds
    return fold


def model_scene(scene: str, model: str, start: bool = False) -> Scene:
    """The scene with this cushion law: its own constants if the scene names the law,
    else the law's defaults (the reader's: Mathavan's e_e = 0.98, mu_w = 0.14...); with
    `start`, the calibration's starting constants (START) instead."""
    tables, source = read_scene_tables(scene)
    physics = tables.setdefault("physics", {})
    if physics.get("cushion_model") != model or start:
        physics["cushion_model"] = model
        for key in ("cushion_restitution", "cushion_friction", "cushion_restitution_speed"):
            physics.pop(key, None)
    if start:
        for key in ("ball_friction_a", "ball_friction_b", "ball_friction_c"):
            physics.pop(key, None)  # Alciatore's, the reader's defaults
        physics.update(START)
        physics.update(START_CUSHION.get(model, {}))
    return scene_from_dict(tables, source)


@dataclass(frozen=True)
class FoldJob:
    """One fold of one law: calibrate on `train` (unless `fixed`), score `test` once a
    window. Fold -1 is the calibration on every shot, whose fit is kept."""

    model: str
    fold: int
    scene: str
    budget: Budget
    fixed: bool
    windows: tuple[Window, ...]
    train: list[Recording]
    test: list[Recording]


@dataclass(frozen=True)
class FoldOutcome:
    fit: Fit | None  # fold -1's calibration on every shot, with every shot's fit
    rows: list[dict[str, Any]]  # a held-out shot's errors (cm) and CPU a window
    calibration_cpu_s: float
    constants: dict[str, float]  # the calibrated table's fitted constants


def fold_jobs(
    recordings: list[Recording], folds: int, models: list[str], base: FoldJob
) -> list[FoldJob]:
    """Every law's folds, each training on the others' shots (`base` gives the rest)."""
    fold_of = folds_of(recordings, folds)
    return [
        replace(
            base,
            model=model,
            fold=fold,
            train=[r for r, f in zip(recordings, fold_of, strict=True) if f != fold],
            test=[r for r, f in zip(recordings, fold_of, strict=True) if f == fold],
        )
        for model in models
        for fold in range(folds)
    ]


def run_fold(job: FoldJob) -> FoldOutcome:
    """Calibrate on the training shots (unless fixed), score the held-out ones; CPU."""
    table = model_scene(job.scene, job.model, start=not job.fixed)
    started = time.process_time()
    if job.fixed:
        calibrated = Fit(table, [])
    else:
        calibrated = calibrate(job.train, table, job.budget, refit=job.fold < 0)
    calibration_cpu = time.process_time() - started
    rows = []
    for window in job.windows:  # each held-out shot's stroke fitted once a window
        for recording in job.test:
            started = time.process_time()
            fit = score([recording], calibrated.table, replace(job.budget, window=window))
            cpu = time.process_time() - started
            rows.append(_row(job, window, fit.shots[0], cpu))
    physics = calibrated.table.physics
    return FoldOutcome(
        fit=calibrated if job.fold < 0 else None,
        rows=rows,
        calibration_cpu_s=calibration_cpu,
        constants={name: getattr(physics, name) for name in fitted_constants(table)},
    )


def _row(job: FoldJob, window: Window, shot: ShotFit, cpu: float) -> dict[str, Any]:
    """A held-out shot's row: its errors (cm), its outcome against the recording's
    (billiards.fit.outcomes: both described, and which parts agree) and its CPU (s)."""
    agreement = shot.agreement
    assert agreement is not None and shot.recorded and shot.simulated  # score gives them
    return {
        "model": job.model,
        "window": window,
        "fold": job.fold,
        "id": shot.shot.id,
        "rmse_cm": shot.errors.rmse * 100,
        "rmse_4s_cm": shot.errors.rmse_early * 100,
        "rmse_4s_weighted_cm": shot.errors.rmse_early_weighted * 100,
        "stroke_cpu_s": cpu,
        "outcome_recorded": shot.recorded.describe(),
        "outcome_simulated": shot.simulated.describe(),
        "first_agrees": int(agreement.first),
        "moved_agrees": int(agreement.moved),
        "point_agrees": "" if agreement.point is None else int(agreement.point),
        "outcome_agrees": int(agreement.sequence),
    }
