"""Pockets (billiards.physics.pockets): drops and jaw contacts at their closed-form times.

Table coordinates: noses along x = 0, L and y = 0, W; the side-bottom pocket's jaws sit
at (L/2 -+ w_s/2, -rho), its capture line is y = -rho; the head-right corner's jaws at
(a, -rho) and (-rho, a), a = w_c / sqrt 2, its capture line x + y = a - rho.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from billiards.physics.engine.result import SimulationResult
from billiards.physics.engine.setup import Setup
from billiards.physics.pockets import pocket_table
from billiards.rules.seed import (
    CORNER_POCKET_WIDTH,
    GRAVITY,
    JAW_RADIUS,
    SIDE_POCKET_WIDTH,
    SLIDING_FRICTION,
)
from tests.hard_checks import (
    DECEL,
    TABLE,
    R,
    check_on_pocket_table,
    check_pocket_sound,
    fingerprint,
    make_setup,
    run,
)

POCKETS = pocket_table(TABLE, R)
RHO = JAW_RADIUS
REACH = R + RHO
A = CORNER_POCKET_WIDTH / math.sqrt(2)
STEPPED = [("event", 1 / 240), ("exact", 1 / 30), ("exact", 1 / 240), ("exact", 1 / 1000)]


def rolled(speed: float, distance: float, decel: float = DECEL) -> float:
    """Time to roll `distance` from `speed`: the root of v t - a t^2 / 2 = d."""
    return (speed - math.sqrt(speed * speed - 2 * decel * distance)) / decel


def pocket_setup(
    positions: list[tuple[float, float]], velocities: list[tuple[float, float]]
) -> Setup:
    return make_setup(np.array(positions), np.array(velocities), pockets=POCKETS)


def edge_events(result: SimulationResult) -> list[tuple[str, str | None, float]]:
    return [(e.kind, e.pocket, e.time) for e in result.events if e.kind != "ball"]


@pytest.mark.parametrize(("method", "dt"), STEPPED)
@pytest.mark.parametrize("speed", [0.8, 3.0])
def test_a_ball_down_a_side_pockets_centre_line_drops_at_the_closed_form_time(
    method: str, dt: float, speed: float
) -> None:
    start = (TABLE[0] / 2, 0.4)
    result = run(pocket_setup([start], [(0.0, -speed)]), method, dt)
    drop = rolled(speed, start[1] + RHO)  # to the capture line y = -rho
    assert edge_events(result) == [("pocket", "side-bottom", pytest.approx(drop, rel=1e-14))]
    assert result.pocketed[0].ball == "b0"
    assert result.final_positions[0] == pytest.approx([TABLE[0] / 2, -RHO], abs=1e-14)
    check_pocket_sound(result, result_setup(result))


def result_setup(result: SimulationResult) -> Setup:
    return make_setup(result.initial_positions, result.initial_velocities, pockets=POCKETS)


@pytest.mark.parametrize(("method", "dt"), STEPPED)
def test_a_ball_down_a_corner_pockets_diagonal_drops_at_the_closed_form_time(
    method: str, dt: float
) -> None:
    speed = 2.0
    start = 0.6  # (0.6, 0.6), rolling towards the head-right corner (0, 0)
    heading = -speed / math.sqrt(2)
    result = run(pocket_setup([(start, start)], [(heading, heading)]), method, dt)
    # x + y = a - rho after (2 * 0.6 - (a - rho)) / sqrt 2 metres.
    drop = rolled(speed, (2 * start - (A - RHO)) / math.sqrt(2))
    assert edge_events(result) == [("pocket", "head-right", pytest.approx(drop, rel=1e-13))]


@pytest.mark.parametrize("method", ["event", "exact"])
@pytest.mark.parametrize("hair", [1e-9, 1e-12])
def test_a_ball_a_hair_inside_the_jaw_line_hits_the_jaw_and_a_hair_outside_drops(
    method: str, hair: float
) -> None:
    """Straight down at the side pocket, its centre r + rho -+ hair from the right jaw's
    centre line: within reach it strikes the jaw at the closed-form time, outside it
    drops."""
    jaw = (TABLE[0] / 2 + SIDE_POCKET_WIDTH / 2, -RHO)
    speed, y0 = 1.5, 0.3
    for offset, kind in ((-hair, "cushion"), (hair, "pocket")):
        x = jaw[0] - REACH - offset  # the path's distance from the jaw: REACH + offset
        result = run(pocket_setup([(x, y0)], [(0.0, -speed)]), method)
        first = edge_events(result)[0]
        if kind == "pocket":
            assert first == ("pocket", "side-bottom", pytest.approx(rolled(speed, y0 + RHO)))
        else:
            miss = jaw[0] - x  # < REACH
            touch = jaw[1] + math.sqrt(REACH * REACH - miss * miss)
            assert first[:2] == ("cushion", "side-bottom")
            assert first[2] == pytest.approx(rolled(speed, y0 - touch), rel=1e-12)
        check_pocket_sound(result, result_setup(result))


@pytest.mark.parametrize("method", ["event", "exact"])
def test_a_ball_rolling_along_a_rail_into_a_corner_drops_where_the_mouth_lets_it(
    method: str,
) -> None:
    """Along the bottom cushion (y = r) towards the head-right corner: the far jaw sits
    at (-rho, a), a - r away from the path, beyond its reach r + rho, so the ball drops
    when x + r = a - rho."""
    assert A - R > REACH
    speed, x0 = 1.0, 0.5
    result = run(pocket_setup([(x0, R)], [(-speed, 0.0)]), method)
    drop = rolled(speed, x0 - (A - RHO - R))
    assert edge_events(result) == [("pocket", "head-right", pytest.approx(drop, rel=1e-14))]


@pytest.mark.parametrize("method", ["event", "exact"])
def test_a_ball_rolling_along_a_rail_into_a_narrow_corner_rattles_off_the_far_jaw(
    method: str,
) -> None:
    """With a corner mouth of 7 cm the far jaw (-rho, a) is within reach of the path
    y = r (a - r < r + rho): the ball strikes it at x = -rho + sqrt(reach^2 - (a - r)^2)."""
    width = 0.07
    a = width / math.sqrt(2)
    assert a - R < REACH
    pockets = pocket_table(TABLE, R, corner_width=width)
    speed, x0 = 1.0, 0.5
    setup = make_setup(np.array([(x0, R)]), np.array([(-speed, 0.0)]), pockets=pockets)
    result = run(setup, method)
    touch = -RHO + math.sqrt(REACH * REACH - (a - R) ** 2)
    first = edge_events(result)[0]
    assert first[:2] == ("cushion", "head-right")
    assert first[2] == pytest.approx(rolled(speed, x0 - touch), rel=1e-12)
    check_pocket_sound(result, setup)


def test_balls_that_never_reach_a_pocket_run_bit_for_bit_as_without_pockets() -> None:
    """Slow balls in the middle of the table, touching and bouncing off cushions far
    from every mouth: pockets on or off, the same run to the last bit."""
    rng = np.random.default_rng(11)
    compared = 0
    for _ in range(40):
        positions = np.column_stack(
            (rng.uniform(0.5, TABLE[0] - 0.5, 6), rng.uniform(0.3, TABLE[1] - 0.3, 6))
        )
        positions[1] = positions[0] + (2 * R, 0.0)  # one touching pair
        first, second = np.triu_indices(6, 1)
        apart = np.hypot(*(positions[first] - positions[second]).T)
        if np.any(apart < 2 * R * (1 - 1e-12)):
            continue
        velocities = rng.normal(0.0, 0.25, (6, 2))
        closed = run(make_setup(positions, velocities))
        opened = run(make_setup(positions, velocities, pockets=POCKETS))
        if any(event.pocket is not None for event in opened.events):
            continue  # it did meet a pocket (a jaw, or a drop)
        assert fingerprint(closed) == fingerprint(opened)
        compared += 1
    assert compared >= 20


def test_the_spin_models_balls_use_the_same_pockets_a_stun_shot_drops_at_its_closed_form_time() -> (
    None
):
    """A stun shot (no spin) slides at mu_s g until v = 5/7 v0, then rolls: down the
    side pocket's centre line it drops when the distance rolled reaches y0 + rho."""
    speed, y0 = 2.0, 0.5
    setup = make_setup(
        np.array([(TABLE[0] / 2, y0)]),
        np.array([(0.0, -speed)]),
        model="spin",
        spins=np.zeros((1, 3)),
        pockets=POCKETS,
    )
    slide = SLIDING_FRICTION * GRAVITY
    slide_time = 2 * speed / (7 * slide)
    slid = speed * slide_time - 0.5 * slide * slide_time**2
    distance = y0 + RHO
    assert slid < distance
    drop = slide_time + rolled(5 / 7 * speed, distance - slid)
    for method in ("event", "exact"):
        result = run(setup, method)
        assert [(e.kind, e.pocket) for e in result.events] == [("pocket", "side-bottom")]
        assert result.events[0].time == pytest.approx(drop, rel=1e-12)


def test_a_rolling_spin_model_ball_strikes_a_jaw_where_the_rolling_model_does() -> None:
    jaw = (TABLE[0] / 2 + SIDE_POCKET_WIDTH / 2, -RHO)
    x = jaw[0] - REACH + 0.01
    start = np.array([(x, 0.3)])
    velocity = np.array([(0.0, -1.5)])
    rolling = run(pocket_setup([(x, 0.3)], [(0.0, -1.5)]))
    natural = np.array([[1.5 / R, 0.0, 0.0]])  # w = z x v / r: rolling from the start
    spin = run(make_setup(start, velocity, model="spin", spins=natural, pockets=POCKETS))
    assert edge_events(spin)[0][:2] == ("cushion", "side-bottom")
    assert edge_events(spin)[0][2] == pytest.approx(edge_events(rolling)[0][2], rel=1e-12)


def test_naive_drops_a_ball_in_its_stepped_way_and_keeps_it_out_of_the_jaws() -> None:
    start = (TABLE[0] / 2, 0.4)
    result = run(pocket_setup([start], [(0.0, -1.0)]), "naive", 1 / 240)
    assert [(e.kind, e.pocket) for e in result.events] == [("pocket", "side-bottom")]
    assert result.events[0].time == pytest.approx(rolled(1.0, start[1] + RHO), abs=1 / 240)


def test_bad_pocket_geometry_is_refused_by_the_physics_too() -> None:
    with pytest.raises(ValueError, match="corner_pocket_width"):
        pocket_table(TABLE, R, corner_width=2 * R)
    with pytest.raises(ValueError, match="side_pocket_width"):
        pocket_table(TABLE, R, side_width=TABLE[0])
    with pytest.raises(ValueError, match="short cushions"):
        pocket_table((2.0, 0.12), R)


@pytest.mark.parametrize("method", ["event", "exact"])
def test_a_sliding_ball_pressed_into_a_jaw_by_its_slip_goes_on_along_the_tangent(
    method: str,
) -> None:
    """On the head-right corner's bottom jaw, moving along its tangent, its slip
    pressing it into the jaw: the jaw holds it (takes the slip's normal part), and it
    never enters the jaw's reach."""
    jaw = POCKETS.jaws[0]
    angle = math.radians(110)
    out = np.array([math.cos(angle), math.sin(angle)])
    start = jaw + POCKETS.jaw_reach * out
    tangent = np.array([-out[1], out[0]])  # towards the pocket
    velocity = 0.1 * tangent  # slow: |v|^2 < reach |a|, it would curve in
    slip = 0.5 * out  # friction opposes it: pushes the ball into the jaw
    offset = (slip - velocity) / R  # = rot90(w_xy): w_xy = (offset_y, -offset_x)
    spins = np.array([[offset[1], -offset[0], 0.0]])
    setup = make_setup(
        np.array([start]), velocity[None], model="spin", spins=spins, pockets=POCKETS
    )
    result = run(setup, method)
    times = np.linspace(0.0, result.rest_time, 2001)
    check_on_pocket_table(result, times)
    assert [e.kind for e in result.events][-1] == "pocket"
