"""Draws frames of a trajectory with moderngl: the GL side of rendering, as passes.

Per frame: the static scene (table, room, lamp: background_pass), soft shadows of the
balls, then the balls, sharp or drawn over their path (ball_pass), and the cue
(cue_pass), into a multisampled framebuffer that is resolved into a plain one and read
back as RGBA rows, top row first (the projection flips y), or, for a film, as yuv420p's
planes (frame_output). While the camera holds still the static scene is drawn once and
copied (colour and depth) at the start of each frame, and the balls at rest are drawn
once over it (settled_pass); only what moves is drawn on top. The pictures are the same
bit for bit.
"""

from __future__ import annotations

from pathlib import Path

import moderngl
import numpy as np
import numpy.typing as npt

from billiards.record.trajectory import Trajectory, ball_state
from billiards.render.gl.background_pass import BackgroundPass
from billiards.render.gl.ball_pass import GONE_BELOW, PATH_POINTS, BallPass, drop_holes
from billiards.render.gl.cue_pass import CuePass
from billiards.render.gl.frame_output import (
    PIXEL_FORMATS,
    FrameOutput,
    region_of,
    union,
)
from billiards.render.gl.programs import Programs
from billiards.render.gl.settled_pass import SettledPass
from billiards.stage.cameras import CameraPose
from billiards.stage.cue import CuePlacement, CueStroke
from billiards.stage.pocket_mesh import build_pocket_liners
from billiards.stage.rack_turns import racked
from billiards.stage.room import Lamp, Lighting, Room, build_ceiling, build_lamp, build_room
from billiards.stage.table import build_table, load_table_mesh
from billiards.stage.table_plan import TableShape

FloatArray = npt.NDArray[np.float64]


class Renderer:
    """Renders one trajectory at a fixed size; reuse it for every frame of a film."""

    def __init__(
        self,
        ctx: moderngl.Context,
        trajectory: Trajectory,
        size: tuple[int, int],
        antialias: int = 4,
        table_mesh: str | Path | None = None,
        cue: bool = True,
    ) -> None:
        """`cue`: draw the cue striking the trajectory's `strike` (if it has one)."""
        self.output = FrameOutput(ctx, size)  # (first: it checks the size)
        self.ctx = ctx
        # Drawn with each object ball's number turned at random as the rack is set.
        self.trajectory = trajectory = racked(trajectory)
        self.size = size
        length, width = trajectory.table_size
        shape = TableShape(length, width)
        room = Room.around(length, width, shape.floor)
        lamp = Lamp(
            (length / 2, width / 2, 0.0),
            length=min(1.35, 0.65 * length),
            spacing=min(0.55, 0.26 * length),
        )
        # Mesh data first, in numpy; then the GL side.
        static = (
            load_table_mesh(table_mesh) if table_mesh else build_table(shape, trajectory.pockets)
        )
        if trajectory.pockets is not None and not table_mesh:
            static.extend(build_pocket_liners(shape, trajectory.pockets))
        static.extend(build_room(room))
        lamp_mesh = build_lamp(lamp, room.ceiling)
        ceiling = build_ceiling(room)
        meshes = (static, lamp_mesh, ceiling)
        kinds = sorted({float(k) for mesh in meshes for k in mesh.materials[:, 3]})
        self.programs = Programs(ctx, kinds, Lighting.over(lamp, room))
        self.background = BackgroundPass(
            ctx,
            self.programs,
            meshes=meshes,
            size=size,
            table_size=(length, width),
            antialias=antialias,
        )
        holes = drop_holes(trajectory, None if table_mesh else shape)
        self.balls = BallPass(
            ctx,
            self.programs,
            trajectory=trajectory,
            holes=holes,
            size=size,
            scene_depth=self.background.depth,
        )
        motion = (trajectory.times, trajectory.positions, trajectory.orientations)
        self.settled = SettledPass(ctx, motion, self.background, self.balls)
        self.cue_pass: CuePass | None = None
        strike = trajectory.strike
        if cue and strike is not None and strike.ball in trajectory.ball_ids:
            # The struck ball's place before it leaves (the film opens before t = 0).
            start = trajectory.positions[0, trajectory.ball_ids.index(strike.ball)]
            stroke = CueStroke.of(strike, start, trajectory.radius, shape)
            self.cue_pass = CuePass(ctx, self.programs, stroke, (length, width))

    def release(self) -> None:
        """Free every GL object this renderer made (the context stays)."""
        passes = (self.programs, self.output, self.background, self.balls, self.settled)
        for made in (*passes, self.cue_pass)[::-1]:
            if made is not None:
                made.release()

    def draw(
        self,
        time: float,
        pose: CameraPose,
        moving: bool = False,
        exposure: float = 0.0,
        pixel_format: str = "rgba",
    ) -> bytes:
        """The picture of the break at `time`, each ball drawn over `exposure` s of its
        path centred on it (motion blur; 0: sharp), as `pixel_format`'s bytes, top row
        first: "rgba" (height x width x 4) or "yuv420p" (a film's: see PIXEL_FORMATS).

        `moving` says the camera will be elsewhere in the next frame: the table and
        room are then drawn without multisampling (its edges cost llvmpipe ~2.5x the
        plain drawing), and at a lower resolution while the picture moves
        LOW_RES_MOTION px a frame or more since the last one (a frame larger than
        720p: at 720p's resolution, or lower, as sample_scale says), and their edges
        smoothed as they are filtered up (when `antialias` asks for any); a still
        camera gets them multisampled once and reuses them. The balls are drawn at the
        full resolution and anti-aliased either way.
        """
        if pixel_format not in PIXEL_FORMATS:
            raise ValueError(f"pixel_format {pixel_format!r}: expected one of {PIXEL_FORMATS}")
        self.programs.set_camera(pose, self.size)
        self.background.prepare(pose, moving)
        centres, turns = self._paths(time, exposure)
        cue = None if self.cue_pass is None else self.cue_pass.stroke.placement(time)
        if moving:  # the background is drawn again next frame: no balls kept in it
            self.output.start_from(self.background.framebuffer, self.background.depth)
            self.balls.draw(centres, turns, pose)
            self._draw_cue(cue)
            return self.output.read_work(pixel_format)
        still, sample = self.settled.still(time, exposure)
        still &= ~self.settled.in_front_of_moving(still, centres, pose)
        resting = np.flatnonzero(still)
        positions, orientations = self.trajectory.positions, self.trajectory.orientations
        self.settled.settle(
            pose, resting, positions[sample][resting], orientations[sample][resting]
        )
        unsettled = np.flatnonzero(~still)
        if cue is None and not np.any(centres[unsettled, :, 2] > GONE_BELOW):
            # Nothing moves in the picture: it is `settled` as it stands.
            return self.settled.picture(self.output, pixel_format)
        self.output.start_from(self.settled.framebuffer, self.settled.depth)
        self.balls.draw(centres, turns, pose, unsettled)
        self._draw_cue(cue)  # over the balls, depth-tested against them
        if pixel_format != "yuv420p":
            return self.output.read_work(pixel_format)
        # `work` is `settled` but where these balls and their shadows (and the cue) are.
        drawn = self.balls.drawn_region(centres[unsettled], pose)
        if cue is not None and self.cue_pass is not None:
            stick = np.vstack([cue.bounds(), self.cue_pass.shadow_corners(cue)])
            drawn = union(drawn, region_of(stick, pose, self.size))
        return self.output.read_over_settled(self.settled.key, drawn)

    def _draw_cue(self, cue: CuePlacement | None) -> None:
        if cue is not None and self.cue_pass is not None:
            self.cue_pass.draw(cue)

    def _paths(self, time: float, exposure: float) -> tuple[FloatArray, FloatArray]:
        """Each ball's centres (N, P, 3) and turns (N, P, 4) at PATH_POINTS instants
        evenly over the open shutter, [time - exposure / 2, time + exposure / 2]."""
        offsets = (np.linspace(-0.5, 0.5, PATH_POINTS) if exposure > 0 else np.zeros(1)) * exposure
        states = [ball_state(self.trajectory, time + float(dt)) for dt in offsets]
        centres = np.stack([positions for positions, _ in states], axis=1)
        turns = np.stack([orientations for _, orientations in states], axis=1)
        if exposure <= 0:
            centres = np.repeat(centres, PATH_POINTS, axis=1)
            turns = np.repeat(turns, PATH_POINTS, axis=1)
        return centres, turns

    def frame(self, time: float, pose: CameraPose, exposure: float = 0.0) -> npt.NDArray[np.uint8]:
        """The picture at `time` as an RGB array (height x width x 3)."""
        data = np.frombuffer(self.draw(time, pose, exposure=exposure), dtype=np.uint8)
        return data.reshape(self.size[1], self.size[0], 4)[..., :3].copy()
