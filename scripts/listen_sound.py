"""Write a scene's sound track to a WAV and print what is in it, to check it by numbers.

    python scripts/listen_sound.py [SCENE] -o break.wav [--seed N] [--slow 0.25]

Prints the loudest moments (one per 1/30 s frame, loudest first) next to the nearest
ball-ball contact, so sync can be read off without listening.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from billiards.render.sound.voices import SAMPLE_RATE, matched_stretch, synthesize, write_wav
from billiards.scene.reader import SceneError, load_scene
from billiards.simulation import simulate_scene

FRAME = 1 / 30  # s


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", nargs="?")
    parser.add_argument("-o", "--output", default="break.wav")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--slow", type=float, default=1.0, help="play everything this fast")
    args = parser.parse_args(argv)
    try:
        scene = load_scene(args.scene)
    except SceneError as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    result = simulate_scene(scene)
    factor = 1.0 / args.slow

    def film_time(times: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        return times * factor

    times = np.array([event.time for event in result.events])
    track = synthesize(
        result.events,
        (result.rest_time + 1.0) * factor,
        seed=args.seed,
        time_map=film_time,
        stretch=matched_stretch(film_time, times) if args.slow != 1.0 else 1.0,
    )
    write_wav(args.output, track, SAMPLE_RATE)
    print(f"wrote {args.output}: {len(track) / SAMPLE_RATE:.2f} s, {len(result.events)} events")
    print(f"peak {np.max(np.abs(track)):.3f}, rms {np.sqrt(np.mean(track**2.0)):.4f}")
    frame = round(FRAME * SAMPLE_RATE)
    frames = len(track) // frame
    peaks = np.abs(track[: frames * frame]).reshape(frames, frame)
    ball_times = film_time(np.array([e.time for e in result.events if e.kind == "ball"]))
    print("  peak   at (s)   nearest ball-ball contact (ms)")
    for index in np.argsort(peaks.max(axis=1))[::-1][:10]:
        at = (index * frame + int(np.argmax(peaks[index]))) / SAMPLE_RATE
        nearest = 1e3 * np.min(np.abs(ball_times - at)) if len(ball_times) else float("nan")
        print(f"  {peaks[index].max():.3f}  {at:8.4f}   {nearest:10.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
