"""Three of docs/film's reference pictures, drawn with the film's own cameras and clock.

    python scripts/film_stills.py   # docs/film/drop.jpg, moving_edges.jpg, cue_shadow.jpg

drop.jpg: pocket_shot's 1 falling into its pocket, the film's frames (640x360, its
pocket view) from the one before the pocket event on, each cropped round the hole.
moving_edges.jpg: a moving-camera frame of the default film (1280x720, the camera
easing to the wide view), a cushion and the far rail cropped and enlarged 3x, drawn
with `--antialias 0` (edges not smoothed) above and the default (the meshes' edges
drawn over the drawing as lines) below.
cue_shadow.jpg: pool_break's cue 0.02 s before it strikes, seen from the side (640x360),
with its shadow (above) and without (below).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from billiards.record.trajectory import Trajectory
from billiards.record.window import cue_strike_of, film_trajectory
from billiards.render.film import camera_poses, camera_timeline
from billiards.render.film_clock import FilmClock
from billiards.render.gl.context import create_context
from billiards.render.gl.renderer import Renderer
from billiards.scene.reader import load_scene
from billiards.scene.render_table import RenderSettings
from billiards.simulation import simulate_scene
from billiards.stage.cameras import CameraPose

# Pillow's scalable default font: its bitmap one (no size) draws no spaces.
LABEL_FONT = ImageFont.load_default(size=13)
Poses = list[tuple[CameraPose, bool]]


def film_of(scene: str | None, settings: RenderSettings) -> tuple[Trajectory, FilmClock, Poses]:
    loaded = load_scene(scene)
    trajectory = film_trajectory(simulate_scene(loaded), settings, strike=cue_strike_of(loaded))
    clock = FilmClock.of(trajectory, settings.fps, settings.slow_motion)
    return trajectory, clock, list(camera_poses(camera_timeline(trajectory, settings), clock))


def drop_strip(out: Path, frames: int = 5) -> None:
    settings = RenderSettings(width=640, height=360)
    trajectory, clock, poses = film_of("pocket_shot", settings)
    drop = next(event for event in trajectory.events if event.kind == "pocket")
    first = int(np.searchsorted(clock.sim_times, drop.time)) - 1
    exposures = clock.exposures(settings.shutter)
    ctx = create_context()
    renderer = Renderer(ctx, trajectory, (settings.width, settings.height))
    hole = trajectory.pockets.holes[trajectory.pockets.names.index(drop.pocket)]  # type: ignore[union-attr]
    tiles = []
    for frame in range(first, first + frames):
        time, (pose, _) = float(clock.sim_times[frame]), poses[frame]
        picture = renderer.frame(time, pose, float(exposures[frame]))
        x, y = pose.project(np.array([[hole[0], hole[1], 0.0]]), settings.width, settings.height)[0]
        x0 = int(np.clip(x - 64, 0, settings.width - 128))
        y0 = int(np.clip(y - 80, 0, settings.height - 128))
        tile = Image.fromarray(picture[y0 : y0 + 128, x0 : x0 + 128]).resize((256, 256))
        ImageDraw.Draw(tile).text(
            (6, 4), f"{time - drop.time:+.3f} s", fill=(255, 255, 255), font=LABEL_FONT
        )
        tiles.append(tile)
    renderer.release()
    ctx.release()
    strip = Image.new("RGB", (256 * len(tiles) + 4 * (len(tiles) - 1), 256), "white")
    for index, tile in enumerate(tiles):
        strip.paste(tile, (260 * index, 0))
    strip.save(out, quality=90)


def moving_edges(out: Path, frame: int = 346) -> None:
    settings = RenderSettings(width=1280, height=720)
    trajectory, clock, poses = film_of(None, settings)
    exposures = clock.exposures(settings.shutter)
    rows = []
    for antialias in (0, settings.antialias):
        ctx = create_context()
        renderer = Renderer(ctx, trajectory, (settings.width, settings.height), antialias)
        for index in range(frame - 1, frame + 1):  # the frame before sets the motion
            pose, moving = poses[index]
            assert moving, "the frame is not one of a moving camera's"
            data = renderer.draw(
                float(clock.sim_times[index]), pose, moving, float(exposures[index])
            )
        picture = np.frombuffer(data, np.uint8).reshape(settings.height, settings.width, 4)[..., :3]
        renderer.release()
        ctx.release()
        crops = [picture[500:620, 500:620], picture[50:130, 600:760]]
        row = Image.new("RGB", (360 + 4 + 480, 360), "white")
        row.paste(Image.fromarray(crops[0]).resize((360, 360), Image.Resampling.NEAREST), (0, 0))
        row.paste(Image.fromarray(crops[1]).resize((480, 240), Image.Resampling.NEAREST), (364, 0))
        label = "edges as drawn (--antialias 0)" if antialias == 0 else "edges smoothed (default)"
        ImageDraw.Draw(row).text((370, 250), label, fill=(0, 0, 0), font=LABEL_FONT)
        rows.append(row)
    sheet = Image.new("RGB", (rows[0].width, 2 * 360 + 4), "white")
    for index, row in enumerate(rows):
        sheet.paste(row, (0, 364 * index))
    sheet.save(out, quality=92)


def cue_shadow(out: Path, time: float = -0.02) -> None:
    settings = RenderSettings(width=640, height=360)
    trajectory, _, _ = film_of("pool_break", settings)
    assert trajectory.strike is not None
    x, y, _ = trajectory.positions[0, trajectory.ball_ids.index(trajectory.strike.ball)]
    pose = CameraPose((x - 0.45, y - 0.75, 0.5), (x - 0.3, y, 0.0), 40.0)
    ctx = create_context()
    renderer = Renderer(ctx, trajectory, (settings.width, settings.height))
    cue = renderer.cue_pass
    assert cue is not None
    pictures = [renderer.frame(time, pose)]
    cue.shadow_rect = lambda placement: None  # type: ignore[method-assign]
    pictures.append(renderer.frame(time, pose))
    renderer.release()
    ctx.release()
    sheet = Image.new("RGB", (settings.width, 2 * settings.height + 4), "white")
    for index, (picture, label) in enumerate(zip(pictures, ("shadow", "no shadow"), strict=True)):
        tile = Image.fromarray(picture)
        ImageDraw.Draw(tile).text((6, 4), label, fill=(255, 255, 255), font=LABEL_FONT)
        sheet.paste(tile, (0, (settings.height + 4) * index))
    sheet.save(out, quality=92)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--out", type=Path, default=Path("docs/film"))
    args = parser.parse_args()
    drop_strip(args.out / "drop.jpg")
    moving_edges(args.out / "moving_edges.jpg")
    cue_shadow(args.out / "cue_shadow.jpg")
    print(f"wrote drop.jpg, moving_edges.jpg and cue_shadow.jpg in {args.out}")


if __name__ == "__main__":
    main()
