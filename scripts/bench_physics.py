"""Physics speed: wall time per seed break, by method and step.

    python scripts/bench_physics.py [--repeats 21] [--scene SCENE]

Prints a markdown table: method x dt, median warm wall time per break (after one
untimed run), events and events per second, steps taken; then the same scene with
`[table] pockets` off and on, timed alternately (the issue's bound: on costs at most
1.3x off, per break); then the cold time of
`python -m billiards.simulate` (interpreter start, imports and one break) as a user
sees it. The machine's speed swings from minute to minute: compare rows of one run.
"""

from __future__ import annotations

import argparse
import platform
import statistics
import subprocess
import sys
import time
from dataclasses import replace

import numpy as np

from billiards.scene.reader import Scene, load_scene
from billiards.simulation import simulate_scene

CASES = [
    ("event", None),
    ("exact", 1 / 30),
    ("exact", 1 / 240),
    ("exact", 1 / 1000),
    ("naive", 1 / 240),
    ("naive", 1 / 1000),
]


def warm_time(
    scene_path: str | None, method: str, dt: float | None, repeats: int
) -> tuple[float, int, int]:
    scene = load_scene(scene_path)
    result = simulate_scene(scene, method=method, dt=dt)  # warm: imports, caches, allocations
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        result = simulate_scene(scene, method=method, dt=dt)
        times.append(time.perf_counter() - start)
    return statistics.median(times), len(result.events), result.steps


def pockets_row(scene: Scene, method: str, dt: float | None, repeats: int) -> str:
    """One row: the scene with pockets off and on, timed alternately in one sitting."""
    tables = {on: replace(scene, table=replace(scene.table, pockets=on)) for on in (False, True)}
    times: dict[bool, list[float]] = {False: [], True: []}
    events = {}
    for on, table in tables.items():  # warm
        events[on] = len(simulate_scene(table, method=method, dt=dt).events)
    for _ in range(repeats):
        for on, table in tables.items():
            start = time.perf_counter()
            simulate_scene(table, method=method, dt=dt)
            times[on].append(time.perf_counter() - start)
    closed, open_ = statistics.median(times[False]), statistics.median(times[True])
    step = "-" if dt is None else f"1/{round(1 / dt)}"
    per_event = open_ / events[True] / (closed / events[False])
    return (
        f"| {method} | {step} | {closed * 1e3:.2f} | {open_ * 1e3:.2f} | {open_ / closed:.2f} | "
        f"{events[False]} | {events[True]} | {per_event:.2f} |"
    )


def cold_time(scene_path: str | None, repeats: int = 5) -> float:
    command = [sys.executable, "-m", "billiards.simulate"] + ([scene_path] if scene_path else [])
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=21, help="timed runs per row (median)")
    parser.add_argument("--scene", default=None, help="scene file (default: the seed break)")
    args = parser.parse_args()

    print(f"# Physics speed: {args.scene or 'the seed break'}")
    print()
    print(f"`python scripts/bench_physics.py --repeats {args.repeats}`")
    print(
        f"on {platform.machine()}, {platform.python_implementation()} {platform.python_version()}, numpy {np.__version__}"
    )
    print()
    print("| method | dt (s) | warm wall time (ms, median) | events | events/s | steps |")
    print("| --- | --- | ---: | ---: | ---: | ---: |")
    for method, dt in CASES:
        seconds, events, steps = warm_time(args.scene, method, dt, args.repeats)
        step = "-" if dt is None else f"1/{round(1 / dt)}"
        print(
            f"| {method} | {step} | {seconds * 1e3:.2f} | {events} | {events / seconds:,.0f} | {steps} |"
        )
    print()
    print("Pockets off and on (`[table] pockets`), timed alternately, ms median:")
    print()
    print("| method | dt (s) | off | on | on/off | events off | events on | per event on/off |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    scene = load_scene(args.scene)
    for method, dt in CASES[:3]:
        print(pockets_row(scene, method, dt, args.repeats))
    print()
    print(
        f"cold `python -m billiards.simulate` (start, imports, one break): {cold_time(args.scene):.3f} s median of 5"
    )


if __name__ == "__main__":
    main()
