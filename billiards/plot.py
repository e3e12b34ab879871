"""`python -m billiards.plot [SCENE] [-o PICTURE] [--width PX] [--quiet]`

Simulates a scene and draws the shot from above (billiards.pictures.top_view) as a PNG.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from billiards.pictures.top_view import (
    DEFAULT_WIDTH,
    MAX_SIDE,
    PICTURE_FORMATS,
    Layout,
    draw_top_view,
    sample_path_bends,
    save_picture,
)
from billiards.record.trajectory import Trajectory
from billiards.scene.reader import Scene, SceneError, load_scene, shipped_scene_names
from billiards.shell import cli
from billiards.simulation import NonFiniteRun, simulate_scene


def trajectory_for_plot(scene: Scene) -> Trajectory:
    """Simulate the scene and record it for drawing, from t = 0 to rest."""
    result = simulate_scene(scene)
    return sample_path_bends(result, (scene.table.length, scene.table.width))


def main(argv: Sequence[str] | None = None) -> int:
    return cli.run_guarded(lambda: _run(argv))


def build_parser() -> cli.OneLineParser:
    """The command's options (the site's reference is generated from them)."""
    parser = cli.command_parser(
        "python -m billiards.plot",
        "Draw a shot from above: paths, contacts, start and rest positions.",
        shipped_scene_names,
    )
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
    cli.add_force_argument(parser)
    cli.add_quiet_argument(parser, "print nothing on success")
    return parser


def _run(argv: Sequence[str] | None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.width < 64:
        parser.error(f"--width {args.width}: expected at least 64 px")
    output = Path(args.output or cli.default_output(args.scene, ".png"))
    with cli.failing_on(SceneError):
        scene = load_scene(args.scene)
    # Before any simulating or drawing: the picture's name, its place and its size.
    if output.suffix.lower() not in PICTURE_FORMATS:
        return cli.fail(f"{output}: name a .png, .jpg or .webp picture")
    problem = cli.output_problem(output, force=args.force)
    if problem:
        return cli.fail(problem)
    layout = Layout.fit((scene.table.length, scene.table.width), args.width)
    if max(layout.width, layout.height) > MAX_SIDE:
        return cli.fail(
            f"--width {args.width}: expected a picture at most {MAX_SIDE} px a side "
            f"(this table's would be {layout.width} x {layout.height} px)"
        )
    # A number gone wrong is said once, as the run's one line.
    with cli.failing_on(NonFiniteRun, status=cli.EXIT_FAILED), np.errstate(all="ignore"):
        trajectory = trajectory_for_plot(scene)
    image = draw_top_view(trajectory, args.width, Path(scene.source).name)
    with cli.failing_on(OSError, status=cli.EXIT_FAILED, one_line=True):
        save_picture(image, output)
    if not args.quiet:
        cli.say(f"wrote {output} ({image.width} x {image.height} px)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
