"""`python -m billiards.plot [SCENE] [-o PICTURE] [--width PX] [--quiet]`

Simulates a scene and draws the break from above (billiards.top_view) as a PNG.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from billiards.cli import (
    EXIT_FAILED,
    EXIT_USAGE,
    OneLineParser,
    add_force_argument,
    add_scene_argument,
    default_output,
    first_line,
    output_problem,
    run_guarded,
)
from billiards.physics import notice
from billiards.scene import Scene, SceneError, load_scene, shipped_scene_names
from billiards.simulation import NonFiniteRun, simulate_scene
from billiards.top_view import (
    DEFAULT_WIDTH,
    MAX_SIDE,
    PICTURE_FORMATS,
    Layout,
    draw_top_view,
    sample_path_bends,
    save_picture,
)
from billiards.trajectory import Trajectory


def trajectory_for_plot(scene: Scene) -> Trajectory:
    """Simulate the scene and record it for drawing, from t = 0 to rest."""
    result = simulate_scene(scene)
    return sample_path_bends(result, (scene.table.length, scene.table.width))


def main(argv: Sequence[str] | None = None) -> int:
    return run_guarded(lambda: _run(argv))


def build_parser() -> OneLineParser:
    """The command's options (the site's reference is generated from them)."""
    parser = OneLineParser(
        prog="python -m billiards.plot",
        description="Draw the break from above: paths, contacts, start and rest positions.",
    )
    add_scene_argument(parser, shipped_scene_names)
    parser.add_argument(
        "-o",
        "--output",
        help="picture to write, .png, .jpg or .webp (default: named after the scene, "
        "SCENE.png: masse_shot.png, break.png for the seed break)",
    )
    parser.add_argument(
        "--width",
        type=int,
        default=DEFAULT_WIDTH,
        help=f"image width in px, 64 to {MAX_SIDE} (the height follows the table's; "
        "default: %(default)s)",
    )
    add_force_argument(parser)
    parser.add_argument("--quiet", action="store_true", help="print nothing on success")
    return parser


def _run(argv: Sequence[str] | None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    notice.announce = not args.quiet
    if args.width < 64:
        parser.error(f"--width {args.width}: expected at least 64 px")
    output = Path(args.output or default_output(args.scene, ".png"))
    try:
        scene = load_scene(args.scene)
        if output.suffix.lower() not in PICTURE_FORMATS:
            raise SceneError(f"{output}: name a .png, .jpg or .webp picture")
        problem = output_problem(output, force=args.force)
        if problem:  # before any simulating or drawing
            raise SceneError(problem)
    except SceneError as error:
        print(f"error: {error}", file=sys.stderr)
        return EXIT_USAGE
    layout = Layout.fit((scene.table.length, scene.table.width), args.width)
    if max(layout.width, layout.height) > MAX_SIDE:  # before any simulating or drawing
        print(
            f"error: --width {args.width}: expected a picture at most {MAX_SIDE} px a side "
            f"(this table's would be {layout.width} x {layout.height} px)",
            file=sys.stderr,
        )
        return EXIT_USAGE
    try:
        with np.errstate(all="ignore"):  # a number gone wrong is said once, below
            trajectory = trajectory_for_plot(scene)
    except NonFiniteRun as error:
        print(f"error: {error}", file=sys.stderr)
        return EXIT_FAILED
    image = draw_top_view(trajectory, args.width, Path(scene.source).name)
    try:
        save_picture(image, output)
    except OSError as error:
        print(f"error: {first_line(error)}", file=sys.stderr)
        return EXIT_FAILED
    if not args.quiet:
        print(f"wrote {output} ({image.width} x {image.height} px)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
