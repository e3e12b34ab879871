"""The cue's GL side: its mesh uploaded once, drawn over a finished picture where the
stroke (billiards.stage.cue) places it at each frame, over its soft shadow on the
cloth (cue_shadow.frag)."""

from __future__ import annotations

import moderngl
import numpy as np
import numpy.typing as npt

from billiards.render.gl.programs import SQUARE, GLOwner, Programs, static_layout
from billiards.stage.cue import CUE_LENGTH, SECTIONS, CuePlacement, CueStroke, cue_mesh

# m the shadow reaches past the stick's outline seen from above, at most (its penumbra
# under a butt raised this high, under the lamp: see cue_shadow.frag)
SHADOW_MARGIN = 0.06


class CuePass(GLOwner):
    """Draws the stick of one stroke (cue.vert / cue.frag, whose inputs are the static
    meshes'), over its shadow (cue_shadow.frag)."""

    def __init__(
        self,
        ctx: moderngl.Context,
        programs: Programs,
        stroke: CueStroke,
        cloth: tuple[float, float],
    ) -> None:
        """`cloth`: the cloth's length and width (its shadow falls on the cloth only)."""
        super().__init__()
        self.ctx = ctx
        self.program = program = programs.cue
        self.stroke = stroke
        self.cloth = cloth
        mesh = cue_mesh()
        buffer = self.keep(ctx.buffer(mesh.interleaved().tobytes()))
        self.vao = self.keep(ctx.vertex_array(program, [(buffer, *static_layout(program))]))
        self.shadow_program = shadow_program = programs.cue_shadow()
        square = self.keep(ctx.buffer(SQUARE.tobytes()))
        self.shadow_vao = self.keep(
            ctx.vertex_array(shadow_program, [(square, "2f", "in_position")])
        )
        radii = (SECTIONS[0][2], SECTIONS[-1][3])
        self.shadow_program["radii"].value = radii  # type: ignore[union-attr]

    def shadow_rect(self, placement: CuePlacement) -> tuple[float, float, float, float] | None:
        """Where on the cloth its shadow may fall (x0, y0, x1, y1, m); None: off it."""
        butt = placement.tip - CUE_LENGTH * placement.forward
        low = np.minimum(placement.tip[:2], butt[:2]) - SHADOW_MARGIN
        high = np.maximum(placement.tip[:2], butt[:2]) + SHADOW_MARGIN
        low, high = np.maximum(low, 0.0), np.minimum(high, self.cloth)
        if np.any(high <= low):
            return None
        return (float(low[0]), float(low[1]), float(high[0]), float(high[1]))

    def shadow_corners(self, placement: CuePlacement) -> npt.NDArray[np.float64]:
        """The corners (K, 3) of the cloth its shadow may darken (none: K = 0)."""
        rect = self.shadow_rect(placement)
        if rect is None:
            return np.zeros((0, 3))
        x0, y0, x1, y1 = rect
        return np.array([(x, y, 0.0) for x in (x0, x1) for y in (y0, y1)])

    def draw(self, placement: CuePlacement) -> None:
        """The stick where `placement` puts it, into the bound framebuffer: depth-tested
        against what is drawn there (the balls write their depths), its near side only,
        its anti-aliased edge blended (premultiplied); its shadow first, multiplied into
        the cloth where the cloth is seen (depth-tested, not written)."""
        ctx = self.ctx
        rect = self.shadow_rect(placement)
        if rect is not None:
            butt = placement.tip - CUE_LENGTH * placement.forward
            shadow = self.shadow_program
            shadow["rect"].value = rect  # type: ignore[union-attr]
            shadow["tip"].value = tuple(float(v) for v in placement.tip)  # type: ignore[union-attr]
            shadow["butt"].value = tuple(float(v) for v in butt)  # type: ignore[union-attr]
            ctx.enable(moderngl.DEPTH_TEST | moderngl.BLEND)
            ctx.blend_func = moderngl.ZERO, moderngl.SRC_COLOR
            framebuffer = ctx.fbo
            framebuffer.depth_mask = False
            self.shadow_vao.render(moderngl.TRIANGLES)
            framebuffer.depth_mask = True
        model = placement.model_matrix()
        self.program["model"].write(np.ascontiguousarray(model).tobytes())  # type: ignore[union-attr]
        ctx.enable(moderngl.DEPTH_TEST | moderngl.BLEND | moderngl.CULL_FACE)
        ctx.blend_func = moderngl.ONE, moderngl.ONE_MINUS_SRC_ALPHA
        # The mesh is wound counter-clockwise seen from outside; the projection's flipped
        # y turns that over, so GL's "back" faces are the stick's near side.
        ctx.cull_face = "back"
        self.vao.render(moderngl.TRIANGLES)
        ctx.disable(moderngl.CULL_FACE | moderngl.BLEND)
