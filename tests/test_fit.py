"""Fitting recorded shots (billiards.fit): the fitter finds the strokes and constants of
synthetic recordings that the project simulates itself (sampled as the real ones are,
at 50 Hz, with 1 mm of noise), fails on a wrong constant, and refuses bad recordings
with one line (exit 2)."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pytest

pytest.importorskip("scipy")

from billiards.fit import Budget, Recording, Stroke, Track, calibrate, fit_shot, score, shots
from billiards.fit.__main__ import main
from billiards.fit.outcomes import agreement, shot_outcomes
from billiards.fit.recordings import TAILUGE_SCALE, FloatArray, read_recordings
from billiards.fit.shots import (
    Errors,
    fit_stroke,
    prepare,
    residuals,
    runs_errors,
    shot_errors,
    shot_run,
    shot_scene,
)
from billiards.fit.table import with_constants
from billiards.physics.engine.packaging import Run, started
from billiards.scene.reader import Scene, load_scene
from billiards.simulation import prepare_runs, simulate_runs, simulate_scene
from tests.commands import signalled_midway

NOISE = 0.001  # m, the recordings' resolution
SAMPLE = 0.02  # s, their sampling
# Test budgets: small, so the file runs in seconds. A calibration trial polishes its
# strokes 8 rounds from the first frames' estimate (issue 44; Budget.trial_polish).
BUDGET = Budget(population=5, generations=6, polish=8, evaluations=14, passes=1, trial_polish=8)

# Three synthetic shots: (cue, ball 2, ball 3) starting centres, and the stroke.
SHOTS = [
    (((0.70, 0.50), (1.60, 0.80), (2.30, 0.40)), Stroke(2.2, 18.0, 0.3, 0.3)),
    (((2.20, 1.00), (1.10, 0.60), (0.40, 1.10)), Stroke(1.8, 196.0, -0.2, 0.1)),
    (((1.40, 0.20), (1.60, 1.10), (0.50, 0.70)), Stroke(2.0, 70.0, 0.1, -0.2)),
]


def table(**constants: float) -> Scene:
    scene = load_scene("three_cushion")
    return with_constants(scene, constants) if constants else scene


def synthetic(scene: Scene, index: int, seed: int = 0, duration: float = 6.0) -> Recording:
    """Shot `index` simulated on `scene`, each ball sampled every SAMPLE s for `duration`
    s with NOISE of Gaussian noise on each coordinate."""
    positions, stroke = SHOTS[index]
    return recorded(scene, positions, stroke, seed + index, duration, str(index))


def recorded(
    scene: Scene,
    positions: tuple[tuple[float, float], ...],
    stroke: Stroke,
    seed: int,
    duration: float,
    name: str,
) -> Recording:
    """The balls at `positions`, the cue ball (the first) struck with `stroke`, sampled
    as `synthetic` says."""
    rng = np.random.default_rng(seed)
    tracks = {
        ball: Track(np.array([0.0]), np.array([position]))
        for ball, position in zip("123", positions, strict=True)
    }
    shot = prepare(Recording(name, tracks))
    result = simulate_scene(shot_scene(scene, shot, stroke, slack=duration + 1))
    times = np.arange(0.0, duration + SAMPLE / 2, SAMPLE)
    sampled = result.positions_at(times)
    balls = {}
    for column, ball in enumerate("123"):
        noisy = sampled[:, column] + rng.normal(0.0, NOISE, (len(times), 2))
        noisy[0] = positions[column]  # where it was placed: its first sample
        balls[ball] = Track(times, noisy)
    return Recording(name, balls)


@pytest.mark.long
def test_a_stroke_is_recovered_from_its_synthetic_recording() -> None:
    scene = table()
    for index in (0, 1):
        fit = fit_shot(synthetic(scene, index), scene, BUDGET)
        true = SHOTS[index][1]
        # Tolerances: the speed to 1%, the direction to 0.2 degrees, the tip to 0.1 R;
        # the samples then within about the noise (its RMS over two coordinates: 1.4 mm).
        assert fit.stroke.speed == pytest.approx(true.speed, rel=0.01), fit.stroke
        turn = (fit.stroke.direction - true.direction + 180) % 360 - 180
        assert abs(turn) < 0.2, fit.stroke
        assert fit.stroke.side == pytest.approx(true.side, abs=0.1), fit.stroke
        assert fit.stroke.height == pytest.approx(true.height, abs=0.1), fit.stroke
        assert fit.errors.rmse < 2.5 * NOISE, fit.errors


# A stroke fit of synthetic shot 0 at BUDGET on the three_cushion table: its stroke
# (speed, direction, side, height) and squared-error sums, as the fitter found them when
# every run was made into a SimulationResult and sampled by positions_at (8767390).
FITTED_STROKE = ("0x1.18e7f1aa0d26ap+1", "0x1.200010d1a6b04p+4", "0x1.3401fbe718803p-2",
                 "0x1.36b99e57a1c17p-2")  # fmt: skip
FITTED_SQUARES = ("0x1.d70fc194c2ffcp-10", "0x1.2fd0504c990c4p-10")


def test_a_stroke_fit_from_sampled_runs_is_the_fit_from_their_results(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The fitter samples a shot's runs from the compiled loop's logs, its setup packed
    once and each stroke's start set in place (simulation.sample_starts), without making
    a setup or a result a run: the same fit, bit for bit, as through each run's own setup
    (packaging.started), simulate_runs and positions_at, and as pinned."""
    scene = table()
    shot = prepare(synthetic(scene, 0))
    stroke, errors = fit_stroke(scene, shot, BUDGET)
    assert tuple(value.hex() for value in stroke.vector()) == FITTED_STROKE
    assert (errors.squares.hex(), errors.early_squares.hex()) == FITTED_SQUARES

    def from_results(
        run: Run, velocities: np.ndarray, spins: np.ndarray | None, at: FloatArray, source: str
    ) -> list[FloatArray | Exception]:
        runs = [
            started(run, velocities[k], None if spins is None else spins[k])
            for k in range(len(velocities))
        ]
        results = simulate_runs(runs, [source] * len(runs))
        return [item if isinstance(item, Exception) else item.positions_at(at) for item in results]

    monkeypatch.setattr(shots, "sample_starts", from_results)
    assert fit_stroke(scene, shot, BUDGET) == (stroke, errors)


def test_a_struck_shot_run_is_its_scenes_run_bit_for_bit() -> None:
    """A stroke fit makes each shot's run once and sets only the cue ball's start a stroke
    (shots.ShotRun): every number of it is what the stroke's own scene makes."""
    scene = table()
    shot = prepare(synthetic(scene, 1))
    strokes = [Stroke(1.7, 195.3, -0.2, 0.1), Stroke(2.9, -12.0, 0.0, 0.0), Stroke(0.4, 7.0, 0.8)]
    for stroke in strokes:
        struck = shot_run(scene, shot).struck(stroke)
        (made,) = prepare_runs([shot_scene(scene, shot, stroke)])
        assert not isinstance(struck, Exception) and not isinstance(made, Exception)
        assert struck[1:] == made[1:]
        for name, value in vars(made[0]).items():
            mine = getattr(struck[0], name)
            if isinstance(value, np.ndarray):
                assert mine.dtype == value.dtype and mine.tobytes() == value.tobytes(), name
            else:
                assert mine == value, name
    assert shot_run(scene, shot) is shot_run(scene, shot)  # made once


def test_the_stroke_search_prefers_a_close_stroke_whose_outcome_agrees_more() -> None:
    """fit_stroke's `agrees` ranks the polished strokes within budget.agreeing_loss of the
    best: the best of those that agree the most is taken (the best of all when none
    agrees more than it)."""
    scene = table()
    shot = prepare(synthetic(scene, 0))
    best, best_errors = fit_stroke(scene, shot, BUDGET)
    asked: list[list[Stroke]] = []

    def last_agrees(strokes: list[Stroke]) -> list[int]:
        asked.append(strokes)
        return [1] * (len(strokes) - 1) + [2]

    chosen, errors = fit_stroke(scene, shot, BUDGET, agrees=last_agrees)
    (within,) = asked
    assert within[0] == best and chosen == within[-1]
    assert errors.loss(BUDGET) <= BUDGET.agreeing_loss * best_errors.loss(BUDGET)
    assert fit_stroke(scene, shot, BUDGET, agrees=lambda s: [0] * len(s)) == (best, best_errors)


def test_many_runs_errors_at_once_are_each_runs_errors_alone() -> None:
    """runs_errors sums each run's samples as one run's sums them alone (numpy's pairwise
    sum of a row), bit for bit: a fit's losses do not depend on its batches."""
    shot = prepare(synthetic(table(), 0))
    rng = np.random.default_rng(3)

    def alone(positions: np.ndarray) -> Errors:
        squares = early = weighted = weights = 0.0
        for column, (rows, recorded, within, weight) in enumerate(
            zip(shot.samples, shot.recorded, shot.early, shot.weights, strict=True)
        ):
            distance = positions[rows, column] - recorded
            square = distance[:, 0] * distance[:, 0] + distance[:, 1] * distance[:, 1]
            squares += float(square.sum())
            early += float(square[within].sum())
            weighted += float((weight[within] * square[within]).sum())
            weights += float(weight[within].sum())
        return Errors(squares, 0, early, 0, weighted, weights)

    for runs in (1, 2, 7, 40):
        positions = rng.uniform(0.0, 2.0, (runs, len(shot.times), len(shot.order), 2))
        for run, errors in enumerate(runs_errors(shot, positions)):
            assert replace(errors, count=0, early_count=0) == alone(positions[run])


def test_a_synthetic_recording_shows_the_contacts_of_the_run_that_made_it() -> None:
    # The recording is sampled as the real ones are (50 Hz, 1 mm of noise): the outcome
    # read from its tracks is the run's, read from its events.
    scene = table()
    struck = []
    for index in range(len(SHOTS)):
        recording = synthetic(scene, index, duration=8.0)
        shot = prepare(recording)
        recorded, simulated = shot_outcomes(scene, shot, SHOTS[index][1])
        if recorded.first is None:
            assert simulated.first is None
            continue
        struck.append(index)
        assert (recorded.first, recorded.second, recorded.moved, recorded.cushions) == (
            simulated.first,
            simulated.second,
            simulated.moved,
            simulated.cushions,
        ), (index, recorded, simulated)
        # Within two samples of the contact's time (the start is extrapolated too).
        assert recorded.first_time == pytest.approx(simulated.first_time, abs=0.04)
        assert agreement(recorded, simulated).sequence
    assert struck == [0]  # 1 and 2 meet only cushions in 8 s (3 each), read alike


@pytest.mark.long
def test_a_thin_first_contact_missed_by_the_plain_search_is_found_from_the_recording() -> None:
    # The cue ball stands 1.5 cm from ball "2" and cuts it thinly (85% of 2R off its
    # centre): its first samples already show it after the contact, turned by about
    # 30 degrees, and the search about them never reaches the ball. The search seeded
    # by the recording's first contact (billiards.fit.seeds) aims at it and finds the
    # stroke.
    scene = table()
    heading = math.radians(170.0)
    along, across = (math.cos(heading), math.sin(heading)), (-math.sin(heading), math.cos(heading))
    radius = scene.radius
    behind = math.sqrt((2 * radius) ** 2 - (0.85 * 2 * radius) ** 2) + 0.015
    cue = (1.0, 0.7)
    x, y = (
        c + behind * a - 0.85 * 2 * radius * b for c, a, b in zip(cue, along, across, strict=True)
    )
    ball = (x, y)
    stroke = Stroke(1.8, 170.0, 0.1, 0.2)
    recording = recorded(scene, (cue, ball, (2.3, 0.4)), stroke, 0, 6.0, "thin")
    shot = prepare(recording)
    turned = (shot.guess.direction - stroke.direction + 180) % 360 - 180
    assert abs(turned) > 20, shot.guess  # what the first samples show

    plain, _ = fit_stroke(scene, shot, BUDGET)
    recorded_outcome, plain_outcome = shot_outcomes(scene, shot, plain)
    assert recorded_outcome.first == "2"
    assert not agreement(recorded_outcome, plain_outcome).first, plain_outcome

    fit = fit_shot(recording, scene, BUDGET)
    assert fit.agreement is not None and fit.agreement.sequence, fit.simulated
    turn = (fit.stroke.direction - stroke.direction + 180) % 360 - 180
    assert abs(turn) < 0.5 and fit.errors.rmse < 2.5 * NOISE, (fit.stroke, fit.errors.rmse)


@pytest.mark.long
def test_a_wrong_constant_leaves_an_error_no_stroke_can_remove() -> None:
    right = table()
    wrong = table(rolling_friction=1.5 * right.physics.rolling_friction)
    recordings = [synthetic(right, 0), synthetic(right, 2)]
    on_right = score(recordings, right, BUDGET)
    on_wrong = score(recordings, wrong, BUDGET)
    for good, bad in zip(on_right.shots, on_wrong.shots, strict=True):
        assert good.errors.rmse < 2.5 * NOISE
        assert bad.errors.rmse > 4 * good.errors.rmse


@pytest.mark.long
def test_calibration_recovers_the_constants_that_made_the_recordings() -> None:
    truth = table(rolling_friction=0.008, cushion_restitution=0.8)
    recordings = [synthetic(truth, index) for index in range(2)]
    start = table(rolling_friction=0.0055, cushion_restitution=0.9)
    fit = calibrate(
        recordings,
        start,
        replace(BUDGET, evaluations=32, passes=2),
        constants=("rolling_friction", "cushion_restitution"),
    )
    physics = fit.table.physics
    # Tolerance: 5% of each constant, and every shot back within about 3 times the
    # noise's RMS (1.4 mm).
    assert physics.rolling_friction == pytest.approx(0.008, rel=0.05), physics
    assert physics.cushion_restitution == pytest.approx(0.8, rel=0.05), physics
    assert max(shot.errors.rmse for shot in fit.shots) < 4 * NOISE


@pytest.mark.long
def test_calibration_recovers_the_ball_friction_from_the_throw() -> None:
    # The ball-ball friction sets the throw, so where the object balls go: a table with
    # twice Alciatore's b makes recordings that his b cannot match, and the calibration
    # finds the b back from them.
    truth = table(ball_friction_b=0.216)
    recordings = [synthetic(truth, index) for index in range(2)]
    fit = calibrate(
        recordings, table(), replace(BUDGET, evaluations=12), constants=("ball_friction_b",)
    )
    # Tolerance: 10% of b, and every shot back within about 3 times the noise's RMS.
    assert fit.table.physics.ball_friction_b == pytest.approx(0.216, rel=0.1), fit.table.physics
    assert max(shot.errors.rmse for shot in fit.shots) < 4 * NOISE


# --- reading recordings --------------------------------------------------------------------


def write_json(path: Path, shots: list[dict[str, Any]]) -> Path:
    path.write_text(json.dumps(shots))
    return path


def a_shot(**changes: Any) -> dict[str, Any]:
    balls = {
        "1": {"t": [0, 0.02, 0.04], "x": [0.5, 0.55, 0.6], "y": [0.5, 0.5, 0.5]},
        "2": {"t": [0, 1.0], "x": [1.5, 1.5], "y": [0.7, 0.7]},
        "3": {"t": [0, 1.0], "x": [2.0, 2.0], "y": [0.3, 0.3]},
    }
    balls.update(changes)
    return {"id": 7, "balls": {k: v for k, v in balls.items() if v is not None}}


def test_the_three_formats_read_alike(tmp_path: Path) -> None:
    shot = a_shot()
    plain = read_recordings(write_json(tmp_path / "train.json", [shot]))[0]
    half = (1.42, 0.71)
    tailuge = {
        "id": 7,
        "balls": {
            ball: {
                "t": track["t"],
                "x": [(x - half[0]) * TAILUGE_SCALE[0] for x in track["x"]],
                "y": [(y - half[1]) * TAILUGE_SCALE[1] for y in track["y"]],
            }
            for ball, track in shot["balls"].items()
        },
    }
    centred = read_recordings(write_json(tmp_path / "trajectories.json", [tailuge]))[0]
    rows = ["shot,ball,t,x,y"] + [
        f"7,{ball},{t},{x},{y}"
        for ball, track in shot["balls"].items()
        for t, x, y in zip(track["t"], track["x"], track["y"], strict=True)
    ]
    (tmp_path / "shots.csv").write_text("\n".join(rows) + "\n")
    table_rows = read_recordings(tmp_path / "shots.csv")[0]
    for other in (centred, table_rows):
        assert other.id == plain.id == "7"
        for ball, track in plain.balls.items():
            assert np.allclose(other.balls[ball].xy, track.xy, atol=1e-9)
            assert np.array_equal(other.balls[ball].t, track.t)
    assert plain.cue_ball == "1"


@pytest.mark.parametrize(
    ("shot", "expected"),
    [
        (a_shot(**{"3": None}), "2 balls recorded"),
        (a_shot(**{"2": {"t": [0, 1.0, 0.5], "x": [1.5] * 3, "y": [0.7] * 3}}), "never go back"),
        (a_shot(**{"3": {"t": [0, 1.0], "x": [2.0, 2.9], "y": [0.3, 0.3]}}), "off the table"),
    ],
    ids=["a ball missing", "times going back", "off the table"],
)
def test_a_bad_recording_is_one_line_and_exit_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], shot: dict[str, Any], expected: str
) -> None:
    tracks = write_json(tmp_path / "bad.json", [a_shot(), shot])
    status = main(["score", str(tracks), "-o", str(tmp_path / "out"), "--quiet"])
    error = capsys.readouterr().err
    assert status == 2
    assert error.count("\n") == 1 and expected in error and "shot 7" in error, error
    assert not (tmp_path / "out").exists()


def test_score_writes_its_table_of_shots(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    scene = table()
    shots = [synthetic(scene, 0, duration=3.0)]
    data = [
        {
            "id": 5,
            "balls": {
                ball: {
                    "t": track.t.tolist(),
                    "x": track.xy[:, 0].tolist(),
                    "y": track.xy[:, 1].tolist(),
                }
                for ball, track in shots[0].balls.items()
            },
        }
    ]
    tracks = write_json(tmp_path / "synthetic.json", data)
    out = tmp_path / "out"
    args = ["--generations", "3", "--no-pictures"]
    assert main(["score", str(tracks), "-o", str(out), *args]) == 0
    summary = capsys.readouterr().err.splitlines()[-1]
    assert (
        "median RMSE" in summary
        and "outcome as recorded: first object ball 100% (1 of 1)" in summary
    )
    header, row = (out / "shots.csv").read_text().splitlines()
    assert header.startswith("id,cue_ball,rmse_cm,rmse_4s_cm,rmse_4s_weighted_cm,speed,direction")
    values = dict(zip(header.split(","), row.split(","), strict=True))
    assert values["id"] == "5" and values["cue_ball"] == "1"
    # Over 3 s a little more speed and less top spin fit as well (the stroke's own
    # recovery is tested above): the row holds the fit's error and its direction.
    assert float(values["rmse_cm"]) < 1.0
    assert math.isclose(float(values["direction"]), SHOTS[0][1].direction, abs_tol=0.5)
    # Its outcome: the cue ball strikes "2" (about 0.43 s), not "3", in 3 s, as recorded.
    assert values["first_ball_recorded"] == values["first_ball_simulated"] == "2"
    assert values["moved_recorded"] == values["moved_simulated"] == "2"
    assert values["point_recorded"] == values["point_simulated"] == "0"
    assert values["outcome_agrees"] == "1"
    # Again without --force: refused before any work, the file kept.
    assert main(["score", str(tracks), "-o", str(out), *args, "--quiet"]) == 2


@pytest.mark.long
def test_ctrl_c_mid_fit_exits_130_and_writes_nothing(tmp_path: Path) -> None:
    # Sixty shots: a stroke search may converge early, so a few could end within the wait.
    write_json(tmp_path / "shots.json", [{**a_shot(), "id": shot} for shot in range(1, 61)])
    long = ["--generations", "500", "--evaluations", "500"]  # minutes: stopped long before
    arguments = ["calibrate", "shots.json", "-o", "out", *long]
    # Signalled once the fit has begun (its progress bar's first character).
    returncode, errors = signalled_midway(
        "billiards.fit", arguments, tmp_path, 2, after_output=True
    )
    # 130, or killed by the SIGINT itself after saying so (1 run in about 15 here, not
    # understood yet): a shell shows both as 130.
    assert returncode in (130, -2), (returncode, errors[-800:])
    assert "stopped, no output written" in errors and "Traceback" not in errors
    assert sorted(path.name for path in tmp_path.iterdir()) == ["shots.json"]


def test_the_weighted_first_4_s_counts_each_sample_as_tailuge_weighs_it() -> None:
    # Positions off the recording by a known distance: 3 cm for the cue ball and 1 cm
    # for the others within 4 s of the stroke, 50 cm after. The weighted figure sees
    # only the first 4 s, each sample weighing 1 / (1 + t), the cue ball's 1.5 times.
    shot = prepare(synthetic(table(), 0, duration=6.0))
    simulated = np.zeros((len(shot.times), 3, 2))
    for column, (rows, recorded) in enumerate(zip(shot.samples, shot.recorded, strict=True)):
        off = np.where(shot.times[rows] <= 4.0, 0.03 if column == 0 else 0.01, 0.5)
        simulated[rows, column] = recorded + np.stack([off, np.zeros_like(off)], axis=1)
    errors = shot_errors(shot, simulated)
    weights = [
        (1.5 if column == 0 else 1.0) / (1.0 + shot.times[rows][shot.times[rows] <= 4.0])
        for column, rows in enumerate(shot.samples)
    ]
    cue, others = float(weights[0].sum()), float(weights[1].sum() + weights[2].sum())
    expected = math.sqrt((0.03**2 * cue + 0.01**2 * others) / (cue + others))
    assert errors.rmse_early_weighted == pytest.approx(expected, rel=1e-12)
    assert errors.rmse_early < errors.rmse_early_weighted < 0.03  # the cue ball weighs more
    assert errors.rmse > 0.2  # the whole shot sees the 50 cm
    # Window "4s" minimises exactly that; its residuals' squares sum to the loss times
    # a constant of the shot (here, the total weight).
    four = replace(BUDGET, window="4s")
    assert errors.loss(four) == pytest.approx(expected**2, rel=1e-12)
    square_sum = float(np.sum(residuals(shot, [simulated], four)[0] ** 2))
    assert square_sum == pytest.approx(expected**2 * (cue + others), rel=1e-12)
    # The whole-shot window's loss is dominated by the late 50 cm.
    assert errors.loss(BUDGET) > 100 * errors.loss(four)


@pytest.mark.long
def test_a_stroke_fitted_to_the_first_4_s_matches_them_better() -> None:
    # After 4 s the recording of shot 0 is of a table whose cushions keep less energy:
    # a stroke fitted to the whole shot compromises between both halves, one fitted to
    # the first 4 s (window "4s") matches those to the noise.
    scene = table()
    early = synthetic(scene, 0, duration=4.0)
    late = synthetic(table(cushion_restitution=0.6), 0, duration=8.0)
    tracks = {
        ball: Track(
            np.concatenate([early.balls[ball].t, late.balls[ball].t[late.balls[ball].t > 4.0]]),
            np.concatenate([early.balls[ball].xy, late.balls[ball].xy[late.balls[ball].t > 4.0]]),
        )
        for ball in early.balls
    }
    recording = Recording("mixed", tracks)
    whole = fit_shot(recording, scene, BUDGET)
    first = fit_shot(recording, scene, replace(BUDGET, window="4s"))
    assert first.errors.rmse_early_weighted < 2.5 * NOISE
    assert first.stroke.speed == pytest.approx(SHOTS[0][1].speed, rel=0.01), first.stroke
    # (measured: 0.14 cm against 15 cm for the whole-shot fit)
    assert whole.errors.rmse_early_weighted > 10 * first.errors.rmse_early_weighted


def test_score_offers_no_option_it_would_ignore(capsys: pytest.CaptureFixture[str]) -> None:
    """score keeps the scene's constants: --evaluations (calibrate's trials of them) is
    not among its options, and given, it is refused in one line."""
    from billiards.fit.__main__ import build_parser

    with pytest.raises(SystemExit) as stopped:
        build_parser().parse_args(["score", "shots.json", "-o", "out", "--evaluations", "3"])
    assert stopped.value.code == 2
    assert "unrecognized arguments: --evaluations 3" in capsys.readouterr().err
    calibrate = build_parser().parse_args(["calibrate", "shots.json", "-o", "out"])
    assert calibrate.evaluations == Budget.evaluations
