"""This checkout's physics speed against another checkout's, timed alternately.

    git worktree add ../base main      # or any commit to compare against
    python scripts/bench_compare.py --base ../base [--rounds 15] [--scenes break,spin_break]
        [--cases event,exact:240,naive:240]

Each checkout runs in a process of its own (its own `billiards` on sys.path), warm; the
two are asked in turn, case by case and round by round (who goes first alternates), so
both see the same load on a shared machine. Prints a markdown table: per scene and
method, the median warm wall time per run of each checkout over the rounds, the
head/base ratio of the medians and its range over rounds, and the contacts of each
(a changed count means the two give different breaks). A round times `--repeats` runs
and keeps their median.
"""

from __future__ import annotations

import argparse
import json
import platform
import statistics
import subprocess
import sys
from pathlib import Path

# The timing loop each checkout's process runs: one JSON request a line, one answer.
WORKER = r"""
import json, statistics, sys, time
sys.path.insert(0, sys.argv[1])
from billiards.scene.reader import default_scene_path, load_scene
from billiards.simulation import simulate_scene
for line in sys.stdin:
    name, method, dt, repeats = json.loads(line)
    scene = load_scene(default_scene_path().parent / f"{name}.toml")
    result = simulate_scene(scene, method=method, dt=dt)
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        simulate_scene(scene, method=method, dt=dt)
        times.append(time.perf_counter() - start)
    print(json.dumps([statistics.median(times), len(result.events)]), flush=True)
"""


def parse_cases(text: str) -> list[tuple[str, float | None]]:
    """`event,exact:240,naive:240` -> [(method, dt)]: a number after the colon is 1/dt."""
    cases: list[tuple[str, float | None]] = []
    for item in text.split(","):
        method, _, per_second = item.partition(":")
        cases.append((method, 1 / float(per_second) if per_second else None))
    return cases


class Checkout:
    def __init__(self, path: Path) -> None:
        self.path = path
        self.process = subprocess.Popen(
            [sys.executable, "-c", WORKER, str(path)],
            cwd=path,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
        )

    def time(self, name: str, method: str, dt: float | None, repeats: int) -> tuple[float, int]:
        assert self.process.stdin is not None and self.process.stdout is not None
        self.process.stdin.write(json.dumps([name, method, dt, repeats]) + "\n")
        self.process.stdin.flush()
        seconds, events = json.loads(self.process.stdout.readline())
        return float(seconds), int(events)

    def close(self) -> None:
        assert self.process.stdin is not None
        self.process.stdin.close()
        self.process.wait(timeout=30)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--base", required=True, type=Path, help="the other checkout")
    parser.add_argument("--scenes", default="break,hard_break,spin_break,pool_break")
    parser.add_argument("--cases", default="event,exact:240", help="methods, :steps per second")
    parser.add_argument("--rounds", type=int, default=15)
    parser.add_argument("--repeats", type=int, default=3, help="runs per round (median)")
    args = parser.parse_args()
    head_path = Path(__file__).resolve().parents[1]
    base, head = Checkout(args.base.resolve()), Checkout(head_path)
    rows = []
    try:
        for name in args.scenes.split(","):
            for method, dt in parse_cases(args.cases):
                timed: dict[str, list[float]] = {"base": [], "head": []}
                events = {}
                for round_index in range(args.rounds):
                    order = [("base", base), ("head", head)]
                    for label, checkout in order if round_index % 2 == 0 else order[::-1]:
                        seconds, events[label] = checkout.time(name, method, dt, args.repeats)
                        timed[label].append(seconds)
                ratios = [h / b for h, b in zip(timed["head"], timed["base"], strict=True)]
                b, h = statistics.median(timed["base"]), statistics.median(timed["head"])
                step = "-" if dt is None else f"1/{round(1 / dt)}"
                rows.append(
                    f"| {name} | {method} | {step} | {b * 1e3:.2f} | {h * 1e3:.2f} | {h / b:.3f} | "
                    f"{min(ratios):.2f}-{max(ratios):.2f} | {events['base']} | {events['head']} |"
                )
                print(rows[-1], file=sys.stderr, flush=True)
    finally:
        base.close()
        head.close()
    print(f"# Physics speed: {head_path.name} against {args.base}")
    print()
    print(
        f"`python scripts/bench_compare.py --base {args.base} --rounds {args.rounds} "
        f"--repeats {args.repeats} --scenes {args.scenes} --cases {args.cases}` on "
        f"{platform.machine()}, "
        f"{platform.python_implementation()} {platform.python_version()}"
    )
    print()
    print(
        "| scene | method | dt (s) | base (ms) | head (ms) | head/base | per round | "
        "contacts base | contacts head |"
    )
    print("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    print("\n".join(rows))


if __name__ == "__main__":
    main()
