"""A frame's output: its size and samples, the finished picture (`work`) and how it is
read back, as RGBA rows or, for a film, converted by one more pass into yuv420p's
planes (BT.709, limited range: what the encoder takes, so ffmpeg converts nothing),
only where it changed since the last conversion."""

from __future__ import annotations

import math

import moderngl
import numpy as np
import numpy.typing as npt

from billiards.render.gl.programs import GLOwner, compile_program, uniform
from billiards.stage.cameras import NEAR, CameraPose

FloatArray = npt.NDArray[np.float64]
# Per-pixel work follows the frame's size. The pixel counts the passes name, the MSAA
# samples asked (`antialias`) and the moving camera's background (full size, or
# LOW_RES_SCALE when fast) are what a frame of REFERENCE_PIXELS gets, and a smaller one.
# A larger frame's pixels each cover less of the screen, so it takes fewer samples a
# pixel: as many per share of the screen as a 720p frame, and no fewer (sample_scale).
# 1080p: 2x MSAA for 4x, blur steps and thresholds 1.5 times the pixels, a moving
# camera's background drawn at 1280x720 (fast: 896x504, as 720p's) and filtered up.
REFERENCE_PIXELS = 1280 * 720
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


def largest_frame(ctx: moderngl.Context) -> int:
    """The longest side, in pixels, this GL can draw a frame at."""
    viewport = ctx.info["GL_MAX_VIEWPORT_DIMS"]
    return int(min(ctx.info["GL_MAX_RENDERBUFFER_SIZE"], *viewport))


class FrameSizeError(ValueError):
    """A frame larger than the GL can draw: bad input (the size asked), one line."""


def depth_texture(ctx: moderngl.Context, size: tuple[int, int]) -> moderngl.Texture:
    """A depth texture the shaders read depths from (not comparisons), texel by texel."""
    depth = ctx.depth_texture(size)
    depth.compare_func = ""
    depth.filter = (moderngl.NEAREST, moderngl.NEAREST)
    return depth


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


def region_of(points: FloatArray, pose: CameraPose, size: tuple[int, int]) -> Region | None:
    """The pixels round the projections of `points` (K, 3), widened by the margin to
    whole 2x2 blocks; the whole frame if a point is not in front of the eye."""
    width, height = size
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


class Yuv420pPass(GLOwner):
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
        super().__init__()
        width, height = size
        if width % 2 or height % 2:
            raise ValueError(f"yuv420p needs an even size, not {width}x{height}")
        self.ctx = ctx
        self.size = size
        self.program = self.keep(compile_program(ctx, "fullscreen.vert", "yuv420p.frag"))
        uniform(self.program, "picture").value = 0
        uniform(self.program, "texel").value = (1.0 / width, 1.0 / height)
        self.vao = self.keep(ctx.vertex_array(self.program, []))  # corners from gl_VertexID
        half = (width // 2, height // 2)
        targets = [self.keep(ctx.renderbuffer(half, components)) for components in (2, 2, 1, 1)]
        self.framebuffer = self.keep(ctx.framebuffer(color_attachments=targets))
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


class FrameOutput(GLOwner):
    """`work`, where each frame is finished (a copy of the background or of `settled`,
    what moves drawn over it), and the pictures read back."""

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int]) -> None:
        """FrameSizeError if this GL cannot draw a frame of `size`."""
        super().__init__()
        largest = largest_frame(ctx)
        if max(size) > largest:
            raise FrameSizeError(f"{size[0]}x{size[1]}: this GL draws at most {largest} px a side")
        self.ctx = ctx
        self.size = size
        # Its colour a texture: the yuv420p pass reads it.
        self.colour = self.keep(ctx.texture(size, 4))
        self.work = self.keep(
            ctx.framebuffer(
                color_attachments=[self.colour],
                depth_attachment=self.keep(ctx.depth_renderbuffer(size)),
            )
        )
        self._yuv: Yuv420pPass | None = None  # made for the first yuv420p frame
        # What the yuv420p pass last converted: `settled` (its key) outside a region
        # (`drawn`, None: nothing drawn over it), or something else (key None).
        self.holds: tuple[object, ...] | None = None
        self.drawn: Region | None = None

    def start_from(self, picture: moderngl.Framebuffer, depth: moderngl.Texture) -> None:
        """`work` becomes a copy of `picture`, whose depth (balls drawn there included)
        the shadows drawn next leave alone."""
        self.ctx.copy_framebuffer(self.work, picture)
        depth.use(4)
        self.work.use()
        self.ctx.enable(moderngl.DEPTH_TEST)

    def read(
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

    def read_work(self, pixel_format: str) -> bytes:
        """`work` read back whole (a yuv420p conversion then holds no `settled`)."""
        if pixel_format == "yuv420p":
            self.holds = None
        return self.read(self.work, self.colour, pixel_format)

    def read_over_settled(self, key: tuple[object, ...] | None, drawn: Region | None) -> bytes:
        """`work` as yuv420p, where it is the `settled` picture of `key` but in `drawn`:
        if the pass last converted that one (and what was drawn over it within a region),
        only there and here are converted again."""
        region = union(drawn, self.drawn) if self.holds == key else None
        picture = self.read(self.work, self.colour, "yuv420p", region)
        self.holds, self.drawn = key, drawn
        return picture

    def _yuv_pass(self) -> Yuv420pPass:
        """The yuv420p pass, made at the first asking. (Its first conversion is whole:
        `holds` names nothing it converted yet.)"""
        if self._yuv is None:
            self._yuv = self.keep(Yuv420pPass(self.ctx, self.size))
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
