"""A shot's outcome (billiards.fit.outcomes): read from a recording whose contacts are known
by construction, from a simulation's events, and the agreement of the two, by hand."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from billiards.fit import Recording, Track
from billiards.fit.outcomes import (
    MIN_CUSHION_SPEED,
    Outcome,
    agreement,
    count_agreements,
    recorded_outcome,
    simulated_outcome,
)
from billiards.physics.engine.events import Event

RADIUS = 0.03075
SIZE = (2.84, 1.42)  # three_cushion's table
LOW, HIGH_X, HIGH_Y = RADIUS, SIZE[0] - RADIUS, SIZE[1] - RADIUS

# A point by construction: the cue ball "1" runs at 2 m/s through these centres (a ball
# "2" touched at the second, three rails, ball "3" touched at the sixth), then stops.
CUE_PATH = [
    (0.50, 0.40),
    (1.00, 0.60),  # touches "2", which stands 2R beyond along +x, at 0.269 s
    (1.60, HIGH_Y),  # the top rail
    (HIGH_X, 0.90),  # the right rail
    (2.20, LOW),  # the bottom rail
    (1.40, 0.50),  # touches "3", which stands 2R beyond along -y
    (1.20, 0.80),
]
SPEED = 2.0  # m/s
BALL_2 = (1.00 + 2 * RADIUS, 0.60)
BALL_3 = (1.40, 0.50 - 2 * RADIUS)


def _arrivals(path: list[tuple[float, float]]) -> list[float]:
    lengths = [math.dist(a, b) for a, b in itertools.pairwise(path)]
    return [0.0, *np.cumsum(lengths).tolist()]


ARRIVALS = [length / SPEED for length in _arrivals(CUE_PATH)]  # s at each centre
FIRST, SECOND = ARRIVALS[1], ARRIVALS[5]


def sampled(times: np.ndarray, at: list[float], points: list[tuple[float, float]]) -> Track:
    """A track as the recordings are: 50 Hz, rounded to 1 mm, a sample within 2 mm of the
    last kept one dropped (the last always kept)."""
    xy = np.round(
        np.stack(
            [
                np.interp(times, at, [p[0] for p in points]),
                np.interp(times, at, [p[1] for p in points]),
            ],
            axis=1,
        ),
        3,
    )
    keep = [0]
    for index in range(1, len(times)):
        if math.dist(xy[index], xy[keep[-1]]) >= 0.002:
            keep.append(index)
    if keep[-1] != len(times) - 1:
        keep.append(len(times) - 1)
    return Track(times[keep], xy[keep])


def a_point() -> Recording:
    """The cue ball along CUE_PATH from t = 0.1 s; "2" and "3" leave their places along
    the line of centres at 1 m/s for 0.5 s from when they are touched."""
    times = np.arange(0.0, 4.0, 0.02)
    start = 0.1
    cue = sampled(times, [start + a for a in ARRIVALS], CUE_PATH)
    two = sampled(
        times,
        [0, start + FIRST, start + FIRST + 0.5],
        [BALL_2, BALL_2, (BALL_2[0] + 0.5, BALL_2[1])],
    )
    three = sampled(
        times,
        [0, start + SECOND, start + SECOND + 0.5],
        [BALL_3, BALL_3, (BALL_3[0], BALL_3[1] - 0.3)],
    )
    return Recording("point", {"1": cue, "2": two, "3": three})


def test_a_recorded_point_is_read_as_its_contacts_were_made() -> None:
    recording = a_point()
    outcome = recorded_outcome(recording, "1", 0.1, RADIUS, SIZE)
    assert outcome.first == "2" and outcome.second == "3"
    # Times within one sample (0.02 s) of the contacts made: their closest approach.
    assert outcome.first_time == pytest.approx(FIRST, abs=0.02)
    assert outcome.second_time == pytest.approx(SECOND, abs=0.02)
    assert outcome.cushions == 3 and outcome.point is True
    assert outcome.moved == {"2", "3"}


def test_a_recording_that_misses_the_second_ball_scores_no_point() -> None:
    recording = a_point()
    still = recording.balls["3"]
    balls = {**recording.balls, "3": Track(still.t[:1], still.xy[:1])}  # never moves
    outcome = recorded_outcome(Recording("miss", balls), "1", 0.1, RADIUS, SIZE)
    assert outcome.first == "2" and outcome.second is None and outcome.second_time is None
    assert outcome.moved == {"2"} and outcome.point is False
    # Every cushion of the shot, the second ball never reached: the three rails.
    assert outcome.cushions == 3


def events(*made: tuple[float, str, tuple[str, ...]], speed: float = 1.0) -> list[Event]:
    return [Event(time, kind, balls, speed) for time, kind, balls in made]


# The simulated shots: the point as made (its contacts at the recording's times), one
# that strikes "3" first, and one that reaches "3" after only two cushions.
AS_MADE = events(
    (FIRST, "ball", ("1", "2")),
    (ARRIVALS[2], "cushion", ("1",)),
    (ARRIVALS[3], "cushion", ("1",)),
    (ARRIVALS[4], "cushion", ("1",)),
    (SECOND, "ball", ("1", "3")),
    (SECOND + 0.5, "cushion", ("3",)),  # the object ball's own: not the cue ball's
)
THREE_FIRST = events(
    (0.2, "ball", ("3", "1")),
    (0.9, "cushion", ("1",)),
    (1.5, "ball", ("1", "2")),
)
TWO_CUSHIONS = events(
    (FIRST, "ball", ("1", "2")),
    (ARRIVALS[2], "cushion", ("1",)),
    (ARRIVALS[3], "cushion", ("1",)),
    (SECOND - 0.2, "ball", ("1", "3")),
    (SECOND + 0.1, "cushion", ("1",)),  # after the second ball: does not count
)
# The right ball first, but seconds late: the cue ball missed it on its first pass.
LATE = events((FIRST + 3.0, "ball", ("1", "2")))


def test_a_simulated_outcome_is_read_from_its_events() -> None:
    outcome = simulated_outcome(AS_MADE, "1", ("2", "3"), until=4.0)
    assert outcome == Outcome(("2", "3"), "2", FIRST, SECOND, frozenset({"2", "3"}), 3)
    assert outcome.point is True
    other = simulated_outcome(THREE_FIRST, "1", ("2", "3"), until=4.0)
    assert (other.first, other.second, other.cushions, other.point) == ("3", "2", 1, False)
    short = simulated_outcome(TWO_CUSHIONS, "1", ("2", "3"), until=4.0)
    assert (short.second, short.cushions, short.point) == ("3", 2, False)
    late = simulated_outcome(LATE, "1", ("2", "3"), until=4.0)
    assert (late.first, late.second, late.moved) == ("2", None, {"2"})
    # The recording's end cuts the shot: the second ball after it is not reached.
    cut = simulated_outcome(AS_MADE, "1", ("2", "3"), until=SECOND - 0.01)
    assert cut.second is None and cut.moved == {"2"}


def test_a_cushion_grazed_too_slowly_to_be_seen_is_not_counted() -> None:
    grazed = events((0.5, "cushion", ("1",)), speed=0.5 * MIN_CUSHION_SPEED)
    met = events((0.5, "cushion", ("1",)), speed=MIN_CUSHION_SPEED)
    assert simulated_outcome(grazed, "1", ("2", "3"), 4.0).cushions == 0
    assert simulated_outcome(met, "1", ("2", "3"), 4.0).cushions == 1


def test_agreement_with_the_recording_part_by_part() -> None:
    recorded = recorded_outcome(a_point(), "1", 0.1, RADIUS, SIZE)
    same, first, point = (
        agreement(recorded, simulated_outcome(made, "1", ("2", "3"), 4.0))
        for made in (AS_MADE, THREE_FIRST, TWO_CUSHIONS)
    )
    assert (same.first, same.moved, same.second, same.point, same.sequence) == (True,) * 5
    # "3" struck first: the first ball differs, so does the order; the same balls move,
    # and the recording scores where this does not.
    assert (first.first, first.moved, first.second, first.point, first.sequence) == (
        False,
        True,
        False,
        False,
        False,
    )
    # Both balls in the same order, one cushion short: only the point differs.
    assert (point.first, point.moved, point.second, point.point, point.sequence) == (
        True,
        True,
        True,
        False,
        False,
    )
    # The right ball, 3 s late (beyond CONTACT_TIME_AGREES): not the same first contact.
    late = agreement(recorded, simulated_outcome(LATE, "1", ("2", "3"), 4.0))
    assert (late.first, late.moved, late.second, late.point) == (False, False, False, False)
    assert (same.differs(), first.differs(), point.differs()) == ("", "first ball, point", "point")
    # How much agrees, as the stroke search weighs it: the first ball, then the balls
    # moved, then the whole sequence.
    assert (same.level, first.level, point.level, late.level) == (3, 0, 2, 0)
    counts = count_agreements([same, first, point])
    assert (counts.shots, counts.first, counts.moved, counts.point, counts.sequence) == (
        3,
        2,
        3,
        1,
        1,
    )
    assert counts.line().startswith(
        "first object ball 67% (2 of 3), same balls moved 100% (3 of 3)"
    )


def a_kiss(cue_path: list[tuple[float, float]]) -> Recording:
    """The cue ball at 2 m/s along `cue_path` from t = 0.1 s touches "2" at its second
    centre; "2" runs along +x at 1 m/s into "3", which runs on 0.5 m at 1 m/s and stops."""
    times = np.arange(0.0, 5.0, 0.02)
    start = 0.1
    arrivals = [start + a / SPEED for a in _arrivals(cue_path)]
    cue = sampled(times, arrivals, cue_path)
    two_rest = (cue_path[1][0] + 2 * RADIUS, cue_path[1][1])
    three_rest = (1.70, two_rest[1])
    two_stop = (three_rest[0] - 2 * RADIUS, two_rest[1])
    kiss = arrivals[1] + (two_stop[0] - two_rest[0]) / 1.0
    two = sampled(times, [0, arrivals[1], kiss], [two_rest, two_rest, two_stop])
    three_stop = (three_rest[0] + 0.5, three_rest[1])
    three = sampled(times, [0, kiss, kiss + 0.5], [three_rest, three_rest, three_stop])
    return Recording("kiss", {"1": cue, "2": two, "3": three})


def test_a_ball_kissed_by_the_other_is_reached_only_if_the_cue_ball_gets_there() -> None:
    # "3" is set moving by "2", not by the cue ball, which stops far from it: no second.
    away = [(0.50, 0.70), (1.00, 0.70), (1.00, 1.20)]
    kissed = recorded_outcome(a_kiss(away), "1", 0.1, RADIUS, SIZE)
    assert (kissed.first, kissed.second, kissed.moved) == ("2", None, {"2", "3"})
    assert kissed.point is False
    # The cue ball comes off the top rail, turns (at no rail) and touches "3" where it
    # stopped, after it stopped: it reaches the second ball then, after one cushion.
    stopped = (1.70 + 0.5, 0.70)
    there = [
        (0.50, 0.70),
        (1.00, 0.70),
        (1.00, HIGH_Y),
        (2.60, 1.10),
        (stopped[0], stopped[1] + 2 * RADIUS),
    ]
    reached = recorded_outcome(a_kiss(there), "1", 0.1, RADIUS, SIZE)
    arrival = sum(math.dist(a, b) for a, b in itertools.pairwise(there)) / SPEED
    assert (reached.first, reached.second, reached.cushions) == ("2", "3", 1)
    assert reached.second_time == pytest.approx(arrival, abs=0.03)
