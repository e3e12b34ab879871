"""Resolving the rolling model's events, compiled (engine.calendar.Calendar's rules for
one run, in its order): a cushion, a jaw or a drop; a ball-ball contact, with the
rounding floor, grazes asked again, pressed pairs and soft contacts (docs/touching.md).

The rules that need a sliding ball (a held pair, a push, a part) never apply here: a
rolling ball does not slip, so Calendar._held_pair and _parted decline every pair.
"""

from __future__ import annotations

import numpy as np

from billiards.physics.compiled.anchoring import ask_return, flush
from billiards.physics.compiled.arithmetic import exact_sum, length, py_max, py_min
from billiards.physics.compiled.jit import inline, kernel
from billiards.physics.compiled.laws.ball_ball import line_of_centres, pressed_separation
from billiards.physics.compiled.laws.frictionless import frictionless_impulse
from billiards.physics.compiled.laws.held import hold
from billiards.physics.compiled.laws.mirror import mirror_velocity
from billiards.physics.compiled.roots import EPS
from billiards.physics.compiled.state import KIND_BALL, KIND_CUSHION, KIND_POCKET, Log
from billiards.physics.laws.ball_ball import ELASTIC_BELOW


@inline
def record(
    world: tuple, time: float, kind: int, balls: tuple[int, int], speed: float, pocket: int
) -> None:
    """Log a contact and count it (Calendar._record); a ball-ball contact is each ball's
    latest (the TC rule)."""
    _, calendar, _, log = world
    if kind == KIND_BALL:
        calendar.contact_time[balls[0]] = time
        calendar.contact_time[balls[1]] = time
    _log_contact(log, time, kind, balls, speed, pocket)
    calendar.counts[0] += 1


@inline
def _log_contact(
    log: Log, time: float, kind: int, balls: tuple[int, int], speed: float, pocket: int
) -> None:
    row = log.filled[0]
    if row >= len(log.contact_time):
        log.filled[2] = 1
        return
    log.contact_time[row], log.contact_kind[row] = time, kind
    log.contact_balls[row, 0], log.contact_balls[row, 1] = balls
    log.contact_speed[row], log.contact_pocket[row] = speed, pocket
    log.filled[0] = row + 1


@kernel
def resolve_edge(world: tuple, ball: int, time: float, at: np.ndarray) -> None:
    """A cushion (edge 0-3), a jaw, or a drop past a capture line (Calendar._resolve_edge);
    at (6,): the ball's position, velocity and acceleration now."""
    x, y, vx, vy = _edge_outcome(world, ball, time, at)
    kinematics = np.empty((1, 4))
    kinematics[0, 0], kinematics[0, 1], kinematics[0, 2], kinematics[0, 3] = x, y, vx, vy
    balls = np.empty(1, dtype=np.int64)
    balls[0] = ball
    flush(world, balls, time, kinematics)


@kernel
def _edge_outcome(
    world: tuple, ball: int, time: float, at: np.ndarray
) -> tuple[float, float, float, float]:
    """resolve_edge's contact: logged, and the ball's position and velocity after it (a
    held or grazing ball's edge is set to be skipped: calendar.skip)."""
    _, calendar, table, _ = world
    edge = calendar.edge[ball]
    jaw_count = len(table.jaws) if table.pockets else 0
    x, y, vx, vy, ax, ay = at[0], at[1], at[2], at[3], at[4], at[5]
    if edge >= 4 + jaw_count:  # gone, at rest where it crossed, out of every pair
        speed = length(vx, vy)
        record(world, time, KIND_POCKET, (ball, -1), speed, edge - 4 - jaw_count)
        calendar.gone[ball] = True
        return x, y, 0.0, 0.0
    # The unit normal into the cushion or jaw; a cushion contact snaps the centre onto
    # its line.
    pocket = -1
    if edge < 4:
        if edge // 2 == 0:
            x = table.bounds[edge]
            into = (1.0 if edge % 2 else -1.0, 0.0)
        else:
            y = table.bounds[edge]
            into = (0.0, 1.0 if edge % 2 else -1.0)
    else:
        jaw = edge - 4
        into_x, into_y = table.jaws[jaw, 0] - x, table.jaws[jaw, 1] - y
        distance = length(into_x, into_y)
        into = (into_x / distance, into_y / distance)
        pocket = table.jaw_pocket[jaw]
    closing = vx * into[0] + vy * into[1]
    if closing <= ELASTIC_BELOW and ax * into[0] + ay * into[1] > 0:
        # Pressed into the rubber at (nearly) no normal speed: held, the edge skipped.
        vx, vy = hold((vx, vy), into)
        calendar.counts[1] += 1
        if closing > 0:
            record(world, time, KIND_CUSHION, (ball, -1), closing, pocket)
        calendar.skip[0], calendar.skip[1] = ball, edge
        return x, y, vx, vy
    bounced, approach = mirror_velocity((vx, vy), into, table.retention)
    if approach <= 0:  # a tangent graze: no contact; asked again for every other edge
        calendar.skip[0], calendar.skip[1] = ball, edge
        return x, y, vx, vy
    record(world, time, KIND_CUSHION, (ball, -1), approach, pocket)
    return x, y, bounced[0], bounced[1]


@kernel
def resolve_pair(world: tuple, first: int, second: int, time: float, at: np.ndarray) -> None:
    """A contact of two balls (Calendar._resolve_pair); at (2, 6): their positions,
    velocities and accelerations now."""
    _, calendar, table, _ = world
    p1, p2 = (at[0, 0], at[0, 1]), (at[1, 0], at[1, 1])
    v1, v2 = (at[0, 2], at[0, 3]), (at[1, 2], at[1, 3])
    m1, m2 = table.masses[first], table.masses[second]
    normal = line_of_centres(p1, p2)
    elastic = calendar.contact_time[first] == time or calendar.contact_time[second] == time
    restitution = 1.0 if elastic else table.restitution
    after1, after2, approach = frictionless_impulse(normal, v1, m1, v2, m2, restitution)
    # The rounding floor: (v1 - v2).n carries a few ulps of the pair's speeds and of the
    # run's fastest (Calendar._resolve_pair says why).
    sizes = np.array([abs(v1[0]), abs(v1[1]), abs(v2[0]), abs(v2[1])])
    scale = exact_sum(sizes) + calendar.speed_scale[0]
    rounding = 8.0 * EPS * scale + 1e-290
    if approach <= rounding:
        if not _pressed(world, (first, second), time, at, rounding):
            return
        after1, after2 = pressed_separation(normal, v1, m1, v2, m2)
        approach = py_max(approach, 0.0)
        calendar.pressed_at[first, second] = time
    elif _pressed_back(at, (after1[0] - after2[0], after1[1] - after2[1])):
        # A soft contact whose pair parts slower than its accelerations close it.
        after1, after2 = pressed_separation(normal, after1, m1, after2, m2)
    record(world, time, KIND_BALL, (first, second), approach, -1)
    kinematics = np.empty((2, 4))
    kinematics[0, 0], kinematics[0, 1], kinematics[0, 2], kinematics[0, 3] = p1 + after1
    kinematics[1, 0], kinematics[1, 1], kinematics[1, 2], kinematics[1, 3] = p2 + after2
    balls = np.empty(2, dtype=np.int64)
    balls[0], balls[1] = first, second
    flush(world, balls, time, kinematics)


@kernel
def _pressed(
    world: tuple, pair: tuple[int, int], time: float, at: np.ndarray, rounding: float
) -> bool:
    """A rounding-level contact (Calendar._touching_without_closing): True if pressed
    together; otherwise the pair's entry is set to its return, or to never."""
    _, calendar, _, _ = world
    first, second = pair
    rx, ry = at[0, 2] - at[1, 2], at[0, 3] - at[1, 3]
    if length(rx, ry) <= rounding or calendar.pressed_at[first, second] == time:
        # Moving together to rounding, or already pressed apart at this instant.
        ask_return(world, first, second, time)
        return False
    if _curvature(at) < 0:  # pressed together
        return True
    # A graze: asked again for its return (the calendar must never lose a pair).
    return not ask_return(world, first, second, time)


@kernel
def _curvature(at: np.ndarray) -> float:
    """|w|^2 + D.(a1 - a2) at the pair's velocities now (calendar._Touch.curvature)."""
    rx, ry = at[0, 2] - at[1, 2], at[0, 3] - at[1, 3]
    sx, sy = at[0, 0] - at[1, 0], at[0, 1] - at[1, 1]
    return (rx * rx + ry * ry) + (sx * (at[0, 4] - at[1, 4]) + sy * (at[0, 5] - at[1, 5]))


@kernel
def _pressed_back(at: np.ndarray, relative: tuple[float, float]) -> bool:
    """Whether a pair parts slower than min(ELASTIC_BELOW, |w|) while pressed back
    (calendar._pressed_back)."""
    sx, sy = at[0, 0] - at[1, 0], at[0, 1] - at[1, 1]
    distance = length(sx, sy)
    parting = (relative[0] * sx + relative[1] * sy) / distance
    speed = length(relative[0], relative[1])
    if parting >= py_min(ELASTIC_BELOW, speed):
        return False
    pressing = sx * (at[0, 4] - at[1, 4]) + sy * (at[0, 5] - at[1, 5])
    return speed * speed + pressing < 0
