"""billiards and pooltool side by side: CPU per event, one run and many.

    python scripts/bench_pooltool.py --pooltool-python /work/pt-venv/bin/python
        [--runs 256] [--rounds 3] [--best-of 10] [--first-call]

pooltool (`pooltool-billiards`, installed in a venv of its own, never in this
project's) runs in a subprocess of that venv's interpreter; `billiards` runs in this
process. The shots:

- pooltool's 9-ball and 8-ball (15-ball) breaks as it ships them: `pt.get_rack` on
  `pt.Table.from_game_type`, the cue struck at 8 m/s at ball 1 (`pt.aim.at_ball`, its
  default tip, b = 0.25), `pt.simulate`; the rack's random placement seeded
  (`random` and `np.random` 0, and PYTHONHASHSEED=0: its 8-ball rack draws balls from
  a set of strings, whose order follows the process's string hashes);
- this project's seed break (`break`, the rolling model), `spin_break` and
  `pool_break` (the spin model; pockets), as shipped.

For each: contacts a run (ball-ball, cushion, jaw and pocket events; pooltool's
`ball_ball`, `ball_linear_cushion`, `ball_circular_cushion`, `ball_pocket`), events a
run (the contacts and the motion-state changes: pooltool's `sliding_rolling`,
`rolling_stationary`, ...; this project's `transitions`), microseconds of CPU per
event and per contact of one warm run alone (the best of `--best-of`), and many runs:
`--runs` variants with the cue ball moved across the shot by N(0, 1 mm) (seed 0),
runs per CPU-second, the best of `--rounds`. pooltool has no batch, so its figure is
that many single `pt.simulate` calls (the systems copied before the clock starts);
ours is one `billiards.simulation.simulate_batch` call (the scenes made before the
clock starts), which takes the compiled loop for the runs it supports
(`billiards.physics.compiled.runner.supports`) and the numpy engine for the others:
the table says which ran.

`--first-call`: a fresh process that imports the package and runs one break, its CPU
(interpreter, imports, numba compiling or loading, the run), with an empty
`NUMBA_CACHE_DIR` and then again with the cache it left.

Prints a markdown table with the command, the date, the load before and after, and
both numba versions. CPU time throughout (time.process_time; the children's rusage
for the first calls), so a busy machine disturbs it less than wall time.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import resource
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numba
import numpy as np

import billiards
from billiards.physics.compiled import runner
from billiards.physics.engine.result import SimulationResult
from billiards.scene.reader import Scene
from billiards.simulation import setup_from_scene, simulate_batch, simulate_scene

OURS = ("break", "spin_break", "pool_break")
THEIRS = ("NINEBALL", "EIGHTBALL")
JITTER = 0.001  # m: the cue ball's offset across the shot, N(0, JITTER), seed 0

# pooltool's side: one JSON request in argv, one JSON answer on stdout.
WORKER = r"""
import json, random, sys, time
request = json.loads(sys.argv[1])
clock = time.process_time()
import numba, numpy as np, pooltool as pt
imported = time.process_time() - clock
CONTACTS = {"ball_ball", "ball_linear_cushion", "ball_circular_cushion", "ball_pocket"}
SKIP = {"none", "stick_ball"}

def rack(name):
    random.seed(0)
    np.random.seed(0)
    game = getattr(pt.GameType, name)
    table = pt.Table.from_game_type(game)
    system = pt.System(table=table, balls=pt.get_rack(game, table), cue=pt.Cue(cue_ball_id="cue"))
    system.strike(V0=8, phi=pt.aim.at_ball(system, "1"))
    return system

def counts(system):
    kinds = [event.event_type.value for event in system.events]
    contacts = sum(kind in CONTACTS for kind in kinds)
    return contacts, sum(kind not in SKIP for kind in kinds)

def cpu(run):
    clock = time.process_time()
    run()
    return time.process_time() - clock

answer = {"pooltool": pt.__version__, "numba": numba.__version__, "numpy": np.__version__,
          "import_cpu": imported, "shots": {}}
if request.get("first_call"):
    answer["first_cpu"] = cpu(lambda: pt.simulate(rack("NINEBALL"), inplace=True))
    print(json.dumps(answer))
    sys.exit(0)
for name in request["games"]:
    base = rack(name)
    first = base.copy()
    pt.simulate(first, inplace=True)  # warm
    contacts, events = counts(first)
    best = float("inf")
    for _ in range(request["best_of"]):
        system = base.copy()
        best = min(best, cpu(lambda: pt.simulate(system, inplace=True)))
    rng = np.random.default_rng(0)
    offsets = rng.normal(0.0, request["jitter"], request["runs"])
    many, total = float("inf"), 0
    for _ in range(request["rounds"]):
        systems = [base.copy() for _ in offsets]
        for system, offset in zip(systems, offsets):
            system.balls["cue"].state.rvw[0, 0] += offset
        def run_all():
            for system in systems:
                pt.simulate(system, inplace=True)
        many = min(many, cpu(run_all))
        total = sum(counts(system)[1] for system in systems)
    answer["shots"][name] = {"balls": len(base.balls), "contacts": contacts, "events": events,
                             "one_cpu": best, "many_cpu": many, "many_events": total}
print(json.dumps(answer))
"""


def pooltool(python: str, request: dict[str, Any]) -> Any:
    """pooltool's answer to one request, from a process of its own venv."""
    out = subprocess.run(
        [python, "-c", WORKER, json.dumps(request)],
        capture_output=True,
        text=True,
        check=True,
        env=dict(os.environ, PYTHONHASHSEED="0"),
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def cpu(run: Callable[[], object]) -> float:
    clock = time.process_time()
    run()
    return time.process_time() - clock


def variants(name: str, count: int) -> list[Scene]:
    """`count` copies of a shipped scene, the cue ball moved across the shot (y)."""
    scene = billiards.vary(name, {})
    y = scene.balls[0].position[1]
    offsets = np.random.default_rng(0).normal(0.0, JITTER, count)
    return [billiards.vary(name, {"ball.cue.position.y": y + float(dy)}) for dy in offsets]


def our_shot(name: str, runs: int, rounds: int, best_of: int) -> dict[str, Any]:
    """One shipped scene's figures, as pooltool's worker gives its own."""
    scene = billiards.vary(name, {})
    result = simulate_scene(scene)  # warm (and compiled, or loaded from the cache)
    contacts = len(result.events)
    one = min(cpu(lambda: simulate_scene(scene)) for _ in range(best_of))
    scenes = variants(name, runs)
    many = float("inf")
    for _ in range(rounds):
        clock = time.process_time()
        results = list(simulate_batch(scenes))
        many = min(many, time.process_time() - clock)
    done = [r for r in results if isinstance(r, SimulationResult)]
    assert len(done) == len(results)  # no run failed
    setup = setup_from_scene(scene)
    compiled = runner.supports(setup, scene.simulation.method)
    return {
        "balls": len(result.ball_ids),
        "contacts": contacts,
        "events": contacts + len(result.transitions),
        "one_cpu": one,
        "many_cpu": many,
        "many_events": sum(len(r.events) + len(r.transitions) for r in done),
        "engine": f"{setup.model}, " + ("compiled" if compiled else "numpy"),
    }


def first_calls(python: str) -> dict[str, tuple[float, float]]:
    """(empty cache, warm cache) CPU s of a fresh process that imports and runs a break."""
    ours = [sys.executable, "-c", "import billiards; billiards.run('break')"]
    theirs = [python, "-c", WORKER, json.dumps({"first_call": True})]
    found: dict[str, tuple[float, float]] = {}
    for label, command in (("billiards, seed break", ours), ("pooltool, 9-ball break", theirs)):
        with tempfile.TemporaryDirectory() as cache:
            env = dict(os.environ, NUMBA_CACHE_DIR=cache, PYTHONHASHSEED="0")
            cold, warm = (child_cpu(command, env) for _ in range(2))
        found[label] = (cold, warm)
    return found


def child_cpu(command: list[str], env: dict[str, str]) -> float:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(command, env=env, check=True, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def figure(value: float) -> str:
    return f"{value:,.1f}" if value < 100 else f"{value:,.0f}"


def row(label: str, engine: str, shot: dict[str, Any], runs: int) -> str:
    one_ms = shot["one_cpu"] * 1e3
    per_event = shot["one_cpu"] / shot["events"] * 1e6
    per_contact = shot["one_cpu"] / shot["contacts"] * 1e6
    per_run_event = shot["many_cpu"] / shot["many_events"] * 1e6
    return (
        f"| {label} | {engine} | {shot['balls']} | {shot['contacts']} | {shot['events']} "
        f"| {one_ms:.1f} | {per_event:.0f} | {per_contact:.0f} "
        f"| {figure(runs / shot['many_cpu'])} | {per_run_event:.1f} |"
    )


HEADER = [
    "| shot | engine | balls | contacts a run | events a run | one run, ms CPU "
    "| us CPU an event | us CPU a contact | runs per CPU-s (many) | us CPU a run-event (many) |",
    "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pooltool-python", required=True, help="the pooltool venv's python")
    parser.add_argument("--runs", type=int, default=256)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--best-of", type=int, default=10)
    parser.add_argument("--first-call", action="store_true")
    args = parser.parse_args()
    if not Path(args.pooltool_python).is_file():
        print(f"bench_pooltool: no python at {args.pooltool_python}", file=sys.stderr)
        raise SystemExit(2)
    load_before = os.getloadavg()[0]
    request = {
        "games": THEIRS,
        "runs": args.runs,
        "rounds": args.rounds,
        "best_of": args.best_of,
        "jitter": JITTER,
    }
    theirs = pooltool(args.pooltool_python, request)
    ours = {name: our_shot(name, args.runs, args.rounds, args.best_of) for name in OURS}
    firsts = first_calls(args.pooltool_python) if args.first_call else {}
    lines = [
        "$ python " + " ".join(sys.argv),
        f"{datetime.datetime.now(datetime.UTC):%Y-%m-%d %H:%M} UTC, {platform.machine()}, "
        f"{os.cpu_count()} cores, load {load_before:.1f} before, {os.getloadavg()[0]:.1f} after",
        f"billiards: CPython {platform.python_version()}, numba {numba.__version__}, "
        f"numpy {np.__version__}; pooltool {theirs['pooltool']}: numba {theirs['numba']}, "
        f"numpy {theirs['numpy']}; many = {args.runs} variants (best of {args.rounds}), "
        f"one run: best of {args.best_of}",
        "",
        *HEADER,
    ]
    for name, shot in theirs["shots"].items():
        game = {"NINEBALL": "9-ball break", "EIGHTBALL": "8-ball break"}[name]
        lines.append(row(f"pooltool {game}", "pooltool, one at a time", shot, args.runs))
    for name, shot in ours.items():
        lines.append(row(f"billiards `{name}`", shot["engine"], shot, args.runs))
    if firsts:
        lines += [
            "",
            "| fresh process: import, one break | CPU s, empty NUMBA_CACHE_DIR "
            "| CPU s, warm cache |",
            "| --- | ---: | ---: |",
        ]
        lines += [
            f"| {label} | {cold:.2f} | {warm:.2f} |" for label, (cold, warm) in firsts.items()
        ]
    print("\n".join(lines))


if __name__ == "__main__":
    main()
