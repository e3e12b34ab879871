"""Cost of touching balls: wall time and contacts per run, for the hard-case families
of pressed pairs, struck touching clusters, lines at a cushion and frozen inelastic
racks (tests/physics/test_hard_cases.py builds them from (family, index) alone).

    python scripts/bench_touching.py [--cases 60]

Prints a markdown table per family: runs, contacts per run (median, max), wall time
per run (median, max) for the event method, and whether any run was cut by max_events.
Run from the repository root (it reads the generators from the test suite).
"""

from __future__ import annotations

import argparse
import platform
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from billiards.physics.engine.setup import Setup
from tests.hard_checks import run
from tests.physics.test_hard_cases import (
    FAMILIES,
    cluster_case,
    frozen_case,
    line_case,
    pressed_case,
)

BUILDERS: dict[str, Callable[[int], Setup]] = {
    "pressed": pressed_case,
    "cluster": cluster_case,
    "line": line_case,
    "frozen": frozen_case,
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cases", type=int, default=60, help="runs per family (at most its size)")
    args = parser.parse_args()
    print(f"python {platform.python_version()}, {platform.machine()}; event method\n")
    print(
        "| family | runs | contacts median | contacts max | ms median | ms max | cut by max_events |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: | --- |")
    for family, build in BUILDERS.items():
        contacts, walls, cut = [], [], 0
        for index in range(min(args.cases, FAMILIES[family])):
            setup = build(index)
            start = time.perf_counter()
            result = run(setup, "event")
            walls.append(1000 * (time.perf_counter() - start))
            contacts.append(len(result.events))
            cut += len(result.events) > setup.max_events
        print(
            f"| {family} | {len(walls)} | {statistics.median(contacts):.0f} | {max(contacts)} "
            f"| {statistics.median(walls):.1f} | {max(walls):.0f} | {'yes' if cut else 'no'} |"
        )


if __name__ == "__main__":
    main()
