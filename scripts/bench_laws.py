"""The compiled contact laws (billiards.physics.compiled.laws) against the numpy laws.

    python scripts/bench_laws.py [--contacts 2000] [--rounds 3]

Two tables:

- per call: microseconds of CPU per contact of each law, the numpy law called on one
  contact as the numpy engine calls it (CUSHION_LAWS / BALL_LAWS, a run's constants as
  floats) and the compiled law through the dispatch (compiled.laws.rows, a loop over
  `--contacts` contacts inside compiled code, so no Python per contact); the best of
  `--rounds`. Every contact approaches (the law's work is done): a ball at 0.5-5 m/s
  into a cushion or another ball from any angle, spins up to 100 rad/s, the seed's
  constants (rules.seed), seed 0. The results are checked equal before they are timed.
- cold compile: seconds of CPU and wall to compile each law alone, and all of them
  through the dispatch (both rows entries), each in a fresh process with an empty
  NUMBA_CACHE_DIR (after `import numba`, which is timed apart); and the same first call
  in a second process, loading what the first one cached (a law alone is called from a
  small function that cannot be cached: its warm figures include compiling that).

Prints the command, the machine's load and numba's version with the tables.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable

import numba
import numpy as np

from billiards.physics.compiled.laws import BALL_LAW_IDS, CUSHION_LAW_IDS, CushionNumbers
from billiards.physics.compiled.laws.rows import ball_rows, cushion_rows
from billiards.physics.engine.setup import Setup
from billiards.physics.laws import BALL_LAWS, CUSHION_LAWS
from billiards.physics.laws.ball_ball import PairContact
from billiards.physics.laws.cushion import CushionConstants, CushionContact

SETUP = Setup.of([[0.0, 0.0]], model="spin")  # the seed's constants
CUSHION_CONSTANTS = CushionConstants.of(SETUP)
# numpy's mathavan2010 takes milliseconds a contact: fewer of them.
NUMPY_CONTACTS = {"mathavan2010": 100, "mathavan2010_ev": 100}


def approaching(rng: np.random.Generator, count: int) -> tuple[np.ndarray, np.ndarray]:
    """Unit normals (k, 2), half along the axes, and velocities (k, 2) at 0.5-5 m/s
    against them (each has a part along the normal of at least a tenth of its speed)."""
    angle = rng.uniform(0.0, 2.0 * np.pi, count)
    normals = np.stack((np.cos(angle), np.sin(angle)), axis=1)
    axes = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]])
    normals = np.where((rng.random(count) < 0.5)[:, None], axes[rng.integers(0, 4, count)], normals)
    tangents = np.stack((-normals[:, 1], normals[:, 0]), axis=1)
    speed, share = rng.uniform(0.5, 5.0, count), rng.uniform(0.1, 1.0, count)
    along = np.sqrt(1.0 - share * share) * rng.choice([-1.0, 1.0], count)
    velocities = speed[:, None] * (share[:, None] * normals + along[:, None] * tangents)
    return normals, velocities


def timed(call: Callable[[], object], rounds: int) -> float:
    """The best CPU seconds of `rounds` calls."""
    best = float("inf")
    for _ in range(rounds):
        start = time.process_time()
        call()
        best = min(best, time.process_time() - start)
    return best


def cushion_lines(count: int, rounds: int) -> list[str]:
    rng = np.random.default_rng(0)
    into, velocities = approaching(rng, count)
    spins = rng.uniform(-100.0, 100.0, (count, 3))
    masses = np.full(count, SETUP.masses[0])
    numbers = np.tile(CushionNumbers.of(CUSHION_CONSTANTS), (count, 1))
    lines = []
    for law, numpy_law in CUSHION_LAWS.items():
        fast = cushion_rows(CUSHION_LAW_IDS[law], velocities, spins, into, masses, numbers)
        few = NUMPY_CONTACTS.get(law, count)
        contacts = [
            CushionContact(
                velocities[k : k + 1], spins[k : k + 1], into[k : k + 1], masses[k : k + 1]
            )
            for k in range(few)
        ]
        for k, contact in enumerate(contacts):
            slow = numpy_law(contact, CUSHION_CONSTANTS)
            assert all(
                a.tobytes() == b[k : k + 1].tobytes() for a, b in zip(slow, fast, strict=True)
            )

        def numpy_calls(law: str = law, contacts: list[CushionContact] = contacts) -> None:
            for contact in contacts:
                CUSHION_LAWS[law](contact, CUSHION_CONSTANTS)

        def compiled_calls(law_id: int = CUSHION_LAW_IDS[law]) -> None:
            cushion_rows(law_id, velocities, spins, into, masses, numbers)

        slow_us = timed(numpy_calls, rounds) / few * 1e6
        fast_us = timed(compiled_calls, rounds) / count * 1e6
        lines.append(
            f"| {law} (cushion) | {slow_us:.1f} | {fast_us:.3f} | {slow_us / fast_us:,.0f}x |"
        )
    return lines


def ball_lines(count: int, rounds: int) -> list[str]:
    rng = np.random.default_rng(0)
    normals, first = approaching(rng, count)
    velocities = np.stack((-first, np.zeros((count, 2))), axis=1)  # ball 1 runs into ball 2
    spins = np.stack((rng.uniform(-100.0, 100.0, (count, 3)), np.zeros((count, 3))), axis=1)
    masses = np.tile([SETUP.masses[0], 0.165], (count, 1))
    restitutions, radii = np.full(count, SETUP.restitution), np.full(count, SETUP.radius)
    frictions = np.tile(SETUP.ball_friction, (count, 1))
    arguments = (normals, velocities, spins, masses, restitutions, radii, frictions)
    lines = []
    for law, numpy_law in BALL_LAWS.items():
        fast = ball_rows(BALL_LAW_IDS[law], *arguments)
        pairs = [PairContact(normals[k], velocities[k], spins[k], masses[k]) for k in range(count)]
        for k, pair in enumerate(pairs):
            slow = numpy_law(pair, SETUP.restitution, SETUP)
            assert all(
                np.asarray(a).tobytes() == b[k].tobytes() for a, b in zip(slow, fast, strict=True)
            )

        def numpy_calls(law: str = law, pairs: list[PairContact] = pairs) -> None:
            for pair in pairs:
                BALL_LAWS[law](pair, SETUP.restitution, SETUP)

        def compiled_calls(law_id: int = BALL_LAW_IDS[law]) -> None:
            ball_rows(law_id, *arguments)

        slow_us = timed(numpy_calls, rounds) / count * 1e6
        fast_us = timed(compiled_calls, rounds) / count * 1e6
        lines.append(
            f"| {law} (ball) | {slow_us:.1f} | {fast_us:.3f} | {slow_us / fast_us:,.0f}x |"
        )
    return lines


# Compiled in a fresh process: `call` (numba.njit, the options of compiled.jit) calls
# the law once; {law} is imported from {module}, {arguments} are its arguments.
COLD = """
import time
start = time.process_time(), time.perf_counter()
import numba
imported = time.process_time(), time.perf_counter()
import numpy as np
from billiards.physics.compiled.laws import CushionNumbers
from {module} import {law}
numbers = CushionNumbers(0.028575, 0.75, 0.9, 0.2, 0.037, 0.2, 4.15)
{call}
ready = time.process_time(), time.perf_counter()
{first}
done = time.process_time(), time.perf_counter()
print(imported[0] - start[0], done[0] - ready[0], done[1] - ready[1])
"""
ONE_CALL = """
@numba.njit(error_model="numpy")
def call():
    return {law}({arguments})
"""
CUSHION_ARGUMENTS = "(0.3, 1.0), (1.0, 2.0, 3.0), (0.0, 1.0), 0.17, numbers"
BALL_ARGUMENTS = (
    "(-1.0, 0.0), (1.0, 0.2), (0.0, 0.0), (0.0, 0.0, 30.0), (0.0, 0.0, 0.0), 0.17, 0.165, "
    "0.95, 0.028575, (0.01, 0.108, 1.088)"
)
ROWS_FIRST = """
one = np.ones((1, 2)), np.ones((1, 3)), np.array([[0.0, 1.0]]), np.ones(1)
cushion_rows(0, *one, np.array([numbers]))
ball_rows(0, np.array([[-1.0, 0.0]]), np.ones((1, 2, 2)), np.ones((1, 2, 3)), np.ones((1, 2)),
          np.ones(1), np.ones(1), np.ones((1, 3)))
"""


def cold_compile(module: str, law: str, call: str, first: str) -> tuple[float, ...]:
    """In fresh processes: (import numba CPU s, compile CPU s, compile wall s) with an
    empty cache, then the first call's (CPU s, wall s) in another process, the cache warm."""
    code = COLD.format(module=module, law=law, call=call, first=first)
    times = []
    with tempfile.TemporaryDirectory() as cache:
        environment = {**os.environ, "NUMBA_CACHE_DIR": cache}
        for _ in range(2):
            done = subprocess.run(
                [sys.executable, "-c", code],
                env=environment,
                check=True,
                capture_output=True,
                text=True,
            )
            times.append([float(value) for value in done.stdout.split()])
    (imported, cpu, wall), (_, warm_cpu, warm_wall) = times
    return imported, cpu, wall, warm_cpu, warm_wall


def cold_lines() -> list[str]:
    package = "billiards.physics.compiled.laws"
    cases = [
        (f"{package}.mirror", "mirror", CUSHION_ARGUMENTS),
        (f"{package}.han2005", "han2005", CUSHION_ARGUMENTS),
        (f"{package}.mathavan2010", "mathavan2010", CUSHION_ARGUMENTS),
        (f"{package}.mathavan2010", "mathavan2010_ev", CUSHION_ARGUMENTS),
        (f"{package}.frictionless", "frictionless", BALL_ARGUMENTS),
        (f"{package}.frictional", "frictional", BALL_ARGUMENTS),
    ]
    lines = [
        "| compiled | import numba CPU s | cold compile CPU s | cold compile wall s "
        "| warm load CPU s | warm load wall s |",
        "|---|---|---|---|---|---|",
    ]
    rows = [
        (
            f"{law} alone",
            cold_compile(module, law, ONE_CALL.format(law=law, arguments=arguments), "call()"),
        )
        for module, law, arguments in cases
    ]
    every = cold_compile(f"{package}.rows", "ball_rows, cushion_rows", "", ROWS_FIRST)
    rows.append(("every law, through the dispatch (rows entries)", every))
    for name, times in rows:
        lines.append(f"| {name} | " + " | ".join(f"{value:.2f}" for value in times) + " |")
    return lines


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--contacts", type=int, default=2000)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    print("$ python " + " ".join(sys.argv))
    print(f"load {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores, numba {numba.__version__}")
    print()
    print("| law | numpy us/call | compiled us/contact | ratio |")
    print("|---|---|---|---|")
    print("\n".join(cushion_lines(args.contacts, args.rounds)))
    print("\n".join(ball_lines(args.contacts, args.rounds)))
    print()
    print("\n".join(cold_lines()))


if __name__ == "__main__":
    main()
