"""The director: the film's shots chosen from the run's events, not a fixed plan.

From the trajectory alone (no physics), in simulation time:

1. Behind the cue ball while the cue strikes (the "behind_cue" view).
2. The first contact framed: a cue ball whose path to it curves (a massé, a swerve:
   it strays CURVED cm or more from its chord) is framed whole from high above,
   from just after the strike; a straight one gets the low view beside the impact
   ("rack") RACK_BEFORE s before it.
3. While the balls spread: the camera follows the play, reframing every FOLLOW s or
   less (a cut) on the balls that move over that stretch, the fastest one first,
   from above and behind its travel; never one still view for longer while anything
   moves, but for a stretch of quiet play (billiards.render.quiet_play), which the
   film's clock quickens into 1.5 s and one view shows.
4. A cut to each pocket POCKET_LEAD s before a ball drops into it, held until just
   after it has gone.
5. The ending: an ease out to the wide corner view as the last balls come to rest
   (their centres: a ball left spinning in place is not waited for).

Shots are mostly held still between eases and cuts, which keeps the film fast to
draw (a still camera lets the renderer reuse the drawn table). Presets and [[camera]]
tables override it all (billiards.render.film.camera_timeline). No GL here.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from billiards.record.trajectory import Trajectory, ball_state, first_contact_time, last_motion
from billiards.render.quiet_play import quiet_stretches
from billiards.scene.render_table import CameraShot
from billiards.stage.cameras import (
    POCKET_HOLD,
    POCKET_LEAD,
    RACK_AFTER,
    RACK_BEFORE,
    SETTLE_BEFORE_REST,
    SETTLE_EASE,
    CameraPose,
    in_room,
)

FloatArray = npt.NDArray[np.float64]

CURVED = 0.02  # m a path must stray from its chord to be framed as a curve
FOLLOW = 2.5  # s: the longest a view is held while balls move
# Each reframing is a cut, as a vision mixer cuts between cameras: an ease moves the
# camera, and a moving camera's frames cost llvmpipe about twice a still one's (the
# table and room drawn again each frame); with 0.5 s eases the default film took
# 27.6 ms of CPU a frame at 720p, with cuts about 20.
FOLLOW_TRANSITION = "cut"
FOLLOW_EASE = 0.5  # s, if FOLLOW_TRANSITION is "ease"
STRIKE_SEEN = 0.08  # s after the strike, at the least, before the first cut
MOVING = 0.01  # m: a ball that travels less over a stretch is not followed
FRAMING_FOV = 40.0  # degrees, vertical
MARGIN = 0.75  # of the frame's half-size the framed points may fill
SAMPLES = 12  # positions per stretch of time the framing looks at
# The lamp hangs about 0.95 m over the cloth: a framing whose eye would be higher is
# taken from lower down, at the first of these elevations (degrees) that keeps it below.
EYE_BELOW_LAMP = 0.75  # m
ELEVATIONS = (65.0, 55.0, 45.0, 35.0, 27.0, 20.0, 14.0)


ABOVE = math.radians(89.0)  # the elevation of a framing from straight above


def framed_below_lamp(
    points: FloatArray,
    azimuth: float,
    elevation: float,
    aspect: float,
    table: tuple[float, float],
) -> CameraPose:
    """frame_points from `elevation` (radians) or, where its eye would be up at the
    lamp, from the highest of ELEVATIONS below it that keeps it under EYE_BELOW_LAMP.

    Where that eye would be outside the room about the `table` (length, width) -- a
    spread as long as the table, on a square or upright frame, fits only from far
    off -- the points are framed from straight above instead, their longer side across
    a wide frame and up an upright one (the renderer leaves out the lamp over the
    table, and the ceiling for an eye above it, as for the overhead preset)."""
    pose = frame_points(points, azimuth, elevation, aspect)
    for degrees in ELEVATIONS:
        if pose.eye[2] <= EYE_BELOW_LAMP:
            break
        if math.radians(degrees) < elevation:
            pose = frame_points(points, azimuth, math.radians(degrees), aspect)
    if in_room(pose.eye, table):
        return pose
    extent = points.max(axis=0) - points.min(axis=0)
    along_x = bool(extent[0] >= extent[1])
    # Looking along the azimuth from above, the picture's up is the azimuth's way.
    longer_up = aspect < 1.0
    above = 0.0 if along_x == longer_up else math.pi / 2
    return frame_points(points, above, ABOVE, aspect)


def frame_points(points: FloatArray, azimuth: float, elevation: float, aspect: float) -> CameraPose:
    """A still view of `points` (K, 3): looking along the heading `azimuth` (radians,
    from +x counter-clockwise) down at `elevation` (radians), from far enough that
    every point falls within MARGIN of the frame's middle (the target their box's
    centre), and no nearer than 0.5 m."""
    low, high = points.min(axis=0), points.max(axis=0)
    target = 0.5 * (low + high)
    forward = np.array(
        [
            math.cos(elevation) * math.cos(azimuth),
            math.cos(elevation) * math.sin(azimuth),
            -math.sin(elevation),
        ]
    )
    right = np.cross(forward, (0.0, 0.0, 1.0))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    tan_v = math.tan(math.radians(FRAMING_FOV) / 2) * MARGIN
    tan_h = tan_v * aspect
    offsets = points - target
    across, upward, along = offsets @ right, offsets @ up, offsets @ forward
    # Each point fits when |across| <= (d + along) tan_h and |upward| <= (d + along) tan_v.
    distance = float(
        max(
            0.5,
            np.max(np.abs(across) / tan_h - along),
            np.max(np.abs(upward) / tan_v - along),
        )
    )
    eye = target - distance * forward
    return CameraPose(
        (float(eye[0]), float(eye[1]), float(eye[2])),
        (float(target[0]), float(target[1]), float(target[2])),
        FRAMING_FOV,
    )


def _shot(start: float, pose: CameraPose, transition: str = "cut", ease: float = 1.0) -> CameraShot:
    return CameraShot(
        start=start,
        eye=pose.eye,
        target=pose.target,
        fov=pose.fov,
        transition=transition,
        ease=ease,
    )


def _positions(trajectory: Trajectory, start: float, end: float) -> FloatArray:
    """(SAMPLES, N, 3) ball centres over [start, end]."""
    times = np.linspace(start, end, SAMPLES)
    return np.stack([ball_state(trajectory, float(t))[0] for t in times])


def _on_table(points: FloatArray) -> FloatArray:
    """The points of balls still on the table (not dropped)."""
    return points[points[:, 2] > -0.2]


def _cue_index(trajectory: Trajectory) -> int:
    ids = trajectory.ball_ids
    return ids.index("cue") if "cue" in ids else 0


def curved_path(trajectory: Trajectory, end: float) -> FloatArray | None:
    """The cue ball's centres (SAMPLES, 3) from t = 0 to `end` if they stray CURVED or
    more from their chord, else None."""
    path = _positions(trajectory, 0.0, end)[:, _cue_index(trajectory)]
    chord = path[-1, :2] - path[0, :2]
    length = float(np.linalg.norm(chord))
    if length < 1e-9:
        return None
    normal = np.array([-chord[1], chord[0]]) / length
    stray = np.abs((path[:, :2] - path[0, :2]) @ normal)
    return path if float(stray.max()) >= CURVED else None


def _follow_pose(
    trajectory: Trajectory, start: float, end: float, aspect: float, side: float
) -> CameraPose | None:
    """A view of the balls that move over [start, end], behind the fastest one's travel
    (None if none moves)."""
    positions = _positions(trajectory, start, end)  # (S, N, 3)
    travel = np.linalg.norm(positions[-1, :, :2] - positions[0, :, :2], axis=1)
    path = np.sum(np.linalg.norm(np.diff(positions[:, :, :2], axis=0), axis=2), axis=0)
    on_table = positions[:, :, 2].min(axis=0) > 0.0
    moving = np.flatnonzero((path > MOVING) & on_table)
    if len(moving) == 0:
        return None
    lead = int(moving[np.argmax(path[moving])])
    heading = positions[-1, lead, :2] - positions[0, lead, :2]
    if float(np.linalg.norm(heading)) < 1e-6 or travel[lead] < MOVING:
        heading = np.array([1.0, 0.0])
    azimuth = math.atan2(float(heading[1]), float(heading[0])) + side * math.radians(35)
    points = _on_table(positions[:, moving].reshape(-1, 3))
    return framed_below_lamp(points, azimuth, math.radians(55), aspect, trajectory.table_size)


def _pocket_pose(
    trajectory: Trajectory, pocket: str, ball: int, time: float, aspect: float
) -> CameraPose:
    """A view down into `pocket`, from the table's side, with the dropping ball's
    approach (its last quarter second) in it."""
    assert trajectory.pockets is not None
    index = trajectory.pockets.names.index(pocket)
    x, y, radius = (float(v) for v in trajectory.pockets.holes[index])
    hole = np.array([x, y, 0.0])
    approach = _positions(trajectory, max(time - 0.25, 0.0), time)[:, ball]
    length, width = trajectory.table_size
    towards = hole[:2] - np.array([length / 2, width / 2])
    azimuth = math.atan2(float(towards[1]), float(towards[0]))
    rim = hole + radius * np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0]])
    points = np.concatenate([_on_table(approach), rim])
    return framed_below_lamp(points, azimuth, math.radians(40), aspect, trajectory.table_size)


def _opening(
    trajectory: Trajectory, first: float | None, aspect: float
) -> tuple[list[CameraShot], float]:
    """The shots up to the first contact, and when the spread is first followed."""
    start = float(trajectory.times[0])
    shots = [CameraShot(preset="behind_cue")]
    if first is None:
        return shots, min(1.0, float(trajectory.times[-1]))
    curve = curved_path(trajectory, first)
    if curve is not None:
        # The whole curve and the ball it meets, from above and behind its chord.
        contact = next(event for event in trajectory.events if event.kind == "ball")
        met = [trajectory.ball_ids.index(ball) for ball in contact.balls]
        points = np.concatenate([curve, ball_state(trajectory, first)[0][met]])
        heading = curve[-1, :2] - curve[0, :2]
        azimuth = math.atan2(float(heading[1]), float(heading[0]))
        curve_pose = framed_below_lamp(
            points, azimuth, math.radians(65), aspect, trajectory.table_size
        )
        shots.append(_shot(0.25, curve_pose))
        # A long way to the first contact (a carom shot's cushions first): the
        # framing is held no longer than a followed view, then the play is followed.
        return shots, min(first + RACK_AFTER, 0.25 + FOLLOW)
    # (not before the cue has struck: the strike is the first thing to see)
    cut = max(first - RACK_BEFORE, min(STRIKE_SEEN, first), start)
    if cut <= FOLLOW:
        shots.append(CameraShot(start=cut, preset="rack"))
        return shots, first + RACK_AFTER
    # The cue ball rolls long before it meets a ball: followed meanwhile.
    return shots, max(STRIKE_SEEN, start)


def directed_shots(trajectory: Trajectory, aspect: float = 16 / 9) -> tuple[CameraShot, ...]:
    """The film's shots for this run (see the module's docstring)."""
    start = float(trajectory.times[0])
    end = float(trajectory.times[-1])
    first = first_contact_time(trajectory.events)
    shots, spread_from = _opening(trajectory, first, aspect)
    drops = sorted(
        (event.time, event.pocket, event.balls[0])
        for event in trajectory.events
        if event.kind == "pocket" and event.pocket is not None
    )
    if drops and first is not None:
        # A drop soon after the first contact: its pocket as soon as the contact is seen.
        spread_from = min(spread_from, max(drops[0][0] - POCKET_LEAD, first + 0.2))
    last_drop = max((t for t, _, _ in drops), default=-math.inf)
    settle = max(
        last_motion(trajectory) - SETTLE_BEFORE_REST, spread_from + 1.0, last_drop + POCKET_HOLD
    )
    # The middle: follow the play in stretches of FOLLOW s, and visit each pocket.
    quiet = quiet_stretches(trajectory)
    time = spread_from
    side = 1.0
    last_cut = shots[-1].start or start
    while time < settle:
        drop = next(
            ((t, p, b) for t, p, b in drops if time <= t and t - POCKET_LEAD < settle), None
        )
        if drop is not None and drop[0] - POCKET_LEAD <= time + FOLLOW:
            cut = max(drop[0] - POCKET_LEAD, time, last_cut + 0.2)
            if cut > time + 0.3:  # what is left before it: followed
                pose = _follow_pose(trajectory, time, cut, aspect, side)
                if pose is not None:
                    shots.append(_shot(time, pose, FOLLOW_TRANSITION, FOLLOW_EASE))
            ball = trajectory.ball_ids.index(drop[2])
            shots.append(_shot(cut, _pocket_pose(trajectory, drop[1], ball, drop[0], aspect)))
            drops.remove(drop)
            last_cut = cut
            time = drop[0] + POCKET_HOLD
            continue
        stretch_end = min(time + FOLLOW, settle)
        # A quiet stretch, played quickened (quiet_play), is one view: cuts every
        # FOLLOW s of it would come every fraction of a second on the film.
        for low, high in quiet:
            if low <= time < high:
                stretch_end = min(max(stretch_end, high), settle)
        pose = _follow_pose(trajectory, time, stretch_end, aspect, side)
        if pose is None:
            break
        transition = FOLLOW_TRANSITION if len(shots) > 2 else "cut"
        shots.append(_shot(time, pose, transition, FOLLOW_EASE))
        side = -side
        time = stretch_end
    if settle + SETTLE_EASE <= end:
        shots.append(CameraShot(start=settle, preset="corner", transition="ease", ease=SETTLE_EASE))
    return _ordered(shots)


def _ordered(shots: list[CameraShot]) -> tuple[CameraShot, ...]:
    """The shots with strictly increasing starts (a later one replaces an earlier
    one that starts at the same time or before)."""
    kept: list[CameraShot] = []
    for shot in shots:
        while kept and shot.start is not None and (kept[-1].start or -math.inf) >= shot.start:
            kept.pop()
        kept.append(shot)
    return tuple(kept)
