"""What a shot did, as a player sees it (issue 44): the object ball the cue ball strikes
first and when, whether and when it reaches the other, the cushions it meets before that,
so the point (three-cushion's: the cue ball touches both object balls, and at least three
cushions before the second), and which object balls are set moving. Read from a recording
(`recorded_outcome`) and from a simulation's events (`simulated_outcome`); `Agreement`
says where the two agree.

A recording says when a ball is struck: it starts moving. An object ball starts moving at
the first sample from which it stays more than OBJECT_MOVED from where it stood (for
SUSTAINED samples: one sample's glitch is not a contact); its striker is the moving ball
that came closest to it before then (a contact: within 2R + CONTACT_TOLERANCE), and the
contact's time is that closest approach. A simulated contact agrees with a recorded one
when it is with the same ball within CONTACT_TIME_AGREES. The recordings drop a sample closer than 2 mm
to the last one kept, so a ball at rest has no samples: between two samples further apart
than HELD s a ball is taken to stay at the first until one sample's time before the next
(`_held`), not to creep between them. The cue ball's cushions are the turns of its track
at a rail: a sample nearest a rail between samples further from it, where the lines of
the two samples before and the two after meet within RAIL_REACH of the rail
(`recorded_cushions`).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from billiards.fit.recordings import FloatArray, Recording, Track
from billiards.fit.shots import Shot, Stroke, shot_run
from billiards.physics.engine.events import Event
from billiards.scene.reader import Scene
from billiards.simulation import simulate_runs

# An object ball has started moving once this far from where it stood, m (a few times the
# recordings' 1 mm resolution) ...
OBJECT_MOVED = 0.004
# ... and still so this many samples on (or to the track's end).
SUSTAINED = 3
# Two balls touched when their recorded centres came within 2R and this, m: the 50 Hz
# samples, linearly joined, cut the corner where a path turns at a contact.
CONTACT_TOLERANCE = 0.015
# Samples further apart than this, s, mean the ball stood still between them (the
# recordings drop a sample within 2 mm of the last kept one).
HELD = 0.05
# A turn's lines in and out are drawn through samples at most this far apart, s (a slow
# ball's samples come every 0.04-0.1 s: those within 2 mm are dropped).
TURN_SPAN = 0.2
# A turn of the cue ball's track is a cushion when its lines in and out meet within this
# of the rail's line (where a centre touches the cushion nose), m.
RAIL_REACH = 0.015
# Two contacts with the same ball agree when within this of each other, s: on the 122
# recorded shots the fitted strokes' first contacts land within 0.1 s of the recording's,
# or seconds off (the cue ball missed the ball on its first pass and met it later).
CONTACT_TIME_AGREES = 0.5
# The cushions before the second object ball that make a three-cushion point.
POINT_CUSHIONS = 3
# A simulated cushion counts when the cue ball meets it at least this fast, m/s: a ball
# that grazes a rail (its spin pressing it in) turns by a mm or two, which 50 Hz samples
# rounded to 1 mm cannot show (on simulated recordings the reading finds 99% of the
# cushions met faster than this, and about half of the slower).
MIN_CUSHION_SPEED = 0.1


@dataclass(frozen=True)
class Outcome:
    """A shot's sequence of contacts, as a player judges it. Times are s after the stroke."""

    object_balls: tuple[str, str]
    first: str | None  # the object ball the cue ball strikes first (None: neither)
    first_time: float | None
    second_time: float | None  # when the cue ball reaches the other one (None: never)
    moved: frozenset[str]  # the object balls set moving, by any ball
    cushions: int | None  # the cue ball's cushions before second_time (or in the whole
    # shot, if it never gets there); None where they could not be read

    @property
    def second(self) -> str | None:
        """The other object ball, if the cue ball reaches it."""
        if self.first is None or self.second_time is None:
            return None
        return next(ball for ball in self.object_balls if ball != self.first)

    @property
    def point(self) -> bool | None:
        """Three-cushion's point: both object balls, and POINT_CUSHIONS cushions before the
        second; None when the cushions could not be read (and both balls were reached)."""
        if self.second is None:
            return False
        if self.cushions is None:
            return None
        return self.cushions >= POINT_CUSHIONS

    def describe(self) -> str:
        """One short line: '3 at 0.31 s, 2 at 2.10 s after 3 cushions: point'."""
        if self.first is None:
            return "no object ball"
        parts = [f"{self.first} at {self.first_time:.2f} s"]
        cushions = "?" if self.cushions is None else str(self.cushions)
        if self.second is not None:
            parts.append(f"{self.second} at {self.second_time:.2f} s after {cushions} cushions")
        point = {True: "point", False: "no point", None: "point unknown"}[self.point]
        return ", ".join(parts) + f": {point}"


@dataclass(frozen=True)
class Agreement:
    """Where a simulated outcome agrees with the recorded one."""

    first: bool  # the same object ball struck first, at about the same time (or none)
    moved: bool  # the same object balls set moving
    second: bool  # the same first, and the cue ball reaches the second at about the same
    # time in both, or in neither
    point: bool | None  # the same point (None: the recording's cushions not read)

    def differs(self) -> str:
        """What differs, in words ('' when nothing does): 'first ball, point'."""
        parts = [
            ("first ball", self.first),
            ("second ball", self.second or not self.first),
            ("balls moved", self.moved),
            ("point", self.point is not False),
        ]
        return ", ".join(what for what, agrees in parts if not agrees)

    @property
    def level(self) -> int:
        """How much agrees, in the order the stroke search weighs it (fit_stroke's
        `agrees`): 0 not the first object ball, 1 the first, 2 and the same balls set
        moving, 3 and the whole sequence."""
        return int(self.first) + int(self.first and self.moved) + int(self.sequence)

    @property
    def sequence(self) -> bool:
        """All of it: the same first ball, the second reached alike, the same balls moved
        and the same point (where the recording's point could be read)."""
        return self.first and self.moved and self.second and self.point is not False


@dataclass(frozen=True)
class AgreementCounts:
    """How many shots agree, on each part of the outcome."""

    shots: int
    first: int
    moved: int
    second: int
    point: int
    point_read: int  # shots whose recorded point could be read
    sequence: int

    def share(self, part: str) -> float:
        whole = self.point_read if part == "point" else self.shots
        return getattr(self, part) / whole if whole else math.nan

    def line(self) -> str:
        """'first object ball 92% (112 of 122), same balls moved 70% (...), ...'"""
        parts = []
        for part, what in (
            ("first", "first object ball"),
            ("moved", "same balls moved"),
            ("point", "point"),
            ("sequence", "whole sequence"),
        ):
            whole = self.point_read if part == "point" else self.shots
            parts.append(f"{what} {self.share(part):.0%} ({getattr(self, part)} of {whole})")
        return ", ".join(parts)


def count_agreements(agreements: Iterable[Agreement]) -> AgreementCounts:
    made = list(agreements)
    return AgreementCounts(
        shots=len(made),
        first=sum(a.first for a in made),
        moved=sum(a.moved for a in made),
        second=sum(a.second for a in made),
        point=sum(a.point is True for a in made),
        point_read=sum(a.point is not None for a in made),
        sequence=sum(a.sequence for a in made),
    )


def shot_outcomes(table: Scene, shot: Shot, stroke: Stroke) -> tuple[Outcome, Outcome]:
    """The recording's outcome, and the one the stroke gives on the table (until the
    recording's last sample)."""
    cue = shot.order[0]
    size = (table.table.length, table.table.width)
    recorded = recorded_outcome(shot.recording, cue, shot.start, table.radius, size)
    (result,) = simulate_runs([shot_run(table, shot).struck(stroke)], [table.source])
    if isinstance(result, Exception):
        raise result
    simulated = simulated_outcome(result.events, cue, recorded.object_balls, shot.duration)
    return recorded, simulated


def agreement(recorded: Outcome, simulated: Outcome) -> Agreement:
    """Part by part; a contact agrees when it is with the same ball within
    CONTACT_TIME_AGREES of the recording's."""
    first = recorded.first == simulated.first and _same_time(
        recorded.first_time, simulated.first_time
    )
    second = first and _same_time(recorded.second_time, simulated.second_time)
    point = None if recorded.point is None else recorded.point == simulated.point
    return Agreement(
        first=first, moved=recorded.moved == simulated.moved, second=second, point=point
    )


def _same_time(recorded: float | None, simulated: float | None) -> bool:
    """Both None (no such contact), or both within CONTACT_TIME_AGREES."""
    if recorded is None or simulated is None:
        return recorded is None and simulated is None
    return abs(recorded - simulated) <= CONTACT_TIME_AGREES


def simulated_outcome(
    events: Iterable[Event], cue: str, object_balls: tuple[str, str], until: float
) -> Outcome:
    """The outcome of a simulation's events up to `until` s (the recording's end)."""
    first: str | None = None
    first_time = second_time = None
    moved: set[str] = set()
    cushions = 0
    for event in events:
        if event.time > until:
            break
        if event.kind == "ball":
            moved.update(ball for ball in event.balls if ball in object_balls)
            if cue in event.balls:
                other = event.balls[1] if event.balls[0] == cue else event.balls[0]
                if first is None:
                    first, first_time = other, event.time
                elif other != first and second_time is None:
                    second_time = event.time
        elif (
            event.kind == "cushion"
            and event.balls == (cue,)
            and second_time is None
            and event.impact_speed >= MIN_CUSHION_SPEED
        ):
            cushions += 1
    return Outcome(
        object_balls=object_balls,
        first=first,
        first_time=first_time,
        second_time=second_time,
        moved=frozenset(moved),
        cushions=cushions,
    )


def recorded_outcome(
    recording: Recording,
    cue: str,
    start: float,
    radius: float,
    table_size: tuple[float, float],
) -> Outcome:
    """The outcome a recording shows (the module's docstring says how it is read); `start`
    is when the cue ball was struck on the recording's clock."""
    object_balls = tuple(ball for ball in recording.balls if ball != cue)
    assert len(object_balls) == 2, "a three-cushion shot: the cue ball and two object balls"
    pair = (object_balls[0], object_balls[1])
    reach = 2 * radius + CONTACT_TOLERANCE
    moving_from = {cue: start}
    struck = sorted(
        ((motion_start(recording.balls[ball]), ball) for ball in pair),
        key=lambda item: item[0] if item[0] is not None else math.inf,
    )
    first: str | None = None
    first_time = second_time = None
    moved: set[str] = set()
    for seen, ball in struck:
        if seen is None:
            continue
        track = recording.balls[ball]
        moved.add(ball)
        # Its striker: the moving ball that came closest to where it stood before it was
        # seen moving (the cue ball alone, for the first).
        approaches = [
            (closest_approach(recording.balls[other], track.xy[0], since, seen), other)
            for other, since in moving_from.items()
        ]
        (distance, when), striker = min(approaches, key=lambda item: item[0][0])
        if first is None:
            first, first_time = ball, when  # only the cue ball was moving
        elif striker == cue and distance <= reach:
            second_time = when
        moving_from[ball] = when
    if first is not None and second_time is None and len(moved) == 2:
        # The other was set moving by the first object ball: did the cue ball reach it after?
        other = next(ball for ball in pair if ball != first)
        meeting = first_meeting(
            recording.balls[cue], recording.balls[other], moving_from[other], reach
        )
        if meeting is not None:
            second_time = meeting[1]
    end = second_time if second_time is not None else math.inf
    turns = recorded_cushions(recording.balls[cue], radius, table_size)
    cushions = sum(1 for time in turns if start <= time < end)
    return Outcome(
        object_balls=pair,
        first=first,
        first_time=None if first_time is None else first_time - start,
        second_time=None if second_time is None else second_time - start,
        moved=frozenset(moved),
        cushions=cushions,
    )


def motion_start(track: Track) -> float | None:
    """The time of the first sample from which the ball stays more than OBJECT_MOVED from
    its first (SUSTAINED samples, or to the end); None if it never moves."""
    away = np.hypot(*(track.xy - track.xy[0]).T) > OBJECT_MOVED
    for index in np.flatnonzero(away):
        if away[index : index + SUSTAINED].all():
            return float(track.t[index])
    return None


def _held(track: Track) -> tuple[FloatArray, FloatArray]:
    """The track's knots for linear interpolation with its still stretches kept still:
    where two samples are more than HELD s apart, the ball stays at the first until
    one sampling step (0.02 s) before the second."""
    t, xy = track.t, track.xy
    gaps = np.flatnonzero(np.diff(t) > HELD)
    if len(gaps) == 0:
        return t, xy
    times = np.insert(t, gaps + 1, t[gaps + 1] - 0.02)
    points = np.insert(xy, gaps + 1, xy[gaps], axis=0)
    return times, points


def track_at(track: Track, times: FloatArray) -> FloatArray:
    """The ball's recorded centre at these times (N, 2): joined linearly between samples,
    still stretches held (`_held`)."""
    return _at(_held(track), np.asarray(times, dtype=np.float64))


def _at(knots: tuple[FloatArray, FloatArray], times: FloatArray) -> FloatArray:
    t, xy = knots
    return np.stack([np.interp(times, t, xy[:, 0]), np.interp(times, t, xy[:, 1])], axis=1)


def closest_approach(
    track: Track, point: FloatArray, since: float, until: float
) -> tuple[float, float]:
    """How close the ball's centre came to a still point between two times (its track
    joined linearly between samples, still stretches held), and when: (m, s). Exact on
    each straight piece."""
    knots = _held(track)
    inside = (knots[0] > since) & (knots[0] < until)
    times = np.concatenate([[since], knots[0][inside], [until]])
    if times[-1] <= times[0]:
        times = np.array([since, since])
    points = _at(knots, times)
    a, b = points[:-1], points[1:]
    along = b - a
    lengths = (along * along).sum(axis=1)
    share = np.where(
        lengths > 0, ((point - a) * along).sum(axis=1) / np.maximum(lengths, 1e-300), 0.0
    )
    share = np.clip(share, 0.0, 1.0)
    nearest = a + share[:, None] * along
    distances = np.hypot(*(nearest - point).T)
    best = int(np.argmin(distances))
    when = times[best] + share[best] * (times[best + 1] - times[best])
    return float(distances[best]), float(when)


def first_meeting(
    track: Track, other: Track, since: float, reach: float
) -> tuple[float, float] | None:
    """When two moving balls' centres first come within `reach` after `since` (both
    joined linearly on their samples, still stretches held): the closest they come in that
    meeting and when, (m, s); None if they never do. Used only for the cue ball reaching
    an object ball already moving."""
    one, two = _held(track), _held(other)
    end = min(one[0][-1], two[0][-1])
    times = np.unique(np.concatenate([one[0], two[0], [since]]))
    times = times[(times >= since) & (times <= end)]
    if len(times) < 2:
        return None
    # Each piece between merged knots in 8: a closest approach to within a few mm.
    fine = np.unique(np.concatenate([np.linspace(a, b, 9) for a, b in itertools.pairwise(times)]))
    distances = np.hypot(*(_at(one, fine) - _at(two, fine)).T)
    below = distances <= reach
    if not below.any():
        return None
    begin = int(np.argmax(below))
    after = np.flatnonzero(~below[begin:])
    stop = begin + int(after[0]) if len(after) else len(fine)
    best = begin + int(np.argmin(distances[begin:stop]))
    return float(distances[best]), float(fine[best])


def recorded_cushions(track: Track, radius: float, table_size: tuple[float, float]) -> list[float]:
    """The times (recording's clock) at which the ball's track turns at a rail: a sample
    nearer a rail's line (where a centre touches the nose) than the samples on either
    side, where the line through the two samples before it and the line through the two
    after it meet within RAIL_REACH of the rail's line (a turn away from the rail, at a
    ball, meets further out)."""
    t, xy = track.t, track.xy
    length, width = table_size
    rails = (
        xy[:, 0] - radius,
        length - radius - xy[:, 0],
        xy[:, 1] - radius,
        width - radius - xy[:, 1],
    )
    turns: list[float] = []
    for gap in rails:
        for index in range(2, len(t) - 2):
            if not (gap[index] <= gap[index - 1] and gap[index] < gap[index + 1]):
                continue
            apex = _apex(t[index - 2 : index + 3], gap[index - 2 : index + 3])
            if apex is not None and abs(apex[1]) <= RAIL_REACH:
                turns.append(apex[0])
    return sorted(turns)


def _apex(t: FloatArray, gap: FloatArray) -> tuple[float, float] | None:
    """Where the line through the first two (time, gap) points meets the line through the
    last two: (time, gap); None if they do not approach and then leave."""
    if t[1] - t[0] > TURN_SPAN or t[4] - t[3] > TURN_SPAN or t[1] <= t[0] or t[4] <= t[3]:
        return None
    into = (gap[1] - gap[0]) / (t[1] - t[0])
    out = (gap[4] - gap[3]) / (t[4] - t[3])
    if not (into < 0 < out):
        return None
    # gap[1] + into (s - t[1]) = gap[3] + out (s - t[3])
    time = (gap[3] - gap[1] + into * t[1] - out * t[3]) / (into - out)
    return float(time), float(gap[1] + into * (time - t[1]))


def describe_moved(moved: Sequence[str] | frozenset[str]) -> str:
    return "+".join(sorted(moved)) or "-"
