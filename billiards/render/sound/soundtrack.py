"""The film's sound track: billiards.render.sound.voices's clicks and thumps on the film's clock.

Sample k plays at film time clock.start + k / SAMPLE_RATE, so sample 0 plays with
frame 0 (what billiards.render.video expects) and the track is exactly as long as the film.
Numpy only, no GL: `--sound-only` needs no OpenGL context.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from billiards.record.trajectory import CueStrike, Event, Trajectory
from billiards.render.film_clock import FilmClock
from billiards.render.sound.ambience import sound_bed
from billiards.render.sound.voices import matched_stretch, synthesize
from billiards.scene.render_table import RenderSettings


def film_sound(
    events: Sequence[Event],
    clock: FilmClock,
    settings: RenderSettings,
    strike: CueStrike | None = None,
    motion: Trajectory | None = None,
) -> npt.NDArray[np.float32]:
    """The mono track of the film (float32 at SAMPLE_RATE), one click per contact, and
    the cue's `strike` at t = 0 when the film draws the cue ([render] cue). (The strike
    comes after the contacts in the list: their variations stay as they were.) With
    the `motion`, the room's tone and its balls' rolling under them
    (billiards.render.sound.ambience).

    In slow motion each event sits at its slowed film time; with
    slow_motion_sound = "match" its sound is also slowed by the local slow-down
    (longer and lower), with "natural" it keeps its real-speed sound.
    """
    if strike is not None and settings.cue:
        events = (*events, Event(0.0, "strike", (strike.ball,), strike.speed))
    stretch: float | npt.NDArray[np.float64] = 1.0
    if clock.slow_motion is not None and settings.slow_motion_sound == "match":
        # Slowed by the slow motion alone: a contact in quickened quiet play keeps its sound.
        slowed = clock.slow_motion.film_time
        stretch = matched_stretch(slowed, np.array([e.time for e in events]))
    track = synthesize(
        events,
        clock.duration,
        start=clock.start,
        seed=settings.sound_seed,
        time_map=clock.film_time if clock.windows else None,
        stretch=stretch,
    )
    if motion is None:
        return track
    bed = sound_bed(motion, clock, settings.sound_seed)
    return np.clip(track + bed, -1.0, 1.0).astype(np.float32)
