"""A contact sheet of a shipped scene's film: a few frames across its shots, labelled.

    python scripts/contact_sheet.py                      # pool_break -> docs/contact_sheet.jpg
    python scripts/contact_sheet.py --scene break --out sheet.jpg --columns 2

Simulates the scene, records it as the film does and draws the chosen frames with the
film's own cameras, clock and shutter (billiards.render.film), each labelled with its
simulation time and its shot; the moments are picked from the film's own cuts, the
first contact and the pockets, so the sheet follows the scene.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from billiards.record.trajectory import Trajectory, first_contact_time
from billiards.record.window import cue_strike_of, film_trajectory
from billiards.render.director import directed_shots
from billiards.render.film import camera_poses, camera_timeline
from billiards.render.film_clock import FilmClock
from billiards.render.gl.context import create_context
from billiards.render.gl.renderer import Renderer
from billiards.scene.reader import load_scene
from billiards.scene.render_table import CameraShot, RenderSettings
from billiards.simulation import simulate_scene

# Pillow's scalable default font: its bitmap one (no size) drops some spaces.
LABEL_FONT = ImageFont.load_default(size=14)


def moments(trajectory: Trajectory, shots: tuple[CameraShot, ...]) -> list[tuple[float, str]]:
    """(simulation time, what it shows) for each frame of the sheet."""
    first = first_contact_time(trajectory.events)
    start, end = float(trajectory.times[0]), float(trajectory.times[-1])
    picks = [(start + 0.2, "before the shot"), (-0.03, "the cue strikes")]
    if first is not None:
        picks += [(first - 0.05, "the cue ball arrives"), (first + 0.2, "the pack opens")]
    for shot in shots[1:]:
        if shot.start is not None and shot.start + 0.3 < end:
            name = shot.preset or "directed view"
            picks.append((shot.start + 0.3, f"{name} ({shot.transition})"))
            if shot.transition == "ease":
                picks.append((shot.start + 0.5 * shot.ease, f"easing to {name}"))
    drops = [e for e in trajectory.events if e.kind == "pocket"]
    for event in drops[:2]:
        picks.append((event.time + 0.06, f"ball {event.balls[0]} drops ({event.pocket})"))
    picks.append((end - 0.1, "at rest"))
    kept: list[tuple[float, str]] = []
    for time_s, label in sorted(p for p in picks if start <= p[0] <= end):
        if not kept or time_s - kept[-1][0] > 0.15:  # no two frames of one moment
            kept.append((time_s, label))
    return kept


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="pool_break")
    parser.add_argument("--out", default="docs/contact_sheet.jpg")
    parser.add_argument("--size", default="480x270", help="each frame, WxH px")
    parser.add_argument("--columns", type=int, default=3)
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.lower().split("x"))
    scene = load_scene(args.scene)
    settings = scene.render
    settings = RenderSettings(**{**settings.__dict__, "width": width, "height": height})
    trajectory = film_trajectory(simulate_scene(scene), settings, strike=cue_strike_of(scene))
    shots = settings.cameras or directed_shots(trajectory, width / height)
    clock = FilmClock.of(trajectory, settings.fps, settings.slow_motion)
    poses = list(camera_poses(camera_timeline(trajectory, settings), clock))
    exposures = clock.exposures(settings.shutter)
    picks = moments(trajectory, shots)
    ctx = create_context()
    renderer = Renderer(ctx, trajectory, (width, height), settings.antialias)
    tiles = []
    try:
        for time_s, label in picks:
            index = int(np.argmin(np.abs(clock.sim_times - time_s)))
            shown = float(clock.sim_times[index])
            pose, moving = poses[index]
            data = renderer.draw(shown, pose, moving, float(exposures[index]))
            tile = Image.frombytes("RGBA", (width, height), data).convert("RGB")
            ImageDraw.Draw(tile).text(
                (8, 6), f"{shown:.2f} s  {label}", fill=(255, 255, 255), font=LABEL_FONT
            )
            tiles.append(tile)
    finally:
        renderer.release()
        ctx.release()
    rows = -(-len(tiles) // args.columns)
    gap = 4
    sheet = Image.new(
        "RGB",
        (args.columns * (width + gap) - gap, rows * (height + gap) - gap),
        (255, 255, 255),
    )
    for k, tile in enumerate(tiles):
        row, column = divmod(k, args.columns)
        sheet.paste(tile, (column * (width + gap), row * (height + gap)))
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    sheet.save(args.out, quality=88)
    print(f"wrote {args.out} ({len(tiles)} frames of {args.scene}, {width}x{height} each)")


if __name__ == "__main__":
    main()
