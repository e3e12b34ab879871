"""Fitting the model to recorded shots (issue 31; docs/validation.md).

`fit_shot` finds one recorded shot's stroke on a table; `score` fits every shot's
stroke with the table's constants kept; `calibrate` fits the table's constants too.
`read_recordings` reads the recordings (train.json's format, tailuge/billiards'
trajectories.json, or a CSV of shot, ball, t, x, y). Needs the `fit` extra (SciPy).
"""

from __future__ import annotations

from billiards.fit.outcomes import Agreement, Outcome, shot_outcomes
from billiards.fit.recordings import Recording, RecordingError, Track, read_recordings
from billiards.fit.seeds import aimed_strokes, outcome_check
from billiards.fit.shots import Budget, Errors, Shot, Stroke, fit_stroke, prepare
from billiards.fit.table import Fit, FitError, ShotFit, calibrate, score
from billiards.scene.reader import Scene


def fit_shot(recording: Recording, table: Scene, budget: Budget | None = None) -> ShotFit:
    """One recorded shot's stroke on the table (its constants kept), its errors and its
    outcome against the recording's."""
    shot = prepare(recording)
    stroke, errors = fit_stroke(
        table,
        shot,
        budget or Budget(),
        seeds=aimed_strokes(table, shot),
        agrees=outcome_check(table, shot),
    )
    return ShotFit(shot, stroke, errors, *shot_outcomes(table, shot, stroke))


__all__ = [
    "Agreement",
    "Budget",
    "Errors",
    "Fit",
    "FitError",
    "Outcome",
    "Recording",
    "RecordingError",
    "Shot",
    "ShotFit",
    "Stroke",
    "Track",
    "calibrate",
    "fit_shot",
    "read_recordings",
    "score",
]
