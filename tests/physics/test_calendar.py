"""The one calendar's written rules (billiards/physics/engine/calendar.py), in both motion
models: the tie rule (state changes first, then edge contacts, then pairs; by ball
index, x cushions before y; pairs by first index, then second) and what a touching
pair with a rounding-level approach does."""

from __future__ import annotations

import numpy as np
import pytest

from billiards.physics.engine.calendar import Calendar
from billiards.physics.engine.setup import Setup
from billiards.physics.rolling.law import RollingLaw


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
    assert [contact[1] for contact in calendar.log.contacts] == ["cushion", "cushion"]


MODELS = ("rolling", "spin")


@pytest.mark.parametrize("model", MODELS)
def test_simultaneous_events_resolve_changes_then_cushions_then_pairs_by_index(
    monkeypatch: pytest.MonkeyPatch, model: str
) -> None:
    # Four balls at rest (no real contacts); their entries are set to one instant by hand.
    setup = Setup.of([(0.2, 0.2), (0.6, 0.2), (1.0, 0.2), (1.4, 0.2)], model=model)
    calendar = Calendar(setup)
    order: list[tuple[str, int, int]] = []

    def change(ball: int, time: float) -> None:
        order.append(("change", ball, -1))
        calendar.change_time[ball] = np.inf

    def cushion(ball: int, time: float, *state: object) -> None:
        order.append(("cushion", ball, -1))
        calendar.edge_time[ball] = np.inf

    def pair(first: int, second: int, time: float, *state: object) -> None:
        order.append(("pair", first, second))
        calendar.pair_time[first, second] = np.inf

    monkeypatch.setattr(calendar, "_change_state", change)
    monkeypatch.setattr(calendar, "_resolve_edge", cushion)
    monkeypatch.setattr(calendar, "_resolve_pair", pair)
    if model == "spin":  # a rolling ball has no state that ends by itself
        calendar.change_time[[2, 0]] = 2.5
    calendar.edge_time[[3, 1]] = 2.5
    calendar.pair_time[1, 2] = 2.5
    calendar.pair_time[0, 3] = 2.5
    calendar.pair_time[0, 2] = 2.5
    while calendar.next_time() < np.inf:
        assert calendar.resolve_next() == 2.5
    changes = [("change", 0, -1), ("change", 2, -1)] if model == "spin" else []
    assert order == [
        *changes,
        ("cushion", 1, -1),
        ("cushion", 3, -1),
        ("pair", 0, 2),
        ("pair", 0, 3),
        ("pair", 1, 2),
    ]


def grazing_pair(model: str) -> Calendar:
    """Two balls touching along x (exact numbers), the first rolling along y past the
    second at rest: no closing speed (exactly 0), and parting (|w|^2 > 0 = D.a)."""
    radius = 0.03125
    spins = [[-1.0 / radius, 0.0, 0.0], [0.0, 0.0, 0.0]]  # natural roll at (0, 1) m/s
    setup = Setup.of(
        [(0.5, 0.5), (0.5 + 2 * radius, 0.5)],
        [(0.0, 1.0), (0.0, 0.0)],
        radius=radius,
        model=model,
        spins=spins if model == "spin" else None,
    )
    return Calendar(setup)


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("returns_after", [0.0, 0.25])
def test_a_grazing_pair_that_returns_within_the_tick_is_pressed_else_asked_back(
    monkeypatch: pytest.MonkeyPatch, model: str, returns_after: float
) -> None:
    # One behaviour in both models (they used to differ): a rounding-level graze whose
    # return after parting falls at this very instant is pressed apart now (never
    # dropped); a later return becomes the pair's entry.
    calendar = grazing_pair(model)
    asked = calendar.law.pair_times

    def pair_times(
        pairs: tuple[np.ndarray, np.ndarray],
        now: np.ndarray,
        ends: np.ndarray,
        parting: bool,
        runs: np.ndarray,
    ) -> np.ndarray:
        if parting:
            return np.full(len(pairs[0]), now[0] + returns_after)
        return asked(pairs, now, ends, parting, runs)

    monkeypatch.setattr(calendar.law, "pair_times", pair_times)
    calendar._resolve_pair(0, 1, 0.0)
    if returns_after == 0:
        assert [contact[1] for contact in calendar.log.contacts] == ["ball"]
        assert calendar.pressed_at == {(0, 1): 0.0}
    else:
        assert [contact[1] for contact in calendar.log.contacts] == []
        assert calendar.pair_time[0, 1] == 0.25


@pytest.mark.parametrize("model", MODELS)
def test_a_pair_pressed_apart_at_this_instant_is_asked_for_its_return(
    monkeypatch: pytest.MonkeyPatch, model: str
) -> None:
    # Parted by the pressed law at t = 0 and met again at t = 0: no second pressed
    # contact, but the pair keeps an entry (its return after parting), in both models.
    calendar = grazing_pair(model)
    calendar.pressed_at[0, 1] = 0.0
    monkeypatch.setattr(
        calendar.law, "pair_times", lambda pairs, *args: np.full(len(pairs[0]), 0.125)
    )
    calendar._resolve_pair(0, 1, 0.0)
    assert [contact[1] for contact in calendar.log.contacts] == []
    assert calendar.pair_time[0, 1] == 0.125
