"""The exported glTF imported into Blender (the `bpy` package), as an animator would.

    pip install bpy     # Blender as a Python module (Python 3.11 wheels), ~400 MB
    PYTHONPATH=. python scripts/blender_import.py [SCENE] [--linear MM] [--picture P.png]

Exports the shot twice (exact CUBICSPLINE keys, and LINEAR keys within --linear mm),
imports each file with Blender's own glTF importer into an empty scene, and prints
what Blender made of it: the objects, the balls, the cameras, the action, and how far
each ball's location in Blender, at every frame, is from the simulated centre (before
any drop). With --picture it renders a still of the imported scene (Workbench engine,
the film's overhead camera, at --time) to that PNG. Not a test: bpy is not a
dependency of the package (see docs/export.md for what it showed).
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path
from typing import Any

import bpy
import numpy as np

from billiards.export.shot import export_gltf
from billiards.physics.engine.result import SimulationResult
from billiards.scene.reader import load_scene
from billiards.simulation import simulate_scene

FPS = 30


def import_shot(path: Path) -> Any:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.context.scene.render.fps = FPS  # the importer puts a key at t s on frame t * fps
    bpy.ops.import_scene.gltf(filepath=str(path))
    return bpy.context.scene


def worst_gap(scene: Any, result: SimulationResult) -> float:
    """m: the largest distance of a ball's location in Blender from the simulation,
    over every frame until the last ball stops (a pocketed ball: until its drop)."""
    length, width = result.table_size
    drops = {e.balls[0]: e.time for e in result.events if e.kind == "pocket"}
    frames = np.arange(0, int(result.rest_time * FPS) + 1)
    simulated = result.positions_at(frames / FPS)
    worst = 0.0
    for frame in frames:
        scene.frame_set(int(frame))
        for index, ball in enumerate(result.ball_ids):
            if frame / FPS >= drops.get(ball, np.inf):
                continue
            where = bpy.data.objects[f"ball-{ball}"].matrix_world.translation
            x, y = simulated[frame, index]
            worst = max(
                worst, float(np.hypot(where[0] - (x - length / 2), where[1] - (y - width / 2)))
            )
    return worst


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", nargs="?", default="break")
    parser.add_argument("--linear", type=float, default=0.1, metavar="MM")
    parser.add_argument("--picture", type=Path)
    parser.add_argument("--time", type=float, default=1.2, help="s, the picture's moment")
    args = parser.parse_args()
    result = simulate_scene(load_scene(args.scene))
    print(f"Blender {bpy.app.version_string}, {args.scene}, {FPS} frames/s")
    with tempfile.TemporaryDirectory() as work:
        for label, linear in (("CUBICSPLINE", None), (f"LINEAR {args.linear:g} mm", args.linear)):
            path = Path(work) / "shot.glb"
            export_gltf(result, path, linear=None if linear is None else linear / 1000)
            scene = import_shot(path)
            objects = list(scene.objects)
            balls = [o for o in objects if o.name.startswith("ball-")]
            cameras = [o.name for o in objects if o.type == "CAMERA"]
            print(
                f"{label:<16} objects {len(objects)}, balls {len(balls)}, cameras {cameras}, "
                f"actions {len(bpy.data.actions)}; largest gap from the simulation "
                f"{worst_gap(scene, result) * 1000:.3f} mm"
            )
        if args.picture is not None:
            scene.camera = next(
                o for o in objects if "overhead" in o.name or o.name == "camera-top"
            )
            scene.render.engine = "BLENDER_WORKBENCH"
            scene.display.shading.light = "STUDIO"
            scene.display.shading.color_type = "TEXTURE"
            scene.render.resolution_x, scene.render.resolution_y = 960, 540
            scene.frame_set(round(args.time * FPS))
            scene.render.filepath = str(args.picture.resolve())
            bpy.ops.render.render(write_still=True)
            print(f"wrote {args.picture} (t = {args.time:g} s, frame {round(args.time * FPS)})")


if __name__ == "__main__":
    main()
