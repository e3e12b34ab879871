"""The spin model in pictures: balls turn by their own angular velocity in the film,
and the top view samples the curved (parabolic) paths densely enough to draw them."""

from __future__ import annotations

import math

import numpy as np

from billiards.physics.engine.setup import Setup
from billiards.physics.methods.entry import run
from billiards.physics.spin.motion import tip_spin
from billiards.pictures.top_view import sample_path_bends
from billiards.record import quaternions
from billiards.record.sampling import record_trajectory
from billiards.rules.seed import RADIUS


def test_a_ball_spinning_in_place_turns_by_the_integral_of_its_spin() -> None:
    setup = Setup.of([[1.0, 0.5]], model="spin", spins=[[0.0, 0.0, 30.0]], spin_decel=10.0)
    result = run(setup, ("0",), "event", 1 / 240)
    trajectory = record_trajectory(result, fps=4.0)
    index = int(np.searchsorted(trajectory.times, 1.0))
    turned = 30.0 * 1.0 - 0.5 * 10.0 * 1.0**2  # w_z linear: the midpoint rule is exact
    expected = quaternions.about_axis(2, np.array([turned]))[0]
    got = trajectory.orientations[index, 0]
    assert min(np.abs(got - expected).max(), np.abs(got + expected).max()) < 1e-9


def test_a_drawn_ball_turns_backwards_while_it_slides_forwards() -> None:
    velocity = np.array([[2.0, 0.0]])
    spins = tip_spin(velocity, np.array([[0.0, -0.6]]), RADIUS)
    result = run(Setup.of([[0.5, 0.5]], velocity, model="spin", spins=spins), ("0",), "event", 1)
    trajectory = record_trajectory(result, fps=1000.0, end=0.01)  # about 1 rad
    q = trajectory.orientations[-1, 0]
    # The turn so far is about -y (backspin) although the ball moved +x.
    assert q[1] * np.sign(q[3]) < 0
    assert trajectory.positions[-1, 0, 0] > 0.5


def test_the_top_view_samples_the_curved_paths_densely() -> None:
    cut = math.radians(30.0)
    velocity = np.array([[1.5, 0.0], [0.0, 0.0]])
    spins = tip_spin(velocity, np.array([[0.0, 0.4], [0.0, 0.0]]), RADIUS)
    setup = Setup.of(
        [[0.5, 0.5], [1.0, 0.5 + 2 * RADIUS * math.sin(cut)]], velocity, model="spin", spins=spins
    )
    result = run(setup, ("cue", "1"), "event", 1)
    samples = sample_path_bends(result, result.table_size)
    times = samples.times
    middles = 0.5 * (times[:-1] + times[1:])
    chords = 0.5 * (samples.positions[:-1, :, :2] + samples.positions[1:, :, :2])
    off = np.abs(chords - result.positions_at(middles)).max()
    assert off < 2e-5
    # Only the breaks would have cut the cue ball's curve after the contact short.
    breaks = np.unique(np.concatenate([[0.0, result.rest_time], result.path_breaks()]))
    breaks = breaks[breaks <= result.rest_time]
    coarse = result.positions_at(breaks)
    coarse_off = np.abs(
        0.5 * (coarse[:-1] + coarse[1:]) - result.positions_at(0.5 * (breaks[:-1] + breaks[1:]))
    ).max()
    assert coarse_off > 1e-3
