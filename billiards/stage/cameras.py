"""Where the camera is at each moment: named presets, [[camera]] shots, cuts and eases.

A shot's pose is a function of simulation time (so an orbit keeps turning while an
ease blends it into the next shot). The film's own clock is mapped to simulation
time elsewhere (billiards.render.film_clock), so slow motion can be added without
touching the cameras. No GL here: matrices are numpy (pyrr's row-vector layout,
which is what a GLSL mat4 uniform expects when written as raw bytes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from pyrr import matrix44

from billiards.record.trajectory import Trajectory, ball_state, first_contact_time, last_motion
from billiards.scene.render_table import CameraShot
from billiards.stage.room import Room

FloatArray = npt.NDArray[np.float64]
Vec3 = tuple[float, float, float]

NEAR, FAR = 0.03, 25.0  # m: the clip planes (the closest preset eye is ~0.3 m from a ball)
ORBIT_SPEED = 6.0  # degrees/s of the "orbit" preset

# The default film's cuts, in simulation seconds around the first ball-ball contact
# (the slow-motion window of billiards.render.slow_motion sits inside the rack shot).
RACK_BEFORE = 0.15  # s before the impact: the cue ball's last few centimetres
RACK_AFTER = 0.8  # s after it: the pack has opened, the balls start to spread
SETTLE_BEFORE_REST = 1.5  # s before the last ball stops, the ease out begins
SETTLE_EASE = 2.0  # s the ease out to the wide view takes
POCKET_LEAD = 0.6  # s before a drop the director's cut to its pocket comes
POCKET_HOLD = 0.6  # s after the drop the pocket's view stays


DEFAULT_FOV = 40.0  # degrees, vertical: for a shot given by eye and target alone
# The wide presets (corner, orbit) keep the cloth's corners within this share of the
# frame's half-size from its middle, on every table and frame shape.
TABLE_FILL = 0.96
WALL_CLEARANCE = 0.3  # m: the nearest a preset's eye comes to a wall of the room
ROOM_TOP = 1.9  # m above the cloth: the highest a wide preset's eye goes (the ceiling: 2.25)


@dataclass(frozen=True)
class CameraPose:
    eye: Vec3
    target: Vec3
    fov: float  # degrees, vertical
    # Which way is up in the picture (only its part square to the view counts): +z
    # for every shot, turned with the view while an ease turns one shot into the next.
    up: Vec3 = (0.0, 0.0, 1.0)

    def basis(self) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Unit right, up and forward vectors of the view."""
        forward = np.array(self.target) - np.array(self.eye)
        forward /= np.linalg.norm(forward)
        right = np.cross(forward, np.array(self.up))
        length = float(np.linalg.norm(right))
        if length < 1e-9:
            # Looking straight along the up vector (a shot straight down), which then
            # says nothing: the table's length across the picture, as overhead shows it.
            right = np.cross(forward, np.array([0.0, 1.0, 0.0]))
            length = float(np.linalg.norm(right))
        right /= length
        return right, np.cross(right, forward), forward

    def orientation(self) -> FloatArray:
        """The camera's turn from its own frame (x right, y up, looking down -z) to the
        world's: the columns are right, up and backward."""
        right, up, forward = self.basis()
        return np.column_stack((right, up, -forward))

    def view_projection(self, aspect: float, flip_y: bool = True) -> npt.NDArray[np.float32]:
        """View then projection, for `v_row @ M` (GLSL: M * v after a raw upload).

        flip_y turns the picture upside down in GL's bottom-left frame, so rows read
        back from the framebuffer come out top row first, as images and video want.
        """
        _, up, _ = self.basis()
        view = matrix44.create_look_at(np.array(self.eye), np.array(self.target), up)
        projection = matrix44.create_perspective_projection(self.fov, aspect, NEAR, FAR)
        if flip_y:
            projection = projection @ np.diag([1.0, -1.0, 1.0, 1.0])
        return np.asarray(view @ projection, dtype=np.float32)

    def project(self, points: FloatArray, width: int, height: int) -> FloatArray:
        """Pixel coordinates (x right, y down from the top-left corner) of world points."""
        matrix = self.view_projection(width / height, flip_y=False).astype(np.float64)
        homogeneous = np.hstack([points, np.ones((len(points), 1))]) @ matrix
        ndc = homogeneous[:, :3] / homogeneous[:, 3:4]
        x = (ndc[:, 0] + 1) / 2 * width
        y = (1 - ndc[:, 1]) / 2 * height
        return np.stack([x, y], axis=1)


@dataclass(frozen=True)
class Stage:
    """What the presets need to know about the break they film."""

    length: float
    width: float
    cue_start: Vec3  # the cue ball's centre when the film starts
    cue_direction: tuple[float, float]  # unit, the cue ball's first direction of travel
    film_start: float  # s, simulation time of the first frame
    # The cue ball's centre at the first ball-ball contact (where it starts, if none).
    impact: Vec3 = (0.0, 0.0, 0.0)

    @classmethod
    def of(cls, trajectory: Trajectory) -> Stage:
        ids = trajectory.ball_ids
        cue = ids.index("cue") if "cue" in ids else 0
        path = trajectory.positions[:, cue, :2]
        moved = np.linalg.norm(path - path[0], axis=1) > 1e-6
        direction = (1.0, 0.0)
        if moved.any():
            step = path[int(np.argmax(moved))] - path[0]
            unit = step / np.linalg.norm(step)
            direction = (float(unit[0]), float(unit[1]))
        start = trajectory.positions[0, cue]
        impact = start
        first = first_contact_time(trajectory.events)
        if first is not None:
            impact = ball_state(trajectory, first)[0][cue]
        length, width = trajectory.table_size
        return cls(
            length=length,
            width=width,
            cue_start=(float(start[0]), float(start[1]), float(start[2])),
            cue_direction=direction,
            film_start=float(trajectory.times[0]) if len(trajectory.times) else 0.0,
            impact=(float(impact[0]), float(impact[1]), float(impact[2])),
        )


def preset_pose(name: str, stage: Stage, aspect: float = 16 / 9) -> CameraPose:
    """The starting pose of a named preset for this table and break."""
    length, width = stage.length, stage.width
    cx, cy = length / 2, width / 2
    if name == "overhead":
        # High enough that the table and its rails fill the frame: its length across a
        # wide frame, up an upright one (9:16). Higher than the room for a long table
        # or a square frame: the renderer then leaves out the ceiling, as it leaves out
        # the lamp. Tilted a hair so the +z up vector stays usable (and eases into and
        # out of it stay smooth); the tilt says which way is up in the picture.
        fov = 40.0
        upright = aspect < 1.0
        across, up_the_frame = (width, length) if upright else (length, width)
        half_w = (across + 0.45) / 2
        half_h = (up_the_frame + 0.45) / 2
        tan_v = math.tan(math.radians(fov / 2))
        height = max(half_h / tan_v, half_w / (tan_v * aspect))
        if upright:
            return CameraPose((cx - 0.005 * height, cy, height), (cx, cy, 0.0), fov)
        return CameraPose((cx, cy - 0.005 * height, height), (cx, cy, 0.0), fov)
    if name == "behind_cue":
        x, y, _ = stage.cue_start
        dx, dy = stage.cue_direction
        eye = (x - 0.85 * dx, y - 0.85 * dy, 0.32)
        target = (x + 1.0 * dx, y + 1.0 * dy, 0.0)
        return CameraPose(eye, target, 38.0)
    if name == "low_side":
        return CameraPose((cx - 0.35, -0.34, 0.16), (cx + 0.3, cy + 0.15, 0.0), 48.0)
    if name == "rack":
        # Low on the cloth, behind and beside the impact, looking diagonally across the
        # shot line at the rack: the cue ball comes in from the left, the pack opens
        # up in front.
        x, y, _ = stage.impact
        dx, dy = stage.cue_direction
        side = (-dy, dx) if y <= width / 2 else (dy, -dx)  # towards the far cushion
        eye = (x - 0.45 * dx - 0.42 * side[0], y - 0.45 * dy - 0.42 * side[1], 0.12)
        # Aimed a little above the cloth, so the balls sit in the middle of the picture.
        target = (x + 0.2 * dx, y + 0.2 * dy, 0.045)
        return CameraPose(eye, target, 40.0)
    if name == "corner":
        # Low enough that the lamp hangs in the top of the picture; backed away (or
        # widened) until the whole cloth is in the frame.
        corner = CameraPose((-1.1, -0.9, 0.6), (cx + 0.2, cy, 0.15), 45.0)
        if aspect < 1.0:  # an upright frame: from behind the foot, along the length
            corner = CameraPose((-1.0, cy - 0.45, 0.75), (cx, cy, 0.05), 45.0)
        return whole_table(corner, stage, aspect)
    if name == "orbit":
        radius = 0.55 * length + 1.0
        angle = math.radians(-115.0)
        eye = (cx + radius * math.cos(angle), cy + radius * math.sin(angle), 1.05)
        # The whole cloth in the frame from every point of the orbit's circle.
        return whole_table(CameraPose(eye, (cx, cy, -0.05), 40.0), stage, aspect, orbit=True)
    raise ValueError(f"unknown camera preset {name!r}")


def in_room(eye: Vec3, table: tuple[float, float]) -> bool:
    """Whether an eye is within the walls of the room about a table (length, width),
    at least WALL_CLEARANCE from them (Room.around). Its height is not asked:
    the renderer leaves out the ceiling for an eye above it."""
    room = Room.around(table[0], table[1], floor=-0.79)
    (cx, cy), x, y = room.centre, eye[0], eye[1]
    return (
        abs(x - cx) <= room.half_x - WALL_CLEARANCE and abs(y - cy) <= room.half_y - WALL_CLEARANCE
    )


def cloth_corners(stage: Stage) -> FloatArray:
    """(4, 3) the corners of the cloth, between the cushion noses."""
    length, width = stage.length, stage.width
    return np.array([(0.0, 0.0, 0.0), (length, 0.0, 0.0), (length, width, 0.0), (0.0, width, 0.0)])


def fit_distance(points: FloatArray, pose: CameraPose, aspect: float, fill: float) -> float:
    """How far from the pose's target along its line of sight the eye must be for
    every point to fall within `fill` of the frame's half-size from its middle."""
    right, up, forward = pose.basis()
    tan_v = math.tan(math.radians(pose.fov) / 2) * fill
    tan_h = tan_v * aspect
    offsets = points - np.array(pose.target)
    across, upward, along = offsets @ right, offsets @ up, offsets @ forward
    # A point fits when |across| <= (d + along) tan_h and |upward| <= (d + along) tan_v.
    return float(
        max(np.max(np.abs(across) / tan_h - along), np.max(np.abs(upward) / tan_v - along))
    )


def _turned(pose: CameraPose, degrees: float) -> CameraPose:
    """The pose turned about the vertical through its target."""
    angle = math.radians(degrees)
    c, s = math.cos(angle), math.sin(angle)
    (ex, ey, ez), (tx, ty, _) = pose.eye, pose.target
    eye = (tx + c * (ex - tx) - s * (ey - ty), ty + s * (ex - tx) + c * (ey - ty), ez)
    return CameraPose(eye, pose.target, pose.fov)


def whole_table(pose: CameraPose, stage: Stage, aspect: float, orbit: bool = False) -> CameraPose:
    """The pose, its eye backed away along its line of sight until the whole cloth is
    within TABLE_FILL of the frame (never nearer than given); where that would take
    the eye through a wall of the room (Room.around) or past ROOM_TOP, it
    stops there and the lens widens instead. `orbit`: for every turn of the pose
    about the vertical through its target (an orbiting camera), not only this one."""
    corners = cloth_corners(stage)
    turns = np.arange(0.0, 360.0, 15.0) if orbit else np.zeros(1)
    target = np.array(pose.target)
    reach = float(np.linalg.norm(np.array(pose.eye) - target))
    needed = max(fit_distance(corners, _turned(pose, float(t)), aspect, TABLE_FILL) for t in turns)
    if needed <= reach:
        return pose
    _, _, forward = pose.basis()
    room = Room.around(stage.length, stage.width, floor=-0.79)
    # The farthest the eye may go back: inside the walls and under ROOM_TOP.
    limit = needed
    back = -forward
    cx, cy = room.centre
    for axis, centre, half in ((0, cx, room.half_x), (1, cy, room.half_y)):
        if orbit:  # the whole circle inside: its horizontal radius at most the half-size
            horizontal = math.hypot(float(back[0]), float(back[1]))
            if horizontal > 1e-9:
                limit = min(limit, (half - WALL_CLEARANCE) / horizontal)
        elif abs(float(back[axis])) > 1e-9:
            wall = centre + math.copysign(half - WALL_CLEARANCE, float(back[axis]))
            limit = min(limit, (wall - float(target[axis])) / float(back[axis]))
    if back[2] > 1e-9:
        limit = min(limit, (ROOM_TOP - float(target[2])) / float(back[2]))
    distance = max(reach, limit)
    eye = target + back * distance
    fov = pose.fov
    if distance < needed:
        # Widen the lens until the cloth fits from where the eye can be.
        low, high = pose.fov, 120.0
        for _ in range(40):
            fov = 0.5 * (low + high)
            trial = CameraPose((float(eye[0]), float(eye[1]), float(eye[2])), pose.target, fov)
            worst = max(
                fit_distance(corners, _turned(trial, float(t)), aspect, TABLE_FILL) for t in turns
            )
            low, high = (fov, high) if worst > distance else (low, fov)
        fov = high
    return CameraPose((float(eye[0]), float(eye[1]), float(eye[2])), pose.target, fov)


def default_shots(trajectory: Trajectory) -> tuple[CameraShot, ...]:
    """The default film, like the source report's: a wide view of the table before and
    during the break, a cut to a low view beside the rack just before the impact,
    a cut to overhead while the balls spread, and a slow ease out to the wide view
    as the last balls come to rest.

    Mostly still shots joined by cuts: a still camera lets the renderer reuse the
    drawn table and room, which keeps the film faster to render than to play. The
    times are simulation seconds, so the shots keep their moments in slow motion.
    """
    first = first_contact_time(trajectory.events)
    if first is None:  # nothing to see at a rack: wide, then overhead
        return (CameraShot(preset="corner"), CameraShot(start=1.0, preset="overhead"))
    overhead = first + RACK_AFTER
    shots = [
        CameraShot(preset="corner"),
        CameraShot(start=first - RACK_BEFORE, preset="rack"),
        CameraShot(start=overhead, preset="overhead"),
    ]
    settle = max(last_motion(trajectory) - SETTLE_BEFORE_REST, overhead + 1.0)
    if settle + SETTLE_EASE <= float(trajectory.times[-1]):
        shots.append(CameraShot(start=settle, preset="corner", transition="ease", ease=SETTLE_EASE))
    return tuple(shots)


@dataclass(frozen=True)
class _Shot:
    start: float
    pose: CameraPose
    orbit: float  # degrees/s about the vertical through the target
    transition: str
    ease: float


class CameraTimeline:
    """The camera pose at any simulation time, from a list of shots."""

    def __init__(self, shots: tuple[CameraShot, ...], stage: Stage, aspect: float) -> None:
        if not shots:
            raise ValueError("a camera timeline needs at least one shot")
        self.shots: list[_Shot] = []
        for shot in shots:
            if shot.preset:
                base = preset_pose(shot.preset, stage, aspect)
            elif shot.eye is not None and shot.target is not None:
                base = CameraPose(shot.eye, shot.target, DEFAULT_FOV)
            else:  # settings.py guarantees a preset or an eye and a target
                raise ValueError("a camera shot needs a preset or an eye and a target")
            # Whatever the shot gives (eye, target, fov) overrides the preset's.
            pose = CameraPose(
                shot.eye if shot.eye is not None else base.eye,
                shot.target if shot.target is not None else base.target,
                shot.fov if shot.fov is not None else base.fov,
            )
            orbit = (
                shot.orbit
                if shot.orbit is not None
                else (ORBIT_SPEED if shot.preset == "orbit" else 0.0)
            )
            start = shot.start if shot.start is not None else stage.film_start
            self.shots.append(
                _Shot(
                    start=start,
                    pose=pose,
                    orbit=orbit,
                    transition=shot.transition,
                    ease=shot.ease,
                )
            )

    def _shot_pose(self, shot: _Shot, time: float) -> CameraPose:
        if shot.orbit == 0.0:
            return shot.pose
        angle = math.radians(shot.orbit * (time - shot.start))
        ex, ey, ez = shot.pose.eye
        tx, ty, _ = shot.pose.target
        c, s = math.cos(angle), math.sin(angle)
        eye = (tx + c * (ex - tx) - s * (ey - ty), ty + s * (ex - tx) + c * (ey - ty), ez)
        return CameraPose(eye, shot.pose.target, shot.pose.fov)

    def pose(self, time: float) -> CameraPose:
        index = 0
        for k, shot in enumerate(self.shots):
            if shot.start <= time:
                index = k
        shot = self.shots[index]
        pose = self._shot_pose(shot, time)
        if index == 0 or shot.transition != "ease" or time >= shot.start + shot.ease:
            return pose
        previous = self._shot_pose(self.shots[index - 1], time)
        x = (time - shot.start) / shot.ease
        return eased(previous, pose, x * x * (3 - 2 * x))  # smoothstep: no jolt at either end


def level_heading_and_tilt(pose: CameraPose) -> tuple[float, float]:
    """The pan (radians from +x, counter-clockwise seen from above) and tilt (radians
    above the horizontal, negative looking down) of a level camera on a tripod head.

    The pan is read from the right vector, which a level camera keeps horizontal, not
    from the view direction's shadow on the floor: looking (almost) straight down that
    shadow is a speck whose direction rounding decides, while the right vector still
    says which way the picture faces."""
    right, _, forward = pose.basis()
    return math.atan2(float(right[0]), float(-right[1])), math.asin(
        float(np.clip(forward[2], -1.0, 1.0))
    )


def eased(first: CameraPose, second: CameraPose, blend: float) -> CameraPose:
    """The pose `blend` (0 to 1) of the way from `first` to `second`, as an operator
    moves a camera on a level head: the eye along the straight line between, the view
    panned about the vertical and tilted about its own horizontal right vector, both
    at the blend's pace, so the horizon stays level (no roll) all the way.

    The turn per frame still follows the blend's speed: the pan's axis (+z) is square
    to the tilt's (the horizontal right vector), so the view turns at
    sqrt(pan'^2 + tilt'^2) = blend' sqrt(dpan^2 + dtilt^2). Two other ways fail a
    viewer: blending eye and target whips the view round where it passes near the
    vertical (an overhead shot), where the +z up vector barely fixes which way the
    picture faces; the shortest turn between the two orientations (quaternion slerp)
    turns about a slanted axis and rolls the picture mid-ease (11 degrees half way
    from overhead out to the corner view)."""
    pan0, tilt0 = level_heading_and_tilt(first)
    pan1, tilt1 = level_heading_and_tilt(second)
    pan = pan0 + math.remainder(pan1 - pan0, math.tau) * blend  # the shorter way round
    tilt = tilt0 + (tilt1 - tilt0) * blend
    forward = np.array(
        [math.cos(tilt) * math.cos(pan), math.cos(tilt) * math.sin(pan), math.sin(tilt)]
    )
    right = np.array([math.sin(pan), -math.cos(pan), 0.0])
    eye0, eye1 = np.array(first.eye), np.array(second.eye)
    eye = eye0 + (eye1 - eye0) * blend
    reach0 = float(np.linalg.norm(np.array(first.target) - eye0))
    reach1 = float(np.linalg.norm(np.array(second.target) - eye1))
    target = eye + forward * (reach0 + (reach1 - reach0) * blend)
    fov = first.fov + (second.fov - first.fov) * blend

    def vec(v: FloatArray) -> Vec3:
        return (float(v[0]), float(v[1]), float(v[2]))

    return CameraPose(vec(eye), vec(target), fov, vec(np.cross(right, forward)))
