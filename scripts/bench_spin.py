"""The spin model's cost against the rolling model's, on the same scene.

    python scripts/bench_spin.py [--repeats 11] [--scene SCENE]

Runs the scene (default: the shipped spin_break) as written (model = "spin") and again
with [physics] model = "rolling" (same balls, velocities and restitution; spin and tip
ignored), by each method, and prints a markdown table: median warm wall time per run,
contacts, motion-state changes, and the spin/rolling ratio. The issue asks for at most
2x. The machine's speed swings from minute to minute: compare rows of one run.
"""

from __future__ import annotations

import argparse
import dataclasses
import platform
import statistics
import time

from billiards.scene import Scene, default_scene_path, load_scene
from billiards.simulation import simulate_scene

CASES = [("event", None), ("exact", 1 / 30), ("exact", 1 / 240), ("exact", 1 / 1000)]


def warm_time(scene: Scene, method: str, dt: float | None, repeats: int) -> tuple[float, int, int]:
    result = simulate_scene(scene, method=method, dt=dt)  # warm: imports, caches
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        result = simulate_scene(scene, method=method, dt=dt)
        times.append(time.perf_counter() - start)
    return statistics.median(times), len(result.events), len(result.transitions)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=11)
    parser.add_argument("--scene", default=str(default_scene_path().parent / "spin_break.toml"))
    args = parser.parse_args()
    spin = load_scene(args.scene)
    rolling = dataclasses.replace(spin, physics=dataclasses.replace(spin.physics, model="rolling"))
    print(f"# Spin model cost: {args.scene}")
    print(f"\n{platform.processor() or platform.machine()}, median of {args.repeats} warm runs\n")
    print(
        "| method | dt | rolling (ms) | contacts | spin (ms) | contacts | state changes | spin / rolling |"
    )
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for method, dt in CASES:
        rolled, rolled_events, _ = warm_time(rolling, method, dt, args.repeats)
        spun, spun_events, changes = warm_time(spin, method, dt, args.repeats)
        step = "-" if dt is None else f"1/{round(1 / dt)}"
        print(
            f"| {method} | {step} | {rolled * 1e3:.1f} | {rolled_events} | {spun * 1e3:.1f} "
            f"| {spun_events} | {changes} | {spun / rolled:.2f} |"
        )


if __name__ == "__main__":
    main()
