"""Strokes seeded by the recording's own first contact (issue 44, item 2's first step).

The stroke search (billiards.fit.shots.fit_stroke) looks near the speed and direction the
cue ball's first samples show. A thin first contact sits in a basin narrower than the
search's steps, and a contact within a sample or two of the stroke puts the first samples
after it, so the search looks tens of degrees off; a fit that misses it sends the cue ball
past the ball the recording shows it striking (shot 177). The recording says which ball
the cue ball struck first, when, and where both were (billiards.fit.outcomes). Where the
cue ball meets no cushion before it, it runs straight to it (a level cue's swerve is small
over a first contact's distance), so `aimed_strokes` gives strokes aimed at the point 2R
from the object ball along the line of centres (read two ways), and every straight path
that touches the ball: candidates the search polishes beside its own (the best few, with
a few tips). `outcome_check` tells fit_stroke how much of the recording's outcome each
polished stroke gives (the first contact, the balls set moving, the whole sequence), so
that it prefers the one that gives the most when its loss is close.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from billiards.fit.outcomes import (
    agreement,
    recorded_cushions,
    recorded_outcome,
    simulated_outcome,
    track_at,
)
from billiards.fit.shots import GUESS_TIPS, Shot, Stroke, shot_run
from billiards.scene.reader import Scene
from billiards.simulation import simulate_runs

# The aims tried either side of the recorded contact's, degrees: the contact's line of
# centres is read from 50 Hz samples, to within a few degrees of the cut.
AIM_OFFSETS = (-0.1, 0.0, 0.1)
# The straight paths that touch the object ball are tried in this many aims, each at
# these multiples of the first samples' speed.
SCAN_AIMS = 41
SCAN_SPEEDS = (1.0, 1.2)
# The object ball's way off is read from its first sample this far from where it stood, m.
LEAVING = 0.05


def aimed_strokes(table: Scene, shot: Shot) -> list[Stroke]:
    """Strokes aimed to make the recording's first contact: none where the recording's
    cue ball strikes no object ball, or meets a cushion before it does."""
    cue = shot.order[0]
    size = (table.table.length, table.table.width)
    recorded = recorded_outcome(shot.recording, cue, shot.start, table.radius, size)
    if recorded.first is None or recorded.first_time is None:
        return []
    contact_time = shot.start + recorded.first_time
    track = shot.recording.balls[cue]
    turns = recorded_cushions(track, table.radius, size)
    if any(shot.start <= time < contact_time for time in turns):
        return []
    struck = shot.recording.balls[recorded.first]
    rest = struck.xy[0]
    # The line of centres: the way the object ball leaves (throw turns it by a few
    # degrees at most), and the way to where the cue ball was at the contact.
    away = struck.xy - rest
    far = np.flatnonzero(np.hypot(*away.T) > LEAVING)
    contact = track_at(track, np.array([contact_time]))[0]
    normals = [contact - rest]
    if len(far):
        normals.insert(0, -away[far[0]])
    start = shot.recorded[0][0]
    # Every straight path that touches the ball, in SCAN_AIMS aims, at the first samples'
    # speed and more (when the contact comes before those samples, they show the cue
    # ball after it): the aims above are uncertain by a few degrees of the line of
    # centres, which a cue ball a few cm from the ball turns into tens of degrees.
    gap = rest - start
    reach = 2 * table.radius / max(float(np.hypot(*gap)), 2 * table.radius)
    middle, half = math.degrees(math.atan2(gap[1], gap[0])), math.degrees(math.asin(reach))
    strokes = [
        Stroke(shot.guess.speed * scale, float(direction))
        for direction in np.linspace(middle - half, middle + half, SCAN_AIMS)
        for scale in SCAN_SPEEDS
    ]
    for normal in normals:
        length = float(np.hypot(*normal))
        if length == 0.0:
            continue
        aim = rest + 2 * table.radius * normal / length
        direction = math.degrees(math.atan2(aim[1] - start[1], aim[0] - start[0]))
        strokes += [
            Stroke(shot.guess.speed, direction + offset, side, height)
            for offset in AIM_OFFSETS
            for side, height in GUESS_TIPS
        ]
    return strokes


def outcome_check(table: Scene, shot: Shot) -> Callable[[list[Stroke]], list[int]]:
    """How much of the recording's outcome each stroke gives (outcomes.Agreement.level:
    the first object ball, within CONTACT_TIME_AGREES of its time; then the same balls
    set moving; then the whole sequence; fit_stroke's `agrees`), simulated as one batch."""
    cue = shot.order[0]
    size = (table.table.length, table.table.width)
    recorded = recorded_outcome(shot.recording, cue, shot.start, table.radius, size)

    def agrees(strokes: list[Stroke]) -> list[int]:
        run = shot_run(table, shot)
        runs = [run.struck(stroke) for stroke in strokes]
        made = []
        for result in simulate_runs(runs, [table.source] * len(strokes)):
            if isinstance(result, Exception):
                made.append(0)
                continue
            simulated = simulated_outcome(result.events, cue, recorded.object_balls, shot.duration)
            made.append(agreement(recorded, simulated).level)
        return made

    return agrees
