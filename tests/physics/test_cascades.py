"""Issue 30's two cascades, as found (scenes/*.toml, copied from the repro scenes):

- touching_creep_two_balls: two touching balls, one sliding into the other at 1e-9 m/s.
  It made 20,000 contacts by t = 1.5e-10 s at impact speed 0 and stopped only at
  max_events (100,000 contacts, 33-97 s of CPU), with either ball law;
- pressed_on_a_cushion_19_balls: a ball held on a Han 2005 cushion (no cushion
  friction) pressed by a neighbour chattered at 1.94 s (the last 200 contacts within
  8e-11 s, impact speeds below 8e-13 m/s) until max_events (64 s of CPU).

Both came from first_downward_root's hair rule taking a touching pair that parts by a
hair and curves back for a contact now even where the motions that press it end first
(a ball that stops, or stops sliding): the contact changed nothing, and the pair was
found again an ulp of time later (docs/touching.md, section 8). Each run is held to
every invariant of tests/hard_checks.check_spin_case (no overlap beyond 1e-9 m, the
energy never rising, momentum at every contact, under 2 s of CPU, `exact` == `event`),
with a few contacts at the pair.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from billiards.scene.reader import load_scene
from billiards.simulation import setup_from_scene
from tests.hard_checks import check_spin_case

SCENES = Path(__file__).parent / "scenes"


@pytest.mark.parametrize("ball_law", ["frictionless", "frictional"])
def test_a_ball_creeping_into_its_touching_neighbour_comes_to_rest(ball_law: str) -> None:
    setup = replace(
        setup_from_scene(load_scene(SCENES / "touching_creep_two_balls.toml")), ball_law=ball_law
    )
    result = check_spin_case(setup)
    # The one contact at 1e-9 m/s: the struck ball parts by 2.5e-19 m and both stop.
    assert len(result.events) == 1
    assert result.events[0].impact_speed == pytest.approx(1e-9)


def test_a_ball_held_on_a_cushion_and_pressed_by_a_neighbour_comes_to_rest() -> None:
    setup = setup_from_scene(load_scene(SCENES / "pressed_on_a_cushion_19_balls.toml"))
    # m16 spins about the vertical for ever (spinning friction 0): the run ends at
    # max_time with every ball otherwise at rest.
    result = check_spin_case(setup, spins_on=True)
    assert len(result.events) < 100  # 80
    pressed = [
        event for event in result.events if event.balls == ("m11", "m12") and event.time > 1.94
    ]
    assert len(pressed) <= 12  # 9 between 1.9426546 s and 1.9426615 s
