"""`python -m billiards.sweep [SCENE] --runs N --vary KEY=SPEC ... -o DIR`
`python -m billiards.sweep [SCENE] --nudge LO:HI -o DIR`

Many runs of one scene: with --vary, each run draws the varied keys (from --seed and
its own index); with --nudge, the chaos curve (how far the balls at rest part when the
cue ball is moved by each nudge, per method). Runs go to a local Dask cluster (one
worker per core, --workers N; 0 = this process, on its threads) or to --scheduler ADDRESS. Writes the
folder (SCENE_sweep/ unless -o names one) whole or not at all: runs.csv, summary.json,
cloud.png (and chaos.png).
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import os
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from billiards.physics.compiled import notice
from billiards.scene.reader import METHODS, SceneError, shipped_scene_names
from billiards.shell import cli
from billiards.shell.atomic import AtomicFolder
from billiards.simulation import BATCH_SIZE
from billiards.sweep.cluster import (
    Batcher,
    BatchError,
    ClusterError,
    Sweeper,
    dask_missing,
)
from billiards.sweep.records import NudgeRecord, Record, record_for
from billiards.sweep.runs import NUDGE_METHODS, Plan, VaryPlan, nudge_plan
from billiards.sweep.variations import (
    MAX_RUNS,
    SPEC_HELP,
    Variations,
    VaryError,
    check_variations,
    load_scene_data,
    parse_vary,
)

DEFAULT_RUNS = 100


# The most runs a batch holds (its scenes and rows are in one worker's memory at once).
MAX_BATCH = 4096
# The most local workers: the physics is single-threaded, so more processes than twice
# the cores only share them, each with its own copy of numpy (about 100 MB).
MAX_WORKERS = 2 * (os.cpu_count() or 1)


def build_parser() -> argparse.ArgumentParser:
    parser = cli.command_parser(
        "python -m billiards.sweep",
        "Run a scene many times on a Dask cluster: varied inputs (--vary) or "
        "the chaos curve (--nudge).",
        shipped_scene_names,
    )
    parser.add_argument(
        "--vary",
        action="append",
        default=[],
        metavar="KEY=SPEC",
        help=f"vary a numeric scene key (e.g. ball.cue.velocity, rack.gap): {SPEC_HELP}",
    )
    parser.add_argument(
        "--runs",
        type=cli.whole_number(
            1,
            "a whole number of runs >= 1",
            MAX_RUNS,
            " (a sweep's bound: more is several sweeps, each its own --seed)",
        ),
        help=f"number of runs, 1 to {MAX_RUNS:,} (default: the grid's size, or {DEFAULT_RUNS})",
    )
    parser.add_argument(
        "--seed",
        type=cli.whole_number(0, "a whole number >= 0"),
        default=0,
        help="seed of the draws",
    )
    parser.add_argument(
        "--nudge",
        metavar="LO:HI[:N]",
        help="the chaos curve: move the cue ball by log-spaced distances from LO to HI m "
        "(4 per decade, or N)",
    )
    parser.add_argument("--method", choices=METHODS, help="override [simulation] method")
    parser.add_argument(
        "-o",
        "--output",
        help="folder to write (default: named after the scene, SCENE_sweep: "
        "hard_break_sweep, break_sweep for the seed break)",
    )
    cli.add_force_argument(parser)
    parser.add_argument(
        "--workers",
        type=cli.whole_number(
            0,
            "a whole number of workers >= 0",
            MAX_WORKERS,
            " (twice this machine's cores: each run uses one core)",
        ),
        default=os.cpu_count() or 1,
        help=f"local worker processes, 0 to {MAX_WORKERS} (default: one per core, "
        "%(default)s; 0: in this process)",
    )
    parser.add_argument(
        "--scheduler", metavar="ADDRESS", help="run on this Dask scheduler, e.g. tcp://host:8786"
    )
    parser.add_argument(
        "--batch",
        type=cli.whole_number(
            1, "a whole number of runs >= 1", MAX_BATCH, " (a worker holds a batch at once)"
        ),
        help=(
            f"runs per batch, 1 to {MAX_BATCH:,} (default: batches of equal size, as few as "
            f"a whole number of rounds of the workers allows with none over {BATCH_SIZE} runs)"
        ),
    )
    cli.add_quiet_argument(parser, "no progress bar, no summary line")
    parser.add_argument(
        "--dry-run",
        action="store_true",
        help="check everything (the scene, each --vary against its key's bounds, the "
        "output folder), say what would run, and run nothing",
    )
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    return cli.run_guarded(lambda: _run(argv))


def make_plan(args: argparse.Namespace) -> Plan:
    """The plan the arguments ask for; SceneError or VaryError if they are bad."""
    scene_data = load_scene_data(args.scene)
    if args.nudge is not None:
        if args.vary:
            raise VaryError("--nudge: runs the scene as it is; expected no --vary with it")
        methods = (args.method,) if args.method else NUDGE_METHODS
        return nudge_plan(scene_data, args.nudge, methods)
    items = tuple(parse_vary(text) for text in args.vary)
    check_variations(scene_data, items)
    variations = Variations(items, args.seed)
    grid = variations.grid_size
    if args.runs is None and grid > MAX_RUNS:
        raise VaryError(
            f"--vary: the grids have {grid:,} points together: expected at most "
            f"{MAX_RUNS:,} runs (give --runs N to run the first N)"
        )
    runs = args.runs or (grid if grid > 1 else DEFAULT_RUNS)
    return VaryPlan(scene_data, variations, runs, args.method)


def same_shot(plan: Plan) -> bool:
    """Whether every run of the plan is the same shot: more than one run, and no --vary
    but fixed values (a grid of one point)."""
    if not isinstance(plan, VaryPlan) or plan.runs < 2:
        return False
    return all(item.kind == "grid" and len(item.points) == 1 for item in plan.variations.items)


def plan_text(plan: Plan, workers: int, batch: int | None, output: str) -> str:
    """What a dry run says: the runs, how they are cut, what varies, where they go."""
    batcher = Batcher(plan.runs, max(1, workers), batch)
    largest = batch or math.ceil(plan.runs / batcher.count)
    where = f"{workers} workers" if workers else "this process"
    lines = [
        f"{plan.scene_data.source}: {plan.runs:,} runs in {batcher.count:,} batches of up "
        f"to {largest:,} on {where}; would write {output}/ (nothing run or written)"
    ]
    if isinstance(plan, VaryPlan):
        lines += [f"  {item.key} = {item.spec} ({item.kind})" for item in plan.variations.items]
        if same_shot(plan):
            lines.append("  nothing varies: every run is the same shot")
    else:
        lines.append(
            f"  {plan.key}: {len(plan.nudges) - 1} nudges, {plan.nudges[1]:g} to "
            f"{plan.nudges[-1]:g} m, for {', '.join(plan.methods)}"
        )
    return "\n".join(lines)


def _run(argv: Sequence[str] | None) -> int:
    args = build_parser().parse_args(cli.command_words(argv, joined=("--nudge", "--vary")))
    notice.announce = not args.quiet
    args.output = args.output or cli.default_output(args.scene, "_sweep")
    with cli.failing_on(SceneError, VaryError):
        plan = make_plan(args)
    problem = cli.folder_problem(args.output, force=args.force)
    if problem:  # before any simulating
        return cli.fail(problem)
    if args.dry_run:
        print(plan_text(plan, 0 if args.scheduler else args.workers, args.batch, args.output))
        return 0
    needs_dask = args.scheduler is not None or args.workers > 0
    missing = (dask_missing() if needs_dask else None) or _matplotlib_missing()
    if missing:
        return cli.fail(missing, cli.EXIT_FAILED)
    began = time.perf_counter()
    try:
        with Sweeper(args.workers, args.scheduler, args.batch) as sweeper:
            if same_shot(plan):
                print(
                    f"warning: all {plan.runs:,} runs are the same shot: nothing varies "
                    "(give --vary KEY=SPEC a range, or --nudge LO:HI)",
                    file=sys.stderr,
                )
            record = write_sweep(plan, sweeper, Path(args.output), quiet=args.quiet)
            workers = sweeper.workers
    except ClusterError as error:
        return cli.fail(error, cli.EXIT_FAILED if isinstance(error, BatchError) else cli.EXIT_USAGE)
    except OSError as error:
        return cli.fail(cli.first_line(error), cli.EXIT_FAILED)
    if not args.quiet:
        seconds = time.perf_counter() - began
        where = f"{workers} workers" if workers else "this process"
        failed = f", {record.failed} failed" if record.failed else ""
        cli.say(
            f"wrote {Path(args.output)}/ ({record.runs} runs{failed}) in {seconds:.1f} s on {where}: "
            f"{record.runs / seconds:.1f} runs/s"
        )
    return 0


def write_sweep(plan: Plan, sweeper: Sweeper, output: Path, *, quiet: bool = True) -> Record:
    """Run the plan and write its folder whole: runs.csv as batches arrive, then the
    summary and pictures; the folder appears only if all of it was written."""
    from tqdm import tqdm

    record = record_for(plan)
    folder = AtomicFolder(output)
    try:
        with (
            open(folder.temporary / "runs.csv", "w", newline="", encoding="utf-8") as file,
            tqdm(total=plan.runs, unit="run", disable=quiet, file=sys.stderr) as progress,
        ):
            writer = csv.writer(file, lineterminator="\n")
            writer.writerow(record.header())
            for batch in sweeper.run(plan):
                writer.writerows(record.add(row) for row in batch.rows)
                progress.update(len(batch.rows))
        write_results(record, folder.temporary)
    except BaseException:
        folder.discard()
        raise
    folder.commit()
    return record


def write_results(record: Record, folder: Path) -> None:
    from billiards.sweep.pictures import draw_chaos, draw_cloud

    summary = _finite(record.summary())
    (folder / "summary.json").write_text(
        json.dumps(summary, indent=2, allow_nan=False) + "\n", encoding="utf-8"
    )
    scene = record.plan.scene_data.scene
    name = Path(scene.source).name
    shown = len(record.cloud)
    runs = (
        f"{record.runs} runs"
        if shown == record.runs
        else f"the first {shown} of {record.runs} runs"
    )
    size = (scene.table.length, scene.table.width)
    if isinstance(record, NudgeRecord):
        title = f"{name}: {record.nudge_plan.ball} nudged along y; each ball's place at rest"
        draw_chaos(
            folder / "chaos.png",
            record.curves,
            scene.radius,
            f"{name}: how far the balls at rest part when the {record.nudge_plan.ball} ball moves",
        )
    else:
        title = f"{name}: each ball's place at rest over {runs}"
    draw_cloud(folder / "cloud.png", record.cloud, record.ball_ids, size, title)


def _finite(value: Any) -> Any:
    """JSON has no nan: a number that is not finite is null."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {key: _finite(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_finite(item) for item in value]
    return value


# `--workers 0` needs no Dask, but every sweep draws its pictures.
MATPLOTLIB_HINT = 'the sweep\'s pictures need matplotlib: pip install "billiards[sweep]"'


def _matplotlib_missing() -> str | None:
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return MATPLOTLIB_HINT
    return None


if __name__ == "__main__":
    sys.exit(main())
