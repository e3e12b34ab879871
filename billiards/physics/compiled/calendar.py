"""Resolving events, compiled (engine.calendar.Calendar's rules for one run, in its
order), for both motion models: a motion-state change; a cushion, a jaw or a drop; a
ball-ball contact, with the rounding floor, grazes asked again, pressed pairs and soft
contacts (docs/touching.md), and the rules of a ball whose own slip presses it into
what it touches (laws.held: a hold, a push, a part; compiled.laws.held).

A rolling ball never slips, so the held rules decline every rolling pair (as
Calendar._held_pair and _parted do) and its spins stay zero.
"""

from __future__ import annotations

import numpy as np

from billiards.physics.compiled.airborne.ball_ball import (
    frictionless_impulse_3d,
    line_of_centres_3d,
)
from billiards.physics.compiled.airborne.bounces import bounce
from billiards.physics.compiled.airborne.flight import Vector3
from billiards.physics.compiled.anchoring import ask_return
from billiards.physics.compiled.arithmetic import exact_sum, length, py_max, py_min
from billiards.physics.compiled.jit import inline, kernel
from billiards.physics.compiled.laws import held
from billiards.physics.compiled.laws.ball_ball import line_of_centres, pressed_separation
from billiards.physics.compiled.laws.dispatch import ball_law, cushion_law
from billiards.physics.compiled.roots import EPS
from billiards.physics.compiled.spin_motion import state_change
from billiards.physics.compiled.state import (
    KIND_BALL,
    KIND_CUSHION,
    KIND_POCKET,
    MODEL_SPIN,
    Calendar,
    Log,
    Table,
)
from billiards.physics.laws.ball_ball import ELASTIC_BELOW
from billiards.physics.spin.motion import SLIDING

Vector = tuple[float, float]
Spin = tuple[float, float, float]


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
def change_state(world: tuple, ball: int, time: float) -> None:
    """A ball's motion state ends by itself (Calendar._change_state): it starts the next
    one, logged as a transition."""
    anchors, calendar, table, _ = world
    now = calendar.now
    state_change(anchors, ball, time, table, now)
    _queue_one(calendar, ball, now, 1)


@inline
def _queue_one(calendar: Calendar, ball: int, now: np.ndarray, logged: int) -> None:
    """Queue one ball's anchoring from `now` (STATE_WIDTH,): position, velocity,
    (acceleration), spin, height and vertical velocity."""
    row = calendar.queued[0]
    row[0], row[1], row[2], row[3] = now[0], now[1], now[2], now[3]
    row[4], row[5], row[6] = now[6], now[7], now[8]
    row[7], row[8] = now[9], now[10]
    calendar.queued_balls[0] = ball
    calendar.queue[0], calendar.queue[1] = 1, logged


@kernel
def resolve_edge(world: tuple, ball: int, time: float, at: np.ndarray) -> None:
    """A cushion (edge 0-3), a jaw, or a drop past a capture line (Calendar._resolve_edge);
    at (9,): the ball's position, velocity, acceleration and spin now, changed in place
    to its kinematics after."""
    _edge_outcome(world, ball, time, at)
    _queue_one(world[1], ball, at, 0)


@inline
def _edge_outcome(world: tuple, ball: int, time: float, at: np.ndarray) -> None:
    """resolve_edge's contact: logged, and the ball's position, velocity and spin after
    it written into `at` (a held or grazing ball's edge is set to be skipped:
    calendar.skip)."""
    _, calendar, table, _ = world
    edge = calendar.edge[ball]
    if edge < 0:  # a flying ball at a cushion's nose, or over the rail
        _flying_wall(world, ball, time, at, edge)
        return
    jaw_count = len(table.jaws) if table.pockets else 0
    x, y, vx, vy = at[0], at[1], at[2], at[3]
    if edge >= 4 + jaw_count:  # gone, at rest where it crossed, out of every pair
        speed = length(vx, vy)
        pocket = edge - 4 - jaw_count
        if table.flies and at[9] > table.cushion.cushion_height + table.radius:
            pocket = -1  # higher than a ball clears the rail: over the pocket, off the table
        record(world, time, KIND_POCKET, (ball, -1), speed, pocket)
        calendar.gone[ball] = True
        at[2] = at[3] = at[6] = at[7] = at[8] = 0.0
        at[9], at[10] = table.radius, 0.0  # at rest in the pocket, not in the air
        return
    # The unit normal into the cushion or jaw; a cushion contact snaps the centre onto
    # its line.
    pocket = -1
    if edge < 4:
        if edge // 2 == 0:
            at[0] = table.bounds[edge]
            into = (1.0 if edge % 2 else -1.0, 0.0)
        else:
            at[1] = table.bounds[edge]
            into = (0.0, 1.0 if edge % 2 else -1.0)
    else:
        jaw = edge - 4
        into_x, into_y = table.jaws[jaw, 0] - x, table.jaws[jaw, 1] - y
        distance = length(into_x, into_y)
        into = (into_x / distance, into_y / distance)
        pocket = table.jaw_pocket[jaw]
    spin = (at[6], at[7], at[8])
    closing = vx * into[0] + vy * into[1]
    if closing <= ELASTIC_BELOW and at[4] * into[0] + at[5] * into[1] > 0:
        # Pressed into the rubber at (nearly) no normal speed: held, the edge skipped.
        velocity, spin = _held(world, ball, time, ((vx, vy), spin), into, 0.0)
        _write(at, velocity, spin)
        if closing > 0:
            record(world, time, KIND_CUSHION, (ball, -1), closing, pocket)
        calendar.skip[0], calendar.skip[1] = ball, edge
        return
    bounced, turned, approach = cushion_law(
        table.cushion_law, (vx, vy), spin, into, table.masses[ball], table.cushion
    )
    if approach <= 0:  # a tangent graze: no contact; asked again for every other edge
        calendar.skip[0], calendar.skip[1] = ball, edge
        return
    record(world, time, KIND_CUSHION, (ball, -1), approach, pocket)
    _write(at, bounced, turned)


@kernel
def _flying_wall(world: tuple, ball: int, time: float, at: np.ndarray, edge: int) -> None:
    """A flying ball at a cushion's nose (edge -(2 + wall)) or crossing the rail (edge
    -(6 + wall): spin_times.flying_wall_edge). Over the rail it leaves the table: logged
    as a drop with no pocket (a "pocket" event whose pocket is None), gone, at rest
    where it crossed. On the nose (a line along the wall at the cushion's height) it
    meets a fixed body along n = (across, z - h) / R, frictionless, with the cushion's
    restitution e: v' = v - (1 + e) (v.n) n (energy never rises, the spin as it was);
    not approaching, a graze, skipped once."""
    _, calendar, table, _ = world
    code = -edge - 2
    wall = code % 4
    axis = wall // 2
    side = 1.0 if wall % 2 else -1.0
    if code >= 4:
        speed = length(at[2], at[3])
        record(world, time, KIND_POCKET, (ball, -1), speed, -1)
        calendar.gone[ball] = True
        at[2] = at[3] = at[6] = at[7] = at[8] = 0.0
        at[9], at[10] = table.radius, 0.0
        return
    radius = table.radius
    across = side * (table.bounds[wall] - at[axis]) + radius  # from the wall's plane
    rise = at[9] - table.cushion.cushion_height
    # n from the nose to the centre: `across` into the table (-side along the axis).
    inward = (0.0 - side) * (across / radius)
    up = rise / radius
    along = at[2 + axis] * inward + at[10] * up
    if not along < 0:
        calendar.skip[0], calendar.skip[1] = ball, edge
        return
    restitution = table.cushion.cushion_restitution
    change = (1.0 + restitution) * along
    at[2 + axis] = at[2 + axis] - change * inward
    at[10] = at[10] - change * up
    record(world, time, KIND_CUSHION, (ball, -1), 0.0 - along, -1)


@inline
def _write(at: np.ndarray, velocity: Vector, spin: Spin) -> None:
    """A ball's new velocity and spin, into its row `at` (9,)."""
    at[2], at[3] = velocity
    at[6], at[7], at[8] = spin


@kernel
def _held(
    world: tuple,
    ball: int,
    time: float,
    motion: tuple[Vector, Spin],
    into: Vector,
    holder_speed: float,
) -> tuple[Vector, Spin]:
    """held.hold, or wedge for a second holder at this instant (Calendar._held);
    motion: the ball's velocity and spin."""
    _, calendar, table, _ = world
    velocity, spin = held.hold(motion[0], motion[1], into, holder_speed, table.radius)
    if calendar.held_time[ball] == time and (
        calendar.held_into[ball, 0] != into[0] or calendar.held_into[ball, 1] != into[1]
    ):
        spin = held.wedge(velocity, spin, table.radius)  # a second holder: wedged
    calendar.held_time[ball] = time
    calendar.held_into[ball, 0], calendar.held_into[ball, 1] = into
    calendar.counts[1] += 1
    return velocity, spin


@kernel
def resolve_pair(world: tuple, first: int, second: int, time: float, at: np.ndarray) -> None:
    """A contact of two balls (Calendar._resolve_pair); at (2, STATE_WIDTH): their
    positions, velocities, accelerations, spins, heights and vertical velocities now
    (a pair with a ball off the cloth: _flying_pair)."""
    _, calendar, table, _ = world
    if table.flies and _off_the_cloth(at, table.radius):
        _flying_pair(world, (first, second), time, at)
        return
    p1, p2 = (at[0, 0], at[0, 1]), (at[1, 0], at[1, 1])
    v1, v2 = (at[0, 2], at[0, 3]), (at[1, 2], at[1, 3])
    spins = ((at[0, 6], at[0, 7], at[0, 8]), (at[1, 6], at[1, 7], at[1, 8]))
    masses = (table.masses[first], table.masses[second])
    normal = line_of_centres(p1, p2)
    elastic = calendar.contact_time[first] == time or calendar.contact_time[second] == time
    restitution = 1.0 if elastic else table.restitution
    after1, after2, turned1, turned2, approach = ball_law(
        table.ball_law,
        normal,
        (v1, v2, spins[0], spins[1]),
        (masses[0], masses[1], restitution, table.radius, table.ball_friction),
    )
    turned = (turned1, turned2)
    # The rounding floor: (v1 - v2).n carries a few ulps of the pair's speeds and of the
    # run's fastest (Calendar._resolve_pair says why).
    sizes = (abs(v1[0]), abs(v1[1]), abs(v2[0]), abs(v2[1]))
    scale = exact_sum(sizes, calendar.partials) + calendar.speed_scale[0]
    rounding = 8.0 * EPS * scale + 1e-290
    pair = (first, second)
    if approach <= rounding:
        if _held_pair(world, pair, time, at, normal, approach):
            return
        if _parted(world, pair, time, at, normal, rounding):
            return
        if not _pressed(world, pair, time, at, rounding):
            return
        after1, after2 = pressed_separation(normal, v1, masses[0], v2, masses[1])
        turned = spins  # the pressed law is frictionless
        approach = py_max(approach, 0.0)
        calendar.pressed_at[first, second] = time
    elif _pressed_back(at, (after1[0] - after2[0], after1[1] - after2[1])):
        # A soft contact whose pair parts slower than its accelerations close it: held
        # where a ball's own slip presses (unless the TC rule made it elastic), else
        # pressed apart.
        if not elastic and _held_pair(world, pair, time, at, normal, approach):
            return
        after1, after2 = pressed_separation(normal, after1, masses[0], after2, masses[1])
    _pair_contact(world, pair, time, at, ((after1, after2), turned), approach, 0)


@inline
def _off_the_cloth(at: np.ndarray, radius: float) -> bool:
    """Whether either ball of a pair (at's rows) is above the cloth or leaving it."""
    return at[0, 9] > radius or at[1, 9] > radius or at[0, 10] != 0 or at[1, 10] != 0


@kernel
def _flying_pair(world: tuple, pair: tuple[int, int], time: float, at: np.ndarray) -> None:
    """A contact of two balls with one in the air (airborne.ball_ball): frictionless
    along the 3D line of centres, momentum kept in three axes, the spins as they were
    (the TC rule's elastic repeat as on the cloth). A ball on the cloth that the impulse
    pushes down meets the bed at once and bounces (_bed_takes: pooltool resolves its
    ball-table event at once after the ball-ball one, as here); one pushed up leaves
    the cloth. A pair not approaching is a graze: asked again for its return."""
    _, calendar, table, _ = world
    first, second = pair
    p1, p2 = (at[0, 0], at[0, 1], at[0, 9]), (at[1, 0], at[1, 1], at[1, 9])
    v1, v2 = (at[0, 2], at[0, 3], at[0, 10]), (at[1, 2], at[1, 3], at[1, 10])
    elastic = calendar.contact_time[first] == time or calendar.contact_time[second] == time
    restitution = 1.0 if elastic else table.restitution
    normal = line_of_centres_3d(p1, p2)
    masses = (table.masses[first], table.masses[second])
    after1, after2, approach = frictionless_impulse_3d(
        normal, v1, masses[0], v2, masses[1], restitution
    )
    if approach <= 0:
        ask_return(world, first, second, time)
        return
    after1, turned1 = _bed_takes(after1, (at[0, 6], at[0, 7], at[0, 8]), at[0, 9], table)
    after2, turned2 = _bed_takes(after2, (at[1, 6], at[1, 7], at[1, 8]), at[1, 9], table)
    at[0, 10], at[1, 10] = after1[2], after2[2]
    velocities = ((after1[0], after1[1]), (after2[0], after2[1]))
    _pair_contact(world, pair, time, at, (velocities, (turned1, turned2)), approach, 0)


@kernel
def _bed_takes(velocity: Vector3, spin: Spin, height: float, table: Table) -> tuple[Vector3, Spin]:
    """A ball on the cloth (its centre at `height` no more than R) that a contact drives
    down meets the bed at that instant (airborne.bounces.bounce: TP A-14's frictional
    impact, e_t): it is thrown up at e_t of its downward speed, and flies where that
    rises the settling height, else slides on (v_z 0). A ball in the air, or one driven
    up (which leaves the cloth), passes as it is."""
    if height > table.radius or not velocity[2] < 0:
        return velocity, spin
    gravity, restitution, friction, lowest_launch = table.flight
    laws = (table.radius, restitution, friction)
    after, turned, _ = bounce(velocity, spin, laws, gravity, lowest_launch)
    return after, turned


@inline
def _pair_contact(
    world: tuple,
    pair: tuple[int, int],
    time: float,
    at: np.ndarray,
    motion: tuple[tuple[Vector, Vector], tuple[Spin, Spin]],
    speed: float,
    logged: int,
) -> bool:
    """Log a pair's contact and queue its anchoring at its positions in `at` with motion
    (its velocities and spins after); `logged`: the rows whose new state is logged (a
    cloth impulse's, 1 << row). True."""
    record(world, time, KIND_BALL, pair, speed, -1)
    calendar = world[1]
    velocities, spins = motion
    kinematics = calendar.queued
    for row in range(2):
        kinematics[row, 0], kinematics[row, 1] = at[row, 0], at[row, 1]
        kinematics[row, 2], kinematics[row, 3] = velocities[row]
        kinematics[row, 4], kinematics[row, 5], kinematics[row, 6] = spins[row]
        kinematics[row, 7], kinematics[row, 8] = at[row, 9], at[row, 10]
        calendar.queued_balls[row] = pair[row]
    calendar.queue[0], calendar.queue[1] = 2, logged
    return True


@inline
def _slipping(world: tuple, ball: int) -> bool:
    """Whether a ball slides (a slip that can press it into what it touches)."""
    anchors, _, table, _ = world
    return table.model == MODEL_SPIN and anchors.state[ball] == SLIDING


@kernel
def _held_pair(
    world: tuple,
    pair: tuple[int, int],
    time: float,
    at: np.ndarray,
    normal: Vector,
    approach: float,
) -> bool:
    """A sliding ball's own slip presses it into the other: held, or a push
    (Calendar._held_pair; laws.held). True if resolved so."""
    _, calendar, table, _ = world
    first, second = pair
    if table.model != MODEL_SPIN:  # no rolling ball slips: declined, as there
        return False
    # Held again at the same instant only after another hold (a third ball's).
    again = calendar.held_pair_time[first, second] == time
    if _curvature(at) >= 0 or (
        again and calendar.held_pair_holds[first, second] == calendar.counts[1]
    ):
        return False
    nx, ny = normal
    pressing = (
        _slipping(world, first) and at[0, 4] * -nx + at[0, 5] * -ny > 0,
        _slipping(world, second) and at[1, 4] * nx + at[1, 5] * ny > 0,
    )
    if not (pressing[0] or pressing[1]):
        return False
    radius = table.radius
    masses = (table.masses[first], table.masses[second])
    velocities = ((at[0, 2], at[0, 3]), (at[1, 2], at[1, 3]))
    spins = ((at[0, 6], at[0, 7], at[0, 8]), (at[1, 6], at[1, 7], at[1, 8]))
    # A plastic normal impulse first (momentum kept): the two at one normal speed.
    speeds = (
        velocities[0][0] * nx + velocities[0][1] * ny,
        velocities[1][0] * nx + velocities[1][1] * ny,
    )
    momentum = masses[0] * speeds[0] + masses[1] * speeds[1]
    common = momentum / (masses[0] + masses[1])
    along = (-ny, nx)
    slips = (
        radius * (spins[0][0] * along[0] + spins[0][1] * along[1]),
        radius * (spins[1][0] * along[0] + spins[1][1] * along[1]),
    )
    within = (not pressing[0] or abs(common) <= abs(slips[0])) and (
        not pressing[1] or abs(common) <= abs(slips[1])
    )
    logged = 0
    if within:
        motion = _both_held(
            world, pair, time, (velocities, spins), (speeds, common), pressing, normal
        )
    else:
        pushed, motion = _pushed(velocities, spins, masses, pressing, (normal, radius))
        if not pushed:
            return False
        calendar.counts[1] += 1
        logged = 3  # a push's cloth impulses
    calendar.held_pair_time[first, second] = time
    calendar.held_pair_holds[first, second] = calendar.counts[1]
    return _pair_contact(world, pair, time, at, motion, py_max(approach, 0.0), logged)


@kernel
def _both_held(
    world: tuple,
    pair: tuple[int, int],
    time: float,
    motion: tuple[tuple[Vector, Vector], tuple[Spin, Spin]],
    normal_speeds: tuple[Vector, float],
    pressing: tuple[bool, bool],
    normal: Vector,
) -> tuple[tuple[Vector, Vector], tuple[Spin, Spin]]:
    """_held_pair's first way: both at the common normal speed, each pressing ball held
    (Calendar._held_pair). normal_speeds: (each ball's, the common)."""
    (velocities, spins), (speeds, common) = motion, normal_speeds
    nx, ny = normal
    change_first, change_second = common - speeds[0], common - speeds[1]
    (v1x, v1y), (v2x, v2y) = velocities
    first = ((v1x + change_first * nx, v1y + change_first * ny), spins[0])
    second = ((v2x + change_second * nx, v2y + change_second * ny), spins[1])
    if pressing[0]:
        first = _held(world, pair[0], time, first, (-nx, -ny), -common)
    if pressing[1]:
        second = _held(world, pair[1], time, second, (nx, ny), common)
    return (first[0], second[0]), (first[1], second[1])


@kernel
def _pushed(
    velocities: tuple[Vector, Vector],
    spins: tuple[Spin, Spin],
    masses: Vector,
    pressing: tuple[bool, bool],
    geometry: tuple[Vector, float],
) -> tuple[bool, tuple[tuple[Vector, Vector], tuple[Spin, Spin]]]:
    """_held_pair's second way: the first pressing ball pushes the other (held.push, the
    pusher first); geometry: (normal, radius). (False, as given) where it would pull."""
    normal, radius = geometry
    if pressing[0]:
        into = (-normal[0], -normal[1])
        pushed, moved, turned = held.push(velocities, spins, masses, into, radius)
        return pushed, (moved, turned)
    swapped = ((velocities[1], velocities[0]), (spins[1], spins[0]))
    pushed, moved, turned = held.push(
        swapped[0], swapped[1], (masses[1], masses[0]), normal, radius
    )
    return pushed, ((moved[1], moved[0]), (turned[1], turned[0]))


@inline
def _parted(
    world: tuple,
    pair: tuple[int, int],
    time: float,
    at: np.ndarray,
    normal: Vector,
    rounding: float,
) -> bool:
    """A pair pressed with no slip driving it: parted at ELASTIC_BELOW (Calendar._parted;
    held.part). True if resolved so."""
    _, calendar, table, _ = world
    first, second = pair
    relative_x, relative_y = at[0, 2] - at[1, 2], at[0, 3] - at[1, 3]
    if (
        length(relative_x, relative_y) > rounding
        or calendar.pressed_at[first, second] == time
        or _curvature(at) >= 0
    ):
        return False
    sliding = (_slipping(world, first), _slipping(world, second))
    if not (sliding[0] or sliding[1]):
        return False
    velocities = ((at[0, 2], at[0, 3]), (at[1, 2], at[1, 3]))
    spins = ((at[0, 6], at[0, 7], at[0, 8]), (at[1, 6], at[1, 7], at[1, 8]))
    payer = held.payer_of(velocities, spins, sliding, table.radius)
    masses = (table.masses[first], table.masses[second])
    motion = held.part(velocities, spins, masses, normal, payer, (table.radius, ELASTIC_BELOW))
    calendar.pressed_at[first, second] = time
    return _pair_contact(world, pair, time, at, motion, 0.0, 1 << payer)


@inline
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
