"""A shot to take away: an animated glTF 2.0 file (.glb or .gltf) and a replay page.

    from billiards.export import export_gltf
    export_gltf(simulate_scene(load_scene("pool_break")), "shot.glb", html="shot.html")

From a simulation result (exact keys: billiards.export.tracks) or a saved trajectory
(billiards.record.trajectory.Trajectory, sampled keys). No GL here: the table and the ball
textures come from the film's numpy builders (billiards.stage.table, .textures),
the cameras from its presets (billiards.stage.cameras), none of which touch OpenGL.
The writer (billiards.export.shot, .gltf) needs pygltflib, the `export` extra's: it
is imported on first use, so that the command can say so in one line where it is
missing.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from billiards.export.shot import ExportReport, export_gltf

__all__ = ["ExportReport", "export_gltf"]


def __getattr__(name: str) -> Any:
    if name in __all__:
        from billiards.export import shot

        return getattr(shot, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
