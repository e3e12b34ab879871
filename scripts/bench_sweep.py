"""Sweep speed and memory: a plain serial loop against the local Dask cluster.

    python scripts/bench_sweep.py [--runs 600] [--rounds 3] [--memory-runs 5000,50000]

Prints two markdown tables.

Speed: the seed break with the cue ball's y drawn from a normal of 1 mm (`--vary
ball.cue.position.y=0.5325~0.001`), as (a) a plain loop over the same runs in this
process (no CSV, no pictures), and (b) the whole sweep (runs.csv, summary.json,
cloud.png) on a local cluster of 1 and of 2 worker processes, in rounds that run all
three back to back (the cores may be shared: a neighbour's load then slows one round,
not one column). Cluster start-up is timed apart and left out of runs/s; the
pictures (about half a second) are in. Overhead is the share of the workers' time
between the first batch sent and the last received that was not spent inside
batches: scheduling, moving rows, the last batches' wait.

Memory: this process's peak of Python allocations (tracemalloc) while a 2-worker
sweep of a cheap scene (the break cut at 0.05 s) streams its rows to disk, at two
sizes (both at the cloud picture's cap of 5,000 runs): flat, because rows are written
as their batch arrives and only statistics and the capped cloud are kept; what else
grows is Dask's, and capped (the scheduler, in this process for a local cluster, keeps
its last 100 submissions). The runs.csv grows; the process does not.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import platform
import resource
import statistics
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

from billiards.sweep.__main__ import write_sweep
from billiards.sweep.cluster import Sweeper
from billiards.sweep.runs import VaryPlan, run_rows
from billiards.sweep.variations import Variations, load_scene_data, parse_vary

SEED_VARY = "ball.cue.position.y=0.5325~0.001"


def seed_plan(runs: int, *extra: str) -> VaryPlan:
    scene_data = load_scene_data("break")
    items = tuple(parse_vary(text) for text in (SEED_VARY, *extra))
    return VaryPlan(scene_data, Variations(items, seed=0), runs)


def serial_loop(plan: VaryPlan) -> float:
    start = time.perf_counter()
    for run in range(plan.runs):
        run_rows(plan, range(run, run + 1))
    return time.perf_counter() - start


def timed_sweep(plan: VaryPlan, sweeper: Sweeper, folder: Path) -> tuple[float, float, int]:
    """(wall s, scheduling overhead, batches) of a whole sweep on a started cluster; the
    overhead is the share of the workers' time, from the first batch sent to the last
    received, not spent inside batches."""
    busy, batches, running = sweeper.worker_seconds, sweeper.batches, sweeper.run_seconds
    started = time.perf_counter()
    write_sweep(plan, sweeper, folder)
    wall = time.perf_counter() - started
    busy = sweeper.worker_seconds - busy
    overhead = 1 - busy / ((sweeper.run_seconds - running) * sweeper.workers)
    return wall, overhead, sweeper.batches - batches


def _load() -> str:
    return ", ".join(f"{load:.2f}" for load in os.getloadavg())


def speed_table(runs: int, rounds: int, scratch: Path) -> None:
    plan = seed_plan(runs)
    run_rows(plan, range(1))  # warm: imports and caches
    with contextlib.ExitStack() as stack:
        clusters = {}
        for workers in (1, 2):
            began = time.perf_counter()
            clusters[workers] = stack.enter_context(Sweeper(workers))
            print(f"local cluster of {workers}: started in {time.perf_counter() - began:.2f} s")
        speed_rounds(plan, clusters, rounds, scratch)


def speed_rounds(plan: VaryPlan, clusters: dict[int, Sweeper], rounds: int, scratch: Path) -> None:
    runs = plan.runs
    print(f"\nSpeed: the seed break, {runs} runs a sweep, cue ball y ~ N(0.5325, 0.001) m;")
    print("each round runs all three back to back, so a neighbour's load hits them alike\n")
    print(
        "| round | load (1 min) | serial loop runs/s | 1 worker runs/s | 2 workers runs/s "
        "| 2 workers / serial | 2 / 1 worker | overhead (1 w, 2 w) | batches (2 w) |"
    )
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    ratios = []
    for round_ in range(1, rounds + 1):
        load = os.getloadavg()[0]
        serial = runs / serial_loop(plan)
        speeds, overheads, batches = {}, {}, 0
        for workers, sweeper in clusters.items():
            wall, overhead, batches = timed_sweep(plan, sweeper, scratch / f"r{round_}w{workers}")
            speeds[workers] = runs / wall
            overheads[workers] = overhead
        ratios.append(speeds[2] / serial)
        print(
            f"| {round_} | {load:.2f} | {serial:.1f} | {speeds[1]:.1f} | {speeds[2]:.1f} | "
            f"{speeds[2] / serial:.2f}x | {speeds[2] / speeds[1]:.2f}x | "
            f"{overheads[1]:.1%}, {overheads[2]:.1%} | {batches} |"
        )
        sys.stdout.flush()
    print(f"\n2 workers against the serial loop: median {statistics.median(ratios):.2f}x")


def memory_table(sizes: list[int], scratch: Path) -> None:
    print("\nMemory: the break cut at 0.05 s, 2 workers; this process's peak\n")
    print("| runs | wall (s) | runs/s | peak Python allocations (MB) | runs.csv (MB) |")
    print("| ---: | ---: | ---: | ---: | ---: |")
    with Sweeper(2) as sweeper:
        for size in sizes:
            cheap = seed_plan(size, "simulation.max_time=0.05")
            folder = scratch / f"m{size}"
            tracemalloc.start()
            wall, _, _ = timed_sweep(cheap, sweeper, folder)
            _, peak = tracemalloc.get_traced_memory()
            tracemalloc.stop()
            csv_mb = (folder / "runs.csv").stat().st_size / 1e6
            print(f"| {size} | {wall:.1f} | {size / wall:.0f} | {peak / 1e6:.1f} | {csv_mb:.1f} |")
            sys.stdout.flush()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=600, help="runs of each speed sweep")
    parser.add_argument("--rounds", type=int, default=3, help="rounds of the speed table")
    parser.add_argument(
        "--memory-runs", default="5000,50000", help="sweep sizes of the memory table"
    )
    args = parser.parse_args()
    sizes = [int(size) for size in args.memory_runs.split(",")]
    print(
        f"`python scripts/bench_sweep.py --runs {args.runs} --rounds {args.rounds} "
        f"--memory-runs {args.memory_runs}`"
    )
    print(
        f"on {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
        f"Python {platform.python_version()}; load average before: {_load()}\n"
    )
    with tempfile.TemporaryDirectory() as scratch:
        speed_table(args.runs, args.rounds, Path(scratch))
        memory_table(sizes, Path(scratch))
    print(f"\nload average after: {_load()}")
    max_rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"this process's largest resident size over the whole bench: {max_rss:.0f} MB")


if __name__ == "__main__":
    main()
