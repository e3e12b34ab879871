"""The cue's GL side: its mesh uploaded once, drawn over a finished picture where the
stroke (billiards.render.cue) places it at each frame."""

from __future__ import annotations

import moderngl
import numpy as np

from billiards.render.cue import CuePlacement, CueStroke, cue_mesh


class CuePass:
    """Draws the stick of one stroke with `program` (cue.vert / cue.frag, whose inputs
    are the static meshes' `layout`)."""

    def __init__(
        self,
        ctx: moderngl.Context,
        program: moderngl.Program,
        layout: tuple[str, ...],
        stroke: CueStroke,
    ) -> None:
        self.ctx = ctx
        self.program = program
        self.stroke = stroke
        mesh = cue_mesh()
        self.buffer = ctx.buffer(mesh.interleaved().tobytes())
        self.vao = ctx.vertex_array(program, [(self.buffer, *layout)])

    def placement(self, time: float) -> CuePlacement | None:
        return self.stroke.placement(time)

    def draw(self, placement: CuePlacement) -> None:
        """The stick where `placement` puts it, into the bound framebuffer: depth-tested
        against what is drawn there (the balls write their depths), its near side only,
        its anti-aliased edge blended (premultiplied)."""
        ctx = self.ctx
        model = placement.model_matrix()
        self.program["model"].write(np.ascontiguousarray(model).tobytes())  # type: ignore[union-attr]
        ctx.enable(moderngl.DEPTH_TEST | moderngl.BLEND | moderngl.CULL_FACE)
        ctx.blend_func = moderngl.ONE, moderngl.ONE_MINUS_SRC_ALPHA
        # The mesh is wound counter-clockwise seen from outside; the projection's flipped
        # y turns that over, so GL's "back" faces are the stick's near side.
        ctx.cull_face = "back"
        self.vao.render(moderngl.TRIANGLES)
        ctx.disable(moderngl.CULL_FACE | moderngl.BLEND)

    def release(self) -> None:
        self.vao.release()
        self.buffer.release()
