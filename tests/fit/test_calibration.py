"""A calibration not anchored on one seed (issue 44, item 4): every candidate set of
table constants fits its strokes from the same kinematic estimate, the one the
recordings' first frames give, never from another candidate's fitted strokes; and the
cross-validation's report gives each fold's median beside the median over all shots."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np
import pytest

pytest.importorskip("scipy")

import billiards.fit.table as table_module
from billiards.fit import calibrate
from billiards.fit.cross_validation import FoldJob, FoldOutcome, fold_spread
from billiards.fit.recordings import read_recordings
from billiards.fit.shots import Errors, Shot, Stroke, prepare
from billiards.fit.table import START_TIPS, calibration_steps, kinematic_starts
from billiards.scene.reader import Scene
from scripts.validation_tracks import print_report
from tests.fit.test_data import needs_recordings, project_recordings
from tests.test_fit import BUDGET, synthetic, table

# The smallest calibration that tries a few candidates.
TINY = replace(BUDGET, evaluations=8, passes=2, trial_polish=1, starts=1)


def test_every_candidate_fits_its_strokes_from_the_same_first_frames_estimate(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    recordings = [synthetic(table(), index, duration=2.0) for index in range(2)]
    tried: list[tuple[float, list[list[Stroke]]]] = []
    fit_trial_strokes = table_module.fit_trial_strokes

    def spy(
        trial: Scene, shots: list[Shot], starts: list[list[Stroke]], budget: Any
    ) -> tuple[list[Stroke], list[Errors]]:
        tried.append((trial.physics.rolling_friction, [list(options) for options in starts]))
        return fit_trial_strokes(trial, shots, starts, budget)

    monkeypatch.setattr(table_module, "fit_trial_strokes", spy)
    steps: list[int] = []
    calibrate(recordings, table(), TINY, steps.append, ("rolling_friction",), refit=False)
    # Several candidates, at different constants, over two passes...
    assert len({constant for constant, _ in tried}) >= 3
    assert len(steps) == len(tried) <= calibration_steps(len(recordings), TINY)
    # ... every one from the very same strokes: the recordings' first frames' estimate.
    expected = [kinematic_starts(prepare(recording)) for recording in recordings]
    assert all(starts == expected for _, starts in tried)


def test_the_kinematic_estimate_is_the_first_frames_velocity_with_every_start_tip() -> None:
    recording = synthetic(table(), 0, duration=2.0)
    shot = prepare(recording)
    starts = kinematic_starts(shot)
    assert [(s.speed, s.direction) for s in starts] == [
        (shot.guess.speed, shot.guess.direction)
    ] * len(START_TIPS)
    assert {(s.side, s.height) for s in starts} >= {(0.0, 0.0), (0.3, 0.3), (-0.6, 0.0)}
    assert all(np.hypot(s.side, s.height) <= 0.8 + 1e-12 for s in starts)  # on the ball
    # The first frames show the stroke that made them: synthetic shot 0 is struck at
    # 2.2 m/s, 18 degrees.
    assert shot.guess.direction == pytest.approx(18.0, abs=1.0)
    assert shot.guess.speed == pytest.approx(2.2, rel=0.1)


def held_out_rows(medians: dict[int, list[float]]) -> list[dict[str, Any]]:
    return [
        {
            "model": "han2005",
            "window": "shot",
            "fold": fold,
            "id": f"{fold}-{k}",
            "rmse_cm": value,
            "rmse_4s_cm": value / 2,
            "rmse_4s_weighted_cm": value / 4,
            "stroke_cpu_s": 0.5,
            "outcome_recorded": "",
            "outcome_simulated": "",
            "first_agrees": 1,
            "moved_agrees": 1,
            "point_agrees": "",
            "outcome_agrees": 1,
        }
        for fold, values in medians.items()
        for k, value in enumerate(values)
    ]


def test_the_fold_spread_is_each_fold_s_median_and_their_range() -> None:
    rows = held_out_rows({0: [10.0, 12.0, 30.0], 1: [8.0, 9.0], 2: [14.0]})
    spread = fold_spread(rows, "han2005", "shot", "rmse_cm")
    assert spread.medians == {0: 12.0, 1: 8.5, 2: 14.0}
    assert (spread.low, spread.high) == (8.5, 14.0)
    assert spread.quartiles() == (10.25, 13.0)
    assert spread.line() == "12.00 | 8.50 | 14.00 (min 8.50, max 14.00, IQR 10.25-13.00)"
    assert fold_spread(rows, "mirror", "shot", "rmse_cm").medians == {}


def test_the_cross_validation_report_lists_every_fold_s_median(
    capsys: pytest.CaptureFixture[str],
) -> None:
    rows = held_out_rows({0: [10.0, 12.0, 30.0], 1: [8.0, 9.0]})
    jobs, outcomes = [], []
    for fold in (0, 1):
        jobs.append(
            FoldJob(
                model="han2005",
                fold=fold,
                scene="three_cushion",
                budget=BUDGET,
                fixed=False,
                windows=("shot",),
                train=[],
                test=[],
            )
        )
        mine = [row for row in rows if row["fold"] == fold]
        outcomes.append(
            FoldOutcome(
                fit=None, rows=mine, calibration_cpu_s=1.0, constants={"rolling_friction": 0.01}
            )
        )
    print_report(["han2005"], ["shot"], jobs, outcomes)
    out = capsys.readouterr().out
    assert "han2005 shot, whole shot: 12.00 | 8.50 (min 8.50, max 12.00," in out
    assert "han2005 shot, first 4 s: 6.00 | 4.25 (min 4.25, max 6.00," in out
    assert "han2005 shot, first 4 s weighted: 3.00 | 2.12" in out


@needs_recordings
def test_every_recorded_shot_has_a_kinematic_estimate_a_cue_can_play() -> None:
    path = project_recordings()
    assert path is not None
    for recording in read_recordings(path):
        starts = kinematic_starts(prepare(recording))
        speeds = {start.speed for start in starts}
        assert len(speeds) == 1 and 0.1 < speeds.pop() < 10.0, recording.id  # m/s
        assert all(np.isfinite(start.direction) for start in starts), recording.id
