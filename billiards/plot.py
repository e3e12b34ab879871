"""`python -m billiards.plot [SCENE] -o break.png [--width PX] [--quiet]`

Simulates a scene and draws the break from above (billiards.top_view) as a PNG.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path

from billiards.cli import OneLineParser
from billiards.render.settings import render_settings
from billiards.scene import Scene, SceneError, load_scene
from billiards.simulation import simulate_scene
from billiards.top_view import DEFAULT_WIDTH, draw_top_view, sample_path_bends, save_png
from billiards.trajectory import Trajectory


def trajectory_for_plot(scene: Scene) -> Trajectory:
    """Simulate the scene and record it for drawing, from t = 0 to rest."""
    result = simulate_scene(scene)
    return sample_path_bends(result, (scene.table.length, scene.table.width))


def main(argv: Sequence[str] | None = None) -> int:
    parser = OneLineParser(
        prog="python -m billiards.plot",
        description="Draw the break from above: paths, contacts, start and rest positions.",
    )
    parser.add_argument("scene", nargs="?", help="scene TOML file (default: the seed break)")
    parser.add_argument(
        "-o", "--output", default="break.png", help="PNG to write (default: %(default)s)"
    )
    parser.add_argument(
        "--width", type=int, default=DEFAULT_WIDTH, help="image width in px (default: %(default)s)"
    )
    parser.add_argument("--quiet", action="store_true", help="print nothing on success")
    args = parser.parse_args(argv)
    if args.width < 64:
        parser.error(f"--width {args.width}: expected at least 64 px")
    output = Path(args.output)
    try:
        scene = load_scene(args.scene)
        render_settings(scene)  # unused here, but a bad [render] is the same error everywhere
        if not output.parent.is_dir():
            raise SceneError(f"{output}: the folder {output.parent} does not exist")
    except SceneError as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    trajectory = trajectory_for_plot(scene)
    image = draw_top_view(trajectory, args.width, Path(scene.source).name)
    save_png(image, output)
    if not args.quiet:
        print(f"wrote {output} ({image.width} x {image.height} px)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
