"""The compiled loop (billiards.physics.compiled) against the numpy engine.

    python scripts/bench_compiled.py [--runs 256] [--rounds 3] [--threads 2]
                                     [--balls 16,50,100,200]

Three tables, CPU time of this process (wall time where threads run):

- one run: microseconds of CPU per event (a contact or a drop, as the calendar
  resolves them; and for the spin model a motion-state change too, each an event the
  loop resolves) of the seed break, hard_break and a random 16-ball scene (the hard
  cases' scene family), and in the spin model spin_break, three_cushion (Han 2005
  cushions, the frictional ball law), pool_break (pockets, Han 2005), english_bank with
  Mathavan 2010 cushions and a random 16-ball spin scene with random spins, by the
  numpy engine (methods.entry with the compiled loop refused) and by the compiled
  loop, each run alone, the best of `--rounds`;
- many runs: `--runs` seed-break variants in one call (the cue ball's y ~ N(0.5325,
  0.001) m, as a sweep draws it, seed 0): the numpy batch (engine.batch), the compiled
  loop alone (packed and logged, no results made), and with its results serially and on
  `--threads` threads (jit.thread_count: numba's thread count,
  set here); runs per CPU-second, and per wall-second;
- many balls: random scenes of `--balls` balls in the rolling model (the hard cases'
  family, seed 1), compiled, microseconds of CPU per event and its ratio to the first
  count's (issue 43: at most 3x from 16 to 200 balls).

The compiled loop is compiled (or loaded from numba's cache) before any timing; the
results of every column are checked equal before they are timed. Prints the command,
the machine's load and numba's version with the tables.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Callable
from dataclasses import replace

import numba
import numpy as np

from billiards.physics.compiled import loop
from billiards.physics.compiled import runner as compiled
from billiards.physics.compiled.state import MODELS
from billiards.physics.engine.packaging import Run
from billiards.physics.engine.result import SimulationResult
from billiards.physics.methods import entry as methods
from billiards.scene.reader import default_scene_path, load_scene
from billiards.simulation import _run_of


def numpy_engine(items: list[Run]) -> list[SimulationResult]:
    """The numpy engine's results (the compiled loop refused every run)."""
    supports = methods.compiled.supports
    methods.compiled.supports = lambda setup, method: False
    try:
        results = list(methods.run_batch(items))
    finally:
        methods.compiled.supports = supports
    assert all(isinstance(result, SimulationResult) for result in results)
    return results  # type: ignore[return-value]


def compiled_serial(items: list[Run]) -> list[SimulationResult]:
    return compiled.run_compiled(items)


def compiled_threads(items: list[Run]) -> list[SimulationResult]:
    return compiled.run_compiled(items, threads=True)


def compiled_loop(items: list[Run]) -> None:
    """The compiled loop over the runs, packed and logged, without making their results
    (what the fitter's samples and a summary need; the results' Python is the rest)."""
    runs = compiled._packed(
        [setup for setup, *_ in items], [item[2] for item in items], [item[3] for item in items]
    )
    balls = max(len(setup.positions) for setup, *_ in items)
    model = MODELS.index(items[0][0].model)  # one model a call, as run_compiled's
    room = compiled._first_room(len(items), balls, model)
    logs = compiled._logs(len(items), room, balls, model)
    loop.run_many(runs, logs, 0, len(items))
    assert not logs.filled[:, 2].any()  # no log overflowed: every run ran whole


def timed(run: Callable[[list[Run]], object], items: list[Run], rounds: int) -> tuple[float, float]:
    """The best (CPU s, wall s) of `rounds` calls."""
    best = (float("inf"), float("inf"))
    for _ in range(rounds):
        cpu, wall = time.process_time(), time.perf_counter()
        run(items)
        best = min(best, (time.process_time() - cpu, time.perf_counter() - wall))
    return best


def variants(count: int) -> list[Run]:
    base = _run_of(load_scene(default_scene_path()), "event", None)
    rng = np.random.default_rng(0)
    runs = []
    for _ in range(count):
        positions = base[0].positions.copy()
        positions[0, 1] = rng.normal(0.5325, 0.001)
        runs.append((replace(base[0], positions=positions), base[1], "event", base[3]))
    return runs


def random_scene(count: int, seed: int = 1) -> Run:
    """`count` balls anywhere on the seed's table, apart, each at up to 3 m/s in any
    direction (the random draws' seed: 1 for the tables here)."""
    base = _run_of(load_scene(default_scene_path()), "event", None)[0]
    rng = np.random.default_rng(seed)
    low, high = base.bounds[[0, 2]], base.bounds[[1, 3]]
    placed: list[np.ndarray] = []
    while len(placed) < count:
        candidate = rng.uniform(low, high)
        if all(np.hypot(*(candidate - other)) > 2.0 * base.radius for other in placed):
            placed.append(candidate)
    speeds, angles = rng.uniform(0.0, 3.0, count), rng.uniform(0.0, 2.0 * np.pi, count)
    velocities = np.stack([speeds * np.cos(angles), speeds * np.sin(angles)], axis=1)
    setup = replace(
        base, positions=np.array(placed), velocities=velocities, masses=np.full(count, 0.165)
    )
    return (setup, tuple(f"b{n}" for n in range(count)), "event", 1 / 240)


def spin_scenes() -> dict[str, Run]:
    """The spin model's rows: spin_break, three_cushion, pool_break, english_bank with
    Mathavan 2010's cushions (nose at 1.6 R), and the random 16-ball scene with spins up
    to 100 rad/s on each axis (seed 2)."""
    folder = default_scene_path().parent
    scenes = {
        name: _run_of(load_scene(folder / f"{name}.toml"), "event", None)
        for name in ("spin_break", "three_cushion", "pool_break")
    }
    bank = _run_of(load_scene(folder / "english_bank.toml"), "event", None)
    nose = 1.6 * bank[0].radius
    integrated = replace(bank[0], cushion_law="mathavan2010", cushion_height=nose)
    scenes["english_bank, mathavan2010"] = (integrated, *bank[1:])
    setup, ids, method, dt = random_scene(16)
    spins = np.random.default_rng(2).uniform(-100.0, 100.0, (16, 3))
    scenes["random 16 balls, spin"] = (replace(setup, model="spin", spins=spins), ids, method, dt)
    return scenes


def events_of(result: SimulationResult) -> int:
    """The events the loop resolved: contacts, and the spin model's state changes."""
    return len(result.events) + len(result.transitions)


def one_run_table(rounds: int) -> list[str]:
    scenes = {
        name: _run_of(load_scene(default_scene_path().parent / f"{name}.toml"), "event", None)
        for name in ("break", "hard_break")
    }
    scenes["random 16 balls"] = random_scene(16)
    scenes.update(spin_scenes())
    lines = [
        "| run | model | events | numpy us/event | compiled us/event | ratio |",
        "|---|---|---|---|---|---|",
    ]
    for name, item in scenes.items():
        reference = numpy_engine([item])[0]
        assert compiled.supports(item[0], item[2]), name
        assert compiled_serial([item])[0].events == reference.events
        events = events_of(reference)
        slow = timed(numpy_engine, [item], rounds)[0] / events * 1e6
        fast = timed(compiled_serial, [item], max(rounds, 20))[0] / events * 1e6
        model = item[0].model
        lines.append(
            f"| {name} | {model} | {events} | {slow:.0f} | {fast:.1f} | {slow / fast:.0f}x |"
        )
    return lines


def balls_table(counts: list[int], rounds: int) -> list[str]:
    """The rolling model's cost per event as the table fills: random scenes of each
    count, compiled, each run alone (the numpy engine not timed: minutes at 200 balls)."""
    lines = [
        "| random balls | events | compiled us/event | x the first row |",
        "|---|---|---|---|",
    ]
    first = 0.0
    for count in counts:
        item = random_scene(count)
        events = events_of(compiled_serial([item])[0])
        cost = timed(compiled_serial, [item], rounds)[0] / events * 1e6
        first = first or cost
        lines.append(f"| {count} | {events} | {cost:.1f} | {cost / first:.1f}x |")
    return lines


def many_runs_table(count: int, rounds: int) -> list[str]:
    items = variants(count)
    reference = numpy_engine(items)
    for checked in (compiled_serial, compiled_threads):
        assert [r.events for r in checked(items)] == [r.events for r in reference]
    events = sum(len(result.events) for result in reference)
    lines = [
        f"| {count} seed-break variants ({events} events) | CPU s | wall s | runs per CPU-s "
        "| runs per wall-s | us CPU per run-event |",
        "|---|---|---|---|---|---|",
    ]
    columns: dict[str, Callable[[list[Run]], object]] = {
        "numpy batch": numpy_engine,
        "compiled loop alone (no results made)": compiled_loop,
        "compiled, serial": compiled_serial,
        f"compiled, {numba.get_num_threads()} threads": compiled_threads,
    }
    for name, column in columns.items():
        cpu, wall = timed(column, items, rounds)
        lines.append(
            f"| {name} | {cpu:.3f} | {wall:.3f} | {count / cpu:,.0f} | {count / wall:,.0f} "
            f"| {cpu / events * 1e6:.2f} |"
        )
    return lines


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=256)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument(
        "--balls",
        type=lambda text: [int(count) for count in text.split(",")],
        default=[16, 50, 100, 200],
        help="the random scenes' ball counts of the third table",
    )
    args = parser.parse_args()
    numba.set_num_threads(min(args.threads, numba.config.NUMBA_NUM_THREADS))  # type: ignore[attr-defined]
    compiled_serial(variants(1))  # compiled, or loaded from the cache, before timing
    compiled_serial([spin_scenes()["spin_break"]])
    compiled_threads(variants(2))
    print("$ python " + " ".join(sys.argv))
    print(f"load {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores, numba {numba.__version__}")
    print()
    print("\n".join(one_run_table(args.rounds)))
    print()
    print("\n".join(many_runs_table(args.runs, args.rounds)))
    print()
    print("\n".join(balls_table(args.balls, args.rounds)))


if __name__ == "__main__":
    main()
