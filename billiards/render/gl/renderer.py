"""Draws frames of a trajectory with moderngl: the GL side of rendering.

Per frame: the static scene (table, room, lamp), soft shadows of the balls (a decal on
the cloth, or for a ball near the cushions a box that finds the table's surface in
the static scene's depth), then the balls, sharp or (moving, with the shutter open)
drawn over their path, into a multisampled framebuffer that is resolved into a plain
one and read back as RGBA rows, top row first (the projection flips y), or, for a
film, converted by one more pass into yuv420p's planes (BT.709, limited range: what
the encoder takes, so ffmpeg converts nothing) and read back as those bytes.

While the camera holds still the static scene is drawn once into a cached
framebuffer and copied (colour and depth) at the start of each frame; only the
shadows and balls are drawn on top. The pictures are the same bit for bit. The last
few still poses' static scenes are kept, so a shot the film returns to is not drawn
again. While the camera holds still, the balls at rest (from this frame's open shutter
until at least HOLD_STILL s on) are drawn once, with their shadows, over a copy of the
static scene (`settled`); each frame starts from that and draws only the moving balls.
A resting ball that a moving one may be seen behind is drawn with it instead, far to
near as before; what differs is a moving ball's shadow under a resting ball's one-pixel
anti-aliased fringe, which is not seen (in the default film, 21 pixels of 2 frames).
"""

from __future__ import annotations

import importlib.resources
import math
from dataclasses import dataclass
from pathlib import Path
from typing import TypeVar, cast

import moderngl
import numpy as np
import numpy.typing as npt

from billiards.record.quaternions import rotation_matrices
from billiards.record.trajectory import Trajectory, ball_state
from billiards.render.gl.cue_pass import CuePass
from billiards.stage import geometry
from billiards.stage.cameras import NEAR, CameraPose
from billiards.stage.cue import CueStroke
from billiards.stage.edge_lines import LINE_ATTRIBUTES, LINE_FORMAT, edge_lines
from billiards.stage.pocket_mesh import build_pocket_liners
from billiards.stage.rack_turns import racked
from billiards.stage.textures import ball_texture

Resource = TypeVar("Resource")
FloatArray = npt.NDArray[np.float64]
Colour = tuple[float, float, float]
GL_SRGB8_ALPHA8 = 0x8C43
# A ball whose centre is below this has dropped out of sight (a pocketed ball is put at
# billiards.record.trajectory.GONE_DEPTH): it is not drawn, nor is its shadow.
GONE_BELOW = -0.5  # m
SHADOW_LIFT = 0.0003  # m: a shadow decal floats this far above the cloth
# cos of the lamp shades' cut-off: a pool of light on the cloth, falling off towards
# the rails and the corners (lighting.glsl's smoothstep runs from here to nearly 1).
SPOT_CONE = 0.62
LIGHTS = 4  # lighting.glsl's: the lamp's three spots and the room's fill
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
# Still poses whose drawn static scene is kept (a colour and a depth buffer each,
# 7.4 MB at 720p, 16.6 MB at 1080p).
KEPT_BACKGROUNDS = 3
# While the camera moves the picture this many pixels a frame or more, the static
# scene is drawn at LOW_RES_SCALE of the frame's size (each side) and filtered up:
# it costs about half, and its softness is far below the smear of that motion (the
# default film's ease moves it 8 to 31 px a frame). Multisampling it instead costs
# llvmpipe 4.5x its drawing at 2x; its edges are smoothed as it is filtered up
# (upscale.frag's SMOOTH_EDGES), and drawing it at 0.65 rather than 0.7 pays for that.
LOW_RES_MOTION = 8.0  # px of a 720p frame
LOW_RES_SCALE = 0.65  # of a 720p frame's size (see sample_scale)
# Per-pixel work follows the frame's size. The pixel counts above, the MSAA samples
# asked (`antialias`) and the moving camera's background (full size, or LOW_RES_SCALE
# when fast) are what a frame of REFERENCE_PIXELS gets, and a smaller one. A larger
# frame's pixels each cover less of the screen, so it takes fewer samples a pixel: as
# many per share of the screen as a 720p frame, and no fewer (sample_scale). 1080p:
# 2x MSAA for 4x, blur steps and thresholds 1.5 times the pixels, a moving camera's
# background drawn at 1280x720 (fast: 896x504, as 720p's) and filtered up.
REFERENCE_PIXELS = 1280 * 720
# A ball that stays exactly where it is from this frame's open shutter until at least
# this long after is drawn into `settled` rather than every frame (so the set drawn
# there changes seldom: each change redraws it).
HOLD_STILL = 0.5  # s
# What `Renderer.draw` hands back, named as ffmpeg names them: "rgba" (4 bytes a pixel,
# for stills and tests) or "yuv420p" (a film's: the Y plane, then U and V at half the
# width and height, 1.5 bytes a pixel; BT.709, limited range, see yuv420p.frag).
PIXEL_FORMATS = ("rgba", "yuv420p")
# A rectangle of a frame's pixels: x0, y0 (top-left, included), x1, y1 (excluded).
Region = tuple[int, int, int, int]
# Pixels added round the projected boxes of what a moving ball draws (its fringe).
REGION_MARGIN = 3


def sample_scale(size: tuple[int, int]) -> float:
    """How many times finer than a REFERENCE_PIXELS frame's a frame of `size` is, along
    each side: sqrt of the pixels' ratio, and 1 for that size or a smaller one (whose
    settings are the reference's). Samples per pixel fall by its square (MSAA) or by it
    (distances in pixels along a streak, the low-resolution background's side)."""
    return max(1.0, math.sqrt(size[0] * size[1] / REFERENCE_PIXELS))


def msaa_samples(antialias: int, size: tuple[int, int], most: int) -> int:
    """The multisampling of a frame of `size` asked for `antialias` samples a pixel
    (0, 2, 4 or 8, as at 720p): the fewest, by powers of two, that give at least as many
    per share of the screen (0 for one sample), and at most `most` (the GL's)."""
    if antialias <= 1:
        return 0
    area = sample_scale(size) ** 2
    samples = 1
    while samples * area < antialias:
        samples *= 2
    samples = min(samples, most)
    return samples if samples > 1 else 0


def union(first: Region | None, second: Region | None) -> Region | None:
    """The smallest region holding both (None: nothing)."""
    if first is None or second is None:
        return first if second is None else second
    return (
        min(first[0], second[0]),
        min(first[1], second[1]),
        max(first[2], second[2]),
        max(first[3], second[3]),
    )


def uniform(program: moderngl.Program, name: str) -> moderngl.Uniform:
    """A program's uniform by name (moderngl's lookup also returns attributes)."""
    return cast(moderngl.Uniform, program[name])


def shader_source(name: str) -> str:
    """A shader's text from billiards.shaders (its `#include` lines left to moderngl)."""
    return (importlib.resources.files("billiards.shaders") / name).read_text(encoding="utf-8")


def largest_frame(ctx: moderngl.Context) -> int:
    """The longest side, in pixels, this GL can draw a frame at."""
    viewport = ctx.info["GL_MAX_VIEWPORT_DIMS"]
    return int(min(ctx.info["GL_MAX_RENDERBUFFER_SIZE"], *viewport))


def static_layout(program: moderngl.Program) -> tuple[str, ...]:
    """The static meshes' vertex format for `program`, then its inputs' names (an input
    the compiler dropped from it is skipped over)."""
    parts, names = [], []
    for size, name in ((3, "in_position"), (3, "in_normal"), (3, "in_color"), (4, "in_material")):
        if name in program:
            parts.append(f"{size}f")
            names.append(name)
        else:
            parts.append(f"{4 * size}x")
    return (" ".join(parts), *names)


def register_shader_includes(ctx: moderngl.Context) -> None:
    """Let moderngl expand `#include "x.glsl"` with billiards.shaders' .glsl files."""
    for file in importlib.resources.files("billiards.shaders").iterdir():
        if file.name.endswith(".glsl"):
            ctx.includes[file.name] = file.read_text(encoding="utf-8")


class FrameSizeError(ValueError):
    """A frame larger than the GL can draw: bad input (the size asked), one line."""


@dataclass(frozen=True)
class Lighting:
    """The lamp's three spots, a dim fill under the ceiling, and the ambient light."""

    positions: tuple[Colour, ...]  # m
    colours: tuple[Colour, ...]  # linear RGB, irradiance at 1 m
    cones: tuple[float, ...]
    ambient_sky: Colour = (0.06, 0.056, 0.05)
    ambient_ground: Colour = (0.015, 0.02, 0.015)
    light_radius: float = 0.12  # m: the size of each shade's glowing mouth

    def __post_init__(self) -> None:
        # lighting.glsl: LIGHTS lights, the last the all-round fill, the others spots.
        if len(self.positions) != LIGHTS or min(self.cones[:-1]) < -0.5 < self.cones[-1]:
            raise ValueError(f"expected {LIGHTS - 1} spots and then the fill: {self.cones}")

    @classmethod
    def over(cls, lamp: geometry.Lamp, room: geometry.Room) -> Lighting:
        """Warm spots in the lamp's shades, and a dimmer fill for the room around."""
        spots = lamp.light_positions()
        spot: Colour = (0.95, 0.855, 0.72)
        fill: Colour = (2.2, 2.05, 1.9)
        cx, cy = room.centre
        return cls(
            positions=(*spots, (cx, cy, room.ceiling - 0.2)),
            colours=(*(spot for _ in spots), fill),
            cones=(*(SPOT_CONE for _ in spots), -1.0),
        )


def _cube_faces() -> list[list[tuple[float, float, float]]]:
    """The unit cube [-1, 1]^3 as 12 triangles (3 corners each), wound
    counter-clockwise seen from outside."""
    triangles = []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            u, v = (axis + 1) % 3, (axis + 2) % 3
            corners = []
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                point = [0.0, 0.0, 0.0]
                point[axis], point[u], point[v] = sign, a * sign, b
                corners.append((point[0], point[1], point[2]))
            triangles += [
                [corners[0], corners[1], corners[2]],
                [corners[0], corners[2], corners[3]],
            ]
    return triangles


class Yuv420pPass:
    """A film frame's last GL pass: a finished RGBA picture (a texture of `size`) as
    yuv420p's bytes, BT.709 in limited range (yuv420p.frag), what the encoder takes.

    One fragment a 2x2 block of the picture writes its four Y values, its U and its V
    into four targets half the picture's size each way (the Y plane's even rows, its
    odd rows, U, V); they are read back in yuv420p's order. On llvmpipe the whole pass
    costs more CPU than ffmpeg's own conversion (swscale) would (about 17 ms against
    11 a 1080p frame), so a frame that differs from the last one converted only in a
    region converts (and reads back) only that region.
    """

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int]) -> None:
        width, height = size
        if width % 2 or height % 2:
            raise ValueError(f"yuv420p needs an even size, not {width}x{height}")
        self.ctx = ctx
        self.size = size
        self.program = ctx.program(
            vertex_shader=shader_source("fullscreen.vert"),
            fragment_shader=shader_source("yuv420p.frag"),
        )
        uniform(self.program, "picture").value = 0
        uniform(self.program, "texel").value = (1.0 / width, 1.0 / height)
        self.vao = ctx.vertex_array(self.program, [])  # corners from gl_VertexID
        half = (width // 2, height // 2)
        self.targets = [ctx.renderbuffer(half, components) for components in (2, 2, 1, 1)]
        self.framebuffer = ctx.framebuffer(color_attachments=self.targets)
        self.planes = np.zeros(width * height * 3 // 2, dtype=np.uint8)  # as last read

    def convert(self, picture: moderngl.Texture, region: Region | None = None) -> bytes:
        """The picture (row 0 its top) as yuv420p: the Y plane, then U, then V.

        With a `region` (pixels x0, y0, x1, y1, even), only that part is converted and
        read back: the rest is what the last conversion left, so the caller must know
        the picture is unchanged there since then.
        """
        width, height = self.size
        x0, y0, x1, y1 = region if region is not None else (0, 0, width, height)
        if x1 <= x0 or y1 <= y0:
            return self.planes.tobytes()
        # (in the half-size targets: one fragment a 2x2 block)
        block = (x0 // 2, y0 // 2, (x1 - x0) // 2, (y1 - y0) // 2)
        self.framebuffer.scissor = block  # (applied by use)
        self.framebuffer.use()
        self.ctx.disable(moderngl.BLEND)
        picture.use(0)
        self.vao.render(moderngl.TRIANGLES, vertices=3)
        # Off again while bound (which turns GL's scissor test off): copy_framebuffer's
        # blit obeys the test, and would copy only this region into the next frame.
        # (moderngl takes None, the whole target, though its stub says a tuple.)
        self.framebuffer.scissor = None  # type: ignore[assignment]
        # Whole rows of the targets, from the region's first to its last.
        rows = (0, block[1], width // 2, block[3])
        first, count = block[1], block[3]
        luma = self.planes[: width * height].reshape(height // 2, 2, width)
        for parity in (0, 1):  # the Y plane's even rows, then its odd ones
            data = self.framebuffer.read(rows, components=2, attachment=parity, alignment=1)
            luma[first : first + count, parity] = np.frombuffer(data, np.uint8).reshape(
                count, width
            )
        chroma = width * height // 4
        for plane in (0, 1):  # U, then V
            self.framebuffer.read_into(
                self.planes,
                rows,
                components=1,
                attachment=2 + plane,
                alignment=1,
                write_offset=width * height + plane * chroma + first * (width // 2),
            )
        return self.planes.tobytes()

    def release(self) -> None:
        self.framebuffer.release()
        for target in self.targets:
            target.release()
        self.vao.release()
        self.program.release()


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
        self.ctx = ctx
        # Drawn with each object ball's number turned at random as the rack is set.
        self.trajectory = trajectory = racked(trajectory)
        self.size = size
        self.radius = trajectory.radius
        height = size[1]
        length, table_width = trajectory.table_size
        shape = geometry.TableShape(length, table_width)
        self.room = geometry.Room.around(length, table_width, shape.floor)
        self.lamp = geometry.Lamp(
            (length / 2, table_width / 2, 0.0),
            length=min(1.35, 0.65 * length),
            spacing=min(0.55, 0.26 * length),
        )
        self.lighting = Lighting.over(self.lamp, self.room)

        # Mesh data first, in numpy; then the GL side.
        static = (
            geometry.load_table_mesh(table_mesh)
            if table_mesh
            else geometry.build_table(shape, trajectory.pockets)
        )
        # The hole each ball drops into (x, y, the liner's radius; radius -1: none), for
        # the ball shaders' light below the cloth (lighting.glsl's through_hole).
        self.holes = np.zeros((len(trajectory.ball_ids), 3))
        self.holes[:, 2] = -1.0
        if trajectory.pockets is not None and not table_mesh:
            static.extend(build_pocket_liners(shape, trajectory.pockets))
            cuts = geometry.pocket_cuts(shape, trajectory.pockets)
            for event in trajectory.events:
                if event.kind == "pocket" and event.pocket is not None:
                    ball = trajectory.ball_ids.index(event.balls[0])
                    self.holes[ball] = cuts[trajectory.pockets.names.index(event.pocket)].hole
        static.extend(geometry.build_room(self.room))
        lamp = geometry.build_lamp(self.lamp, self.room.ceiling)
        self.lamp_bottom = float(lamp.bounds()[0][2])
        ceiling = geometry.build_ceiling(self.room)

        self._resources: list[object] = []
        register_shader_includes(ctx)
        # One scene program per kind of surface (geometry's pattern), each compiled for
        # its kind alone: a CPU rasterizer would otherwise work out every pattern at
        # every pixel and keep one.
        kinds = sorted({float(k) for mesh in (static, lamp, ceiling) for k in mesh.materials[:, 3]})
        self.scene_programs = {
            kind: self._program("scene.vert", "scene.frag", f"PATTERN {kind:.1f}") for kind in kinds
        }
        self.ball_program = self._program("ball.vert", "ball.frag")
        self.blur_program = self._program("ball_blur.vert", "ball_blur.frag")
        self.shadow_program = self._program("shadow.vert", "shadow.frag")
        self.decal_program = self._program("shadow_decal.vert", "shadow.frag", "ON_CLOTH")
        # A moving camera's background is not multisampled: its edges are smoothed by
        # drawing the meshes' edges over it as lines (edge_lines.py), when anti-aliasing
        # is asked at all.
        self.smooth_edges = antialias > 1
        self.upscale_program = self._program("upscale.vert", "upscale.frag")
        self.cue_program = self._program("cue.vert", "cue.frag")
        self.edge_program = self._program("edge_lines.vert", "edge_lines.frag")
        uniform(self.edge_program, "picture").value = 2
        self.programs: tuple[moderngl.Program, ...] = (
            *self.scene_programs.values(),
            self.ball_program,
            self.blur_program,
            self.shadow_program,
            self.decal_program,
            self.cue_program,
            self.edge_program,
        )
        for program in self.programs:
            self._set_lighting(program)

        self.static_vaos = self._surface_arrays(static)
        self.lamp_vaos = self._surface_arrays(lamp)
        self.ceiling_vaos = self._surface_arrays(ceiling)
        self.static_edges = self._edge_array(static) if self.smooth_edges else None
        self.lamp_edges = self._edge_array(lamp) if self.smooth_edges else None
        self.ceiling_edges = self._edge_array(ceiling) if self.smooth_edges else None
        # Copies of a drawing's colour (by size) that its edges' lines read
        self._edge_copies: dict[tuple[int, int], tuple[moderngl.Framebuffer, moderngl.Texture]]
        self._edge_copies = {}

        count = len(trajectory.ball_ids)
        corners = np.array([(-1, -1), (1, -1), (1, 1), (-1, -1), (1, 1), (-1, 1)], dtype=np.float32)
        self.square_vbo = self._keep(ctx.buffer(corners.tobytes()))
        self.ball_vao = self._keep(
            ctx.vertex_array(self.ball_program, [(self.square_vbo, "2f", "in_position")])
        )
        self.blur_vao = self._keep(
            ctx.vertex_array(self.blur_program, [(self.square_vbo, "2f", "in_position")])
        )
        self.upscale_vao = self._keep(
            ctx.vertex_array(self.upscale_program, [(self.square_vbo, "2f", "in_position")])
        )
        uniform(self.upscale_program, "low_colour").value = 2
        uniform(self.upscale_program, "low_depth").value = 3
        # Shadows: a decal on the cloth for a ball away from the cushions, a box for one
        # near them (or off the cloth), whose shadow may fall on a cushion or the rail.
        cube = np.array([corner for face in _cube_faces() for corner in face], dtype=np.float32)
        self.cube_vbo = self._keep(ctx.buffer(cube.tobytes()))
        self.box_centres = self._keep(
            ctx.buffer(reserve=max(count, 1) * SHADOW_INSTANCE, dynamic=True)
        )
        self.decal_centres = self._keep(
            ctx.buffer(reserve=max(count, 1) * SHADOW_INSTANCE, dynamic=True)
        )
        stretch = ("4f 3f/i", "in_start", "in_end")
        self.shadow_vao = self._keep(
            ctx.vertex_array(
                self.shadow_program,
                [(self.cube_vbo, "3f", "in_position"), (self.box_centres, *stretch)],
            )
        )
        self.decal_vao = self._keep(
            ctx.vertex_array(
                self.decal_program,
                [
                    (self.square_vbo, "2f", "in_position"),
                    (self.decal_centres, *stretch),
                ],
            )
        )
        for program in self.scene_programs.values():
            if "table_size" in program:
                uniform(program, "table_size").value = (length, table_width)
        self.reach = 3.0 * self.radius
        for program in (self.shadow_program, self.decal_program):
            uniform(program, "radius").value = self.radius
            uniform(program, "reach").value = self.reach
            uniform(program, "light_radius").value = self.lighting.light_radius
        # (the decals' program knows its surface: it has none of these)
        uniform(self.shadow_program, "viewport").value = (float(size[0]), float(size[1]))
        uniform(self.shadow_program, "scene_depth").value = 1
        uniform(self.shadow_program, "settled_depth").value = 4
        uniform(self.decal_program, "lift").value = SHADOW_LIFT
        for program in (self.ball_program, self.blur_program):
            uniform(program, "radius").value = self.radius
        self.pixel_angle = 0.0
        self.cue_pass: CuePass | None = None
        strike = trajectory.strike
        if cue and strike is not None and strike.ball in trajectory.ball_ids:
            # The struck ball's place before it leaves (the film opens before t = 0).
            start = trajectory.positions[0, trajectory.ball_ids.index(strike.ball)]
            stroke = CueStroke.of(strike, start, self.radius, shape)
            shadow = self._program("cue_shadow.vert", "cue_shadow.frag")
            uniform(shadow, "lamp_radius").value = self.lighting.light_radius
            spots = self.lighting.positions[:-1]
            uniform(shadow, "lamp_height").value = sum(z for _, _, z in spots) / len(spots)
            uniform(shadow, "lift").value = SHADOW_LIFT
            self.programs = (*self.programs, shadow)  # its camera set with theirs
            self.cue_pass = self._keep(
                CuePass(
                    ctx,
                    self.cue_program,
                    static_layout(self.cue_program),
                    stroke,
                    shadow,
                    (length, table_width),
                )
            )

        tex_width = 512 if height >= 400 else 256
        self.textures = []
        for ball_id in trajectory.ball_ids:
            pixels = ball_texture(ball_id, tex_width)
            texture = ctx.texture(
                (pixels.shape[1], pixels.shape[0]),
                4,
                pixels.tobytes(),
                internal_format=GL_SRGB8_ALPHA8,
            )
            texture.build_mipmaps()
            texture.filter = (moderngl.LINEAR_MIPMAP_LINEAR, moderngl.LINEAR)
            texture.anisotropy = 4.0
            texture.repeat_y = False
            self.textures.append(self._keep(texture))

        # The static scene is drawn multisampled (when asked) and resolved, colour and
        # depth, into `background`; each frame starts from a copy of it in `work`.
        largest = largest_frame(ctx)
        if max(self.size) > largest:
            width, height = self.size
            raise FrameSizeError(f"{width}x{height}: this GL draws at most {largest} px a side")
        self.samples = samples = msaa_samples(antialias, self.size, ctx.max_samples)
        # A streak shorter than this (in this frame's pixels) is drawn sharp.
        self.sharp_below = SHARP_BELOW * sample_scale(self.size)
        self.static = self._framebuffer(samples)
        # (its depth a texture: the shadows find the table's surface in it)
        self.background_depth = self._keep(ctx.depth_texture(self.size))
        self.background_depth.compare_func = ""  # read depths, not comparisons
        self.background_depth.filter = (moderngl.NEAREST, moderngl.NEAREST)
        self.background = self._keep(
            ctx.framebuffer(
                color_attachments=[self._keep(ctx.renderbuffer(self.size, 4))],
                depth_attachment=self.background_depth,
            )
        )
        # The finished pictures, `work` and `settled`, have textures for colour: the
        # yuv420p pass reads them.
        self.work_colour = self._keep(ctx.texture(self.size, 4))
        self.work = self._keep(
            ctx.framebuffer(
                color_attachments=[self.work_colour],
                depth_attachment=self._keep(ctx.depth_renderbuffer(self.size)),
            )
        )
        # The static scene with the balls at rest drawn in (its depth a texture: a moving
        # ball's shadow is not cast on them, as none is cast on a ball).
        self.settled_depth = self._keep(ctx.depth_texture(self.size))
        self.settled_depth.compare_func = ""
        self.settled_depth.filter = (moderngl.NEAREST, moderngl.NEAREST)
        self.settled_colour = self._keep(ctx.texture(self.size, 4))
        self.settled = self._keep(
            ctx.framebuffer(
                color_attachments=[self.settled_colour],
                depth_attachment=self.settled_depth,
            )
        )
        self._yuv: Yuv420pPass | None = None  # made for the first yuv420p frame
        # What the yuv420p pass last converted: `settled` (its key) outside a region
        # (None: nothing drawn over it), or something else (key None).
        self._yuv_holds: tuple[object, ...] | None = None
        self._yuv_drawn: Region | None = None
        self._settled_key: tuple[object, ...] | None = None
        # `settled` read back (per pixel format) while nothing moves
        self._settled_pictures: dict[str, bytes] = {}
        self._background_version = 0
        # Per recorded sample, how many times each ball has moved since the first (F, N):
        # a ball is still between two samples when the count is the same at both.
        positions, orientations = trajectory.positions, trajectory.orientations
        changed = np.any(positions[1:] != positions[:-1], axis=2) | np.any(
            orientations[1:] != orientations[:-1], axis=2
        )
        self._moves = np.concatenate(
            [np.zeros((1, changed.shape[1]), dtype=np.int64), np.cumsum(changed, axis=0)]
        )
        # The static scene at a lower resolution, for a fast-moving camera; and for a
        # slowly moving one, at 720p's resolution for a frame larger than 720p, else
        # None (drawn straight into `background`).
        scale = sample_scale(self.size)
        self.low, self.low_colour, self.low_depth = self._reduced(LOW_RES_SCALE / scale)
        self.reduced = self._reduced(1.0 / scale) if scale > 1.0 else None
        self._background_pose: CameraPose | None = None
        self._background_sharp = False  # drawn with multisampling
        # Copies of `background` for the last few still poses, so a film that comes
        # back to a shot (the default's wide view, at its start and end) reuses it.
        self._kept: dict[CameraPose, moderngl.Framebuffer] = {}

    # --- resources ------------------------------------------------------------------

    def _keep(self, resource: Resource) -> Resource:
        self._resources.append(resource)
        return resource

    def _program(self, vertex: str, fragment: str, define: str = "") -> moderngl.Program:
        """A program of two shaders, the fragment one compiled with `define` (such as
        "PATTERN 3.0") #defined."""
        fragment_source = shader_source(fragment)
        if define:
            version, rest = fragment_source.split("\n", 1)
            fragment_source = f"{version}\n#define {define}\n{rest}"
        program = self.ctx.program(
            vertex_shader=shader_source(vertex), fragment_shader=fragment_source
        )
        self._resources.append(program)
        return program

    def _surface_arrays(self, mesh: geometry.Mesh) -> list[moderngl.VertexArray]:
        """The mesh's triangles, one vertex array per kind of surface, each with its
        kind's scene program, in the order the kinds first appear in the mesh."""
        data = mesh.interleaved()
        kinds = mesh.materials[:, 3]
        _, first = np.unique(kinds, return_index=True)
        arrays = []
        for kind in kinds[np.sort(first)]:
            buffer = self._keep(self.ctx.buffer(data[kinds == kind].tobytes()))
            program = self.scene_programs[float(kind)]
            arrays.append(
                self._keep(
                    self.ctx.vertex_array(
                        program,
                        [(buffer, *static_layout(program))],
                    )
                )
            )
        return arrays

    def _reduced(
        self, scale: float
    ) -> tuple[moderngl.Framebuffer, moderngl.Texture, moderngl.Texture]:
        """A framebuffer `scale` of the frame's size a side, its colour and depth
        textures filtered (for `_upscale`)."""
        size = (max(1, round(self.size[0] * scale)), max(1, round(self.size[1] * scale)))
        colour = self._keep(self.ctx.texture(size, 4))
        depth = self._keep(self.ctx.depth_texture(size))
        depth.compare_func = ""
        for texture in (colour, depth):
            texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
            texture.repeat_x = texture.repeat_y = False
        framebuffer = self._keep(
            self.ctx.framebuffer(color_attachments=[colour], depth_attachment=depth)
        )
        return framebuffer, colour, depth

    def _edge_array(self, mesh: geometry.Mesh) -> moderngl.VertexArray | None:
        """The mesh's edges worth smoothing as GL lines (None: it has none)."""
        lines = edge_lines(mesh)
        if len(lines) == 0:
            return None
        buffer = self._keep(self.ctx.buffer(lines.tobytes()))
        layout = [name if name in self.edge_program else "" for name in LINE_ATTRIBUTES]
        formats = LINE_FORMAT.split()
        parts = [
            f if name else f"{4 * int(f[0])}x" for f, name in zip(formats, layout, strict=True)
        ]
        return self._keep(
            self.ctx.vertex_array(
                self.edge_program, [(buffer, " ".join(parts), *(n for n in layout if n))]
            )
        )

    def _framebuffer(self, samples: int, depth: bool = True) -> moderngl.Framebuffer:
        colour = self._keep(self.ctx.renderbuffer(self.size, 4, samples=samples))
        depth_buffer = (
            self._keep(self.ctx.depth_renderbuffer(self.size, samples=samples)) if depth else None
        )
        framebuffer = self.ctx.framebuffer(
            color_attachments=[colour], depth_attachment=depth_buffer
        )
        self._resources.append(framebuffer)
        return framebuffer

    def _set_lighting(self, program: moderngl.Program) -> None:
        light = self.lighting
        arrays = {
            "light_position": light.positions,
            "light_color": light.colours,
            "light_cone": light.cones,
        }
        for name, values in arrays.items():
            if name in program:  # a shader may not use every light uniform
                # (nor every light's: the compiler drops the fill's unused cone)
                used = uniform(program, name).array_length
                uniform(program, name).write(np.array(values[:used], dtype=np.float32).tobytes())
        for name, value in (
            ("ambient_sky", light.ambient_sky),
            ("ambient_ground", light.ambient_ground),
        ):
            if name in program:
                uniform(program, name).value = value

    def release(self) -> None:
        """Free every GL object this renderer made (the context stays)."""
        for resource in reversed(self._resources):
            resource.release()  # type: ignore[attr-defined]
        self._resources.clear()

    # --- drawing ------------------------------------------------------------------------

    def _set_camera(self, pose: CameraPose) -> None:
        view_projection = pose.view_projection(self.size[0] / self.size[1])
        matrix = view_projection.tobytes()
        inverse = np.linalg.inv(view_projection.astype(np.float64)).astype(np.float32)
        uniform(self.shadow_program, "inverse_view_projection").write(inverse.tobytes())
        for program in self.programs:
            uniform(program, "view_projection").write(matrix)
            if "camera_position" in program:
                uniform(program, "camera_position").value = pose.eye
        right, up, _ = pose.basis()
        for program in (self.ball_program, self.blur_program):
            uniform(program, "camera_right").value = tuple(float(v) for v in right)
            uniform(program, "camera_up").value = tuple(float(v) for v in up)
        self.pixel_angle = 2 * math.tan(math.radians(pose.fov) / 2) / self.size[1]
        for program in (self.ball_program, self.blur_program, self.cue_program):
            uniform(program, "pixel_angle").value = self.pixel_angle

    def _draw_static(self, framebuffer: moderngl.Framebuffer, pose: CameraPose) -> None:
        framebuffer.use()
        self.ctx.disable(moderngl.BLEND)
        self.ctx.enable(moderngl.DEPTH_TEST)
        framebuffer.depth_mask = True
        framebuffer.clear(0.0, 0.0, 0.0, 1.0, depth=1.0)
        for surfaces in self.static_vaos:
            surfaces.render()
        # A camera above the lamp and over the table (overhead shots) would see
        # only the lamp: leave it out then, as a film crew would.
        if not self._above_lamp(pose):
            for surfaces in self.lamp_vaos:
                surfaces.render()
        # Nor the ceiling, for a camera above it (an overhead view of a long table, or
        # of a table on a square or upright film, is taken from higher than a room).
        if not self._above_ceiling(pose):
            for surfaces in self.ceiling_vaos:
                surfaces.render()

    def _above_lamp(self, pose: CameraPose) -> bool:
        x, y, z = pose.eye
        length, width = self.trajectory.table_size
        return z >= self.lamp_bottom and -0.3 < x < length + 0.3 and -0.3 < y < width + 0.3

    def _above_ceiling(self, pose: CameraPose) -> bool:
        return pose.eye[2] >= self.room.ceiling

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

    def _still(self, time: float, exposure: float) -> tuple[npt.NDArray[np.bool_], int]:
        """Which balls stay exactly where they are from the open shutter's start until
        HOLD_STILL s after its end, and the recorded sample that holds them there."""
        times = self.trajectory.times
        last = len(times) - 1
        start = int(np.clip(np.searchsorted(times, time - exposure / 2, "right") - 1, 0, last))
        end = int(np.clip(np.searchsorted(times, time + exposure / 2 + HOLD_STILL), 0, last))
        return self._moves[end] == self._moves[start], start

    def _draw_balls(
        self,
        centres: FloatArray,
        turns: FloatArray,
        pose: CameraPose,
        balls: npt.NDArray[np.intp] | None = None,
    ) -> None:
        """Shadows, then the balls far to near, of `balls` (all if None), each along its
        path's PATH_POINTS centres (N, P, 3) and turns (N, P, 4)."""
        index_of = np.arange(len(centres)) if balls is None else balls
        centres, turns = centres[index_of], turns[index_of]
        # Drawn while any part of its path is above GONE_BELOW.
        visible = np.flatnonzero(centres[:, :, 2].max(axis=1) > GONE_BELOW)
        if len(visible) == 0:
            return
        shown = index_of[visible]
        centres, turns = centres[visible], turns[visible]
        middle = centres[:, PATH_POINTS // 2]
        eye = np.array(pose.eye)
        # Sharp, or a streak: how far it moves on screen over the open shutter.
        travel = np.linalg.norm(np.diff(centres, axis=1), axis=2).sum(axis=1)
        distance = np.linalg.norm(middle - eye, axis=1)
        streak = travel / np.maximum(distance * self.pixel_angle, 1e-12)
        sharp = streak < self.sharp_below
        ctx = self.ctx
        # Shadows: multiplied into the cloth, depth-tested but not written; a moving
        # ball's one per straight stretch of its path, each with its share.
        boxes: list[tuple[float, ...]] = []
        decals: list[tuple[float, ...]] = []
        length, width = self.trajectory.table_size
        for index in range(len(shown)):
            if sharp[index]:
                starts, ends = middle[index][None], middle[index][None]
            else:
                starts, ends = centres[index][:1], centres[index][-1:]
            points = np.concatenate([starts, ends])
            x, y, z = points[:, 0], points[:, 1], points[:, 2]
            clear = self.reach + 0.01  # of the cushions' noses, and on the cloth
            on_cloth = np.all(np.abs(z - self.radius) < 1e-3)
            inside = np.all((x > clear) & (x < length - clear) & (y > clear) & (y < width - clear))
            (decals if on_cloth and inside else boxes).extend(
                (*start, 1.0, *end) for start, end in zip(starts, ends, strict=True)
            )
        target = ctx.fbo  # `work`, or `settled` for the balls at rest
        self.background_depth.use(1)
        ctx.enable(moderngl.BLEND)
        ctx.blend_func = moderngl.ZERO, moderngl.SRC_COLOR
        target.depth_mask = False
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
        # Balls far to near, premultiplied: a near ball's fringe covers the one behind.
        ctx.blend_func = moderngl.ONE, moderngl.ONE_MINUS_SRC_ALPHA
        target.depth_mask = True
        centre = uniform(self.ball_program, "center")
        rotation = uniform(self.ball_program, "rotation")
        path = uniform(self.blur_program, "path")
        turn = uniform(self.blur_program, "turns")
        holes = (uniform(self.ball_program, "hole"), uniform(self.blur_program, "hole"))
        rotations = rotation_matrices(turns[:, PATH_POINTS // 2])
        for index in np.argsort(-distance, kind="stable"):
            self.textures[shown[index]].use(0)
            for hole in holes:
                hole.value = tuple(float(v) for v in self.holes[shown[index]])
            if sharp[index]:  # the ball where it is
                centre.value = tuple(float(c) for c in middle[index])
                # GLSL matrices are column-major: the transpose's rows are R's columns.
                rotation.write(np.ascontiguousarray(rotations[index].T, np.float32).tobytes())
                self.ball_vao.render(moderngl.TRIANGLES)
                continue
            path.write(np.ascontiguousarray(centres[index], dtype=np.float32).tobytes())
            turn.write(np.ascontiguousarray(turns[index], dtype=np.float32).tobytes())
            self.blur_vao.render(moderngl.TRIANGLES)
        ctx.disable(moderngl.BLEND)

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
        self._set_camera(pose)
        self._prepare_background(pose, moving)
        centres, turns = self._paths(time, exposure)
        cue = None if self.cue_pass is None else self.cue_pass.placement(time)
        if moving:  # the background is drawn again next frame: no balls kept in it
            self._start_from(self.background, self.background_depth)
            self._draw_balls(centres, turns, pose)
            if cue is not None and self.cue_pass is not None:
                self.cue_pass.draw(cue)
        else:
            still, sample = self._still(time, exposure)
            still &= ~self._in_front_of_moving(still, centres, pose)
            self._settle(pose, still, sample)
            unsettled = np.flatnonzero(~still)
            if cue is None and not np.any(centres[unsettled, :, 2] > GONE_BELOW):
                # Nothing moves in the picture: it is `settled` as it stands.
                if pixel_format not in self._settled_pictures:
                    self._settled_pictures[pixel_format] = self._read(
                        self.settled, self.settled_colour, pixel_format
                    )
                    if pixel_format == "yuv420p":
                        self._yuv_holds, self._yuv_drawn = self._settled_key, None
                return self._settled_pictures[pixel_format]
            self._start_from(self.settled, self.settled_depth)
            self._draw_balls(centres, turns, pose, unsettled)
            if cue is not None and self.cue_pass is not None:
                self.cue_pass.draw(cue)  # over the balls, depth-tested against them
            if pixel_format == "yuv420p":
                # `work` is `settled` but where these balls and their shadows (and the
                # cue) are drawn: if the pass last converted `settled` (and balls within
                # a region), only there and here need converting again.
                drawn = self._drawn_region(centres[unsettled], pose)
                if cue is not None and self.cue_pass is not None:
                    stick = np.vstack([cue.bounds(), self.cue_pass.shadow_corners(cue)])
                    drawn = union(drawn, self._region_of(stick, pose))
                region = (
                    union(drawn, self._yuv_drawn) if self._yuv_holds == self._settled_key else None
                )
                picture = self._read(self.work, self.work_colour, pixel_format, region)
                self._yuv_holds, self._yuv_drawn = self._settled_key, drawn
                return picture
        if pixel_format == "yuv420p":
            self._yuv_holds = None
        return self._read(self.work, self.work_colour, pixel_format)

    def _drawn_region(self, centres: FloatArray, pose: CameraPose) -> Region | None:
        """The pixels that drawing balls along paths `centres` (N, P, 3) may change, with
        their shadows: round each point of a shown ball's path, the box its shadow is
        cast in (shadow.vert's, `reach` about it, down to the cloth), which holds the ball;
        None if none is shown; the whole frame if a box is not all in front of the eye."""
        shown = centres[centres[:, :, 2].max(axis=1) > GONE_BELOW].reshape(-1, 3)
        if len(shown) == 0:
            return None
        reach = self.reach
        offsets = np.array(
            [(dx, dy) for dx in (-reach, reach) for dy in (-reach, reach)], dtype=np.float64
        )
        corners = []
        for z in (np.minimum(shown[:, 2] - reach, -0.01), shown[:, 2] + reach):
            for dx, dy in offsets:
                corners.append(np.stack([shown[:, 0] + dx, shown[:, 1] + dy, z], axis=1))
        return self._region_of(np.concatenate(corners), pose)

    def _region_of(self, points: FloatArray, pose: CameraPose) -> Region | None:
        """The pixels round the projections of `points` (K, 3), widened by the margin to
        whole 2x2 blocks; the whole frame if a point is not in front of the eye."""
        width, height = self.size
        matrix = pose.view_projection(width / height, flip_y=False).astype(np.float64)
        clip = np.hstack([points, np.ones((len(points), 1))]) @ matrix
        if np.any(clip[:, 3] <= NEAR):
            return (0, 0, width, height)
        x = (clip[:, 0] / clip[:, 3] + 1) / 2 * width
        y = (1 - clip[:, 1] / clip[:, 3]) / 2 * height
        # Widened by the margin, to whole 2x2 blocks, inside the frame.
        x0 = max(0, math.floor(x.min()) - REGION_MARGIN) // 2 * 2
        y0 = max(0, math.floor(y.min()) - REGION_MARGIN) // 2 * 2
        x1 = min(width, (math.ceil(x.max()) + REGION_MARGIN + 1) // 2 * 2)
        y1 = min(height, (math.ceil(y.max()) + REGION_MARGIN + 1) // 2 * 2)
        return (x0, y0, x1, y1) if x1 > x0 and y1 > y0 else None

    def _read(
        self,
        picture: moderngl.Framebuffer,
        colour: moderngl.Texture,
        pixel_format: str,
        region: Region | None = None,
    ) -> bytes:
        """A finished `picture` (its `colour` texture) read back as `pixel_format`'s
        bytes (yuv420p: converted within `region` only, when one is given)."""
        if pixel_format == "rgba":
            return picture.read(components=4, alignment=1)
        return self._yuv_pass().convert(colour, region)

    def _yuv_pass(self) -> Yuv420pPass:
        """The yuv420p pass, made at the first asking. (Its first conversion is whole:
        `_yuv_holds` names nothing it converted yet.)"""
        if self._yuv is None:
            self._yuv = self._keep(Yuv420pPass(self.ctx, self.size))
        return self._yuv

    def film_format(self) -> str:
        """The pixel format a film's frames are best drawn in here: "yuv420p" where the
        GL can build the conversion pass (its shader needs GL_ARB_gpu_shader5, GL 4.0:
        llvmpipe has it), else "rgba" (ffmpeg converts)."""
        try:
            self._yuv_pass()
        except moderngl.Error:
            return "rgba"
        return "yuv420p"

    def _in_front_of_moving(
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
        width, height = self.size
        points = pose.project(centres.reshape(-1, 3), width, height).reshape(
            len(centres), PATH_POINTS, 2
        )
        distance = np.linalg.norm(centres - np.array(pose.eye), axis=2)  # (N, P)
        # A ball's reach on screen, px: twice its radius there (its square's off-axis
        # stretch), the fringe, and half its path's longest step between points.
        step = np.linalg.norm(np.diff(points, axis=1), axis=2).max(axis=1)
        reach = 2 * self.radius / (distance.min(axis=1) * self.pixel_angle) + 2 + step / 2
        middle = PATH_POINTS // 2
        # (resting, moving) pairs: the moving ball no nearer, and near it on screen
        further = distance[moving, middle][None, :] >= distance[resting, middle][:, None]
        offsets = points[moving][None, :, :, :] - points[resting, middle][:, None, None, :]
        gaps = np.sqrt(np.sum(offsets * offsets, axis=3)).min(axis=2)
        near = gaps < reach[moving][None, :] + reach[resting][:, None]
        behind[resting] = np.any(further & near, axis=1)
        return behind

    def _start_from(self, picture: moderngl.Framebuffer, depth: moderngl.Texture) -> None:
        """`work` becomes a copy of `picture`, whose depth (balls drawn there included)
        the shadows drawn next leave alone."""
        self.ctx.copy_framebuffer(self.work, picture)
        depth.use(4)
        self.work.use()
        self.ctx.enable(moderngl.DEPTH_TEST)

    def _settle(self, pose: CameraPose, still: npt.NDArray[np.bool_], sample: int) -> None:
        """`settled`: the background with the `still` balls drawn in, as they are at the
        recorded `sample`; drawn again only when the background or those balls change."""
        balls = np.flatnonzero(still)
        centres = self.trajectory.positions[sample][balls]
        turns = self.trajectory.orientations[sample][balls]
        key = (self._background_version, balls.tobytes(), centres.tobytes(), turns.tobytes())
        if key == self._settled_key:
            return
        self._settled_key = key
        self._settled_pictures.clear()
        self.ctx.copy_framebuffer(self.settled, self.background)
        if len(balls) == 0:
            return
        self.background_depth.use(4)  # nothing drawn over the static scene yet
        self.settled.use()
        self.ctx.enable(moderngl.DEPTH_TEST)
        full = np.zeros((len(self.trajectory.ball_ids), PATH_POINTS, 3))
        full_turns = np.zeros((len(self.trajectory.ball_ids), PATH_POINTS, 4))
        full[balls] = centres[:, None, :]
        full_turns[balls] = turns[:, None, :]
        self._draw_balls(full, full_turns, pose, balls)

    def _prepare_background(self, pose: CameraPose, moving: bool) -> None:
        """The static scene seen from `pose` into `background`: as it is if it holds
        that already, copied from a kept one, or drawn (and kept if the camera stays)."""
        sharp = self.samples > 0 and not moving
        if pose == self._background_pose and (self._background_sharp or not sharp):
            return
        self._background_version += 1
        kept = self._kept.pop(pose, None)
        if kept is not None:
            self._kept[pose] = kept  # the most recently used last
            self.ctx.copy_framebuffer(self.background, kept)
            self._background_pose, self._background_sharp = pose, True
            return
        previous = self._background_pose
        fast = LOW_RES_MOTION * sample_scale(self.size)  # in this frame's pixels
        if moving and previous is not None and self._motion(previous, pose) >= fast:
            self._draw_static(self.low, pose)
            self._smooth_edges(self.low, pose)
            self._upscale(self.low_colour, self.low_depth)
        elif moving and self.reduced is not None:
            low, colour, depth = self.reduced
            self._draw_static(low, pose)
            self._smooth_edges(low, pose)
            self._upscale(colour, depth)
        else:
            target = self.static if sharp else self.background
            self._draw_static(target, pose)
            if target is self.static:
                self.ctx.copy_framebuffer(self.background, self.static)  # resolves MSAA
            elif moving:
                self._smooth_edges(target, pose)
        self._background_pose = pose
        self._background_sharp = sharp or self.samples == 0
        if not moving:
            if len(self._kept) < KEPT_BACKGROUNDS:
                kept = self._keep(
                    self.ctx.framebuffer(
                        color_attachments=[self._keep(self.ctx.renderbuffer(self.size, 4))],
                        depth_attachment=self._keep(self.ctx.depth_texture(self.size)),
                    )
                )
            else:  # the least recently used one makes way
                kept = self._kept.pop(next(iter(self._kept)))
            self.ctx.copy_framebuffer(kept, self.background)
            self._kept[pose] = kept

    def _motion(self, previous: CameraPose, pose: CameraPose) -> float:
        """How far (px) the table moves in the picture from `previous` to `pose`: the
        most any of the cloth's corners or its centre moves."""
        length, width = self.trajectory.table_size
        points = np.array(
            [
                (0, 0, 0),
                (length, 0, 0),
                (0, width, 0),
                (length, width, 0),
                (length / 2, width / 2, 0),
            ],
            dtype=np.float64,
        )
        before = previous.project(points, *self.size)
        after = pose.project(points, *self.size)
        return float(np.linalg.norm(after - before, axis=1).max())

    def _upscale(self, colour: moderngl.Texture, depth: moderngl.Texture) -> None:
        """A smaller drawing's `colour` and `depth`, filtered up into `background`."""
        self.background.use()
        self.ctx.disable(moderngl.BLEND)
        self.ctx.enable(moderngl.DEPTH_TEST)
        self.ctx.depth_func = "1"  # always: every pixel takes the low one's depth
        self.background.depth_mask = True
        colour.use(2)
        depth.use(3)
        self.upscale_vao.render(moderngl.TRIANGLES)
        self.ctx.depth_func = "<"

    def _smooth_edges(self, drawing: moderngl.Framebuffer, pose: CameraPose) -> None:
        """The static scene just drawn into `drawing` (not multisampled), its edges
        smoothed where they show (edge_lines.frag), when anti-aliasing is asked."""
        if self.static_edges is None:
            return
        size = drawing.size
        if size not in self._edge_copies:
            texture = self._keep(self.ctx.texture(size, 4))
            texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
            texture.repeat_x = texture.repeat_y = False
            target = self._keep(self.ctx.framebuffer(color_attachments=[texture]))
            self._edge_copies[size] = (target, texture)
        copy, texture = self._edge_copies[size]
        self.ctx.copy_framebuffer(copy, drawing)
        drawing.use()
        self.ctx.disable(moderngl.BLEND)
        self.ctx.enable(moderngl.DEPTH_TEST)
        self.ctx.depth_func = "<="
        drawing.depth_mask = False
        texture.use(2)
        uniform(self.edge_program, "viewport").value = (float(size[0]), float(size[1]))
        self.static_edges.render(moderngl.LINES)
        if self.lamp_edges is not None and not self._above_lamp(pose):
            self.lamp_edges.render(moderngl.LINES)
        if self.ceiling_edges is not None and not self._above_ceiling(pose):
            self.ceiling_edges.render(moderngl.LINES)
        drawing.depth_mask = True
        self.ctx.depth_func = "<"

    def frame(self, time: float, pose: CameraPose, exposure: float = 0.0) -> npt.NDArray[np.uint8]:
        """The picture at `time` as an RGB array (height x width x 3)."""
        data = np.frombuffer(self.draw(time, pose, exposure=exposure), dtype=np.uint8)
        return data.reshape(self.size[1], self.size[0], 4)[..., :3].copy()
