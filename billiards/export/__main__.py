"""python -m billiards.export: a shot as an animated glTF file and/or a replay page.

    python -m billiards.export                              # the seed break -> break.glb
    python -m billiards.export pool_break -o shot.gltf      # one JSON file, data embedded
    python -m billiards.export --html shot.html             # the offline replay page
    python -m billiards.export --trajectory break.npz -o saved.glb   # a saved trajectory

Exit codes: 0 done, 1 a file could not be written, 2 a bad scene, trajectory, option
or output path (one line on stderr, nothing written), 130/143/129 for a signal.
"""

from __future__ import annotations

import argparse
import importlib.util
import math
from pathlib import Path
from typing import TYPE_CHECKING

from billiards.export.tracks import DEFAULT_ANGLE_BOUND
from billiards.scene.reader import shipped_scene_names
from billiards.shell import cli

if TYPE_CHECKING:
    from billiards.export.tracks import ExportedMotion
    from billiards.record.trajectory import Trajectory
    from billiards.scene.reader import Scene
    from billiards.scene.render_table import RenderSettings

TEXTURE_WIDTHS = (128, 256, 512, 1024)


def build_parser() -> argparse.ArgumentParser:
    """The command's options (the site's reference is generated from them)."""
    parser = cli.command_parser(
        "python -m billiards.export",
        "Export a simulated shot as an animated glTF 2.0 file (.glb or .gltf) "
        "for Blender and the web, and/or as a self-contained replay page (--html).",
        shipped_scene_names,
    )
    cli.add_force_argument(parser)
    parser.add_argument(
        "-o",
        "--output",
        help="glTF file to write: .glb (binary) or .gltf (one JSON file); default, unless "
        "only --html is given: named after the scene, SCENE.glb (break.glb for the seed "
        "break, or after a --trajectory file)",
    )
    parser.add_argument("--html", metavar="PAGE", help="also (or only) write a replay page (.html)")
    parser.add_argument(
        "--trajectory",
        help="export a saved trajectory (.npz, from python -m billiards.simulate --trajectory) "
        "instead of simulating",
    )
    parser.add_argument(
        "--angle-error",
        type=float,
        default=DEFAULT_ANGLE_BOUND,
        metavar="DEG",
        help=f"largest rotation error of the sampled rotation keys, degrees; "
        f"default {DEFAULT_ANGLE_BOUND:g}",
    )
    parser.add_argument(
        "--texture-width",
        type=int,
        choices=TEXTURE_WIDTHS,
        default=512,
        help="pixels across each ball's texture; default 512",
    )
    parser.add_argument(
        "--linear",
        type=float,
        metavar="MM",
        help="LINEAR translation keys within MM millimetres of the path instead of exact "
        "CUBICSPLINE ones: for importers that ignore cubic tangents (Blender's)",
    )
    cli.add_quiet_argument(parser, "no summary on stderr")
    return parser


def main(argv: list[str] | None = None) -> int:
    return cli.run_guarded(lambda: _run(build_parser().parse_args(argv)))


def _problem(args: argparse.Namespace) -> str | None:
    """What is wrong with the options, before any work."""
    if not (math.isfinite(args.angle_error) and 0 < args.angle_error <= 90):
        return f"--angle-error {args.angle_error:g}: expected degrees in (0, 90]"
    if args.linear is not None and not (math.isfinite(args.linear) and args.linear > 0):
        return f"--linear {args.linear:g}: expected millimetres above 0"
    if args.output is None and args.html is None:
        # Named after the scene, as every command's output (a saved trajectory: its file).
        named_after = args.scene
        if named_after is None and args.trajectory is not None:
            named_after = Path(args.trajectory).stem
        args.output = cli.default_output(named_after, ".glb")
    outputs = (
        (args.output, (".glb", ".gltf"), "a .glb or .gltf"),
        (args.html, (".html", ".htm"), "an .html"),
    )
    for path, endings, what in outputs:
        if path is None:
            continue
        if Path(path).suffix.lower() not in endings:
            return f"{path}: expected {what} file name"
        problem = cli.output_problem(path, force=args.force)
        if problem:
            return problem
    if args.trajectory is not None and not Path(args.trajectory).is_file():
        return f"{args.trajectory}: no such trajectory file"
    return None


def _run(args: argparse.Namespace) -> int:
    if importlib.util.find_spec("pygltflib") is None:
        return cli.fail(
            "the export needs pygltflib: pip install 'billiards[export]'", cli.EXIT_FAILED
        )
    from billiards.export.shot import export_gltf
    from billiards.scene.reader import SceneError, load_scene

    problem = _problem(args)
    if problem:
        return cli.fail(problem)
    with cli.failing_on(SceneError):
        scene = load_scene(args.scene)
    source, settings, title = _shot(args, scene)
    with cli.failing_on(OSError, ValueError, status=cli.EXIT_FAILED, one_line=True):
        report = export_gltf(
            source,
            output=args.output,
            html=args.html,
            settings=settings,
            angle_bound=args.angle_error,
            texture_width=args.texture_width,
            title=title,
            linear=None if args.linear is None else args.linear / 1000.0,
        )
    if not args.quiet:
        keys = sum(report.translation_keys.values()) / max(len(report.translation_keys), 1)
        for path in report.paths:
            size = report.sizes[path.suffix.lower()]
            cli.say(f"wrote {path} ({size / 1e3:,.0f} kB)")
        cli.say(
            f"{keys:.1f} translation keys a ball, largest deviation from the simulated "
            f"path {report.deviation:.1e} m, rotations within {report.angle_bound:g} deg "
            f"({report.seconds:.2f} s)"
        )
    return 0


def _shot(
    args: argparse.Namespace, scene: Scene
) -> tuple[ExportedMotion | Trajectory, RenderSettings, str]:
    """What to export, the [render] settings to draw it with and its title: the saved
    trajectory (as the scene it was saved from, when no scene is named) or the scene's run."""
    from billiards.record.trajectory import Trajectory
    from billiards.scene.reader import SceneError

    if args.trajectory is None:
        from billiards.simulation import simulate_scene

        result = simulate_scene(scene)
        if not result.complete:
            cli.say(
                f"warning: {scene.source}: the run was stopped by {result.stopped_by} at "
                f"{result.rest_time:g} s, before every ball came to rest; the shot ends there"
            )
        return result, scene.render, Path(scene.source).stem if scene.source else "break"
    with cli.reading_trajectory(args.trajectory, SceneError):
        saved = Trajectory.load(args.trajectory)
    settings = scene.render
    if args.scene is None and saved.render_settings is not None:
        settings = saved.render_settings
    return saved, settings, Path(args.trajectory).name


if __name__ == "__main__":
    raise SystemExit(main())
