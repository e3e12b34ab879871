"""`python -m billiards.sweep` in one process: the --vary keys and specs, run i's inputs,
failed runs, the nudge curve, the output folder, and bad inputs (one line, exit 2).

The Dask cluster's own tests (local, loopback scheduler, a killed worker, Ctrl-C) are
in test_sweep_cluster.py."""

from __future__ import annotations

import csv
import json
import math
import os
import tracemalloc
from pathlib import Path

import pytest

from billiards.scene.reader import load_scene
from billiards.simulation import BATCH_SIZE
from billiards.sweep.__main__ import DEFAULT_RUNS, build_parser, make_plan, write_sweep
from billiards.sweep.cluster import Batcher, Sweeper
from billiards.sweep.records import record_for
from billiards.sweep.runs import Plan, VaryPlan, nudge_plan, run_rows
from billiards.sweep.variations import (
    MAX_RUNS,
    Variations,
    VaryError,
    check_variations,
    load_scene_data,
    parse_vary,
)
from tests.commands import run_module

# The seed break cut off at 0.4 s: a few contacts, a few milliseconds a run.
SHORT = "simulation.max_time=0.4"


def plan(*vary: str, runs: int = 6, seed: int = 0, scene: str = "break") -> VaryPlan:
    scene_data = load_scene_data(scene)
    items = tuple(parse_vary(text) for text in vary)
    check_variations(scene_data, items)
    return VaryPlan(scene_data, Variations(items, seed), runs)


def rows_of(path: Path) -> list[dict[str, str]]:
    with open(path / "runs.csv", newline="", encoding="utf-8") as file:
        return list(csv.DictReader(file))


def test_specs_read_uniform_normal_and_grids() -> None:
    uniform = parse_vary("ball.cue.velocity=9.5:10.5")
    assert (uniform.kind, uniform.a, uniform.b) == ("uniform", 9.5, 10.5)
    normal = parse_vary("ball.cue.position.y=0.5325~0.001")
    assert (normal.kind, normal.a, normal.b) == ("normal", 0.5325, 0.001)
    assert parse_vary("rack.gap=0:0.001:3").points == (0.0, 0.0005, 0.001)
    assert parse_vary("physics.rolling_friction=0.01,0.02").points == (0.01, 0.02)
    assert parse_vary("simulation.max_time=2").points == (2.0,)


@pytest.mark.parametrize(
    ("text", "says"),
    [
        ("physics.rolling_friction=2:1", "the range is empty"),
        ("physics.rolling_friction=a~1", "not a number"),
        ("physics.rolling_friction=0~-1", "negative standard deviation"),
        ("physics.rolling_friction=0:1:1", "grid points"),
        ("physics.rolling_friction=nan:1", "not a finite number"),
        ("physics.rolling_friction", "expected KEY=SPEC"),
    ],
)
def test_a_bad_spec_names_the_key_and_what_was_expected(text: str, says: str) -> None:
    with pytest.raises(VaryError, match=says) as caught:
        parse_vary(text)
    assert "\n" not in str(caught.value)


def test_run_inputs_depend_only_on_the_seed_and_the_run() -> None:
    variations = plan("ball.cue.velocity=2.5:3.5", "physics.rolling_friction=0.01~0.001")
    again = plan("ball.cue.velocity=2.5:3.5", "physics.rolling_friction=0.01~0.001")
    assert variations.run_input(5) == again.run_input(5)
    assert variations.run_input(5) != variations.run_input(4)
    other_seed = plan("ball.cue.velocity=2.5:3.5", "physics.rolling_friction=0.01~0.001", seed=1)
    assert other_seed.run_input(5) != variations.run_input(5)
    speeds = [float(variations.run_input(i)[0][0]) for i in range(50)]
    assert 2.5 <= min(speeds) < 2.7 and 3.3 < max(speeds) < 3.5


def test_a_grid_cycles_with_the_first_key_slowest() -> None:
    grid = plan("rack.gap=0,0.001", "physics.rolling_friction=0.01:0.03:3", runs=6)
    assert grid.variations.grid_size == 6
    assert [value for i in range(7) for value in grid.run_input(i)[0]] == pytest.approx([
        0.0, 0.01, 0.0, 0.02, 0.0, 0.03,
        0.001, 0.01, 0.001, 0.02, 0.001, 0.03,
        0.0, 0.01,
    ])  # fmt: skip


def test_varied_values_reach_the_scene() -> None:
    scene_data = load_scene_data("break")
    base = scene_data.scene
    scene = scene_data.build(
        scene_data.with_values(
            [("ball.cue.velocity", 6.0), ("rack.gap", 0.001), ("ball.5.position.x", 2.0)]
        )
    )
    assert scene.balls[0].velocity == (6.0, 0.0)
    assert scene.ball_ids == base.ball_ids  # the rack, written out, in the same order
    five = scene.ball_ids.index("5")
    assert scene.balls[five].position[0] == 2.0
    # The rest of the rack moved apart by the new gap, from the same apex.
    assert scene.balls[1].position == base.balls[1].position
    assert scene.balls[2].position[0] > base.balls[2].position[0]
    unchanged = scene_data.build(scene_data.with_values([]))
    assert unchanged.balls == base.balls


def test_a_scene_without_balls_gets_the_seed_cue_ball_to_vary(tmp_path: Path) -> None:
    path = tmp_path / "slow.toml"
    path.write_text("[physics]\nrolling_friction = 0.02\n")
    scene_data = load_scene_data(str(path))
    assert scene_data.build(scene_data.with_values([])).balls == load_scene(path).balls
    check_variations(scene_data, [parse_vary("ball.cue.position.y=0.5~0.01")])
    check_variations(scene_data, [parse_vary("rack.apex.x=1.5:1.6")])


@pytest.mark.parametrize(
    ("key", "says"),
    [
        ("ball.cue.velocty", 'unknown key in break (did you mean "ball.cue.velocity"?)'),
        ("physic.rolling_friction", 'did you mean "physics.rolling_friction"?'),
        ("physics.model", "not a numeric key (it holds a string)"),
        ("ball.cue.id", "not a numeric key"),
        ("ball.5.velocity", "at rest, so its speed has no direction"),
    ],
)
def test_an_unusable_key_is_refused_before_any_run(key: str, says: str) -> None:
    with pytest.raises(VaryError, match=".*".join(map(_escape, says.split("*")))):
        plan(f"{key}=1:2")


def _escape(text: str) -> str:
    import re

    return re.escape(text)


def test_a_run_whose_scene_fails_is_a_failed_row_with_its_reason() -> None:
    # x near the apex puts the cue ball on the rack's first ball: the reader refuses it.
    bad = plan("ball.cue.position.x=1.56:1.64", SHORT, runs=2)
    (row,) = run_rows(bad, range(1))
    assert row.failed is not None and "expected no overlap" in row.failed
    assert math.isnan(row.rest_time) and "\n" not in row.failed


def test_rows_run_on_threads_are_the_rows_run_serially() -> None:
    """--workers 0 runs the compiled loop on this process's threads: the same rows."""
    sweep = plan("ball.cue.velocity=2.5:3.5", "ball.cue.position.y=0.5:0.56", SHORT, runs=9)
    serial = run_rows(sweep, range(9))
    threaded = run_rows(sweep, range(9), threads=True)
    assert [row.failed for row in serial] == [None] * 9  # every run simulated, none refused
    for mine, theirs in zip(threaded, serial, strict=True):
        assert mine.positions.tobytes() == theirs.positions.tobytes()
        assert (mine.rest_time, mine.ball_contacts) == (theirs.rest_time, theirs.ball_contacts)


def test_batching_does_not_change_a_byte(tmp_path: Path) -> None:
    sweep = plan("ball.cue.velocity=2.5:3.5", "ball.cue.position.x=1.2:1.7", SHORT, runs=23)
    for size in (1, 7, None):
        with Sweeper(0, batch_size=size) as sweeper:
            write_sweep(sweep, sweeper, tmp_path / f"out{size}")
    csvs = {(tmp_path / f"out{size}" / "runs.csv").read_bytes() for size in (1, 7, None)}
    assert len(csvs) == 1
    rows = rows_of(tmp_path / "outNone")
    assert [row["run"] for row in rows] == [str(i) for i in range(23)]
    failed = [row for row in rows if row["status"] == "failed"]
    assert failed and all(row["reason"] and row["cue_x"] == "" for row in failed)
    summary = json.loads((tmp_path / "outNone" / "summary.json").read_text())
    assert summary["runs"] == 23 and summary["failed"] == len(failed)
    assert set(summary["balls"]) == set(load_scene("break").ball_ids)
    assert summary["vary"]["ball.cue.velocity"]["kind"] == "uniform"
    assert (tmp_path / "outNone" / "cloud.png").stat().st_size > 10_000


def test_pocketed_balls_are_columns_and_probabilities_on_a_table_with_pockets(
    tmp_path: Path,
) -> None:
    """pocket_shot drops ball 1 into the foot-left corner; aimed a little off, it may
    not: each row names the pocket (or nothing), and the summary counts them."""
    sweep = plan("ball.cue.velocity.y=-0.16:-0.13", "simulation.max_time=1", runs=6,
                 scene="pocket_shot")  # fmt: skip
    with Sweeper(0) as sweeper:
        write_sweep(sweep, sweeper, tmp_path / "out")
    rows = rows_of(tmp_path / "out")
    for row in rows:
        run = int(row["run"])
        (expected,) = run_rows(sweep, range(run, run + 1))  # run alone: the same row
        assert row["1_pocket"] == expected.pockets[1]
        assert row["pocketed"] == str(sum(1 for name in expected.pockets if name))
    dropped = sum(row["1_pocket"] == "foot-left" for row in rows)
    assert dropped > 0
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["balls"]["1"]["p_pocketed"] == dropped / 6
    assert summary["balls"]["1"]["p_pocket"] == {"foot-left": dropped / 6}
    # A table without pockets has no pocket columns.
    closed = plan(SHORT, runs=1)
    with Sweeper(0) as sweeper:
        write_sweep(closed, sweeper, tmp_path / "closed")
    assert "pocketed" not in rows_of(tmp_path / "closed")[0]


# A player's spread on masse_shot's stroke: speed, aim and tip (README, Sweeps).
SHOT_NOISE = (
    "ball.cue.cue.speed=2.8~0.05",
    "ball.cue.cue.direction=-25~0.5",
    "ball.cue.cue.tip.side=-0.7~0.03",
    "ball.cue.cue.tip.height=-0.3~0.03",
)


def test_a_strokes_keys_reach_the_stroke_and_a_struck_ball_has_no_velocity_keys() -> None:
    scene_data = load_scene_data("masse_shot")
    scene = scene_data.build(
        scene_data.with_values(
            [
                ("ball.cue.cue.speed", 2.0),
                ("ball.cue.cue.elevation", 30.0),
                ("ball.cue.cue.tip.height", 0.1),
                ("ball.cue.cue.end_mass", 0.01),
            ]
        )
    )
    stroke = scene.balls[0].stroke
    assert stroke is not None
    assert (stroke.speed, stroke.direction, stroke.elevation) == (2.0, -25.0, 30.0)
    assert stroke.tip == (-0.7, 0.1) and stroke.end_mass == 0.01
    assert scene.balls[0].velocity != scene_data.scene.balls[0].velocity
    for key in ("ball.cue.velocity.x", "ball.cue.spin.z", "ball.cue.tip.side"):
        with pytest.raises(VaryError, match="unknown key in masse_shot"):
            plan(f"{key}=1:2", scene="masse_shot")
    with pytest.raises(VaryError, match=_escape('did you mean "ball.cue.cue.speed"')):
        plan("ball.cue.cue.sped=1:2", scene="masse_shot")


@pytest.mark.long
def test_a_shot_noise_sweep_is_one_command(tmp_path: Path) -> None:
    args = [arg for key in SHOT_NOISE for arg in ("--vary", key)]
    run = run_module(
        "billiards.sweep", "masse_shot", *args, "--runs", "12", "--workers", "0", "--quiet",
        "-o", str(tmp_path / "noise"),
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    rows = rows_of(tmp_path / "noise")
    assert len(rows) == 12 and all(row["status"] == "ok" for row in rows)
    speeds = [float(row["ball.cue.cue.speed"]) for row in rows]
    assert len(set(speeds)) == 12 and all(2.5 < speed < 3.1 for speed in speeds)
    summary = json.loads((tmp_path / "noise" / "summary.json").read_text())
    assert 0 < summary["balls"]["1"]["p_contact"] < 1  # the spread makes some miss the 1
    # A draw the reader refuses fails its run alone, saying so: a jump (issue 45: it
    # flies) where there is no gravity to bring it down.
    floating = plan("ball.cue.cue.elevation=70", "physics.gravity=0", runs=1, scene="masse_shot")
    failed = run_rows(floating, range(1))[0].failed
    assert failed is not None and "physics.gravity = 0" in failed


def spans(batcher: Batcher) -> list[tuple[int, int]]:
    return list(iter(batcher.take, None))


def test_batches_are_equal_whole_rounds_of_the_workers_and_cover_every_run() -> None:
    # 2,000 runs on 2 workers: 4 rounds of 250 (3 rounds would be 334 > BATCH_SIZE).
    taken = spans(Batcher(runs=2000, workers=2))
    assert taken == [(250 * n, 250 * (n + 1)) for n in range(8)]
    # Sizes differ by a run at most, and follow one another without gap or overlap.
    for runs, workers in ((1001, 2), (12, 2), (7, 3), (2 * BATCH_SIZE + 1, 1), (1, 4)):
        taken = spans(Batcher(runs, workers))
        sizes = [stop - start for start, stop in taken]
        assert [start for start, _ in taken] == [0, *(stop for _, stop in taken[:-1])]
        assert taken[-1][1] == runs and max(sizes) - min(sizes) <= 1
        assert min(sizes) >= 1 and max(sizes) <= BATCH_SIZE
        assert len(taken) % workers == 0 or runs < workers
    assert spans(Batcher(runs=10, workers=2, size=4)) == [(0, 4), (4, 8), (8, 10)]


@pytest.mark.long
def test_the_nudge_curve_has_one_line_per_method(tmp_path: Path) -> None:
    scene = tmp_path / "short.toml"
    scene.write_text("[simulation]\nmax_time = 1.0\n")
    run = run_module(
        "billiards.sweep", str(scene), "--nudge", "1e-12:1e-6:3", "--workers", "0",
        "-o", str(tmp_path / "chaos"), "--quiet",
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert run.stderr == ""
    rows = rows_of(tmp_path / "chaos")
    assert [(row["method"], float(row["nudge"])) for row in rows[:4]] == [
        ("exact", 0.0), ("exact", pytest.approx(1e-12, rel=1e-3)),
        ("exact", pytest.approx(1e-9, rel=1e-6)), ("exact", pytest.approx(1e-6, rel=1e-9)),
    ]  # fmt: skip
    assert [row["method"] for row in rows] == ["exact"] * 4 + ["event"] * 4 + ["naive"] * 4
    assert all(float(row["divergence"]) == 0 for row in rows[::4])
    exact = [float(row["divergence"]) for row in rows[1:4]]
    assert 0 < exact[0] < exact[1] < exact[2]  # the balls part more, the larger the nudge
    summary = json.loads((tmp_path / "chaos" / "summary.json").read_text())
    assert set(summary["methods"]) == {"exact", "event", "naive"}
    assert len(summary["methods"]["naive"]["curve"]) == 3
    assert sorted(os.listdir(tmp_path / "chaos")) == [
        "chaos.png", "cloud.png", "runs.csv", "summary.json"
    ]  # fmt: skip


def test_the_nudge_plan_spaces_four_per_decade() -> None:
    nudges = nudge_plan(load_scene_data("break"), "1e-15:1e-3", ("exact",)).nudges
    assert nudges[0] == 0.0 and len(nudges) == 1 + 49
    assert nudges[1] == pytest.approx(1e-15) and nudges[-1] == pytest.approx(1e-3)


@pytest.mark.parametrize(
    ("args", "says"),
    [
        (["--vary", "ball.cue.velocty=1:2"], 'did you mean "ball.cue.velocity"?'),
        (["--vary", "physics.model=1:2"], "physics.model: not a numeric key"),
        (["--vary", "rack.gap=1:x"], "rack.gap=1:x: not a number"),
        (["--nudge", "0:1e-3"], "--nudge 0:1e-3: expected lo:hi"),
        (["--nudge", "-1e-9:1e-3"], "--nudge -1e-9:1e-3: expected lo:hi"),
        (["--nudge", "1e-3:1e-9"], "with 0 < lo < hi"),
        (["--nudge", "1e-9:1e-3", "--vary", "rack.gap=0:1"], "no --vary with it"),
        (["--scheduler", "tcp://127.0.0.1:1"], "cannot reach the scheduler"),
        (["--scheduler", "nonsense"], "--scheduler nonsense: cannot reach the scheduler"),
        (["--runs", "0"], "expected a whole number of runs >= 1"),
        (
            ["--runs", "10000000000000"],
            "--runs: '10000000000000': expected a whole number of runs >= 1, at most 1,000,000",
        ),
        (
            ["--vary", "physics.rolling_friction=-0.01:0.02"],
            "--vary physics.rolling_friction=-0.01:0.02: reaches -0.01, outside the key's "
            "bound; expected a number in [0, 10]",
        ),
        (["nowhere.toml"], "no such scene file"),
    ],
)
@pytest.mark.long
def test_bad_input_is_one_line_and_exit_2(tmp_path: Path, args: list[str], says: str) -> None:
    run = run_module("billiards.sweep", *args, "-o", str(tmp_path / "out"), "--quiet")
    assert run.returncode == 2, run.stderr
    assert run.stderr.count("\n") == 1 and says in run.stderr, run.stderr
    assert run.stderr.startswith("error: ")
    assert os.listdir(tmp_path) == []  # no folder, no temporary left


@pytest.mark.long
def test_an_existing_folder_is_kept_unless_forced(tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "mine.txt").write_text("keep")
    args = ["--vary", SHORT, "--runs", "2", "--workers", "0", "-o", str(out), "--quiet"]
    run = run_module("billiards.sweep", *args)
    assert run.returncode == 2 and "already exists and is not empty" in run.stderr
    assert os.listdir(out) == ["mine.txt"]
    run = run_module("billiards.sweep", *args, "--force")
    assert run.returncode == 0, run.stderr
    assert sorted(os.listdir(out)) == ["cloud.png", "runs.csv", "summary.json"]
    assert sorted(os.listdir(tmp_path)) == ["out"]


@pytest.mark.long
def test_without_dask_the_command_says_how_to_install_it(tmp_path: Path) -> None:
    # A `distributed` that cannot be imported stands in for a missing Dask.
    (tmp_path / "distributed").mkdir()
    (tmp_path / "distributed" / "__init__.py").write_text("raise ImportError('no dask')\n")
    env = {"PYTHONPATH": os.pathsep.join([str(tmp_path), os.environ.get("PYTHONPATH", "")])}
    run = run_module("billiards.sweep", "-o", str(tmp_path / "out"), env=env)
    assert run.returncode == 1
    assert run.stderr == 'error: the sweep needs Dask: pip install "billiards[sweep]"\n'
    assert not (tmp_path / "out").exists()


@pytest.mark.long
def test_in_one_process_without_matplotlib_the_command_names_matplotlib(tmp_path: Path) -> None:
    # A `matplotlib` that cannot be imported; `--workers 0` needs no Dask.
    (tmp_path / "matplotlib").mkdir()
    (tmp_path / "matplotlib" / "__init__.py").write_text("raise ImportError('no matplotlib')\n")
    env = {"PYTHONPATH": os.pathsep.join([str(tmp_path), os.environ.get("PYTHONPATH", "")])}
    run = run_module("billiards.sweep", "--workers", "0", "-o", str(tmp_path / "out"), env=env)
    assert run.returncode == 1
    assert run.stderr == (
        'error: the sweep\'s pictures need matplotlib: pip install "billiards[sweep]"\n'
    )
    assert not (tmp_path / "out").exists()


def test_a_sweeps_runs_are_built_without_the_scenes_render_tables(tmp_path: Path) -> None:
    mesh = tmp_path / "table.glb"
    mesh.write_bytes(b"")
    (tmp_path / "shot.toml").write_text('[render]\ntable_mesh = "table.glb"\nfps = 24\n')
    scene_data = load_scene_data(str(tmp_path / "shot.toml"))  # the whole file, checked
    mesh.unlink()  # as on a worker that has no copy of the mesh: no run needs it
    scene = scene_data.build(scene_data.with_values([("physics.rolling_friction", 0.02)]))
    assert scene.physics.rolling_friction == 0.02


# --- every count bounded, every range checked, before any run ---------------------------


def _plan_of(*args: str) -> Plan:
    return make_plan(build_parser().parse_args(list(args)))


@pytest.mark.parametrize(
    ("args", "says"),
    [
        (
            ["--vary", "physics.rolling_friction=0.01~0.005"],
            "reaches (mean +- 4 deviations) -0.01, outside the key's bound; expected a "
            "number in [0, 10]",
        ),
        (["--vary", "rack.gap=0,0.5,2"], "rack.gap=0,0.5,2: reaches 2, outside the key's bound"),
        (
            ["--vary", "ball.cue.position.x=0:1"],
            "reaches 0, outside the key's bound; expected a centre inside the cushions, x in "
            "[0.0286, 2.1014] m",
        ),
        (["--vary", "ball.cue.velocity=500:1500"], "reaches 1500, outside the key's bound"),
        (["--vary", "simulation.max_events=0,10"], "expected a whole number >= 1"),
        (["--vary", "rack.gap=0:0.001:2000000"], "2,000,000 grid points"),
        (
            ["--vary", "rack.gap=0:0.001:2000", "--vary", "physics.gravity=9:10:1000"],
            "the grids have 2,000,000 points together: expected at most 1,000,000 runs",
        ),
        (["--nudge", "1e-9:1e-3:900000"], "900,000 nudges: expected at most 333,332"),
    ],
)
def test_a_range_past_its_keys_bound_or_a_count_past_its_own_is_refused(
    args: list[str], says: str
) -> None:
    with pytest.raises(VaryError) as caught:
        _plan_of(*args)
    assert says in str(caught.value) and "\n" not in str(caught.value)


def test_ranges_within_the_bounds_pass_and_may_still_fail_a_run_alone() -> None:
    struck = ["masse_shot", *(f"--vary={text}" for text in SHOT_NOISE)]
    assert _plan_of(*struck).runs == DEFAULT_RUNS
    # In bounds, yet on the rack's apex ball: that run fails alone (see above).
    assert _plan_of("--vary", "ball.cue.position.x=1.2:1.7").runs == DEFAULT_RUNS
    with pytest.raises(VaryError, match=r"cue\.elevation=80:95: reaches 95"):
        _plan_of("masse_shot", "--vary", "ball.cue.cue.elevation=80:95")


@pytest.mark.parametrize(
    ("args", "says"),
    [
        (["--batch", "99999"], "'99999': expected a whole number of runs >= 1, at most 4,096"),
        (["--workers", "100000"], "'100000': expected a whole number of workers >= 0, at most"),
    ],
)
def test_batches_and_workers_are_bounded(
    args: list[str], says: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as stopped:
        build_parser().parse_args(args)
    assert stopped.value.code == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and says in error


def test_a_sweeps_memory_does_not_grow_with_its_runs() -> None:
    """The issue's 10,000,000,000,000 runs listed every batch up front: the batcher
    computes each as it is taken, and the record keeps sums and a bounded cloud."""
    tracemalloc.start()
    try:
        batcher = Batcher(runs=10**13, workers=2)
        assert batcher.take() == (0, 10**13 // batcher.count)
        record = record_for(_plan_of("--runs", str(MAX_RUNS), "--vary", "rack.gap=0:0.001"))
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert record.plan.runs == MAX_RUNS
    assert peak < 5_000_000


@pytest.mark.long
def test_a_dry_run_checks_everything_and_runs_nothing(tmp_path: Path) -> None:
    out = tmp_path / "out"
    run = run_module(
        "billiards.sweep", "hard_break", "--runs", "1000000", "--workers", "2",
        "--vary", "ball.cue.velocity=9:11", "--dry-run", "-o", str(out),
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert "hard_break: 1,000,000 runs in 3,908 batches of up to 256 on 2 workers" in run.stdout
    assert "ball.cue.velocity = 9:11 (uniform)" in run.stdout
    assert os.listdir(tmp_path) == []


@pytest.mark.long
def test_a_sweep_of_one_shot_says_so(tmp_path: Path) -> None:
    args = ["--vary", SHORT, "--runs", "2", "--workers", "0", "-o", str(tmp_path / "out")]
    run = run_module("billiards.sweep", *args, "--quiet")
    assert run.returncode == 0, run.stderr
    assert run.stderr == "warning: all 2 runs are the same shot: nothing varies " + (
        "(give --vary KEY=SPEC a range, or --nudge LO:HI)\n"
    )
