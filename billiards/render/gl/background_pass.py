"""The static scene's pass: the table, the room and the lamp seen from the camera, drawn
into `background` (its depth a texture: the shadows find the table's surface in it).

While the camera holds still the static scene is drawn once, multisampled when asked,
and resolved into `background`; the last few still poses' are kept, so a shot the film
returns to is not drawn again. While it moves it is drawn plainly (its edges smoothed
by lines over it), and smaller and filtered up while the picture moves fast.
"""

from __future__ import annotations

import moderngl
import numpy as np

from billiards.render.gl.frame_output import depth_texture, msaa_samples, sample_scale
from billiards.render.gl.programs import SQUARE, GLOwner, Programs, static_layout, uniform
from billiards.stage.cameras import CameraPose
from billiards.stage.edge_lines import LINE_ATTRIBUTES, LINE_FORMAT, edge_lines
from billiards.stage.meshes import Mesh

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
Reduced = tuple[moderngl.Framebuffer, moderngl.Texture, moderngl.Texture]


def filtered(texture: moderngl.Texture) -> moderngl.Texture:
    """`texture` read between its texels (linearly) and not repeated: to be filtered up."""
    texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
    texture.repeat_x = texture.repeat_y = False
    return texture


class BackgroundPass(GLOwner):
    """Draws the static scene (the table and the room), the lamp and the ceiling into `framebuffer`
    for a frame of `size`, multisampled `samples` times when still."""

    def __init__(
        self,
        ctx: moderngl.Context,
        programs: Programs,
        meshes: tuple[Mesh, Mesh, Mesh],
        size: tuple[int, int],
        antialias: int,
        table_size: tuple[float, float],
    ) -> None:
        """`meshes`: the static scene, the lamp, the ceiling; `antialias`: samples a pixel, as
        at 720p (msaa_samples); with any, a moving camera's background (not
        multisampled) has its edges smoothed by drawing the meshes' edges over it as
        lines (edge_lines.py)."""
        super().__init__()
        self.ctx, self.programs, self.size = ctx, programs, size
        self.samples = samples = msaa_samples(antialias, size, ctx.max_samples)
        smooth_edges = antialias > 1
        self.table_size = table_size
        static, lamp, ceiling = meshes
        self.lamp_bottom = float(lamp.bounds()[0][2])
        self.ceiling = float(ceiling.bounds()[0][2])
        for program in programs.scene.values():
            if "table_size" in program:
                uniform(program, "table_size").value = table_size
        self.static_vaos = self._surface_arrays(static)
        self.lamp_vaos = self._surface_arrays(lamp)
        self.ceiling_vaos = self._surface_arrays(ceiling)
        uniform(programs.edge, "picture").value = 2
        self.static_edges = self._edge_array(static) if smooth_edges else None
        self.lamp_edges = self._edge_array(lamp) if smooth_edges else None
        self.ceiling_edges = self._edge_array(ceiling) if smooth_edges else None
        # Copies of a drawing's colour (by size) that its edges' lines read
        self._edge_copies: dict[tuple[int, int], tuple[moderngl.Framebuffer, moderngl.Texture]]
        self._edge_copies = {}
        square = self.keep(ctx.buffer(SQUARE.tobytes()))
        self.upscale_vao = self.keep(
            ctx.vertex_array(programs.upscale, [(square, "2f", "in_position")])
        )
        uniform(programs.upscale, "low_colour").value = 2
        uniform(programs.upscale, "low_depth").value = 3
        # Drawn multisampled (when asked) into `static`, resolved, colour and depth,
        # into `framebuffer`.
        self.static = self.keep(
            ctx.framebuffer(
                color_attachments=[self.keep(ctx.renderbuffer(size, 4, samples=samples))],
                depth_attachment=self.keep(ctx.depth_renderbuffer(size, samples=samples)),
            )
        )
        self.depth = self.keep(depth_texture(ctx, size))
        self.framebuffer = self._colour_and(self.depth)
        # At a lower resolution, for a fast-moving camera; and for a slowly moving one,
        # at 720p's resolution for a frame larger than 720p, else None (drawn straight
        # into `framebuffer`).
        scale = sample_scale(size)
        self.low, self.low_colour, self.low_depth = self._reduced(LOW_RES_SCALE / scale)
        self.reduced = self._reduced(1.0 / scale) if scale > 1.0 else None
        self.pose: CameraPose | None = None
        self.sharp = False  # drawn with multisampling
        self.version = 0  # counts each change of the picture
        # Copies for the last few still poses, so a film that comes back to a shot (the
        # default's wide view, at its start and end) reuses it.
        self._kept: dict[CameraPose, moderngl.Framebuffer] = {}

    def _colour_and(self, depth: moderngl.Texture) -> moderngl.Framebuffer:
        colour = self.keep(self.ctx.renderbuffer(self.size, 4))
        return self.keep(self.ctx.framebuffer(color_attachments=[colour], depth_attachment=depth))

    def _surface_arrays(self, mesh: Mesh) -> list[moderngl.VertexArray]:
        """The mesh's triangles, one vertex array per kind of surface, each with its
        kind's scene program, in the order the kinds first appear in the mesh."""
        data = mesh.interleaved()
        kinds = mesh.materials[:, 3]
        _, first = np.unique(kinds, return_index=True)
        arrays = []
        for kind in kinds[np.sort(first)]:
            buffer = self.keep(self.ctx.buffer(data[kinds == kind].tobytes()))
            program = self.programs.scene[float(kind)]
            arrays.append(
                self.keep(self.ctx.vertex_array(program, [(buffer, *static_layout(program))]))
            )
        return arrays

    def _edge_array(self, mesh: Mesh) -> moderngl.VertexArray | None:
        """The mesh's edges worth smoothing as GL lines (None: it has none)."""
        lines = edge_lines(mesh)
        if len(lines) == 0:
            return None
        buffer = self.keep(self.ctx.buffer(lines.tobytes()))
        program = self.programs.edge
        layout = [name if name in program else "" for name in LINE_ATTRIBUTES]
        formats = LINE_FORMAT.split()
        parts = [
            f if name else f"{4 * int(f[0])}x" for f, name in zip(formats, layout, strict=True)
        ]
        return self.keep(
            self.ctx.vertex_array(program, [(buffer, " ".join(parts), *(n for n in layout if n))])
        )

    def _reduced(self, scale: float) -> Reduced:
        """A framebuffer `scale` of the frame's size a side, its colour and depth
        textures filtered (for `_upscale`)."""
        size = (max(1, round(self.size[0] * scale)), max(1, round(self.size[1] * scale)))
        colour = self.keep(filtered(self.ctx.texture(size, 4)))
        depth = self.keep(self.ctx.depth_texture(size))
        depth.compare_func = ""
        filtered(depth)
        framebuffer = self.keep(
            self.ctx.framebuffer(color_attachments=[colour], depth_attachment=depth)
        )
        return framebuffer, colour, depth

    def draw_static(self, framebuffer: moderngl.Framebuffer, pose: CameraPose) -> None:
        framebuffer.use()
        self.ctx.disable(moderngl.BLEND)
        self.ctx.enable(moderngl.DEPTH_TEST)
        framebuffer.depth_mask = True
        framebuffer.clear(0.0, 0.0, 0.0, 1.0, depth=1.0)
        for surfaces in self.static_vaos:
            surfaces.render()
        # A camera above the lamp and over the table (overhead shots) would see
        # only the lamp: leave it out then, as a film crew would.
        if not self.above_lamp(pose):
            for surfaces in self.lamp_vaos:
                surfaces.render()
        # Nor the ceiling, for a camera above it (an overhead view of a long table, or
        # of a table on a square or upright film, is taken from higher than a room).
        if not self.above_ceiling(pose):
            for surfaces in self.ceiling_vaos:
                surfaces.render()

    def above_lamp(self, pose: CameraPose) -> bool:
        x, y, z = pose.eye
        length, width = self.table_size
        return z >= self.lamp_bottom and -0.3 < x < length + 0.3 and -0.3 < y < width + 0.3

    def above_ceiling(self, pose: CameraPose) -> bool:
        return pose.eye[2] >= self.ceiling

    def prepare(self, pose: CameraPose, moving: bool) -> None:
        """The static scene seen from `pose` into `framebuffer`: as it is if it holds
        that already, copied from a kept one, or drawn (and kept if the camera stays)."""
        sharp = self.samples > 0 and not moving
        if pose == self.pose and (self.sharp or not sharp):
            return
        self.version += 1
        kept = self._kept.pop(pose, None)
        if kept is not None:
            self._kept[pose] = kept  # the most recently used last
            self.ctx.copy_framebuffer(self.framebuffer, kept)
            self.pose, self.sharp = pose, True
            return
        previous = self.pose
        fast = LOW_RES_MOTION * sample_scale(self.size)  # in this frame's pixels
        if moving and previous is not None and self._motion(previous, pose) >= fast:
            self._draw_reduced((self.low, self.low_colour, self.low_depth), pose)
        elif moving and self.reduced is not None:
            self._draw_reduced(self.reduced, pose)
        else:
            target = self.static if sharp else self.framebuffer
            self.draw_static(target, pose)
            if target is self.static:
                self.ctx.copy_framebuffer(self.framebuffer, self.static)  # resolves MSAA
            elif moving:
                self._smooth_edges(target, pose)
        self.pose = pose
        self.sharp = sharp or self.samples == 0
        if not moving:
            if len(self._kept) < KEPT_BACKGROUNDS:
                kept = self._colour_and(self.keep(self.ctx.depth_texture(self.size)))
            else:  # the least recently used one makes way
                kept = self._kept.pop(next(iter(self._kept)))
            self.ctx.copy_framebuffer(kept, self.framebuffer)
            self._kept[pose] = kept

    def _motion(self, previous: CameraPose, pose: CameraPose) -> float:
        """How far (px) the table moves in the picture from `previous` to `pose`: the
        most any of the cloth's corners or its centre moves."""
        length, width = self.table_size
        corners = [(x, y, 0.0) for y in (0.0, width) for x in (0.0, length)]
        points = np.array([*corners, (length / 2, width / 2, 0.0)])
        before = previous.project(points, *self.size)
        after = pose.project(points, *self.size)
        return float(np.linalg.norm(after - before, axis=1).max())

    def _draw_reduced(self, reduced: Reduced, pose: CameraPose) -> None:
        """The static scene drawn smaller, its edges smoothed, and filtered up into
        `framebuffer`: every pixel takes the smaller drawing's depth."""
        drawing, colour, depth = reduced
        self.draw_static(drawing, pose)
        self._smooth_edges(drawing, pose)
        self.framebuffer.use()
        self.ctx.disable(moderngl.BLEND)
        self.ctx.enable(moderngl.DEPTH_TEST)
        self.ctx.depth_func = "1"  # always
        self.framebuffer.depth_mask = True
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
            texture = self.keep(filtered(self.ctx.texture(size, 4)))
            target = self.keep(self.ctx.framebuffer(color_attachments=[texture]))
            self._edge_copies[size] = (target, texture)
        copy, texture = self._edge_copies[size]
        self.ctx.copy_framebuffer(copy, drawing)
        drawing.use()
        self.ctx.disable(moderngl.BLEND)
        self.ctx.enable(moderngl.DEPTH_TEST)
        self.ctx.depth_func = "<="
        drawing.depth_mask = False
        texture.use(2)
        uniform(self.programs.edge, "viewport").value = (float(size[0]), float(size[1]))
        self.static_edges.render(moderngl.LINES)
        if self.lamp_edges is not None and not self.above_lamp(pose):
            self.lamp_edges.render(moderngl.LINES)
        if self.ceiling_edges is not None and not self.above_ceiling(pose):
            self.ceiling_edges.render(moderngl.LINES)
        drawing.depth_mask = True
        self.ctx.depth_func = "<"
