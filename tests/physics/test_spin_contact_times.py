"""The spin model's contact times against closed forms (physics/spin/contact_times.py).

Each expected time is computed here by other means: the textbook quadratic formula for
a parabola meeting a line, bisection on |p(t) - J| for a jaw, a hand-solved quadratic
for a pair.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest

from billiards.physics.pockets import pocket_table
from billiards.physics.rolling.contact_times import cushion_contacts as rolling_cushion_contacts
from billiards.physics.rolling.motion import Anchors
from billiards.physics.spin.contact_times import (
    cushion_contacts,
    cushion_roots,
    falling_roots,
    pair_contacts,
    pocket_edge_times,
)
from billiards.physics.spin.motion import REST, ROLLING, SLIDING, SPINNING

R = 0.0286
TABLE = (2.13, 1.065)
BOUNDS = np.array([R, TABLE[0] - R, R, TABLE[1] - R])
POCKETS = pocket_table(TABLE, R)
JAWS = len(POCKETS.jaws)


def rows(*values: tuple[float, float]) -> np.ndarray:
    return np.array(values, dtype=np.float64)


def line_time(start: float, speed: float, acceleration: float, line: float) -> float:
    """First t > 0 with start + speed t + acceleration t^2 / 2 = line, crossing it
    towards the far side (the textbook formula; inf if never)."""
    if acceleration == 0:
        t = (line - start) / speed if speed else math.inf
        return t if t > 0 else math.inf
    discriminant = speed * speed + 2 * acceleration * (line - start)
    if discriminant < 0:
        return math.inf
    roots = sorted((-speed + sign * math.sqrt(discriminant)) / acceleration for sign in (1.0, -1.0))
    inside = start < line  # the side the ball starts on
    for t in roots:
        heading = speed + acceleration * t
        if t > 0 and (heading > 0 if inside else heading < 0):
            return t
    return math.inf


def first_root(f: Callable[[float], float], end: float, steps: int = 4000) -> float:
    """The first sign change of f on [0, end] from + to -, bisected to the last bit."""
    low = 0.0
    for k in range(1, steps + 1):
        high = end * k / steps
        if f(high) <= 0:
            break
        low = high
    else:
        return math.inf
    while True:
        middle = 0.5 * (low + high)
        if middle in (low, high):
            return high
        low, high = (middle, high) if f(middle) > 0 else (low, middle)


# --- cushions -------------------------------------------------------------------------

# A sliding ball: its friction pulls it along -slip, here (-1.0, 0.6) m/s^2, so its path
# is the parabola p0 + v0 t + a t^2 / 2.
SLIDE_P0 = (1.0, 0.5)
SLIDE_V0 = (1.5, 0.5)
SLIDE_A = (-1.0, 0.6)


def test_a_sliding_ball_meets_each_cushion_line_where_its_parabola_does() -> None:
    tau = cushion_roots(rows(SLIDE_P0), rows(SLIDE_V0), rows(SLIDE_A), BOUNDS)
    expected = [
        line_time(SLIDE_P0[axis], SLIDE_V0[axis], SLIDE_A[axis], float(BOUNDS[wall]))
        for wall, axis in enumerate((0, 0, 1, 1))
    ]
    # x = r: the pull reverses it and brings it back (3.5 s); y = r: never.
    assert math.isfinite(expected[0]) and expected[2] == math.inf
    assert tau.shape == (1, 4)
    assert tau[0].tolist() == pytest.approx(expected, rel=1e-13)


def test_a_sliding_ball_curves_into_the_side_cushion_first_within_its_slide() -> None:
    t0 = 0.25
    y_time = line_time(SLIDE_P0[1], SLIDE_V0[1], SLIDE_A[1], float(BOUNDS[3]))
    x_time = line_time(SLIDE_P0[0], SLIDE_V0[0], SLIDE_A[0], float(BOUNDS[1]))
    assert y_time < x_time  # heading mostly along x, but the pull curves it into y = W - r

    def contact(duration: float) -> tuple[float, int]:
        times, walls = cushion_contacts(
            rows(SLIDE_P0),
            rows(SLIDE_V0),
            rows(SLIDE_A),
            np.array([t0]),
            np.array([duration]),
            np.array([SLIDING]),
            BOUNDS,
            None,
            60.0,
        )
        return float(times[0]), int(walls[0])

    time, wall = contact(2.0)
    assert wall == 3
    assert time == pytest.approx(t0 + y_time, rel=1e-14)
    # A slide that ends first (the ball then rolls on a new anchor): no contact in it.
    assert contact(0.9 * y_time)[0] == math.inf


def test_a_rolling_ball_meets_the_cushion_when_the_rolling_model_says() -> None:
    decel = 0.01 * 9.81
    p0, v0 = (1.0, 0.5), (-0.6, 0.8)  # speed 1 m/s
    acceleration = (-decel * v0[0], -decel * v0[1])
    times, walls = cushion_contacts(
        rows(p0),
        rows(v0),
        rows(acceleration),
        np.array([0.0]),
        np.array([1.0 / decel]),  # until it stops
        np.array([ROLLING]),
        BOUNDS,
        None,
        60.0,
    )
    along = (BOUNDS[3] - p0[1]) / v0[1]  # path length to y = W - r
    arrival = (1.0 - math.sqrt(1.0 - 2 * decel * along)) / decel
    assert walls[0] == 3
    assert times[0] == pytest.approx(arrival, rel=1e-13)
    anchors = Anchors.start(rows(p0), rows(v0), decel)
    rolling_times, rolling_walls = rolling_cushion_contacts(anchors, np.array([0]), BOUNDS)
    assert rolling_walls[0] == 3
    assert times[0] == pytest.approx(rolling_times[0], rel=1e-13)


# --- pockets --------------------------------------------------------------------------


def edges(
    p0: tuple[float, float],
    v0: tuple[float, float],
    acceleration: tuple[float, float],
    state: int = SLIDING,
    duration: float = 5.0,
    skip: int | None = None,
) -> np.ndarray:
    walls = cushion_roots(rows(p0), rows(v0), rows(acceleration), BOUNDS)
    found = pocket_edge_times(
        rows(p0),
        rows(v0),
        rows(acceleration),
        np.array([duration]),
        np.array([state]),
        walls,
        POCKETS,
        60.0,
        None if skip is None else (np.array([True]), np.array([skip])),
    )
    assert found.shape == (1, 4 + JAWS + len(POCKETS.names))
    return found[0]


def test_a_sliding_ball_meets_a_jaw_where_its_centre_is_r_plus_rho_from_the_jaws() -> None:
    jaw = POCKETS.jaws[0]  # head-right pocket, on the y = 0 rail
    p0 = (float(jaw[0]) + 0.15, float(jaw[1]) + 0.12)
    v0, acceleration = (-0.9, -0.6), (0.3, -0.5)

    def gap(t: float) -> float:
        x = p0[0] + v0[0] * t + 0.5 * acceleration[0] * t * t - jaw[0]
        y = p0[1] + v0[1] * t + 0.5 * acceleration[1] * t * t - jaw[1]
        return math.sqrt(x * x + y * y) - POCKETS.jaw_reach

    expected = first_root(gap, 1.0)
    assert 0.05 < expected < 0.5
    assert edges(p0, v0, acceleration)[4] == pytest.approx(expected, rel=1e-12)
    # Sought only within the state: a slide that ends first meets no jaw.
    assert edges(p0, v0, acceleration, duration=0.5 * expected)[4] == math.inf


def test_a_ball_drops_past_the_side_capture_line_and_meets_no_cushion_in_the_mouth() -> None:
    level = float(POCKETS.capture_level[1])  # side-bottom: captured when -y > level
    p0, v0, acceleration = (TABLE[0] / 2, 0.1), (0.05, -1.0), (0.0, -0.4)
    found = edges(p0, v0, acceleration)
    capture = 4 + JAWS + 1
    assert found[capture] == pytest.approx(
        line_time(p0[1], v0[1], acceleration[1], -level), rel=1e-13
    )
    # Its cushion line y = r is crossed in the mouth, where no cushion is.
    assert math.isfinite(cushion_roots(rows(p0), rows(v0), rows(acceleration), BOUNDS)[0, 2])
    assert found[2] == math.inf
    times, index = cushion_contacts(
        rows(p0),
        rows(v0),
        rows(acceleration),
        np.array([1.5]),
        np.array([5.0]),
        np.array([SLIDING]),
        BOUNDS,
        POCKETS,
        60.0,
    )
    assert index[0] == capture and times[0] == 1.5 + found[capture]
    # A skipped edge is ignored; nothing else changes.
    skipped = edges(p0, v0, acceleration, skip=capture)
    assert skipped[capture] == math.inf
    others = np.arange(len(found)) != capture
    assert np.array_equal(skipped[others], found[others])


@pytest.mark.parametrize("state", [SPINNING, REST])
def test_a_ball_neither_sliding_nor_rolling_meets_no_edge(state: int) -> None:
    assert np.isinf(edges((0.2, 0.1), (-1.0, -0.5), (0.0, 0.0), state=state)).all()


# --- pairs ----------------------------------------------------------------------------

# Two sliding balls on one line: relative velocity W = (1.5, 0), relative acceleration
# (-2, 0), separation D = (-d, 0). They touch when d - 1.5 t + t^2 = 2r, i.e.
# t^2 - 1.5 t + 0.26 = 0 for d = 2r + 0.26: t = (1.5 - sqrt(2.25 - 1.04)) / 2 = 0.2.
GAP = 2 * R + 0.26
PAIR_POSITION = rows((0.5, 0.5), (0.5 + GAP, 0.5))
PAIR_VELOCITY = rows((1.2, 0.4), (-0.3, 0.4))  # a common (0, 0.4) does not matter
PAIR_ACCELERATION = rows((-1.5, -0.6), (0.5, -0.6))


def pair_time(
    change_time: tuple[float, float] = (9.0, 9.0),
    state: tuple[int, int] = (SLIDING, SLIDING),
    parting: bool = False,
    position: np.ndarray = PAIR_POSITION,
    velocity: np.ndarray = PAIR_VELOCITY,
    acceleration: np.ndarray = PAIR_ACCELERATION,
) -> float:
    found = pair_contacts(
        np.array([0]),
        np.array([1]),
        1.0,
        position,
        velocity,
        acceleration,
        np.array(state),
        np.array(change_time),
        np.full(2, np.inf),
        R,
        60.0,
        parting,
    )
    assert found.shape == (1,)
    return float(found[0])


def test_two_sliding_balls_meet_at_the_hand_solved_time() -> None:
    assert pair_time() == pytest.approx(1.2, rel=1e-13)  # now + 0.2


def test_a_touching_pair_meets_now_if_closing_and_on_its_return_if_parting() -> None:
    # Touching now (D = (-2r, 0)), the relative acceleration (1, 0) pulling them
    # together: d(t) = -2r + w t + t^2 / 2.
    touching = rows((0.5, 0.5), (0.5 + 2 * R, 0.5))
    acceleration = rows((0.5, 0.0), (-0.5, 0.0))
    closing = rows((0.25, 0.0), (-0.25, 0.0))  # w = 0.5: closing now
    assert pair_time(position=touching, velocity=closing, acceleration=acceleration) == 1.0
    # Judged no contact now: only a return counts, and d(t) closes through 0 and then
    # grows for good: none.
    assert (
        pair_time(position=touching, velocity=closing, acceleration=acceleration, parting=True)
        == math.inf
    )
    # w = -0.5: parting now, back at 2r when -0.5 t + 0.5 t^2 = 0, t = 1.
    parting = rows((-0.25, 0.0), (0.25, 0.0))
    found = pair_time(position=touching, velocity=parting, acceleration=acceleration, parting=True)
    assert found == pytest.approx(2.0, rel=1e-12)


def test_a_pair_is_sought_only_until_either_ball_changes_state() -> None:
    assert pair_time(change_time=(9.0, 1.15)) == math.inf
    assert pair_time(change_time=(1.25, 9.0)) == pytest.approx(1.2, rel=1e-13)


def test_a_pair_of_balls_at_rest_is_never_examined() -> None:
    assert pair_time(state=(REST, SPINNING)) == math.inf


def test_only_a_sliding_or_rolling_balls_acceleration_counts() -> None:
    # The second ball spins in place (an acceleration left in its row is stale): only
    # the first's parabola closes the gap, d - 1.2 t + 0.75 t^2 = 2r.
    velocity = rows((1.2, 0.0), (0.0, 0.0))
    acceleration = rows((-1.5, 0.0), (0.5, 0.0))
    expected = (1.2 - math.sqrt(1.44 - 4 * 0.75 * 0.26)) / (2 * 0.75)
    found = pair_time(state=(SLIDING, SPINNING), velocity=velocity, acceleration=acceleration)
    assert found == pytest.approx(1.0 + expected, rel=1e-13)


# --- falling_roots ----------------------------------------------------------------------


def test_falling_roots_finds_the_root_where_the_gap_falls() -> None:
    # t^2 - 5 t + 6 = (t - 2)(t - 3): falls through 0 at 2, rises at 3.
    assert falling_roots(np.array(6.0), np.array(-5.0), np.array(1.0)) == 2.0
    # 5 t - t^2: 0 at 0 and opening, then falling through 0 at 5.
    assert falling_roots(np.array(0.0), np.array(5.0), np.array(-1.0)) == pytest.approx(5.0)
    # Linear: 1 - 4 t.
    assert falling_roots(np.array(1.0), np.array(-4.0), np.array(0.0)) == 0.25


def test_falling_roots_gives_inf_for_a_gap_that_never_closes() -> None:
    c = np.array([1.0, 1.0, 1.0, 1.0])
    b = np.array([0.0, -1.0, 2.0, 0.0])
    a = np.array([1.0, 1.0, 0.0, 0.0])
    # 1 + t^2; 1 - t + t^2 (no real root); 1 + 2 t; 1 (constant)
    assert np.isinf(falling_roots(c, b, a)).all()


def test_falling_roots_gives_zero_for_a_touching_and_closing_gap() -> None:
    c = np.array([0.0, -1e-17, 0.0])
    b = np.array([-1.0, -0.5, 0.0])
    a = np.array([0.5, 0.0, -1.0])
    # Touching and closing; just past by rounding and closing; touching, still, pulled in.
    assert falling_roots(c, b, a).tolist() == [0.0, 0.0, 0.0]


def test_a_rising_root_does_not_count() -> None:
    # Just past the line by rounding and leaving it (c < 0, b > 0): g = -1e-18 + t -
    # 0.1 t^2 has a root at 1e-18 where it rises, and one at 10 where it falls again.
    tau = falling_roots(np.array(-1e-18), np.array(1.0), np.array(-0.1))
    assert tau == pytest.approx(10.0, rel=1e-14)
    # Touching and opening, never to return: no root at all.
    assert falling_roots(np.array(0.0), np.array(1.0), np.array(0.1)) == math.inf


def test_falling_roots_broadcasts() -> None:
    c = np.array([[6.0], [1.0]])
    b = np.array([-5.0, -4.0, 1.0])
    a = np.array(1.0)
    tau = falling_roots(c, b, a)
    assert tau.shape == (2, 3)
    # 6 - 5 t + t^2: 2; 6 - 4 t + t^2 and 6 + t + t^2: no real root.
    assert tau[0].tolist() == [2.0, math.inf, math.inf]
    # 1 - 5 t + t^2: (5 - sqrt(21)) / 2; 1 - 4 t + t^2: 2 - sqrt(3); 1 + t + t^2: none.
    assert tau[1, 0] == pytest.approx((5 - math.sqrt(21)) / 2, rel=1e-14)
    assert tau[1, 1] == pytest.approx(2 - math.sqrt(3), rel=1e-14)
    assert tau[1, 2] == math.inf
