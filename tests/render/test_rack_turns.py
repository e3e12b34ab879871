"""The rack's balls lie with their numbers turned at random, the same in every film of
a scene (billiards.stage.rack_turns)."""

from __future__ import annotations

import dataclasses

import numpy as np

from billiards.record import quaternions
from billiards.stage.rack_turns import rack_turns, racked
from tests.render.fixtures import rolling_trajectory


def number_directions(turns: np.ndarray) -> np.ndarray:
    """Where each ball's number (its body +z: identity shows it straight up) points."""
    return quaternions.rotation_matrices(turns)[:, :, 2]


def test_a_scene_racks_its_balls_the_same_way_every_time() -> None:
    first, second = rack_turns(rolling_trajectory()), rack_turns(rolling_trajectory())
    assert first.tobytes() == second.tobytes()


def test_a_differently_set_scene_racks_them_differently() -> None:
    trajectory = rolling_trajectory()
    moved = trajectory.positions.copy()
    moved[:, 5, 0] += 0.001
    other = dataclasses.replace(trajectory, positions=moved)
    assert not np.allclose(rack_turns(trajectory)[1:], rack_turns(other)[1:])


def test_the_numbers_face_every_way_and_the_cue_ball_keeps_its_own() -> None:
    trajectory = rolling_trajectory()
    turns = rack_turns(trajectory)
    assert trajectory.ball_ids[0] == "cue"
    assert turns[0].tolist() == list(quaternions.IDENTITY)
    np.testing.assert_allclose(np.linalg.norm(turns, axis=1), 1.0, atol=1e-12)
    up = number_directions(turns[1:])[:, 2]
    # Uniform turns: the number's height is uniform in [-1, 1]; of 15 balls some face
    # down and some up, and few face straight up (none with the identity's up = 1).
    assert up.min() < -0.2 < 0.2 < up.max()
    assert np.sum(up > 0.95) <= 3


def test_the_drawn_ball_turns_first_then_rolls_as_recorded() -> None:
    trajectory = rolling_trajectory()
    drawn = racked(trajectory)
    turns = rack_turns(trajectory)
    last = -1
    expected = quaternions.multiply(trajectory.orientations[last], turns)
    np.testing.assert_allclose(drawn.orientations[last], expected, atol=1e-15)
    # The rolling carries the number round with the ball: its direction is the rolled one.
    rolled = quaternions.rotation_matrices(trajectory.orientations[last])
    np.testing.assert_allclose(
        number_directions(drawn.orientations[last]),
        np.einsum("nij,nj->ni", rolled, number_directions(turns)),
        atol=1e-12,
    )
    assert drawn.positions is trajectory.positions
