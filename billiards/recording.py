"""What a film shows of a simulation: its recording window, decided once.

Both commands record through here: `render` before drawing, `simulate --trajectory`
to save what `render --trajectory` will draw later; below both, and no GL, so that
`simulate` needs nothing of the render package. Takes any RecordedMotion (a
simulation result), so the renderer still never imports the physics.
"""

from __future__ import annotations

import math

from billiards.render_settings import RenderSettings
from billiards.trajectory import RecordedMotion, Trajectory, record_trajectory

# Recorded states per film frame more when the shutter is open (film_trajectory).
SHUTTER_STEPS = 4


def film_trajectory(
    motion: RecordedMotion, settings: RenderSettings, still_time: float | None = None
) -> Trajectory:
    """From [render] lead before the shot to tail after the rest (or one still at
    `still_time`), sampled densely enough for the film's slow motion."""
    start = -settings.lead
    end = motion.rest_time + settings.tail
    # Slowed frames fall between recorded ones: record densely enough that the slowed
    # part still has about one recorded state per film frame.
    # With the shutter open, SHUTTER_STEPS recorded states per frame more, so that the
    # renderer's path over each frame's open shutter is the exact one at those states.
    steps = SHUTTER_STEPS if settings.shutter > 0 else 1
    fps = settings.fps * math.ceil(1.0 / settings.slow_motion - 1e-9) * steps
    if still_time is not None:
        # Put the still's time exactly on a recorded frame, so no interpolation
        # blurs a contact that happens between frames.
        fps = settings.fps * steps
        steps = math.floor((still_time - start) * fps)
        start = still_time - steps / fps
        end = max(end, still_time)
    return record_trajectory(motion, fps=fps, start=start, end=end)
