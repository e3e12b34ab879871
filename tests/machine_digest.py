"""What the machine-independence test compares across CPU kernels: one JSON object of
digests, printed by `python -m tests.machine_digest [--all]`.

It covers what a run's result depends on: the shipped scenes (their pinned fingerprints,
tests/test_fingerprints.py), a sample of the hard-case families of both models with and
without pockets (and the spin model's strikes with the frictional ball law, english into
Mathavan 2010 cushions), and a sweep's draws (uniform, normal, the nudge grid). `--all` takes
every pinned (scene, method, step) and larger samples.
"""

from __future__ import annotations

import hashlib
import json
import sys
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from billiards.physics.engine.setup import Setup
from billiards.scene.reader import default_scene_path, load_scene
from billiards.simulation import simulate_scene
from billiards.sweep import draws
from billiards.sweep.variations import Variations, parse_vary
from tests.hard_checks import run
from tests.physics import test_hard_cases, test_pocket_hard_cases, test_spin_hard_cases
from tests.test_fingerprints import PINS, fingerprint

# The default sample: every scene by `event` (`exact` equals it, tested in-process), and
# `naive` in both models.
SAMPLE_PINS = [key for key in PINS if key[1] == "event" and key[2] is None] + [
    ("break", "naive", None),
    ("follow_shot", "naive", None),
]
# Random scenes of up to 40 balls take a second each: only in the full run.
FULL_ONLY = {"scene"}


def pin_key(name: str, method: str, dt: float | None) -> str:
    return f"{name}/{method}/{dt!r}"


def _families() -> dict[str, Callable[[int], Setup]]:
    spin = test_spin_hard_cases
    return {
        "rack": test_hard_cases.rack_case,
        "scene": test_hard_cases.scene_case,
        "pressed": test_hard_cases.pressed_case,
        "strike": spin.strike,
        "english": spin.english,
        "mathavan_english": lambda i: replace(spin.english(i), cushion_law="mathavan2010"),
        "pocket_strike": lambda i: spin.with_pockets(spin.strike(i)),
        "frictional_strike": lambda i: replace(spin.strike(i), ball_law="frictional"),
        "pocket_rack": lambda i: test_pocket_hard_cases.on_the_table(test_hard_cases.rack_case(i)),
        "jaw_shot": test_pocket_hard_cases.jaw_shot_case,
    }


def digests(every_pin: bool = False) -> dict[str, str]:
    out: dict[str, str] = {}
    scenes = default_scene_path().parent
    for name, method, dt in PINS if every_pin else SAMPLE_PINS:
        result = simulate_scene(load_scene(scenes / f"{name}.toml"), method=method, dt=dt)
        out[pin_key(name, method, dt)] = fingerprint(result)
    cases = 6 if every_pin else 2
    for family, make in _families().items():
        if family in FULL_ONLY and not every_pin:
            continue
        for index in range(cases):
            out[f"{family}/{index}"] = fingerprint(run(make(index), "event"))
    variations = Variations(
        (parse_vary("ball.cue.velocity=2.5:3.5"), parse_vary("ball.cue.position.y=0.5325~0.001")),
        seed=7,
    )
    drawn = [value for run_index in range(200) for _, value in variations.values(run_index)]
    rng = np.random.default_rng(3)
    drawn += [draws.normal(rng, 0.0, 1.0) for _ in range(2000)]  # the tails too
    drawn += list(draws.geometric_points(1e-15, 1e-3, 49))
    out["sweep draws"] = hashlib.sha256(np.array(drawn).tobytes()).hexdigest()[:32]
    return out


if __name__ == "__main__":
    json.dump(digests(every_pin="--all" in sys.argv[1:]), sys.stdout, indent=0)
