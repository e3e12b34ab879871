"""The calendar's written tie rule (billiards/physics/calendar.py): contacts at the same
instant go cushions first, then pairs; cushions by ball index, x cushions before y;
pairs by first index, then second."""

from __future__ import annotations

import numpy as np
import pytest

from billiards.physics.calendar import Calendar
from billiards.physics.rolling_law import RollingLaw
from billiards.physics.setup import Setup


def test_a_ball_into_an_exact_corner_meets_the_x_cushion_then_the_y_cushion_at_once() -> None:
    # Exactly representable numbers: both cushion lines are 0.46875 m away along each axis.
    setup = Setup.of([(1.5, 0.5)], [(1.0, 1.0)], table_size=(2.0, 1.0), radius=0.03125)
    calendar = Calendar(setup)
    assert isinstance(calendar.law, RollingLaw)
    first = calendar.resolve_next()
    after_first = calendar.law.anchors.v0[0].copy()
    second = calendar.resolve_next()
    assert first == second  # one instant, two contacts
    assert after_first[0] < 0 < after_first[1]  # the x cushion first
    assert np.all(calendar.law.anchors.v0[0] < 0)  # then the y cushion
    assert calendar.log.kinds == ["cushion", "cushion"]


def test_simultaneous_contacts_resolve_cushions_first_then_pairs_by_index(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Four balls at rest (no real contacts); their entries are set to one instant by hand.
    setup = Setup.of([(0.2, 0.2), (0.6, 0.2), (1.0, 0.2), (1.4, 0.2)])
    calendar = Calendar(setup)
    order: list[tuple[str, int, int]] = []

    def cushion(ball: int, time: float) -> None:
        order.append(("cushion", ball, -1))
        calendar.edge_time[ball] = np.inf

    def pair(first: int, second: int, time: float) -> None:
        order.append(("pair", first, second))
        calendar.pair_time[first, second] = np.inf

    monkeypatch.setattr(calendar, "_resolve_edge", cushion)
    monkeypatch.setattr(calendar, "_resolve_pair", pair)
    calendar.edge_time[[3, 1]] = 2.5
    calendar.pair_time[1, 2] = 2.5
    calendar.pair_time[0, 3] = 2.5
    calendar.pair_time[0, 2] = 2.5
    while calendar.next_time() < np.inf:
        assert calendar.resolve_next() == 2.5
    assert order == [
        ("cushion", 1, -1),
        ("cushion", 3, -1),
        ("pair", 0, 2),
        ("pair", 0, 3),
        ("pair", 1, 2),
    ]
