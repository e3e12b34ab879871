"""Contact times against their closed forms (billiards/physics/rolling/contact_times.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from billiards.physics.engine.setup import Setup
from billiards.physics.rolling.contact_times import cushion_contacts, pair_contacts
from billiards.physics.rolling.motion import Anchors

R = 0.0286
A = 0.01 * 9.81  # m/s^2, mu g


def _anchors(
    positions: list[tuple[float, float]], velocities: list[tuple[float, float]]
) -> Anchors:
    return Anchors.start(np.array(positions, float), np.array(velocities, float), A)


def _arrival(speed: float, distance: float) -> float:
    """Time to roll `distance` from `speed` at constant deceleration A."""
    return (speed - math.sqrt(speed * speed - 2 * A * distance)) / A


def test_a_ball_reaches_the_cushion_when_it_has_rolled_to_the_cushion_line() -> None:
    setup = Setup.of([(0.5, 0.4)], [(1.2, 0.0)])
    times, walls = cushion_contacts(
        _anchors([(0.5, 0.4)], [(1.2, 0.0)]), np.array([0]), setup.bounds
    )
    length = setup.table_size[0]
    assert walls[0] == 1  # the x = L - r cushion
    assert times[0] == pytest.approx(_arrival(1.2, length - R - 0.5), rel=1e-14)


def test_a_diagonal_ball_meets_the_nearer_cushion_first() -> None:
    setup = Setup.of([(1.0, 0.5)], [(-0.6, 0.8)])
    times, walls = cushion_contacts(
        _anchors([(1.0, 0.5)], [(-0.6, 0.8)]), np.array([0]), setup.bounds
    )
    width = setup.table_size[1]
    along = (width - R - 0.5) / 0.8  # path length to the y = W - r cushion
    assert walls[0] == 3
    assert times[0] == pytest.approx(_arrival(1.0, along), rel=1e-14)


def test_a_ball_that_stops_short_of_every_cushion_never_reaches_one() -> None:
    setup = Setup.of([(1.0, 0.5)], [(0.3, 0.0)])  # rolls 0.46 m, 0.5 m from the cushion
    times, _ = cushion_contacts(_anchors([(1.0, 0.5)], [(0.3, 0.0)]), np.array([0]), setup.bounds)
    assert times[0] == np.inf


def _pair_time(
    positions: list[tuple[float, float]], velocities: list[tuple[float, float]]
) -> float:
    anchors = _anchors(positions, velocities)
    cushions = np.full(2, np.inf)
    found = pair_contacts(anchors, np.array([0]), np.array([1]), 0.0, cushions, R)
    return float(found[0])


def test_two_balls_rolling_head_on_meet_at_the_root_of_their_closing_quadratic() -> None:
    # gap(t) = d - (v1 + v2) t + A t^2 (both slow at A towards each other) reaches 2r
    v1, v2, d = 1.0, 0.7, 0.6
    c = d - 2 * R
    expected = ((v1 + v2) - math.sqrt((v1 + v2) ** 2 - 4 * A * c)) / (2 * A)
    found = _pair_time([(0.5, 0.5), (0.5 + d, 0.5)], [(v1, 0.0), (-v2, 0.0)])
    assert found == pytest.approx(expected, rel=1e-13)


def test_a_ball_rolling_into_one_at_rest_meets_it_after_rolling_the_gap() -> None:
    v, d = 0.8, 0.5
    found = _pair_time([(0.5, 0.5), (0.5 + d, 0.5)], [(v, 0.0), (0.0, 0.0)])
    assert found == pytest.approx(_arrival(v, d - 2 * R), rel=1e-14)


def test_a_ball_that_stops_first_is_met_by_the_other_from_its_rest_position() -> None:
    # ball 1 rolls away slowly and stops; ball 0 follows faster and reaches it at rest
    slow, fast, d = 0.1, 0.3, 0.3
    stop_1 = 0.5 + d + slow * slow / (2 * A)
    expected = _arrival(fast, stop_1 - 2 * R - 0.5)
    assert expected > slow / A  # the contact comes after ball 1 has stopped
    found = _pair_time([(0.5, 0.5), (0.5 + d, 0.5)], [(fast, 0.0), (slow, 0.0)])
    assert found == pytest.approx(expected, rel=1e-13)


def test_a_ball_passing_wider_than_two_radii_misses() -> None:
    offset = 2 * R * (1 + 1e-9)
    assert _pair_time([(0.5, 0.5), (1.0, 0.5 + offset)], [(1.0, 0.0), (0.0, 0.0)]) == np.inf
    inside = 2 * R * (1 - 1e-9)
    assert _pair_time([(0.5, 0.5), (1.0, 0.5 + inside)], [(1.0, 0.0), (0.0, 0.0)]) < np.inf
