"""What a film shows of a simulation: its recording window, decided once.

Both commands record through here: `render` before drawing, `simulate --trajectory`
to save what `render --trajectory` will draw later; below both, and no GL, so that
`simulate` needs nothing of the render package. Takes any RecordedMotion (a
simulation result), so the renderer still never imports the physics.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from billiards.record.drop import off_table_end
from billiards.record.sampling import record_trajectory
from billiards.record.trajectory import CueStrike, RecordedMotion, Trajectory
from billiards.rules import seed
from billiards.scene.reader import Scene
from billiards.scene.render_table import RenderSettings

# Recorded states per film frame more when the shutter is open (film_trajectory).
SHUTTER_STEPS = 4


def film_trajectory(
    motion: RecordedMotion,
    settings: RenderSettings,
    still_time: float | None = None,
    strike: CueStrike | None = None,
) -> Trajectory:
    """From [render] lead before the shot to tail after the last ball's centre stops
    (motion_end: a ball left spinning in place is not filmed on; or one still at
    `still_time`), sampled densely enough for the film's slow motion, with the cue's
    `strike` (cue_strike_of(scene)) for the film to draw."""
    start = -settings.lead
    end = motion_end(motion) + settings.tail
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
    recorded = record_trajectory(motion, fps=fps, start=start, end=end)
    return recorded if strike is None else dataclasses.replace(recorded, strike=strike)


# s: the grid on which motion_end looks for the last ball's stop (a frame at 1000 fps).
STOP_GRID = 1e-3
STILL = 1e-9  # m: a ball whose centre moves less over a STOP_GRID step is still


def motion_end(motion: RecordedMotion) -> float:
    """s, when the last ball's centre stops moving (to STOP_GRID s): the film's motion
    ends there. The run's rest_time can be later: a ball may go on spinning in place
    (masse_shot's for 4.4 s), which a film need not wait for; a ball that left the
    table (issue 45) moves until it is out of sight (record.drop.off_table_end)."""
    return max(_stops(motion), off_table_end(motion))


def _stops(motion: RecordedMotion) -> float:
    """motion_end on the table (a ball that left it is drawn flying on: off_table_end)."""
    rest = motion.rest_time
    if rest <= 0.0:
        return max(rest, 0.0)
    times = np.append(np.arange(0.0, rest, STOP_GRID), rest)
    positions = motion.positions_at(times)
    moved = np.any(np.abs(np.diff(positions, axis=0)) > STILL, axis=(1, 2))
    if not moved.any():
        return 0.0
    last = int(np.flatnonzero(moved)[-1])
    return float(times[min(last + 1, len(times) - 1)])


# The ball a scene's velocity is given to, which a cue then strikes in the film.
CUE_BALL = "cue"


def cue_strike_of(scene: Scene) -> CueStrike | None:
    """The stroke the film's cue plays: the first ball's `cue = {...}`; else, for a cue
    ball given a velocity, a level cue along it, at its `tip` (else the centre), as
    fast as billiards.scene.stroke's law (TP A-30) needs to give it that speed. None when
    no ball is struck at t = 0."""
    for ball in scene.balls:
        if ball.stroke is not None:
            stroke = ball.stroke
            return CueStrike(
                ball=ball.id,
                direction=stroke.direction,
                elevation=stroke.elevation,
                tip=stroke.tip,
                speed=stroke.speed,
            )
    for ball in scene.balls:
        speed = math.hypot(*ball.velocity)
        if ball.id == CUE_BALL and speed > 0:
            side, height = ball.tip if ball.tip is not None else (0.0, 0.0)
            # v = 2 V / (1 + m / M + (5/2) b^2 / R^2), for the cue's V
            cue_speed = (
                speed * (1.0 + ball.mass / seed.STICK_MASS + 2.5 * (side**2 + height**2)) / 2
            )
            direction = math.degrees(math.atan2(ball.velocity[1], ball.velocity[0]))
            return CueStrike(
                ball=ball.id,
                direction=direction,
                elevation=0.0,
                tip=(side, height),
                speed=cue_speed,
            )
    return None
