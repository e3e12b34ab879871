"""The balls' pass: soft shadows of the balls (a decal on the cloth, or for a ball near
the cushions a box that finds the table's surface in the static scene's depth), then
the balls, sharp or (moving, with the shutter open) drawn over their path."""

from __future__ import annotations

import moderngl
import numpy as np
import numpy.typing as npt

from billiards.record.quaternions import rotation_matrices
from billiards.record.trajectory import Trajectory
from billiards.render.gl.frame_output import Region, region_of, sample_scale
from billiards.render.gl.programs import SHADOW_LIFT, SQUARE, GLOwner, Programs, uniform
from billiards.stage.cameras import CameraPose
from billiards.stage.meshes import CUBE_CORNERS, CUBE_TRIANGLES
from billiards.stage.table_plan import TableShape, pocket_cuts
from billiards.stage.textures import ball_texture

FloatArray = npt.NDArray[np.float64]
GL_SRGB8_ALPHA8 = 0x8C43
# A ball whose centre is below this has dropped out of sight (a pocketed ball is put at
# billiards.record.drop.GONE_DEPTH): it is not drawn, nor is its shadow.
GONE_BELOW = -0.5  # m
# Motion blur: a ball's path over the open shutter is given to the shaders as this many
# points evenly in time (exact there), straight between them; ball_blur.frag draws it
# as one continuous streak over that path.
PATH_POINTS = 5
# A moving ball's shadow: one instance, averaged over the open shutter along the chord
# from its path's first point to its last (shadow.frag). (A stretch for each of the
# path's segments, multiplied by their shares, showed light seams where they met;
# the shadow is soft, and a bend within 1/60 s is slight.)
SHADOW_INSTANCE = 7 * 4  # bytes: the stretch's start and share (4f), its end (3f)
# A ball whose streak is shorter than this many pixels is drawn sharp (the cheaper way).
# (In pixels of a 720p frame: see sample_scale.)
SHARP_BELOW = 1.0


def drop_holes(trajectory: Trajectory, shape: TableShape | None) -> FloatArray:
    """The hole each ball drops into (x, y, the liner's radius; radius -1: none), for
    the ball shaders' light below the cloth (lighting.glsl's through_hole); `shape`: the
    table as built (None: a table mesh of one's own, which has no holes)."""
    holes = np.zeros((len(trajectory.ball_ids), 3))
    holes[:, 2] = -1.0
    if trajectory.pockets is None or shape is None:
        return holes
    cuts = pocket_cuts(shape, trajectory.pockets)
    for event in trajectory.events:
        if event.kind == "pocket" and event.pocket is not None:
            ball = trajectory.ball_ids.index(event.balls[0])
            holes[ball] = cuts[trajectory.pockets.names.index(event.pocket)].hole
    return holes


class BallPass(GLOwner):
    """Draws the trajectory's balls (each its texture, and the hole it drops into, from
    `holes`) and their shadows, over the static scene whose depth is `scene_depth`."""

    def __init__(
        self,
        ctx: moderngl.Context,
        programs: Programs,
        trajectory: Trajectory,
        holes: FloatArray,
        size: tuple[int, int],
        scene_depth: moderngl.Texture,
    ) -> None:
        super().__init__()
        self.ctx, self.programs, self.holes, self.scene_depth = ctx, programs, holes, scene_depth
        self.size = size
        self.table_size = trajectory.table_size
        self.radius = radius = trajectory.radius
        self.reach = 3.0 * radius
        # A streak shorter than this (in this frame's pixels) is drawn sharp.
        self.sharp_below = SHARP_BELOW * sample_scale(size)
        square = self.keep(ctx.buffer(SQUARE.tobytes()))
        on_square = [(square, "2f", "in_position")]
        self.ball_vao = self.keep(ctx.vertex_array(programs.ball, on_square))
        self.blur_vao = self.keep(ctx.vertex_array(programs.blur, on_square))
        # Shadows: a decal on the cloth for a ball away from the cushions, a box for one
        # near them (or off the cloth), whose shadow may fall on a cushion or the rail.
        # The box: the cube [-1, 1]^3, wound counter-clockwise seen from outside.
        cube = (2.0 * CUBE_CORNERS[CUBE_TRIANGLES] - 1.0).astype(np.float32)
        cube_vbo = self.keep(ctx.buffer(cube.tobytes()))
        reserve = max(len(trajectory.ball_ids), 1) * SHADOW_INSTANCE
        self.box_centres = self.keep(ctx.buffer(reserve=reserve, dynamic=True))
        self.decal_centres = self.keep(ctx.buffer(reserve=reserve, dynamic=True))
        stretch = ("4f 3f/i", "in_start", "in_end")
        self.shadow_vao = self.keep(
            ctx.vertex_array(
                programs.shadow, [(cube_vbo, "3f", "in_position"), (self.box_centres, *stretch)]
            )
        )
        self.decal_vao = self.keep(
            ctx.vertex_array(programs.decal, [*on_square, (self.decal_centres, *stretch)])
        )
        for program in (programs.shadow, programs.decal):
            uniform(program, "radius").value = radius
            uniform(program, "reach").value = self.reach
            uniform(program, "light_radius").value = programs.lighting.light_radius
        # (the decals' program knows its surface: it has none of these)
        uniform(programs.shadow, "viewport").value = (float(size[0]), float(size[1]))
        uniform(programs.shadow, "scene_depth").value = 1
        uniform(programs.shadow, "settled_depth").value = 4
        uniform(programs.decal, "lift").value = SHADOW_LIFT
        for program in (programs.ball, programs.blur):
            uniform(program, "radius").value = radius
        self.textures = [self._texture(ball_id, size[1]) for ball_id in trajectory.ball_ids]

    def _texture(self, ball_id: str, height: int) -> moderngl.Texture:
        pixels = ball_texture(ball_id, 512 if height >= 400 else 256)
        size = (pixels.shape[1], pixels.shape[0])
        texture = self.ctx.texture(size, 4, pixels.tobytes(), internal_format=GL_SRGB8_ALPHA8)
        texture.build_mipmaps()
        texture.filter = (moderngl.LINEAR_MIPMAP_LINEAR, moderngl.LINEAR)
        texture.anisotropy = 4.0
        texture.repeat_y = False
        return self.keep(texture)

    def draw(
        self,
        centres: FloatArray,
        turns: FloatArray,
        pose: CameraPose,
        balls: npt.NDArray[np.intp] | None = None,
    ) -> None:
        """Shadows, then the balls far to near, of `balls` (all if None), each along its
        path's PATH_POINTS centres (N, P, 3) and turns (N, P, 4), into the bound
        framebuffer (`work`, or `settled` for the balls at rest)."""
        index_of = np.arange(len(centres)) if balls is None else balls
        centres, turns = centres[index_of], turns[index_of]
        # Drawn while any part of its path is above GONE_BELOW.
        visible = np.flatnonzero(centres[:, :, 2].max(axis=1) > GONE_BELOW)
        if len(visible) == 0:
            return
        shown = index_of[visible]
        centres, turns = centres[visible], turns[visible]
        middle = centres[:, PATH_POINTS // 2]
        # Sharp, or a streak: how far it moves on screen over the open shutter.
        travel = np.linalg.norm(np.diff(centres, axis=1), axis=2).sum(axis=1)
        distance = np.linalg.norm(middle - np.array(pose.eye), axis=1)
        streak = travel / np.maximum(distance * self.programs.pixel_angle, 1e-12)
        sharp = streak < self.sharp_below
        self._draw_shadows(centres, middle, sharp)
        # Balls far to near, premultiplied: a near ball's fringe covers the one behind.
        self.ctx.blend_func = moderngl.ONE, moderngl.ONE_MINUS_SRC_ALPHA
        self.ctx.fbo.depth_mask = True
        rotations = rotation_matrices(turns[:, PATH_POINTS // 2])
        for index in np.argsort(-distance, kind="stable"):
            self._draw_ball(
                shown[index], centres[index], turns[index], sharp[index], rotations[index]
            )
        self.ctx.disable(moderngl.BLEND)

    def _draw_shadows(
        self, centres: FloatArray, middle: FloatArray, sharp: npt.NDArray[np.bool_]
    ) -> None:
        """The shown balls' shadows, multiplied into what is drawn, depth-tested but not
        written: a sharp ball's at its place, a moving one's along its path's chord."""
        boxes: list[tuple[float, ...]] = []
        decals: list[tuple[float, ...]] = []
        length, width = self.table_size
        clear = self.reach + 0.01  # of the cushions' noses, and on the cloth
        for index in range(len(centres)):
            if sharp[index]:
                starts, ends = middle[index][None], middle[index][None]
            else:
                starts, ends = centres[index][:1], centres[index][-1:]
            points = np.concatenate([starts, ends])
            x, y, z = points[:, 0], points[:, 1], points[:, 2]
            on_cloth = np.all(np.abs(z - self.radius) < 1e-3)
            inside = np.all((x > clear) & (x < length - clear) & (y > clear) & (y < width - clear))
            (decals if on_cloth and inside else boxes).extend(
                (*start, 1.0, *end) for start, end in zip(starts, ends, strict=True)
            )
        ctx = self.ctx
        self.scene_depth.use(1)
        ctx.enable(moderngl.BLEND)
        ctx.blend_func = moderngl.ZERO, moderngl.SRC_COLOR
        ctx.fbo.depth_mask = False
        if decals:  # depth-tested: only where the cloth is seen
            self.decal_centres.write(np.array(decals, dtype=np.float32).tobytes())
            self.decal_vao.render(instances=len(decals))
        if boxes:
            self.box_centres.write(np.array(boxes, dtype=np.float32).tobytes())
            ctx.disable(moderngl.DEPTH_TEST)  # the box is a volume: its back faces, all
            ctx.enable(moderngl.CULL_FACE)
            # The projection's flipped y turns the picture's winding over: GL's "back"
            # faces are the box's near ones.
            ctx.cull_face = "back"
            self.shadow_vao.render(instances=len(boxes))
            ctx.disable(moderngl.CULL_FACE)
            ctx.enable(moderngl.DEPTH_TEST)

    def _draw_ball(
        self, ball: int, path: FloatArray, turns: FloatArray, sharp: bool, rotation: FloatArray
    ) -> None:
        """Ball `ball` sharp, where it is at its path's middle (turned by `rotation`),
        or along its `path` (P, 3) and `turns` (P, 4)."""
        programs = self.programs
        self.textures[ball].use(0)
        for program in (programs.ball, programs.blur):
            uniform(program, "hole").value = tuple(float(v) for v in self.holes[ball])
        if sharp:
            uniform(programs.ball, "center").value = tuple(float(c) for c in path[PATH_POINTS // 2])
            # GLSL matrices are column-major: the transpose's rows are R's columns.
            matrix = np.ascontiguousarray(rotation.T, np.float32)
            uniform(programs.ball, "rotation").write(matrix.tobytes())
            self.ball_vao.render(moderngl.TRIANGLES)
            return
        uniform(programs.blur, "path").write(np.ascontiguousarray(path, np.float32).tobytes())
        uniform(programs.blur, "turns").write(np.ascontiguousarray(turns, np.float32).tobytes())
        self.blur_vao.render(moderngl.TRIANGLES)

    def drawn_region(self, centres: FloatArray, pose: CameraPose) -> Region | None:
        """The pixels that drawing balls along paths `centres` (N, P, 3) may change, with
        their shadows: round each point of a shown ball's path, the box its shadow is
        cast in (shadow.vert's, `reach` about it, down to the cloth), which holds the ball;
        None if none is shown; the whole frame if a box is not all in front of the eye."""
        shown = centres[centres[:, :, 2].max(axis=1) > GONE_BELOW].reshape(-1, 3)
        if len(shown) == 0:
            return None
        # shadow.vert's reach: longer for a ball in the air.
        reach = self.reach + 2.0 * np.maximum(shown[:, 2] - self.radius, 0.0)
        signs = [(sx, sy) for sx in (-1.0, 1.0) for sy in (-1.0, 1.0)]
        corners = []
        for z in (np.minimum(shown[:, 2] - reach, -0.01), shown[:, 2] + reach):
            for sx, sy in signs:
                corner = [shown[:, 0] + sx * reach, shown[:, 1] + sy * reach, z]
                corners.append(np.stack(corner, axis=1))
        return region_of(np.concatenate(corners), pose, self.size)
