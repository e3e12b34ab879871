"""The renderer's shader programs, compiled from billiards.shaders (one scene program per
kind of surface), lit by the room's Lighting and given each frame's camera; and what
every pass shares: the GL objects it keeps for release, uniforms by name, the square."""

from __future__ import annotations

import importlib.resources
import math
from collections.abc import Iterable
from typing import Any, TypeVar, cast

import moderngl
import numpy as np

from billiards.stage.cameras import CameraPose
from billiards.stage.room import Lighting

Resource = TypeVar("Resource")
# Two triangles over [-1, 1]^2: each ball, decal and full-screen pass draws this square.
SQUARE = np.array([(-1, -1), (1, -1), (1, 1), (-1, -1), (1, 1), (-1, 1)], dtype=np.float32)
SHADOW_LIFT = 0.0003  # m: a shadow decal floats this far above the cloth


def uniform(program: moderngl.Program, name: str) -> moderngl.Uniform:
    """A program's uniform by name (moderngl's lookup also returns attributes)."""
    return cast(moderngl.Uniform, program[name])


def shader_source(name: str) -> str:
    """A shader's text from billiards.shaders (its `#include` lines left to moderngl)."""
    return (importlib.resources.files("billiards.shaders") / name).read_text(encoding="utf-8")


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


def compile_program(
    ctx: moderngl.Context, vertex: str, fragment: str, define: str = ""
) -> moderngl.Program:
    """A program of two shaders, the fragment one compiled with `define` (such as
    "PATTERN 3.0") #defined."""
    fragment_source = shader_source(fragment)
    if define:
        version, rest = fragment_source.split("\n", 1)
        fragment_source = f"{version}\n#define {define}\n{rest}"
    return ctx.program(vertex_shader=shader_source(vertex), fragment_shader=fragment_source)


class GLOwner:
    """Keeps the GL objects it makes, and frees them, last made first, on release (the
    context stays)."""

    def __init__(self) -> None:
        self._resources: list[Any] = []

    def keep(self, resource: Resource) -> Resource:
        self._resources.append(resource)
        return resource

    def release(self) -> None:
        for resource in reversed(self._resources):
            resource.release()
        self._resources.clear()


class Programs(GLOwner):
    """Every program the passes draw with, compiled once for a renderer."""

    def __init__(self, ctx: moderngl.Context, kinds: Iterable[float], lighting: Lighting) -> None:
        """`kinds`: the static meshes' kinds of surface (geometry's patterns)."""
        super().__init__()
        self.ctx = ctx
        self.lighting = lighting
        for file in importlib.resources.files("billiards.shaders").iterdir():
            if file.name.endswith(".glsl"):  # for moderngl's `#include "x.glsl"`
                ctx.includes[file.name] = file.read_text(encoding="utf-8")
        # One scene program per kind of surface, each compiled for its kind alone: a CPU
        # rasterizer would otherwise work out every pattern at every pixel and keep one.
        self.scene = {
            kind: self.compile("scene.vert", "scene.frag", f"PATTERN {kind:.1f}") for kind in kinds
        }
        self.ball = self.compile("ball.vert", "ball.frag")
        self.blur = self.compile("ball_blur.vert", "ball_blur.frag")
        self.shadow = self.compile("shadow.vert", "shadow.frag")
        self.decal = self.compile("shadow_decal.vert", "shadow.frag", "ON_CLOTH")
        self.upscale = self.compile("upscale.vert", "upscale.frag")
        self.cue = self.compile("cue.vert", "cue.frag")
        self.edge = self.compile("edge_lines.vert", "edge_lines.frag")
        # Those given the camera each frame.
        self.viewing: tuple[moderngl.Program, ...] = (
            *self.scene.values(),
            *(self.ball, self.blur, self.shadow, self.decal, self.cue, self.edge),
        )
        for program in self.viewing:
            self._light(program)
        self.pixel_angle = 0.0  # rad a pixel spans at the frame's centre, for the camera

    def compile(self, vertex: str, fragment: str, define: str = "") -> moderngl.Program:
        return self.keep(compile_program(self.ctx, vertex, fragment, define))

    def cue_shadow(self) -> moderngl.Program:
        """The cue's shadow's program (cue_shadow.frag), its lamp and lift set, given the
        camera with the others from now on."""
        shadow = self.compile("cue_shadow.vert", "cue_shadow.frag")
        uniform(shadow, "lamp_radius").value = self.lighting.light_radius
        spots = self.lighting.positions[:-1]
        uniform(shadow, "lamp_height").value = sum(z for _, _, z in spots) / len(spots)
        uniform(shadow, "lift").value = SHADOW_LIFT
        self.viewing = (*self.viewing, shadow)
        return shadow

    def _light(self, program: moderngl.Program) -> None:
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

    def set_camera(self, pose: CameraPose, size: tuple[int, int]) -> None:
        """Every viewing program seen from `pose` in a frame of `size`."""
        view_projection = pose.view_projection(size[0] / size[1])
        matrix = view_projection.tobytes()
        inverse = np.linalg.inv(view_projection.astype(np.float64)).astype(np.float32)
        uniform(self.shadow, "inverse_view_projection").write(inverse.tobytes())
        for program in self.viewing:
            uniform(program, "view_projection").write(matrix)
            if "camera_position" in program:
                uniform(program, "camera_position").value = pose.eye
        right, up, _ = pose.basis()
        for program in (self.ball, self.blur):
            uniform(program, "camera_right").value = tuple(float(v) for v in right)
            uniform(program, "camera_up").value = tuple(float(v) for v in up)
        self.pixel_angle = 2 * math.tan(math.radians(pose.fov) / 2) / size[1]
        for program in (self.ball, self.blur, self.cue):
            uniform(program, "pixel_angle").value = self.pixel_angle
