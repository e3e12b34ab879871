"""A pocketed ball's drop, as drawn: its fall from the capture line into its hole."""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from billiards.record.pocket_shapes import PocketShapes
from billiards.record.trajectory import RecordedMotion

FloatArray = npt.NDArray[np.float64]


# A pocketed ball's drop: from the capture line it falls under gravity and carries on
# with its speed into the hole (a slow one rolls round the edge first: tipped_fall),
# held inside the hole's edge once it is below the cloth, and is taken away (far below
# the bed) once it has sunk DROP_GONE radii: by then it is dark in its liner
# (shaders/ball.frag darkens it as it sinks), so it never vanishes while it can be seen.
DROP_GRAVITY = 9.81  # m/s^2
DROP_GONE = 4.0  # radii sunk
GONE_DEPTH = -1.0  # m, z of a ball that has dropped


# A ball that reaches the capture line slower than sqrt(g r) rolls round the hole's edge
# before it leaves it (a faster one leaves it at once: the cloth cannot hold it on a
# curve of its radius). Its turn about the edge is found on this many angles.
TIP_STEPS = 2000


def tipped_fall(elapsed: FloatArray, speed: float, radius: float) -> tuple[FloatArray, FloatArray]:
    """A slow ball's path over the hole's edge, `elapsed` (F,) s after its centre crossed
    it at `speed` (< sqrt(g r)): how far its centre is past the edge (F,) and its height
    (F,), both m.

    It rolls about the edge (moment of inertia 7/5 m r^2 about it: the angle from the
    vertical grows as theta'' = 5/7 g/r sin theta, from theta' = speed / r) until the
    cloth's push would have to pull, at cos theta = (7 v^2 / (g r) + 10) / 17, and
    then flies under gravity from there (Walker's sphere rolling off an edge)."""
    gr = DROP_GRAVITY * radius
    leave = math.acos((7.0 * speed * speed / gr + 10.0) / 17.0)
    thetas = np.linspace(0.0, leave, TIP_STEPS + 1)
    # theta'^2 from energy: (speed / r)^2 + 10/7 g/r (1 - cos theta)
    rates = np.sqrt(
        (speed / radius) ** 2 + (10.0 / 7.0) * DROP_GRAVITY / radius * (1.0 - np.cos(thetas))
    )
    steps = np.diff(thetas) * 0.5 * (1.0 / rates[1:] + 1.0 / rates[:-1])
    clock = np.concatenate([[0.0], np.cumsum(steps)])  # s to reach each angle
    theta = np.interp(elapsed, clock, thetas)
    along = radius * np.sin(theta)
    height = radius * np.cos(theta)
    flying = elapsed - clock[-1]
    speed_out = radius * rates[-1]  # along the circle, at the angle it leaves
    late = flying > 0
    along[late] = radius * math.sin(leave) + speed_out * math.cos(leave) * flying[late]
    height[late] = (
        radius * math.cos(leave)
        - speed_out * math.sin(leave) * flying[late]
        - 0.5 * DROP_GRAVITY * flying[late] ** 2
    )
    return along, height


def drop_heights(
    times: FloatArray, drops: FloatArray, radius: float
) -> tuple[FloatArray, FloatArray]:
    """z (F, N) of balls pocketed at `drops` (N,) (inf: never) at `times` (F,), and the
    time (F, N) in s each has been falling (0 before its drop)."""
    fallen = np.maximum(times[:, None] - drops[None, :], 0.0)
    depth = 0.5 * DROP_GRAVITY * fallen * fallen
    z = np.where(depth < DROP_GONE * radius, radius - depth, GONE_DEPTH)
    return z, fallen


def drop_pocketed(
    positions: FloatArray,
    times: FloatArray,
    motion: RecordedMotion,
    pockets: PocketShapes,
    radius: float,
) -> None:
    """Move pocketed balls (in place) from where they crossed the capture line down
    into their hole, and out of sight (drop_heights): each goes
    on at its speed at the capture, kept within the drawn hole (PocketShapes.edge_radii)
    less its radius as it sinks below the cloth, as a liner's wall would keep it."""
    ball_ids = motion.ball_ids
    drops = np.full(len(ball_ids), np.inf)
    hole = np.zeros((len(ball_ids), 2))
    room = np.zeros(len(ball_ids))
    edges = pockets.edge_radii()
    for event in motion.events:
        if event.kind == "pocket" and event.pocket is not None:
            ball = ball_ids.index(event.balls[0])
            index = pockets.names.index(event.pocket)
            drops[ball] = event.time
            hole[ball] = pockets.holes[index, :2]
            room[ball] = edges[index] - radius
    dropped = np.flatnonzero(np.isfinite(drops))
    if len(dropped) == 0:
        return
    z, fallen = drop_heights(times, drops, radius)
    step = 1e-4  # s: the capture velocity from the exact path just before it
    capture = np.empty((len(dropped), 2))
    velocity = np.empty((len(dropped), 2))
    for k, ball in enumerate(dropped.tolist()):
        before, at = motion.positions_at(np.array([drops[ball] - step, drops[ball]]))[:, ball]
        capture[k], velocity[k] = at, (at - before) / step
    elapsed = fallen[:, dropped]  # (F, D)
    free = capture[None] + velocity[None] * elapsed[..., None]
    for k, ball in enumerate(dropped.tolist()):
        speed = float(np.hypot(*velocity[k]))
        if 0.0 < speed * speed < DROP_GRAVITY * radius:  # it rolls round the edge first
            along, height = tipped_fall(elapsed[:, k], speed, radius)
            free[:, k] = capture[k] + (velocity[k] / speed) * along[:, None]
            falling_here = elapsed[:, k] > 0
            z[:, ball] = np.where(
                falling_here & (height <= radius - DROP_GONE * radius),
                GONE_DEPTH,
                np.where(falling_here, height, z[:, ball]),
            )
    offset = free - hole[dropped][None]
    distance = np.maximum(np.linalg.norm(offset, axis=2), 1e-12)
    # Room to move: from wherever the capture was to the hole less a radius, as the
    # ball sinks its first radius below the cloth.
    sunk = np.clip((radius - z[:, dropped]) / radius, 0.0, 1.0)
    start_room = np.linalg.norm(capture - hole[dropped], axis=1)
    allowed = np.maximum(room[dropped], start_room)[None] * (1 - sunk) + room[dropped][None] * sunk
    held = hole[dropped][None] + offset * (np.minimum(distance, allowed) / distance)[..., None]
    falling = elapsed > 0
    gone = z[:, dropped] == GONE_DEPTH
    held = np.where(gone[..., None], hole[dropped][None], held)  # gone: at the hole's centre
    positions[:, dropped, :2] = np.where(falling[..., None], held, positions[:, dropped, :2])
    positions[:, dropped, 2] = z[:, dropped]


# A ball that leaves the table (over the rail, or high over a pocket: an event of kind
# "pocket" with no pocket, issue 45) flies on from where it crossed, on its parabola
# (its velocity there kept), and is taken away once its centre is this far below the
# cloth: past the table's edge and falling to the floor (0.79 m down), out of sight.
OFF_TABLE_GONE = 0.45  # m below the cloth


def departures(motion: RecordedMotion) -> list[tuple[int, float, FloatArray, FloatArray]]:
    """Each ball that left the table: (its index, a time t just before it left, its centre
    (x, y, z) then and its velocity (3,) then), from its exact path."""
    heights = getattr(motion, "heights_at", None)
    if heights is None:
        return []
    found = []
    step = 1e-4  # s: the flight's velocity from its exact path just before it left
    for event in motion.events:
        if event.kind != "pocket" or event.pocket is not None:
            continue
        ball = motion.ball_ids.index(event.balls[0])
        at = np.array([event.time - 2 * step, event.time - step])
        # The motion's own centres: a result on a table without pockets clamps its
        # centres to the cushion lines, which this ball has crossed.
        exact = getattr(motion, "motion", motion)
        flat, lift = exact.positions_at(at)[:, ball], heights(at)[:, ball]
        centre = np.array([*flat[1], lift[1]])
        # A difference of the parabola: the vertical velocity at its midpoint.
        climb = (lift[1] - lift[0]) / step - 0.5 * DROP_GRAVITY * step
        velocity = np.array([*((flat[1] - flat[0]) / step), climb])
        found.append((ball, float(at[1]), centre, velocity))
    return found


def off_table_end(motion: RecordedMotion) -> float:
    """s, when the last ball that left the table is out of sight (fly_off_table); -inf
    if none left it."""
    end = -math.inf
    for _, time, centre, velocity in departures(motion):
        end = max(end, out_of_sight(time, centre, velocity))
    return end


def out_of_sight(time: float, centre: FloatArray, velocity: FloatArray) -> float:
    """s, when a ball flying from `centre` (3,) at `velocity` (3,) at `time` falls to
    OFF_TABLE_GONE below the cloth: the later root of its parabola."""
    fall = float(centre[2]) + OFF_TABLE_GONE
    climb = float(velocity[2])
    return time + (climb + math.sqrt(climb * climb + 2 * DROP_GRAVITY * fall)) / DROP_GRAVITY


def flight_at(
    departure: tuple[int, float, FloatArray, FloatArray], times: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """A departed ball's centre (T, 3) and velocity (T, 3) on its flight at `times`."""
    _, time, centre, velocity = departure
    elapsed = (np.asarray(times, dtype=np.float64) - time)[:, None]
    fall = np.array([0.0, 0.0, -DROP_GRAVITY])
    return centre + velocity * elapsed + 0.5 * fall * elapsed * elapsed, velocity + fall * elapsed


def fly_off_table(positions: FloatArray, times: FloatArray, motion: RecordedMotion) -> None:
    """Move balls that left the table (in place) from where they crossed on along their
    flight, under gravity, then out of sight (GONE_DEPTH) once fallen OFF_TABLE_GONE."""
    for departure in departures(motion):
        ball, time = departure[0], departure[1]
        after = times > time
        centres, _ = flight_at(departure, times[after])
        positions[after, ball, :2] = centres[:, :2]
        positions[after, ball, 2] = np.where(
            centres[:, 2] > -OFF_TABLE_GONE, centres[:, 2], GONE_DEPTH
        )
