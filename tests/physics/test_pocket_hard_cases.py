"""Hard cases on a table with pockets: every exact run keeps the invariants.

The checks (tests/hard_checks.check_pocket_sound): no ball overlaps another, until it
drops no ball is past a cushion where the cushion exists, inside a jaw's reach or past
a capture line (each by more than 1e-9 m), a ball drops on its capture line and nothing
involves it afterwards, kinetic energy never rises, momentum is conserved at every
ball-ball contact; and "exact" at a step reproduces "event" bit for bit (so does a
rerun). As in test_hard_cases, the random families run a seeded sample by default and
in full under `pytest -m hard`.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from billiards.physics.engine.result import SampledMotion
from billiards.physics.engine.setup import Setup
from billiards.physics.pockets import pocket_of, pocket_table
from tests.hard_checks import (
    TABLE,
    R,
    check_methods_agree_bit_for_bit,
    check_no_pocketed_overlap,
    check_pocket_sound,
    generate_families,
    make_setup,
    run,
)
from tests.physics.test_hard_cases import jammed_line, rack_case, scene_case

POCKETS = pocket_table(TABLE, R)
FAMILIES = {"pocket_rack": 400, "pocket_scene": 200, "jaw_shot": 400}
SAMPLE = {"pocket_rack": 12, "pocket_scene": 8, "jaw_shot": 16}
SAMPLE_SEED = 20261130


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    generate_families(metafunc, FAMILIES, SAMPLE, SAMPLE_SEED)


def assert_pocket_case(setup: Setup) -> None:
    reference = run(setup, "event")
    assert reference.complete, "the run hit max_time or max_events"
    check_pocket_sound(reference, setup)
    check_methods_agree_bit_for_bit(setup, reference)


def on_the_table(setup: Setup) -> Setup:
    """The setup with pockets, less any ball that would start already past a capture
    line (a scene file refuses those)."""
    keep = pocket_of(POCKETS, setup.positions) < 0
    return replace(
        setup,
        positions=setup.positions[keep],
        velocities=setup.velocities[keep],
        masses=setup.masses[keep],
        pockets=POCKETS,
    )


def jaw_shot_case(index: int) -> Setup:
    """A ball at 0.1 to 10 m/s aimed past a random jaw with its centre's path at the
    jaw's reach r + rho, give or take 0 to 1e-9 m (a graze at 1e-12 m, an exact
    tangent), from any direction a ball on the table can come; two more balls at
    random, one of them moving."""
    rng = np.random.default_rng([7, index])
    while True:
        jaw = POCKETS.jaws[int(rng.integers(len(POCKETS.jaws)))]
        angle = rng.uniform(0, 2 * math.pi)
        heading = np.array([math.cos(angle), math.sin(angle)])
        side = np.array([-heading[1], heading[0]])
        miss = POCKETS.jaw_reach + float(rng.choice([0.0, -1e-12, 1e-12, -1e-9, 1e-9, -0.01]))
        back = float(rng.uniform(0.1, 0.8))
        start = jaw + side * miss - heading * back
        inside = R <= start[0] <= TABLE[0] - R and R <= start[1] <= TABLE[1] - R
        if inside and pocket_of(POCKETS, start[None])[0] < 0:
            break
    others = np.column_stack((rng.uniform(R, TABLE[0] - R, 2), rng.uniform(R, TABLE[1] - R, 2)))
    positions = np.vstack([start, others])
    first, second = np.triu_indices(3, 1)
    if np.any(np.hypot(*(positions[first] - positions[second]).T) < 2 * R):
        positions = positions[:1]
    velocities = np.zeros_like(positions)
    velocities[0] = heading * float(rng.uniform(0.1, 10.0))
    if len(positions) > 1:
        velocities[1] = rng.normal(0.0, 2.0, 2)
    return on_the_table(make_setup(positions, velocities))


def test_random_break_with_pockets_keeps_every_invariant(pocket_rack: int) -> None:
    assert_pocket_case(on_the_table(rack_case(pocket_rack)))


def test_random_scene_with_pockets_keeps_every_invariant(pocket_scene: int) -> None:
    assert_pocket_case(on_the_table(scene_case(pocket_scene)))


def test_shot_at_a_jaws_tip_keeps_every_invariant(jaw_shot: int) -> None:
    assert_pocket_case(jaw_shot_case(jaw_shot))


def test_two_balls_dropping_at_the_same_instant_keep_every_invariant() -> None:
    """Mirror images on a table whose numbers are all exact in binary: the two drops
    (side-bottom, side-top) fall at the same instant, resolved in the tie order."""
    table = (2.0, 1.0)
    pockets = pocket_table(table, R, jaw_radius=0.0078125)
    setup = Setup.of(
        [(1.0, 0.5 - 0.25), (1.0, 0.5 + 0.25)],
        [(0.0, -1.0), (0.0, 1.0)],
        table_size=table,
        pockets=pockets,
        max_time=600.0,
    )
    reference = run(setup, "event")
    drops = [(e.balls, e.pocket, e.time) for e in reference.events if e.kind == "pocket"]
    assert drops == [(("b0",), "side-bottom", drops[0][2]), (("b1",), "side-top", drops[0][2])]
    check_pocket_sound(reference, setup)
    check_methods_agree_bit_for_bit(setup, reference)


def test_a_drop_at_the_same_instant_as_a_ball_contact_keeps_every_invariant() -> None:
    """One ball drops into the side-bottom pocket at the very instant two others meet
    (the dropping ball's start tuned by ulps until the two times are equal)."""
    striker = ((0.5, 0.6), (1.2, 0.0))
    target = (0.5 + 2 * R + 0.35, 0.6)
    start_y = 0.35 - POCKETS.jaw_radius
    for _ in range(400):
        setup = make_setup(
            np.array([(TABLE[0] / 2, start_y), striker[0], target]),
            np.array([(0.0, -1.2), striker[1], (0.0, 0.0)]),
            pockets=POCKETS,
        )
        reference = run(setup, "event")
        drop = next(e.time for e in reference.events if e.kind == "pocket")
        contact = next(e.time for e in reference.events if e.kind == "ball")
        if drop == contact:
            break
        start_y = float(np.nextafter(start_y, -math.inf if drop > contact else math.inf))
    assert drop == contact, "no placement gave the same instant"
    check_pocket_sound(reference, setup)
    check_methods_agree_bit_for_bit(setup, reference)


@pytest.mark.parametrize("count", [5, pytest.param(12, marks=pytest.mark.hard)])
@pytest.mark.parametrize("dt", [1 / 30, 1 / 240])
def test_naive_never_outputs_an_overlap_in_a_line_jammed_against_a_cushion_with_pockets(
    count: int, dt: float
) -> None:
    # test_hard_cases' jammed line on a table with pockets: the pushes there are free and
    # the table's hold (cushions where they exist, jaws) put each ball back afterwards,
    # undoing half of every push at the cushion: up to 0.9 mm of overlap was left.
    setup = jammed_line(count, pockets=POCKETS)
    result = run(setup, "naive", dt)
    assert isinstance(result.motion, SampledMotion)
    check_no_pocketed_overlap(result, result.motion.times)
