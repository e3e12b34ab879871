"""`python -m billiards.simulate [SCENE] [--method M] [--dt S] [--times T1,T2] [--json]`

Simulates a scene (the seed break by default) and prints a short summary, or with
--json one JSON object: ball ids, events, rest time, final positions and samples.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import sys
from collections.abc import Sequence

import numpy as np

from billiards.physics.engine.result import SimulationResult
from billiards.physics.methods.entry import METHODS
from billiards.record.result_json import MAX_TIMES, result_json
from billiards.record.window import cue_strike_of, film_trajectory
from billiards.scene.bounds import BOUNDS
from billiards.scene.reader import Scene, SceneError, load_scene, shipped_scene_names
from billiards.shell import cli
from billiards.shell.atomic import atomic_output
from billiards.simulation import NonFiniteRun, simulate_scene


def _parse_times(text: str) -> list[float]:
    expected = "expected comma-separated times in s from 0, e.g. 0.5,1,2"
    try:
        times = [float(part) for part in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text}: {expected}") from None
    if not all(np.isfinite(times)) or min(times) < 0:
        raise argparse.ArgumentTypeError(f"{text}: {expected}")
    if len(times) > MAX_TIMES:
        raise argparse.ArgumentTypeError(
            f"{len(times):,} times: expected at most {MAX_TIMES:,} (sample more sparsely, or "
            "use the library's Result.positions in parts)"
        )
    return times


def _step_seconds(text: str) -> float:
    """--dt: within [simulation] dt's bound (docs/scene_bounds.md)."""
    bound = BOUNDS["simulation.dt"]
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not (np.isfinite(value) and bound.low <= value <= bound.high):
        raise argparse.ArgumentTypeError(f"--dt {text!r}: expected seconds in {bound.range_text()}")
    return value


def build_parser() -> argparse.ArgumentParser:
    parser = cli.command_parser(
        "python -m billiards.simulate",
        "Simulate a scene exactly: a summary table, or JSON with --json.",
        shipped_scene_names,
    )
    parser.add_argument("--method", choices=METHODS, help="override [simulation] method")
    parser.add_argument(
        "--dt",
        type=_step_seconds,
        help="override [simulation] dt, seconds (1e-6 to 1, at most max_time)",
    )
    parser.add_argument("--times", type=_parse_times, help="sample positions at these times (s)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument(
        "--trajectory",
        metavar="NPZ",
        help="also save the film's trajectory: an .npz of every ball's position and "
        "orientation at each frame, and the contacts (numpy reads it; python -m "
        "billiards.render --trajectory films it)",
    )
    cli.add_force_argument(parser)
    return parser


def summary(result: SimulationResult, source: str) -> str:
    ball_events = sum(1 for event in result.events if event.kind == "ball")
    cushion_events = sum(1 for event in result.events if event.kind == "cushion")
    step = f", dt = {result.dt:.6g} s, {result.steps} steps" if result.dt else ""
    drops = {drop.ball: drop for drop in result.pocketed}
    dropped = f"; {len(drops)} pocketed" if result.pockets is not None else ""
    lines = [
        f"{source}: {len(result.ball_ids)} balls, method {result.method}{step}",
        f"{ball_events} ball-ball and {cushion_events} cushion contacts{dropped}; "
        + (
            f"the last ball stops at {result.rest_time:.4f} s"
            if result.complete
            else f"STOPPED by {result.stopped_by} at {result.rest_time:.4f} s, "
            "before every ball came to rest"
        ),
        "",
        f"{'ball':>6} {'x (m)':>9} {'y (m)':>9} {'contacts':>9}"
        + (f"  {'pocketed':<22}" if result.pockets is not None else ""),
    ]
    for index, ball_id in enumerate(result.ball_ids):
        x, y = result.final_positions[index]
        contacts = sum(
            1 for event in result.events if ball_id in event.balls and event.kind != "pocket"
        )
        line = f"{ball_id:>6} {x:9.4f} {y:9.4f} {contacts:9d}"
        if ball_id in drops:
            line += f"  {drops[ball_id].pocket} at {drops[ball_id].time:.4f} s"
        lines.append(line)
    return "\n".join(lines)


def save_film_trajectory(result: SimulationResult, scene: Scene, path: str) -> None:
    """Save what the film would show, with the scene's render settings, whole or not at all."""
    trajectory = dataclasses.replace(
        film_trajectory(result, scene.render, strike=cue_strike_of(scene)),
        scene_source=scene.source,
        render_settings=scene.render,
    )
    with atomic_output(path, ".npz") as temporary:
        trajectory.save(temporary)


def main(argv: Sequence[str] | None = None) -> int:
    return cli.run_guarded(lambda: _run(argv))


def _run(argv: Sequence[str] | None) -> int:
    args = build_parser().parse_args(cli.command_words(argv, joined=("--times",)))
    with cli.failing_on(SceneError):
        scene = load_scene(args.scene)
    if args.dt is not None and args.dt > scene.simulation.max_time:
        return cli.fail(
            f"--dt {args.dt:g}: expected a step no longer than {scene.source}'s "
            f"max_time ({scene.simulation.max_time:g} s)"
        )
    if args.trajectory:
        problem = cli.output_problem(args.trajectory, force=args.force)
        if problem is None and not args.trajectory.endswith(".npz"):
            problem = f"{args.trajectory}: a trajectory is an .npz file (name it .npz)"
        if problem:  # before any simulating
            return cli.fail(problem)
    # A number gone wrong is said once, as the run's one line.
    with (
        cli.failing_on(SceneError),
        cli.failing_on(NonFiniteRun, status=cli.EXIT_FAILED),
        np.errstate(all="ignore"),
    ):
        result = simulate_scene(scene, method=args.method, dt=args.dt)
    if not result.complete:
        cli.say(
            f"warning: {scene.source}: stopped by {result.stopped_by} at "
            f"{result.rest_time:g} s, before every ball came to rest"
        )
    if args.trajectory:
        with cli.failing_on(OSError, status=cli.EXIT_FAILED, one_line=True):
            save_film_trajectory(result, scene, args.trajectory)
        cli.say(f"wrote {args.trajectory} (the film's trajectory)")
    if args.json:
        try:  # strict JSON: no NaN or Infinity, and nothing printed unless all of it is
            text = json.dumps(result_json(result, args.times, scene), allow_nan=False)
        except ValueError as error:
            return cli.fail(f"{scene.source}: {cli.first_line(error)}", cli.EXIT_FAILED)
        sys.stdout.write(text + "\n")
    else:
        print(summary(result, scene.source))
        if args.times:
            positions = result.positions_at(np.array(args.times))
            for t, sample in zip(args.times, positions, strict=True):
                where = ", ".join(
                    f"{ball_id} ({x:.4f}, {y:.4f})"
                    for ball_id, (x, y) in zip(result.ball_ids, sample, strict=True)
                )
                print(f"t = {t:g} s: {where}")
    return 0


def run() -> int:
    try:
        return main()
    except BrokenPipeError:
        # The reader (say, `| head`) left early: not an error of ours.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0


if __name__ == "__main__":
    sys.exit(run())
