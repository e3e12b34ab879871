"""What the moving camera's anti-aliasing costs: CPU ms per moving frame, on against off.

    python scripts/bench_moving_edges.py                    # 1280x720 and 1920x1080
    python scripts/bench_moving_edges.py --sizes 1920x1080 --rounds 8

The default film's frames whose camera moves are drawn (and read back as the film's
yuv420p) by two renderers in one process, the default `antialias` and 0, alternating
frame by frame (which one goes first swaps each round), each after the still frame
before it where there is one (drawn untimed, so each starts from the state the film
leaves). CPU time (`time.process_time`, llvmpipe's threads included) per moving frame,
for each round; the table gives the range over rounds and of the per-round ratio, so a
machine shared with other work still compares like with like.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Callable

from billiards.record.window import cue_strike_of, film_trajectory
from billiards.render.film import camera_poses, camera_timeline
from billiards.render.film_clock import FilmClock
from billiards.render.gl.context import create_context
from billiards.render.gl.renderer import Renderer
from billiards.scene.reader import load_scene
from billiards.scene.render_table import RenderSettings
from billiards.simulation import simulate_scene


def moving_frame_costs(
    size: tuple[int, int],
    makers: dict[str, Callable[..., Renderer]],
    rounds: int,
) -> tuple[int, dict[str, list[float]]]:
    """The number of moving frames, and per renderer its CPU ms per moving frame in each
    round. `makers` build a renderer from (ctx, trajectory, size)."""
    settings = RenderSettings(width=size[0], height=size[1])
    scene = load_scene(None)
    trajectory = film_trajectory(simulate_scene(scene), settings, strike=cue_strike_of(scene))
    clock = FilmClock.of(trajectory, settings.fps, settings.slow_motion)
    cameras = camera_timeline(trajectory, settings)
    exposures = clock.exposures(settings.shutter)
    frames = list(camera_poses(cameras, clock))
    moving = [index for index, (_, turning) in enumerate(frames) if turning]
    ctx = create_context()
    renderers = {name: make(ctx, trajectory, size) for name, make in makers.items()}
    names = list(renderers)
    spent: dict[str, list[float]] = {name: [] for name in names}

    def draw(name: str, index: int) -> None:
        pose, turning = frames[index]
        renderers[name].draw(
            float(clock.sim_times[index]), pose, turning, float(exposures[index]), "yuv420p"
        )

    try:
        for index in moving[:3]:  # warm up: shaders compiled, buffers made
            for name in names:
                draw(name, index)
        for round_ in range(rounds):
            order = names if round_ % 2 == 0 else names[::-1]
            used = dict.fromkeys(names, 0.0)
            for index in moving:
                for name in order:
                    if index - 1 not in moving and index > 0:
                        draw(name, index - 1)  # the still frame before: untimed
                    started = time.process_time()
                    draw(name, index)
                    used[name] += time.process_time() - started
            for name in names:
                spent[name].append(used[name] / len(moving) * 1000)
    finally:
        for renderer in renderers.values():
            renderer.release()
        ctx.release()
    return len(moving), spent


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--sizes", default="1280x720,1920x1080")
    parser.add_argument("--rounds", type=int, default=6)
    args = parser.parse_args()
    antialias = RenderSettings.antialias
    makers: dict[str, Callable[..., Renderer]] = {
        "on": lambda ctx, trajectory, size: Renderer(ctx, trajectory, size, antialias),
        "off": lambda ctx, trajectory, size: Renderer(ctx, trajectory, size, 0),
    }
    print(f"# python scripts/bench_moving_edges.py {' '.join(sys.argv[1:])}".strip())
    print(f"# load average before: {', '.join(f'{v:.1f}' for v in os.getloadavg())}")
    print(
        f"| size | moving frames | antialias {antialias}: CPU ms | antialias 0: CPU ms "
        "| on / off, per round |"
    )
    print("| --- | --- | --- | --- | --- |")
    for text in args.sizes.split(","):
        width, height = (int(v) for v in text.lower().split("x"))
        count, spent = moving_frame_costs((width, height), makers, args.rounds)
        ratios = [on / off for on, off in zip(spent["on"], spent["off"], strict=True)]
        print(
            f"| {width}x{height} | {count} | {min(spent['on']):.1f}-{max(spent['on']):.1f} "
            f"| {min(spent['off']):.1f}-{max(spent['off']):.1f} "
            f"| {min(ratios):.3f}-{max(ratios):.3f} (median {sorted(ratios)[len(ratios) // 2]:.3f}) |",
            flush=True,
        )
    print(f"# load average after: {', '.join(f'{v:.1f}' for v in os.getloadavg())}")


if __name__ == "__main__":
    main()
