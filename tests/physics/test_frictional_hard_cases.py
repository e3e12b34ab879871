"""The hard cases again with the frictional ball-ball law (issue 20): the generated
families of the spin model (touching balls with spin, frozen shots, strikes into racks
and frozen racks, with and without pockets) and the rolling model's (pressed pairs,
struck touching clusters, lines at a cushion, frozen inelastic racks) turned into the
spin model with every ball rolling, all with `ball_law = "frictional"`. Each run is held
to tests/hard_checks.check_spin_case: ended by itself, no overlap beyond 1e-9 m (naive's
steps too, for the small cases), nothing past a cushion, jaw or capture line, the
translational plus rotational energy never rising, momentum kept at every ball-ball
contact, `exact` == `event` bit for bit.

A seeded sample of each family runs by default (23 cases); `pytest -m hard` runs them
all (1,332): 3 fail (XFAIL below, each with what fails), all only by CPU time near the
limit.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np
import pytest

from billiards.physics.engine.setup import Setup
from billiards.physics.spin.motion import rolling_spin
from tests.hard_checks import R, check_spin_case, generate_families
from tests.physics import test_hard_cases as rolling
from tests.physics import test_spin_hard_cases as spin
from tests.physics import test_spin_touching_cases as touching


def frictional(setup: Setup) -> Setup:
    return replace(setup, ball_law="frictional")


def spinning(setup: Setup) -> Setup:
    """A rolling-model case in the spin model: every ball rolling at its velocity."""
    spins = np.zeros((len(setup.positions), 3))
    spins[:, :2] = rolling_spin(setup.velocities, R)
    return replace(setup, model="spin", spins=spins, slide_decel=0.2 * 9.81)


# family -> (builder of case i, size, default sample, run naive too)
BUILDERS: dict[str, tuple[Callable[[int], Setup], int, int, bool]] = {
    "rest_cluster": (touching.rest_cluster_case, 120, 2, True),
    "cushion_press": (touching.cushion_press_case, 80, 2, True),
    "moving_pair": (touching.moving_pair_case, 80, 2, True),
    "tiny": (touching.tiny_case, 60, 2, True),
    "frozen_shot": (touching.frozen_shot_case, 100, 2, True),
    "strike": (spin.strike, 60, 2, False),
    "spin_frozen": (spin.frozen, 12, 1, False),
    "pocket_strike": (lambda i: spin.with_pockets(spin.strike(i)), 60, 1, False),
    "english": (spin.english, 40, 2, True),
    "pressed": (lambda i: spinning(rolling.pressed_case(i)), 300, 2, True),
    "cluster": (lambda i: spinning(rolling.cluster_case(i)), 240, 2, True),
    "line": (lambda i: spinning(rolling.line_case(i)), 120, 2, True),
    "frozen": (lambda i: spinning(rolling.frozen_case(i)), 60, 1, False),
}
FAMILIES = {name: size for name, (_, size, _, _) in BUILDERS.items()}
SAMPLE = {name: sample for name, (_, _, sample, _) in BUILDERS.items()}
SAMPLE_SEED = 20261202

# family -> {case: what still fails}, measured 2026-12-02 under -m hard on the shared
# 2-core machine, on the calendar with issue 22's held soft contacts (main's c7ac45d):
# 1,329 of 1,332 pass. (On the calendar before it, 13 failed: pairs pressed together by
# their own slips chattering at ELASTIC_BELOW, and the tiny family's two overlaps; that
# calendar change fixed all but cluster 208 and line 113, and brought line 51, a ball
# squeezed between two held by each in turn at one instant, until the TC rule's elastic
# second contact was exempted from the hold: 311 events.) CPU
# seconds from two runs, loaded; event counts are exact; in brackets the same case with
# the frictionless law.
XFAIL: dict[str, dict[int, str]] = {
    "cluster": {208: "735 events, 2.0-2.9 s of CPU (frictionless: 1,064 events, 3.2-4.3 s)"},
    "line": {
        12: "1,441 events, 2.4-2.5 s of CPU: b6 pressed into b7 at a retention-0 cushion "
        "is parted (laws.held.part) 1,344 times in 1e-8 s, each parting only as fast as "
        "the little slip the frictional contact left it pays for (frictionless: 133 "
        "events; 200 before the TC rule's exemption from the soft hold)",
        113: "2,568-2,650 events, 2.4-2.8 s of CPU (frictionless: 11,876 events, 10 s)",
    },
}
# Of those, the cases whose only failure is a CPU time under 2x WALL_LIMIT (2 s) on this
# loaded machine, which a quiet one may bring under it: not strict.
LENIENT: dict[str, set[int]] = {"cluster": {208}, "line": {12, 113}}


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    generate_families(metafunc, FAMILIES, SAMPLE, SAMPLE_SEED, XFAIL, LENIENT)


def check(family: str, case: int) -> None:
    build, _, _, naive = BUILDERS[family]
    check_spin_case(frictional(build(case)), naive=naive)


def test_touching_balls_at_rest_with_spin_and_friction(rest_cluster: int) -> None:
    check("rest_cluster", rest_cluster)


def test_a_ball_pressed_by_slip_against_a_held_ball_with_friction(cushion_press: int) -> None:
    check("cushion_press", cushion_press)


def test_a_pair_moving_together_with_friction(moving_pair: int) -> None:
    check("moving_pair", moving_pair)


@pytest.mark.long
def test_tiny_speeds_with_large_spins_and_friction(tiny: int) -> None:
    check("tiny", tiny)


def test_frozen_follow_and_draw_shots_with_friction(frozen_shot: int) -> None:
    check("frozen_shot", frozen_shot)


def test_random_strikes_into_racks_with_friction(strike: int) -> None:
    check("strike", strike)


def test_frozen_rack_spin_breaks_with_friction(spin_frozen: int) -> None:
    check("spin_frozen", spin_frozen)


def test_random_strikes_with_pockets_and_friction(pocket_strike: int) -> None:
    check("pocket_strike", pocket_strike)


def test_english_into_a_cushion_past_a_ball_with_friction(english: int) -> None:
    check("english", english)


def test_rolling_pressed_pairs_with_friction(pressed: int) -> None:
    check("pressed", pressed)


def test_struck_touching_clusters_with_friction(cluster: int) -> None:
    check("cluster", cluster)


@pytest.mark.long
def test_touching_lines_at_a_cushion_with_friction(line: int) -> None:
    check("line", line)


def test_frozen_inelastic_racks_with_friction(frozen: int) -> None:
    check("frozen", frozen)
