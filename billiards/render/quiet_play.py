"""Quiet play, quickened: no film holds long on balls that barely move.

A stretch in which every ball on the table moves slower than CRAWL (a break's last
balls rolling out, a massé's object ball creeping on) is played quicker, so that it
takes LONGEST_HOLD s of film whatever its length in simulation time: the seed break's
last cue ball, 2.4 s of rolling under 0.25 m/s, takes 1.5 s. The quickening eases in
and out (billiards.render.slow_motion's windows, at a speed above 1), so the picture
and the sound track's rolling never jolt; contacts in it keep their natural sound.

Never quickened: the opening (up to OPENING s after the first contact, the slow-motion
window's side of it), a drop and the approach to it (the director's cut to the pocket
and its hold), and the ending after the last ball's centre stops (the ease out to the
wide view and the tail). No GL here.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from billiards.record.trajectory import Trajectory, first_contact_time, last_motion
from billiards.render.slow_motion import SlowMotion
from billiards.stage.cameras import POCKET_HOLD, POCKET_LEAD

FloatArray = npt.NDArray[np.float64]

CRAWL = 0.25  # m/s: a ball slower than this barely moves (about four diameters a second)
LONGEST_HOLD = 1.5  # s of film: the longest any stretch of balls barely moving is shown
QUICK_EASE = 0.25  # s of simulation time over which the quickening sets in and lets go
OPENING = 0.6  # s after the first contact (or the first frame, if none) never quickened
DROP_MARGIN = 0.2  # s before the director's cut to a pocket, never quickened either


def quiet_stretches(trajectory: Trajectory) -> list[tuple[float, float]]:
    """The stretches (start, end) of simulation time, longer than LONGEST_HOLD, in which
    every ball on the table is slower than CRAWL, outside the opening, the drops and
    the ending."""
    times = np.asarray(trajectory.times, dtype=np.float64)
    if len(times) < 2:
        return []
    positions = trajectory.positions
    steps = np.diff(times)
    speeds = np.linalg.norm(np.diff(positions[:, :, :2], axis=0), axis=2) / steps[:, None]
    on_table = (positions[:-1, :, 2] > 0.0) & (positions[1:, :, 2] > 0.0)
    falling = np.any(np.diff(positions[:, :, 2], axis=0) != 0.0, axis=1)
    quiet = (np.where(on_table, speeds, 0.0).max(axis=1) < CRAWL) & ~falling
    first = first_contact_time(trajectory.events)
    opening = (first if first is not None else float(times[0])) + OPENING
    ending = last_motion(trajectory)
    fenced = [(-np.inf, opening), (ending, np.inf)]
    fenced += [
        (event.time - POCKET_LEAD - DROP_MARGIN, event.time + POCKET_HOLD)
        for event in trajectory.events
        if event.kind == "pocket"
    ]
    for low, high in fenced:  # an interval touching a fenced range is not quiet
        quiet &= (times[1:] <= low) | (times[:-1] >= high)
    stretches = []
    edges = np.diff(np.concatenate([[0], quiet.astype(np.int8), [0]]))
    for begin, stop in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1), strict=True):
        start, end = float(times[begin]), float(times[stop])
        if end - start > LONGEST_HOLD:
            stretches.append((start, end))
    return stretches


def quickened(stretch: tuple[float, float]) -> SlowMotion:
    """The window that plays `stretch` in LONGEST_HOLD s of film, its eases inside it.

    A window from a to b with eases e on each side plays (b - a + 2e) + g (b - a + e)
    s of film, g = 1/speed - 1 (SlowMotion.extra); over the stretch [a - e, b + e] of
    length L that is L + g (L - e), which is LONGEST_HOLD for g = (HOLD - L) / (L - e).
    """
    start, end = stretch
    length = end - start
    gain = (LONGEST_HOLD - length) / (length - QUICK_EASE)
    return SlowMotion(1.0 / (1.0 + gain), start + QUICK_EASE, end - QUICK_EASE, QUICK_EASE)


def quick_windows(trajectory: Trajectory) -> tuple[SlowMotion, ...]:
    """The film's quickened windows, one per quiet stretch."""
    return tuple(quickened(stretch) for stretch in quiet_stretches(trajectory))
