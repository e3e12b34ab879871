"""Many runs at once: the serial loop of simulate_scene against simulate_batch.

    python scripts/bench_batch.py [--runs 100] [--rounds 3] [--flat 1000,10000]
                                  [--cases seed,spin_seed,spin_break,pool_break] [--profile]

Issue 19's table, on one core (this process), for four families of runs whose inputs
are drawn as a sweep draws them (billiards.sweep: PCG64 and draws.normal, seed 0):

- `seed`: the seed break (rolling model), the cue ball's y ~ N(0.5325, 0.001) m;
- `spin_seed`: the same break in the spin model ([physics] model = "spin");
- `spin_break`: the shipped spin_break, its tip drawn (side ~ N(0, 0.02), height ~
  N(-0.05, 0.02), in radii);
- `pool_break`: the shipped pool_break (spin, Han 2005, pockets), the cue ball's y ~
  N(0.5, 0.001) m;
- `hard_break`: the Sweeps example (velocity and position drawn);
- `constants` (issue 35): the seed break with its rolling friction ~ U(0.009, 0.011),
  sliding friction ~ U(0.18, 0.22), ball restitution ~ U(0.9, 1) and cushion retention
  ~ U(0.7, 0.8) drawn per run, nothing else (before issue 35, a batch of one a run);
- `counts` (issue 35): the `seed` family with its last 0-3 balls taken away (run i
  keeps 16 - i % 4): a batch mixing 13-16 balls, to compare with `seed` per run-event.

Each round times (CPU time of this process) the serial loop and simulate_batch on the
same scenes, back to back
(a neighbour's load then hits a round, not a column); the table gives the range over
rounds of runs/s, of microseconds per run-event (an event: a contact, a drop or a
motion-state change, as the calendar resolves them) and of the batch/serial speedup,
and the speedup of each column's fastest round (best / best: on a shared machine the
round a neighbour disturbed least, for the loop and the batch alike).
Scenes are built before timing. Memory is this process's peak of Python allocations
(tracemalloc) over one more pass of each, results dropped as they come; `--flat` runs
the seed break cut at 0.05 s through simulate_batch at each size to show whether that
peak grows with the number of runs, and states it per run of a batch (BATCH_SIZE runs). `--profile` prints
cProfile's top functions for one seed break.

`--batch-only` times simulate_batch alone; with PYTHONPATH set to another tree (e.g.
`git worktree add /tmp/old def110f`) it times that tree's engine on the same scenes, for
old/new comparisons alternated in one sitting.

`--kernel` measures what a calendar over a run axis would gain on the hottest call of
a seed break (contact_times.pair_contacts, 58% of its cProfile time): R seed-break runs
are each taken to their 10th event, then the pairs of the two balls the next contact
would re-anchor (29 pairs a run) are asked R times, one call per run, against once,
with the runs' anchors stacked as rows (run, ball) and pairs only within a run. The
stacked call is timed at one `now` for all runs (the calendar would pass one per run),
so it measures cost only: its times are not the runs' own.
"""

from __future__ import annotations

import argparse
import copy
import cProfile
import dataclasses
import os
import platform
import pstats
import sys
import time
import tracemalloc
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass

import numpy as np

from billiards.physics.engine.calendar import Calendar
from billiards.physics.engine.result import SimulationResult
from billiards.physics.rolling.contact_times import pair_contacts
from billiards.physics.rolling.motion import Anchors
from billiards.scene.reader import Scene
from billiards.simulation import BATCH_SIZE, setup_from_scene, simulate_batch, simulate_scene
from billiards.sweep.variations import SceneData, Variations, load_scene_data, parse_vary


@dataclass(frozen=True)
class Case:
    name: str
    scene: str  # a shipped scene
    vary: tuple[str, ...]  # --vary specs
    spin: bool = False  # set [physics] model = "spin"
    fewer: int = 0  # run i drops its last i % (fewer + 1) balls


CASES = {
    "seed": Case("seed break, rolling", "break", ("ball.cue.position.y=0.5325~0.001",)),
    "spin_seed": Case(
        "seed break, spin model", "break", ("ball.cue.position.y=0.5325~0.001",), spin=True
    ),
    "spin_break": Case(
        "spin_break, tip drawn",
        "spin_break",
        ("ball.cue.tip.side=0~0.02", "ball.cue.tip.height=-0.05~0.02"),
    ),
    "pool_break": Case("pool_break", "pool_break", ("ball.cue.position.y=0.5~0.001",)),
    "hard_break": Case(
        "hard_break (the Sweeps example)",
        "hard_break",
        ("ball.cue.velocity=9.5:10.5", "ball.cue.position.y=0.5325~0.001"),
    ),
    "constants": Case(
        "seed break, 4 constants drawn",
        "break",
        (
            "physics.rolling_friction=0.009:0.011",
            "physics.sliding_friction=0.18:0.22",
            "physics.ball_restitution=0.9:1.0",
            "table.cushion_retention=0.7:0.8",
        ),
    ),
    "counts": Case(
        "seed break, 13-16 balls", "break", ("ball.cue.position.y=0.5325~0.001",), fewer=3
    ),
}


def scene_data(case: Case) -> SceneData:
    data = load_scene_data(case.scene)
    if not case.spin:
        return data
    tables = copy.deepcopy(data.data)
    tables.setdefault("physics", {})["model"] = "spin"
    return SceneData(tables, data.build(copy.deepcopy(tables)))


def scenes(case: Case, runs: int, *extra: str) -> Iterator[Scene]:
    """Run i's scene, drawn as a sweep's run i (seed 0)."""
    data = scene_data(case)
    variations = Variations(tuple(parse_vary(text) for text in (*case.vary, *extra)), seed=0)
    for run in range(runs):
        scene = data.build(data.with_values(variations.values(run)))
        kept = len(scene.balls) - run % (case.fewer + 1)
        yield dataclasses.replace(scene, balls=scene.balls[:kept])


def serial(batch: list[Scene]) -> Iterator[SimulationResult | Exception]:
    for scene in batch:
        yield simulate_scene(scene)


def batched(batch: list[Scene]) -> Iterator[SimulationResult | Exception]:
    return simulate_batch(batch)


def events_of(outcome: SimulationResult | Exception) -> int:
    if isinstance(outcome, Exception):
        raise outcome
    return len(outcome.events) + len(outcome.transitions)


def timed(
    loop: Callable[[list[Scene]], Iterable[SimulationResult | Exception]], batch: list[Scene]
) -> tuple[float, int]:
    """CPU seconds of this process in one pass (not wall: the machine may be shared, and
    a neighbour's load would count) and the events it resolved (results dropped as
    they come)."""
    start = time.process_time()
    events = sum(events_of(outcome) for outcome in loop(batch))
    return time.process_time() - start, events


def peak_bytes(
    loop: Callable[[list[Scene]], Iterable[SimulationResult | Exception]], batch: list[Scene]
) -> int:
    tracemalloc.start()
    for outcome in loop(batch):
        events_of(outcome)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return peak


def span(values: list[float], form: str) -> str:
    low, high = min(values), max(values)
    return f"{low:{form}}-{high:{form}}" if f"{low:{form}}" != f"{high:{form}}" else f"{low:{form}}"


def speed_table(keys: list[str], runs: int, rounds: int) -> None:
    print(f"Speed: {runs} runs a family, {rounds} rounds, ranges over rounds\n")
    print(
        "| family | events a run | serial runs/CPU-s | batch runs/CPU-s | serial us/run-event "
        "| batch us/run-event | batch / serial | best / best | serial peak MB | batch peak MB |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for key in keys:
        case = CASES[key]
        batch = list(scenes(case, runs))
        timed(serial, batch[:2])  # warm: imports and caches
        rates: dict[str, list[float]] = {"serial": [], "batch": []}
        costs: dict[str, list[float]] = {"serial": [], "batch": []}
        ratios = []
        events = 0
        for _ in range(rounds):
            walls = {}
            for name, loop in (("serial", serial), ("batch", batched)):
                wall, events = timed(loop, batch)
                walls[name] = wall
                rates[name].append(runs / wall)
                costs[name].append(wall / events * 1e6)
            ratios.append(walls["serial"] / walls["batch"])
        memory = {
            name: peak_bytes(loop, batch) / 1e6
            for name, loop in (("serial", serial), ("batch", batched))
        }
        print(
            f"| {case.name} | {events / runs:.0f} | {span(rates['serial'], '.1f')} "
            f"| {span(rates['batch'], '.1f')} | {span(costs['serial'], '.0f')} "
            f"| {span(costs['batch'], '.1f')} | {span(ratios, '.2f')}x "
            f"| {max(rates['batch']) / max(rates['serial']):.2f}x "
            f"| {memory['serial']:.2f} | {memory['batch']:.2f} |"
        )
        sys.stdout.flush()


def batch_only_table(keys: list[str], runs: int, rounds: int) -> None:
    """simulate_batch alone (no serial loop), CPU seconds a round: for comparing two
    trees in one sitting (PYTHONPATH=OTHER_TREE python scripts/bench_batch.py
    --batch-only, alternately with this tree)."""
    import billiards

    print(f"Batch only, billiards from {billiards.__file__.rsplit('/billiards/', 1)[0]}\n")
    print("| family | runs | events a run | CPU s a round | best us/run-event |")
    print("| --- | ---: | ---: | --- | ---: |")
    for key in keys:
        batch = list(scenes(CASES[key], runs))
        timed(batched, batch[:4])  # warm
        seconds = []
        events = 0
        for _ in range(rounds):
            cpu, events = timed(batched, batch)
            seconds.append(cpu)
        listed = ", ".join(f"{value:.3f}" for value in seconds)
        print(
            f"| {key} | {runs} | {events / runs:.1f} | {listed} "
            f"| {min(seconds) / events * 1e6:.2f} |"
        )
        sys.stdout.flush()


def flat_table(sizes: list[int]) -> None:
    print(
        f"\nMemory against runs: the seed break cut at 0.05 s, simulate_batch (batch size {BATCH_SIZE})\n"
    )
    print("| runs | wall (s) | peak Python allocations (MB) | kB per run of a batch |")
    print("| ---: | ---: | ---: | ---: |")
    for size in sizes:
        start = time.perf_counter()
        tracemalloc.start()
        for outcome in simulate_batch(scenes(CASES["seed"], size, "simulation.max_time=0.05")):
            events_of(outcome)
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
        per_run = peak / 1e3 / min(size, BATCH_SIZE)
        print(f"| {size} | {time.perf_counter() - start:.1f} | {peak / 1e6:.2f} | {per_run:.1f} |")
        sys.stdout.flush()


def profile_seed_break() -> None:
    scene = next(scenes(CASES["seed"], 1))
    simulate_scene(scene)  # warm
    profiler = cProfile.Profile()
    profiler.enable()
    for _ in range(20):
        result = simulate_scene(scene)
    profiler.disable()
    events = len(result.events) + len(result.transitions)
    print(f"\nProfile: 20 seed breaks ({events} events each), cProfile, by own time\n")
    stats = pstats.Stats(profiler, stream=sys.stdout)
    stats.sort_stats("tottime").print_stats(25)


def kernel_table(sizes: list[int], rounds: int) -> None:
    print(
        "\nThe pair-time kernel (pair_contacts) after a seed break's 10th event, 29 pairs a run\n"
    )
    print("| runs | one call a run (us a run) | one call for all (us a run) | gain |")
    print("| ---: | ---: | ---: | ---: |")
    for size in sizes:
        states = []
        for scene in scenes(CASES["seed"], size):
            calendar = Calendar(setup_from_scene(scene))
            for _ in range(10):
                calendar.resolve_next()
            anchors = calendar.law.anchors  # type: ignore[attr-defined]
            count = len(calendar.edge_time)
            balls = [0, 1]
            pairs = [(min(b, o), max(b, o)) for b in balls for o in range(count) if o != b]
            pairs = sorted(set(pairs))
            first = np.array([p[0] for p in pairs])
            second = np.array([p[1] for p in pairs])
            states.append((anchors, first, second, calendar.next_time(), calendar.edge_time))
        radius = setup_from_scene(next(scenes(CASES["seed"], 1))).radius
        stacked = _stacked(states)
        alone_times, stacked_times = [], []
        for _ in range(rounds):
            start = time.perf_counter()
            for anchors, first, second, now, ends in states:
                pair_contacts(anchors, first, second, now, ends, radius)
            alone_times.append((time.perf_counter() - start) / size * 1e6)
            start = time.perf_counter()
            pair_contacts(*stacked, radius)
            stacked_times.append((time.perf_counter() - start) / size * 1e6)
        alone, together = min(alone_times), min(stacked_times)
        print(f"| {size} | {alone:.1f} | {together:.2f} | {alone / together:.0f}x |")
        sys.stdout.flush()


def _stacked(
    states: list[tuple[Anchors, np.ndarray, np.ndarray, float, np.ndarray]],
) -> tuple[Anchors, np.ndarray, np.ndarray, float, np.ndarray]:
    """The runs' anchors as rows (run, ball), their pairs offset to their run's rows."""
    offsets = np.cumsum([0] + [len(state[0].t0) for state in states])
    fields = ("t0", "p0", "v0", "speed", "direction", "rest_after", "stop_time", "rest_position")
    joined = {name: np.concatenate([getattr(s[0], name) for s in states]) for name in fields}
    anchors = Anchors(**joined, decel=states[0][0].decel)
    first = np.concatenate([s[1] + offset for s, offset in zip(states, offsets, strict=False)])
    second = np.concatenate([s[2] + offset for s, offset in zip(states, offsets, strict=False)])
    ends = np.concatenate([s[4] for s in states])
    return anchors, first, second, float(np.median([s[3] for s in states])), ends


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=100, help="runs of each family")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--cases", default=",".join(CASES), help="families, comma-separated")
    parser.add_argument("--flat", default="", help="sizes of the memory-against-runs table")
    parser.add_argument("--profile", action="store_true", help="profile one seed break")
    parser.add_argument(
        "--batch-only", action="store_true", help="time simulate_batch alone (no serial loop)"
    )
    parser.add_argument(
        "--kernel", default="", help="runs of the pair-kernel table, e.g. 1,10,100,1000"
    )
    args = parser.parse_args()
    keys = args.cases.split(",")
    print(" ".join(["`python scripts/bench_batch.py", *sys.argv[1:]]) + "`")
    load = ", ".join(f"{value:.2f}" for value in os.getloadavg())
    print(
        f"on {platform.processor() or platform.machine()}, {os.cpu_count()} cores (one used), "
        f"Python {platform.python_version()}; load average before: {load}\n"
    )
    if args.batch_only:
        batch_only_table(keys, args.runs, args.rounds)
    else:
        speed_table(keys, args.runs, args.rounds)
    if args.flat:
        flat_table([int(size) for size in args.flat.split(",")])
    if args.kernel:
        kernel_table([int(size) for size in args.kernel.split(",")], args.rounds)
    if args.profile:
        profile_seed_break()
    load = ", ".join(f"{value:.2f}" for value in os.getloadavg())
    print(f"\nload average after: {load}")


if __name__ == "__main__":
    main()
