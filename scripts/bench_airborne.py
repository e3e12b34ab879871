"""The airborne kernels (billiards.physics.compiled.airborne): what they cost to compile
cold and to run.

    python scripts/bench_airborne.py [--rows 100000]

Two tables, CPU time of this process: the seconds each probe entry takes at its first
call, compiling its kernels into an empty numba cache (a fresh temporary NUMBA_CACHE_DIR,
set before numba is imported; compiled.roots' first_downward_root, which the loop
compiles anyway, before the clock starts), and nanoseconds a row at `--rows` rows, the
best of three calls. Prints the command and the machine's load with the tables.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from typing import Any

os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="airborne-cold-")

import numpy as np  # after the cache folder is chosen

from billiards.physics.compiled import roots


def probe_inputs(rows: int) -> dict[str, tuple[Any, ...]]:
    """Each probe entry's arguments: `rows` rows of plausible numbers (seed 0)."""
    rng = np.random.default_rng(0)
    radius, gravity = 0.0286, 9.81
    impacts = rng.uniform(-3, 3, (rows, 9))
    impacts[:, 2] = -rng.uniform(0.1, 5, rows)
    impacts[:, 6:9] = (radius, 0.5, 0.2)
    jumps = np.ascontiguousarray(impacts[:, [0, 1, 3, 4, 5, 2, 6, 7, 8]])
    jumps[:, 5] *= -1.0
    pairs = np.zeros((rows, 22))
    pairs[:, 0:3] = (0.5, 0.5, 0.15)
    pairs[:, 9:12] = np.column_stack([rng.uniform(0.4, 0.6, (rows, 2)), np.full(rows, radius)])
    pairs[:, 3:6] = rng.uniform(-2, 2, (rows, 3))
    pairs[:, 8] = -gravity
    pairs[:, 18:21] = (radius, 1.0, 0.5)
    walls = np.column_stack([
        rng.uniform(0.05, 0.5, rows), -rng.uniform(0.5, 5, rows), np.full(rows, radius),
        rng.uniform(0, 3, rows), np.full(rows, radius), np.full(rows, 0.036322),
        np.full(rows, gravity), np.full(rows, 5.0),
    ])  # fmt: skip
    hops = np.column_stack([impacts, np.full(rows, gravity), np.full(rows, 0.005)])
    balls = rng.uniform(-3, 3, (rows, 15))
    balls[:, 0:6] = (0.5, 0.5, 0.1, 0.5, 0.5, 0.1 - 2 * radius)
    balls[:, [9, 13, 14]] = (0.17, 0.165, 0.9)
    bernstein = roots.BERNSTEIN
    return {
        "flights": (rng.uniform(0, 1, (rows, 8)),),
        "landings": (
            np.column_stack(
                [rng.uniform(0, 0.3, rows), rng.uniform(-3, 3, rows), np.full(rows, gravity)]
            ),
        ),
        "bed_impacts": (impacts,),
        "jumps": (jumps,),
        "bounce_counts": (np.column_stack([-impacts[:, 2], impacts[:, 7], hops[:, 9:11]]),),
        "bounce_sequences": (hops,),
        "ball_contacts": (pairs, bernstein),
        "cushion_contacts": (walls, bernstein),
        "ball_impacts": (balls,),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=100_000)
    rows = parser.parse_args().rows
    print("$ python", " ".join(sys.argv), f"   (load {os.getloadavg()[0]:.2f})")
    start = time.process_time()
    from billiards.physics.compiled.airborne import probe

    inputs = {
        name: tuple(np.ascontiguousarray(a) if isinstance(a, np.ndarray) else a for a in args)
        for name, args in probe_inputs(rows).items()
    }
    print(f"\n{'entry':18s} {'cold compile (s CPU)':>21s} {'ns a row':>10s}")
    total = time.process_time() - start
    for name, args in inputs.items():
        entry = getattr(probe, name)
        first = tuple(a[:1] if isinstance(a, np.ndarray) else a for a in args)
        begin = time.process_time()
        entry(*first)
        cold = time.process_time() - begin
        total += cold
        best = np.inf
        for _ in range(3):
            begin = time.process_time()
            entry(*args)
            best = min(best, time.process_time() - begin)
        print(f"{name:18s} {cold:21.2f} {best * 1e9 / rows:10.1f}")
    print(f"{'all':18s} {total:21.2f}")


if __name__ == "__main__":
    main()
