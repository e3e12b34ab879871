"""The cushion laws' cost in the fitter's batches: CPU per impact and per run.

    python scripts/bench_cushion_laws.py [TRACKS] [--shots 5] [--strokes 8] [--rounds 3]
                                         [--fits 1]
                                         [--laws mirror,han2005,mathavan2010,mathavan2010_ev]

A batch as billiards.fit simulates one (issue 31): the shipped three_cushion scene with
its cushion_model set to each law, `--strokes` strokes of each of the first `--shots`
recordings of TRACKS (train.json or its folder; without it, $BILLIARDS_RECORDINGS's,
else ../shared/data/carom_tracks beside the repository, and none is one line; billiards.fit.shots.
shot_scene, the strokes drawn around the first samples' own, seed 0), all of them in
one simulate_batch. Each round runs every law once, alternately (a neighbour's load
then hits a round, not a column), timing CPU time of this process:

- `ms/run`: the whole batch, per run (scenes built before timing);
- `law ms/impact`: the time spent in the cushion law, per impact (a row moving into
  the cushion), the law called as the batch calls it (a call carries the rows of every
  run whose next event is a cushion contact: `rows/call`);
- `alone ms/impact`: the same impacts again, one row a call.

The table gives each column's median over rounds (min-max in brackets for ms/run), and
the ratio of each law's ms/run to han2005's. A second table times `--fits` stroke fits
(billiards.fit.shots.fit_stroke, its default budget: a differential evolution and a
polish, a few hundred runs in batches of up to a few dozen) of the first recording per
law, laws alternated: its CPU time, its runs, and the law's share. To compare with
another tree (before and after a change), run it with PYTHONPATH set to that tree's
root, alternately.
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field, replace

import numpy as np

import billiards
from billiards.fit import shots
from billiards.fit.recordings import MissingRecordings, read_recordings, recordings_path
from billiards.fit.shots import Stroke, prepare, shot_scene
from billiards.physics import laws
from billiards.physics.engine.packaging import Run
from billiards.physics.laws.cushion import CushionConstants, CushionContact
from billiards.physics.numerics.arrays import FloatArray
from billiards.scene.reader import Scene, find_scene, load_scene
from billiards.simulation import setup_from_scene, simulate_batch


@dataclass
class Spent:
    """What one law's batch cost in one round."""

    run: float = 0.0  # s of CPU for the whole batch
    law: float = 0.0  # s of CPU inside the law
    impacts: int = 0
    calls: int = 0
    most: int = 0  # impacts in the largest call
    rows: list[tuple[np.ndarray, ...]] = field(default_factory=list)  # the impacts' arguments


def batch_scenes(tracks: str, law: str, shots: int, strokes: int) -> list[Scene]:
    table = load_scene(find_scene("three_cushion"))
    table = replace(table, physics=replace(table.physics, cushion_model=law))
    rng = np.random.default_rng(0)
    scenes = []
    for recording in read_recordings(tracks)[:shots]:
        shot = prepare(recording)
        for _ in range(strokes):
            stroke = Stroke(
                shot.guess.speed * rng.uniform(0.9, 1.1),
                shot.guess.direction + rng.uniform(-1.0, 1.0),
                rng.uniform(-0.5, 0.5),
                rng.uniform(-0.5, 0.5),
            )
            scenes.append(shot_scene(table, shot, stroke))
    return scenes


@contextmanager
def counting(law: str, spent: Spent, keep_rows: bool = False) -> Iterator[None]:
    """While inside, the law (as the calendars take it from the registry) adds its CPU
    time, calls and impacts to `spent` (and, keep_rows, each impact's arguments)."""
    plain = laws.CUSHION_LAWS[law]

    def counted(
        balls: CushionContact, constants: CushionConstants
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        velocities, spins, into, masses = balls
        start = time.process_time()
        out = plain(balls, constants)
        spent.law += time.process_time() - start
        moving_in = velocities[:, 0] * into[:, 0] + velocities[:, 1] * into[:, 1] > 0.0
        spent.impacts += int(moving_in.sum())
        spent.calls += 1
        spent.most = max(spent.most, int(moving_in.sum()))
        if keep_rows:
            spent.rows += [
                (velocities[k : k + 1], spins[k : k + 1], into[k : k + 1], masses[k : k + 1])
                for k in np.nonzero(moving_in)[0]
            ]
        return out

    laws.CUSHION_LAWS[law] = counted
    try:
        yield
    finally:
        laws.CUSHION_LAWS[law] = plain


def timed_batch(scenes: list[Scene], law: str) -> Spent:
    """The batch's CPU time, then (a second pass) the law's share of it and its impacts."""
    spent = Spent()
    start = time.process_time()
    results = list(simulate_batch(scenes))
    spent.run = time.process_time() - start
    assert not any(isinstance(result, Exception) for result in results)
    with counting(law, spent, keep_rows=True):
        list(simulate_batch(scenes))
    return spent


def timed_fit(tracks: str, law: str) -> tuple[Spent, int]:
    """One stroke fit (billiards.fit.shots.fit_stroke, its default budget) of the first
    recording on the table with this law: its CPU time, the law's share, and how many
    runs it simulated."""
    shot = prepare(read_recordings(tracks)[0])
    table = load_scene(find_scene("three_cushion"))
    table = replace(table, physics=replace(table.physics, cushion_model=law))
    plain_batch = shots.sample_starts
    runs = 0

    def counted_batch(
        run: Run, velocities: FloatArray, spins: FloatArray | None, times: FloatArray, source: str
    ) -> list[FloatArray | Exception]:
        nonlocal runs
        runs += len(velocities)
        return plain_batch(run, velocities, spins, times, source)

    spent = Spent()
    shots.sample_starts = counted_batch  # type: ignore[assignment]
    try:
        with counting(law, spent):
            start = time.process_time()
            shots.fit_stroke(table, shot)
            spent.run = time.process_time() - start
    finally:
        shots.sample_starts = plain_batch
    return spent, runs


def alone(law: str, spent: Spent, setup: CushionConstants) -> float:
    """CPU s per impact with the batch's impacts one row a call."""
    plain = laws.CUSHION_LAWS[law]
    start = time.process_time()
    for row in spent.rows:
        plain(CushionContact(*row), setup)
    return (time.process_time() - start) / max(len(spent.rows), 1)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "tracks",
        nargs="?",
        help="train.json or its folder (default: $BILLIARDS_RECORDINGS, else "
        "../shared/data/carom_tracks beside the repository)",
    )
    parser.add_argument("--shots", type=int, default=5)
    parser.add_argument("--strokes", type=int, default=8)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--laws", default="mirror,han2005,mathavan2010,mathavan2010_ev")
    parser.add_argument(
        "--fits", type=int, default=1, help="stroke fits per law (0: none), alternated"
    )
    args = parser.parse_args(argv)
    try:
        args.tracks = str(recordings_path(args.tracks))
    except MissingRecordings as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    names = args.laws.split(",")
    scenes = {law: batch_scenes(args.tracks, law, args.shots, args.strokes) for law in names}
    runs = len(next(iter(scenes.values())))
    setups = {}
    for law in names:  # the setup a run hands its law (its constants, numbers)
        setups[law] = CushionConstants.of(setup_from_scene(scenes[law][0]))
        list(simulate_batch(scenes[law][:2]))  # warm
    load_before = os.getloadavg()
    rounds: dict[str, list[tuple[Spent, float]]] = {law: [] for law in names}
    for _ in range(args.rounds):
        for law in names:
            spent = timed_batch(scenes[law], law)
            rounds[law].append((spent, alone(law, spent, setups[law])))
    fits: dict[str, list[tuple[Spent, int]]] = {law: [] for law in names}
    for _ in range(args.fits):
        for law in names:
            fits[law].append(timed_fit(args.tracks, law))
    load_after = os.getloadavg()

    print(f"$ python scripts/bench_cushion_laws.py {' '.join(sys.argv[1:])}")
    print(f"\nbilliards from {os.path.dirname(billiards.__file__)}, {platform.machine()},")
    print(
        f"{runs} runs in one batch ({args.shots} shots x {args.strokes} strokes), "
        f"{args.rounds} rounds, load {load_before[0]:.2f} -> {load_after[0]:.2f}\n"
    )
    print(
        "| law | ms/run (CPU) | x han2005 | impacts/run | rows/call (mean, max) "
        "| law ms/impact | alone ms/impact |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    han = statistics.median(s.run for s, _ in rounds["han2005"]) if "han2005" in rounds else None
    for law in names:
        per_run = [1e3 * spent.run / runs for spent, _ in rounds[law]]
        spent = rounds[law][0][0]
        in_law = statistics.median(1e3 * s.law / max(s.impacts, 1) for s, _ in rounds[law])
        one = statistics.median(1e3 * a for _, a in rounds[law])
        ratio = f"{statistics.median(s.run for s, _ in rounds[law]) / han:.1f}" if han else "-"
        print(
            f"| {law} | {statistics.median(per_run):.2f} ({min(per_run):.2f}-{max(per_run):.2f}) "
            f"| {ratio} | {spent.impacts / runs:.1f} | {spent.impacts / max(spent.calls, 1):.1f}, {spent.most} "
            f"| {in_law:.4f} | {one:.4f} |"
        )
    if args.fits:
        print(f"\nOne stroke fit of the first recording (fit_stroke), median of {args.fits}:\n")
        print("| law | s CPU | x han2005 | runs | ms/run | s in the law | law ms/impact |")
        print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
        han_fit = (
            statistics.median(s.run for s, _ in fits["han2005"]) if "han2005" in fits else None
        )
        for law in names:
            cpu = statistics.median(s.run for s, _ in fits[law])
            in_law = statistics.median(s.law for s, _ in fits[law])
            spent, fit_runs = fits[law][0]
            ratio = f"{cpu / han_fit:.1f}" if han_fit else "-"
            print(
                f"| {law} | {cpu:.3f} | {ratio} | {fit_runs} | {1e3 * cpu / fit_runs:.3f} "
                f"| {in_law:.2f} | {1e3 * in_law / max(spent.impacts, 1):.4f} |"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
