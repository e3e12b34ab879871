"""A break recorded at a frame rate: the only thing physics and rendering share.

Positions are ball centres in metres (z = radius: balls stay on the cloth).
Orientations are unit quaternions (billiards.record.quaternions: x, y, z, w, body to world).
At t = 0 every ball has the identity orientation. `ball_state` reads the balls back
at any time between the recorded samples.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
import numpy.typing as npt

from billiards.physics.engine.events import Event
from billiards.record import quaternions
from billiards.rules.pocket_rule import corner_reach, pocket_places
from billiards.scene.render_table import (
    RenderSettings,
    parse_render_settings,
    settings_from_record,
    settings_record,
)
from billiards.scene.tables import TableReader

if TYPE_CHECKING:  # the renderer loads the trajectory, never the physics' geometry
    from billiards.physics.pockets import PocketTable

FloatArray = npt.NDArray[np.float64]


class RecordedMotion(Protocol):
    """What a simulation result offers for recording (billiards.physics.SimulationResult)."""

    @property
    def ball_ids(self) -> tuple[str, ...]: ...
    @property
    def radius(self) -> float: ...
    @property
    def table_size(self) -> tuple[float, float]: ...
    @property
    def rest_time(self) -> float: ...
    @property
    def events(self) -> tuple[Event, ...]: ...
    @property
    def model(self) -> str:
        """The motion model that ran: "rolling" or "spin" (physics.motion_law.MOTION_LAWS)."""
        ...

    @property
    def pockets(self) -> PocketTable | None:
        """The table's pockets (None: a table without pockets, drawn without holes)."""
        ...

    @property
    def curved_paths(self) -> bool:
        """Whether paths curve between the path breaks (a drawing needs samples there)."""
        ...

    def positions_at(self, times: FloatArray) -> FloatArray:
        """Ball centres (T x N x 2) at the given times, evaluated exactly."""
        ...

    def path_breaks(self) -> FloatArray:
        """Sorted times at which any ball's path may bend (its contacts, or the steps)."""
        ...

    def spins_at(self, times: FloatArray) -> FloatArray:
        """Angular velocities (T x N x 3), world axes; a rolling ball's is z x v / r."""
        ...


@dataclass(frozen=True)
class PocketShapes:
    """A pocketed table's shapes, for drawing (billiards.physics.pockets.PocketTable).

    Table coordinates in m (the cushion noses along x = 0, L and y = 0, W)."""

    names: tuple[str, ...]  # (P,) e.g. "foot-left", "side-top"
    holes: FloatArray  # (P, 3) each hole's centre x, y and its radius
    mouths: FloatArray  # (P, 2, 2) the two points where the cushion noses end
    jaws: FloatArray  # (J, 2) centres of the noses' rounded ends
    jaw_radius: float  # m

    @classmethod
    def of(cls, pockets: PocketTable) -> PocketShapes:
        """The shapes of the physics' pockets: its jaws, and the holes and mouths laid
        out from the same places and widths (billiards.rules.pocket_rule.pocket_places). A
        corner's hole is centred on its corner, w_c / 2 across; a side's, w_s / 2
        behind the nose, as wide."""
        a = corner_reach(pockets.corner_width)
        half = pockets.side_width / 2.0
        holes: list[tuple[float, float, float]] = []
        mouths: list[tuple[tuple[float, float], tuple[float, float]]] = []
        for x, y, sx, sy in pocket_places(pockets.table_size):
            if sx:
                holes.append((x, y, pockets.corner_width / 2.0))
                mouths.append(((x + sx * a, y), (x, y + sy * a)))
            else:
                holes.append((x, y - sy * half, half))
                mouths.append(((x - half, y), (x + half, y)))
        return cls(
            names=pockets.names,
            holes=np.array(holes),
            mouths=np.array(mouths),
            jaws=pockets.jaws,
            jaw_radius=pockets.jaw_radius,
        )

    def edge_radii(self) -> FloatArray:
        """(P,) m: each hole's radius as drawn, the distance from its centre to its
        capture line (the line through the pocket's two jaw centres, where a ball's
        centre drops: billiards.physics.pockets), so that the hole's edge is where the
        physics lets a ball fall, not a few millimetres past it."""
        first, second = self.jaws[0::2], self.jaws[1::2]  # two jaws per pocket, in order
        along = second - first
        normal = np.column_stack((-along[:, 1], along[:, 0]))
        normal /= np.linalg.norm(normal, axis=1, keepdims=True)
        offset = self.holes[:, :2] - first
        return np.abs(np.einsum("ij,ij->i", offset, normal))


# A pocketed ball's drop: from the capture line it falls under gravity and carries on
# with its speed into the hole (a slow one rolls round the edge first: tipped_fall), held inside the hole's edge once it is below the cloth,
# and is taken away (far below the bed) once it has sunk DROP_GONE radii: by then it
# is dark in its liner (shaders/ball.frag darkens it as it sinks), so it never
# vanishes while it can be seen.
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


@dataclass(frozen=True)
class CueStrike:
    """The stroke that sets the film going, for drawing the cue: at t = 0 its tip meets
    `ball` and the ball leaves. From the scene's `cue = {...}` (billiards.scene.stroke's
    line, elevation and tip), or, for a cue ball given a velocity, a level cue along
    that velocity (its `tip`, else the centre) at the speed that gives it."""

    ball: str
    direction: float  # degrees from +x, counterclockwise: the cue's line on the cloth
    elevation: float  # degrees above the cloth
    tip: tuple[float, float]  # (side, height) / r where the cue's axis meets the ball
    speed: float  # m/s, the cue's at the strike


def first_contact_time(events: Sequence[Event]) -> float | None:
    """s, simulation time of the first ball-ball contact (None if balls never touch)."""
    return next((e.time for e in events if e.kind == "ball"), None)


def last_motion(trajectory: Trajectory) -> float:
    """s, the last recorded time a ball's centre still moves (a ball that only spins in
    place does not count): the film's last visible motion, where its ending is timed."""
    positions = trajectory.positions
    if len(positions) < 2:
        return float(trajectory.times[0]) if len(positions) else 0.0
    moved = np.any(np.abs(np.diff(positions, axis=0)) > 1e-9, axis=(1, 2))
    if not moved.any():
        return float(trajectory.times[0])
    return float(trajectory.times[int(np.flatnonzero(moved)[-1]) + 1])


@dataclass(frozen=True)
class Trajectory:
    ball_ids: tuple[str, ...]
    radius: float  # m
    table_size: tuple[float, float]  # (length, width) in m
    times: FloatArray  # (F,) s, increasing; evenly spaced at fps when recorded for a film
    positions: FloatArray  # (F, N, 3) m
    orientations: FloatArray  # (F, N, 4) quaternions (x, y, z, w)
    events: tuple[Event, ...]
    rest_time: float  # s, when the last ball stopped (or max_time)
    # The scene it came from, so that a saved trajectory renders like that scene: its
    # file name and its render settings, as the scene reader read and checked them
    # (None: not saved from a scene).
    scene_source: str = ""
    render_settings: RenderSettings | None = None
    # The pockets the physics had (None: a table without pockets, drawn without holes).
    pockets: PocketShapes | None = None
    # The cue's stroke at t = 0 (None: no ball is struck; the film draws no cue).
    strike: CueStrike | None = None

    @property
    def fps(self) -> float:
        """Samples per second, from the first two (meaningful for evenly spaced times)."""
        if len(self.times) < 2:
            return 0.0
        return 1.0 / float(self.times[1] - self.times[0])

    def save(self, path: str | Path) -> None:
        np.savez_compressed(
            path,
            ball_ids=np.array(self.ball_ids),
            radius=self.radius,
            table_size=np.array(self.table_size),
            times=self.times,
            positions=self.positions,
            orientations=self.orientations,
            event_times=np.array([e.time for e in self.events], dtype=np.float64),
            event_kinds=np.array([e.kind for e in self.events], dtype=str),
            event_balls=np.array([",".join(e.balls) for e in self.events], dtype=str),
            event_speeds=np.array([e.impact_speed for e in self.events], dtype=np.float64),
            event_pockets=np.array([e.pocket or "" for e in self.events], dtype=str),
            rest_time=self.rest_time,
            scene=np.array(json.dumps(self._scene_record())),
            **_pocket_arrays(self.pockets),
            **_strike_arrays(self.strike),
        )

    def _scene_record(self) -> dict[str, Any]:
        settings = self.render_settings
        record = None if settings is None else settings_record(settings)
        return {"source": self.scene_source, "render_settings": record}

    @classmethod
    def load(cls, path: str | Path) -> Trajectory:
        """A saved trajectory; ValueError (or KeyError) if the file is not one, and
        SceneError for an older file whose [render] tables are bad."""
        with np.load(path) as data:
            count = len(data["event_times"])
            pockets = data["event_pockets"] if "event_pockets" in data else [""] * count
            events = tuple(
                Event(
                    float(t), str(kind), tuple(str(balls).split(",")), float(speed), pocket or None
                )
                for t, kind, balls, speed, pocket in zip(
                    data["event_times"],
                    data["event_kinds"],
                    data["event_balls"],
                    data["event_speeds"],
                    (str(name) for name in pockets),
                    strict=True,
                )
            )
            size = data["table_size"]
            return cls(
                ball_ids=tuple(str(i) for i in data["ball_ids"]),
                radius=float(data["radius"]),
                table_size=(float(size[0]), float(size[1])),
                times=data["times"],
                positions=data["positions"],
                orientations=data["orientations"],
                events=events,
                rest_time=float(data["rest_time"]),
                pockets=_pockets_of(data),
                strike=_strike_of(data),
                **_scene_of(data),
            )


def _pocket_arrays(pockets: PocketShapes | None) -> dict[str, Any]:
    if pockets is None:
        return {}
    return {
        "pocket_names": np.array(pockets.names),
        "pocket_holes": pockets.holes,
        "pocket_mouths": pockets.mouths,
        "pocket_jaws": pockets.jaws,
        "pocket_jaw_radius": pockets.jaw_radius,
    }


def _pockets_of(data: Any) -> PocketShapes | None:
    if "pocket_names" not in data:
        return None
    return PocketShapes(
        names=tuple(str(name) for name in data["pocket_names"]),
        holes=data["pocket_holes"],
        mouths=data["pocket_mouths"],
        jaws=data["pocket_jaws"],
        jaw_radius=float(data["pocket_jaw_radius"]),
    )


def _strike_arrays(strike: CueStrike | None) -> dict[str, Any]:
    if strike is None:
        return {}
    numbers = (strike.direction, strike.elevation, *strike.tip, strike.speed)
    return {"strike_ball": np.array(strike.ball), "strike": np.array(numbers, dtype=np.float64)}


def _strike_of(data: Any) -> CueStrike | None:
    if "strike_ball" not in data:  # no stroke, or saved before strikes were kept
        return None
    direction, elevation, side, height, speed = (float(v) for v in data["strike"])
    return CueStrike(str(data["strike_ball"]), direction, elevation, (side, height), speed)


def _scene_of(data: Any) -> dict[str, Any]:
    """The scene fields of a saved trajectory (none in files from before they existed)."""
    if "scene" not in data:
        return {}
    scene = json.loads(str(data["scene"]))
    source = str(scene["source"])
    if "render_settings" in scene:
        record = scene["render_settings"]
        settings = None if record is None else settings_from_record(record)
    else:
        # Saved before the settings were typed: the scene's [render] and [[camera]]
        # tables as its file had them, read as the scene reader reads them.
        tables = TableReader(scene["render"], "", source)
        settings = parse_render_settings(tables)
        tables.finish()
    return {"scene_source": source, "render_settings": settings}


def record_trajectory(
    motion: RecordedMotion,
    fps: float = 30.0,
    start: float = 0.0,
    end: float | None = None,
    table_size: tuple[float, float] | None = None,
) -> Trajectory:
    """Sample a simulation at `fps` from `start` to `end` (default: rest time).

    Before t = 0 the balls wait at their starting places, so a film can open a moment
    before the cue ball moves. Orientations follow the rolling rotation over the path
    each ball actually travelled, including the bends at its contacts between frames.
    """
    stop = motion.rest_time if end is None else end
    count = max(int(np.floor((stop - start) * fps + 1e-9)) + 1, 1)
    return sample_trajectory(motion, start + np.arange(count) / fps, table_size)


def sample_trajectory(
    motion: RecordedMotion,
    times: FloatArray,
    table_size: tuple[float, float] | None = None,
    *,
    turn: bool = True,
) -> Trajectory:
    """Sample a simulation at any increasing times (record_trajectory's even ones, or
    say every contact for a picture of the paths). With turn=False the orientations
    stay at the identity: a picture from above does not need them, and for a stepped
    run they cost a loop over every step."""
    flat = motion.positions_at(times)
    if not turn:
        orientations = np.tile(np.array(quaternions.IDENTITY), (*flat.shape[:2], 1))
    elif motion.model == "spin":
        orientations = spin_orientations(motion, times)
    else:
        orientations = rolling_orientations(motion, times)
    positions = np.concatenate([flat, np.full((*flat.shape[:2], 1), motion.radius)], axis=2)
    pockets = None if motion.pockets is None else PocketShapes.of(motion.pockets)
    if pockets is not None:
        _drop_pocketed(positions, times, motion, pockets, motion.radius)
    return Trajectory(
        ball_ids=motion.ball_ids,
        radius=motion.radius,
        table_size=table_size or motion.table_size,
        times=times,
        positions=positions,
        orientations=orientations,
        events=motion.events,
        rest_time=motion.rest_time,
        pockets=pockets,
    )


def _drop_pocketed(
    positions: FloatArray,
    times: FloatArray,
    motion: RecordedMotion,
    pockets: PocketShapes,
    radius: float,
) -> None:
    """Move pocketed balls (in place) from where they crossed the capture line down
    into their hole, and out of sight (billiards.record.trajectory.drop_heights): each goes
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


def rolling_orientations(motion: RecordedMotion, times: FloatArray) -> FloatArray:
    """Each ball's orientation (F, N, 4) at `times`, starting from identity at t = 0.

    Between two path breaks a ball rolls straight, so the rotation over a stretch of
    length s in direction phi is the report's three-step rotation
    Rz(phi) Ry(s / r) Rz(-phi), applied on the left of the orientation so far.
    """
    breaks = motion.path_breaks()
    breaks = breaks[(breaks > 0) & (breaks < times[-1])]
    grid = np.union1d(np.maximum(times, 0.0), breaks)
    grid = np.union1d(grid, [0.0])
    positions = motion.positions_at(grid)
    steps = np.diff(positions, axis=0)  # (G-1, N, 2): straight stretches
    count = positions.shape[1]
    orientation = np.tile(np.array(quaternions.IDENTITY), (count, 1))
    at_grid = np.empty((len(grid), count, 4))
    at_grid[0] = orientation
    for index, step in enumerate(steps, start=1):
        orientation = quaternions.multiply(rolling_rotation(step, motion.radius), orientation)
        # Renormalise: thousands of products would otherwise drift off the unit sphere.
        orientation /= np.linalg.norm(orientation, axis=1, keepdims=True)
        at_grid[index] = orientation
    lookup = np.searchsorted(grid, np.maximum(times, 0.0))
    return at_grid[lookup]


# The spin model's balls turn by their own angular velocity, integrated on a grid at
# least this fine (and through every path break, where it jumps).
SPIN_STEP = 1.0 / 480.0  # s


def spin_orientations(motion: RecordedMotion, times: FloatArray) -> FloatArray:
    """Each ball's orientation (F, N, 4) at `times` in the spin model, from identity at
    t = 0: the angular velocity w(t) (piecewise linear between breaks) integrated by the
    midpoint rule on a grid through every break, each step a turn by w dt about w. For
    the picture only; orientation never feeds back into the motion."""
    end = float(np.max(times))
    breaks = motion.path_breaks()
    breaks = breaks[(breaks > 0) & (breaks < end)]
    grid = np.union1d(np.maximum(times, 0.0), breaks)
    grid = np.union1d(grid, np.arange(0.0, end, SPIN_STEP))
    middles = 0.5 * (grid[:-1] + grid[1:])
    turns = np.asarray(motion.spins_at(middles)) * np.diff(grid)[:, None, None]  # (G-1, N, 3)
    count = turns.shape[1] if len(turns) else len(motion.ball_ids)
    orientation = np.tile(np.array(quaternions.IDENTITY), (count, 1))
    at_grid = np.empty((len(grid), count, 4))
    at_grid[0] = orientation
    for index, turn in enumerate(turns, start=1):
        orientation = quaternions.multiply(rotation_vector_turn(turn), orientation)
        orientation /= np.linalg.norm(orientation, axis=1, keepdims=True)
        at_grid[index] = orientation
    lookup = np.searchsorted(grid, np.maximum(times, 0.0))
    return at_grid[lookup]


def rotation_vector_turn(turn: FloatArray) -> FloatArray:
    """Quaternions (N, 4) turning by |turn| radians about turn / |turn| (N, 3)."""
    angle = np.sqrt(np.sum(turn * turn, axis=1))
    with np.errstate(invalid="ignore", divide="ignore"):
        axis = np.where(angle[:, None] > 0, turn / angle[:, None], 0.0)
    quaternion = np.empty((len(turn), 4))
    quaternion[:, :3] = axis * np.sin(0.5 * angle)[:, None]
    quaternion[:, 3] = np.cos(0.5 * angle)
    return quaternion


def rolling_rotation(step: FloatArray, radius: float) -> FloatArray:
    """Quaternions (N, 4) for rolling along `step` (N, 2) without slipping:
    Rz(phi) * Ry(s / r) * Rz(-phi), a turn by s / r about (-sin phi, cos phi, 0)."""
    length = np.hypot(step[:, 0], step[:, 1])
    phi = np.arctan2(step[:, 1], step[:, 0])
    angle = length / radius
    turn_z = quaternions.about_axis(2, phi)
    roll_y = quaternions.about_axis(1, angle)
    unturn_z = quaternions.about_axis(2, -phi)
    return quaternions.multiply(turn_z, quaternions.multiply(roll_y, unturn_z))


def ball_state(trajectory: Trajectory, time: float) -> tuple[FloatArray, FloatArray]:
    """Ball centres (N x 3) and orientations (N x 4) at a simulation time.

    Exact at the recorded samples; between them, centres are interpolated linearly and
    orientations by normalised linear interpolation (both far below a pixel at film
    frame rates). Clamped to the recorded span.
    """
    times = trajectory.times
    if time <= times[0]:
        return trajectory.positions[0], trajectory.orientations[0]
    if time >= times[-1]:
        return trajectory.positions[-1], trajectory.orientations[-1]
    index = int(np.searchsorted(times, time, side="right")) - 1
    t0, t1 = float(times[index]), float(times[index + 1])
    if time == t0:
        return trajectory.positions[index], trajectory.orientations[index]
    weight = (time - t0) / (t1 - t0)
    p0, p1 = trajectory.positions[index], trajectory.positions[index + 1]
    q0, q1 = trajectory.orientations[index], trajectory.orientations[index + 1]
    return p0 * (1 - weight) + p1 * weight, quaternions.blend(q0, q1, weight)
