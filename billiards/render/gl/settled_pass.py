"""The settled balls' pass: while the camera holds still, the balls at rest (from this
frame's open shutter until at least HOLD_STILL s on) are drawn once, with their
shadows, over a copy of the static scene (`settled`); each frame starts from that and
draws only the moving balls. A resting ball that a moving one may be seen behind is
drawn with it instead, far to near as before; what differs is a moving ball's shadow
under a resting ball's one-pixel anti-aliased fringe, which is not seen (in the default
film, 21 pixels of 2 frames)."""

from __future__ import annotations

import moderngl
import numpy as np
import numpy.typing as npt

from billiards.render.gl.background_pass import BackgroundPass
from billiards.render.gl.ball_pass import GONE_BELOW, PATH_POINTS, BallPass
from billiards.render.gl.frame_output import FrameOutput, depth_texture
from billiards.render.gl.programs import GLOwner
from billiards.stage.cameras import CameraPose

FloatArray = npt.NDArray[np.float64]
# A ball that stays exactly where it is from this frame's open shutter until at least
# this long after is drawn into `settled` rather than every frame (so the set drawn
# there changes seldom: each change redraws it).
HOLD_STILL = 0.5  # s


class SettledPass(GLOwner):
    """`settled` for a trajectory sampled at `times` with `positions` and `orientations`
    (F, N, ...): the `background` with the balls at rest drawn in by `balls`."""

    def __init__(
        self,
        ctx: moderngl.Context,
        samples: tuple[FloatArray, FloatArray, FloatArray],
        background: BackgroundPass,
        balls: BallPass,
    ) -> None:
        """`samples`: the trajectory's times, positions and orientations."""
        super().__init__()
        self.ctx, self.background, self.balls = ctx, background, balls
        self.times, positions, orientations = samples
        size = background.size
        # Its depth a texture: a moving ball's shadow is not cast on the balls drawn
        # here, as none is cast on a ball.
        self.depth = self.keep(depth_texture(ctx, size))
        self.colour = self.keep(ctx.texture(size, 4))  # (the yuv420p pass reads it)
        self.framebuffer = self.keep(
            ctx.framebuffer(color_attachments=[self.colour], depth_attachment=self.depth)
        )
        self.key: tuple[object, ...] | None = None  # what is drawn there
        self._pictures: dict[str, bytes] = {}  # read back (per pixel format) as it stands
        # Per recorded sample, how many times each ball has moved since the first (F, N):
        # a ball is still between two samples when the count is the same at both.
        changed = np.any(positions[1:] != positions[:-1], axis=2) | np.any(
            orientations[1:] != orientations[:-1], axis=2
        )
        self._moves = np.concatenate(
            [np.zeros((1, changed.shape[1]), dtype=np.int64), np.cumsum(changed, axis=0)]
        )

    def still(self, time: float, exposure: float) -> tuple[npt.NDArray[np.bool_], int]:
        """Which balls stay exactly where they are from the open shutter's start until
        HOLD_STILL s after its end, and the recorded sample that holds them there."""
        last = len(self.times) - 1
        start = int(np.clip(np.searchsorted(self.times, time - exposure / 2, "right") - 1, 0, last))
        end = int(np.clip(np.searchsorted(self.times, time + exposure / 2 + HOLD_STILL), 0, last))
        return self._moves[end] == self._moves[start], start

    def in_front_of_moving(
        self, still: npt.NDArray[np.bool_], centres: FloatArray, pose: CameraPose
    ) -> npt.NDArray[np.bool_]:
        """The still balls that a moving ball further from the eye may show behind (their
        squares on screen meet): drawn with it, far to near, their fringes blend over
        it, as they could not from `settled`."""
        shown = centres[:, :, 2].max(axis=1) > GONE_BELOW
        moving = np.flatnonzero(~still & shown)
        resting = np.flatnonzero(still & shown)
        behind = np.zeros(len(still), dtype=bool)
        if len(moving) == 0 or len(resting) == 0:
            return behind
        width, height = self.background.size
        points = pose.project(centres.reshape(-1, 3), width, height).reshape(
            len(centres), PATH_POINTS, 2
        )
        distance = np.linalg.norm(centres - np.array(pose.eye), axis=2)  # (N, P)
        # A ball's reach on screen, px: twice its radius there (its square's off-axis
        # stretch), the fringe, and half its path's longest step between points.
        step = np.linalg.norm(np.diff(points, axis=1), axis=2).max(axis=1)
        pixel_angle = self.balls.programs.pixel_angle
        reach = 2 * self.balls.radius / (distance.min(axis=1) * pixel_angle) + 2 + step / 2
        middle = PATH_POINTS // 2
        # (resting, moving) pairs: the moving ball no nearer, and near it on screen
        further = distance[moving, middle][None, :] >= distance[resting, middle][:, None]
        offsets = points[moving][None, :, :, :] - points[resting, middle][:, None, None, :]
        gaps = np.sqrt(np.sum(offsets * offsets, axis=3)).min(axis=2)
        near = gaps < reach[moving][None, :] + reach[resting][:, None]
        behind[resting] = np.any(further & near, axis=1)
        return behind

    def settle(
        self, pose: CameraPose, balls: npt.NDArray[np.intp], centres: FloatArray, turns: FloatArray
    ) -> None:
        """`settled`: the background with `balls` drawn in at `centres` (K, 3) turned by
        `turns` (K, 4); drawn again only when the background or those balls change."""
        key = (self.background.version, balls.tobytes(), centres.tobytes(), turns.tobytes())
        if key == self.key:
            return
        self.key = key
        self._pictures.clear()
        self.ctx.copy_framebuffer(self.framebuffer, self.background.framebuffer)
        if len(balls) == 0:
            return
        self.background.depth.use(4)  # nothing drawn over the static scene yet
        self.framebuffer.use()
        self.ctx.enable(moderngl.DEPTH_TEST)
        count = len(self._moves[0])
        full = np.zeros((count, PATH_POINTS, 3))
        full_turns = np.zeros((count, PATH_POINTS, 4))
        full[balls] = centres[:, None, :]
        full_turns[balls] = turns[:, None, :]
        self.balls.draw(full, full_turns, pose, balls)

    def picture(self, output: FrameOutput, pixel_format: str) -> bytes:
        """`settled` as it stands, read back as `pixel_format` once while it stands."""
        if pixel_format not in self._pictures:
            self._pictures[pixel_format] = output.read(self.framebuffer, self.colour, pixel_format)
            if pixel_format == "yuv420p":
                output.holds, output.drawn = self.key, None
        return self._pictures[pixel_format]
