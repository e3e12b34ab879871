"""The spin model's motion law: sliding, rolling, spinning in place and rest, each a
motion state with a constant acceleration (spin.motion). A ball's path is a parabola
for its state's duration; the state's end (slide -> roll, roll -> spin or rest, spin
-> rest) is its change_time, where the calendar re-anchors it. Contacts are sought only
within the current states (spin.contact_times), so they stay exact across a change.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from billiards.physics.engine import motion_law
from billiards.physics.engine.motion_law import Pairs, Skips
from billiards.physics.engine.setup import Setup
from billiards.physics.numerics.arithmetic import at_rows
from billiards.physics.numerics.arrays import BoolArray, Dynamics, FloatArray, IntArray, Kinematics
from billiards.physics.pockets import PocketRows
from billiards.physics.spin.contact_times import cushion_contacts, pair_contacts
from billiards.physics.spin.motion import (
    REST,
    ROLLING,
    SLIDING,
    STATE_NAMES,
    classify,
    rolling_spin,
    spin_state,
    state_laws,
)
from billiards.physics.spin.result import SpinMotion, logged_spin_motion


class SpinLaw:
    state_names: tuple[str, ...] = STATE_NAMES

    def __init__(self, setups: Sequence[Setup]) -> None:
        # The runs' pockets (all or none: batch.shape_of), each run's table its own.
        tables = [setup.pockets for setup in setups if setup.pockets is not None]
        self.pockets = PocketRows.of(tables, motion_law.ball_count(setups)) if tables else None
        self.count = motion_law.ball_count(setups)
        names = ("radius", "decel", "slide_decel", "spin_decel", "max_time")
        constants = (motion_law.row_constant(setups, self.count, name) for name in names)
        self.radius, self.decel, self.slide_decel, self.spin_decel, self.max_time = constants
        self.bounds = motion_law.row_bounds(setups, self.count)
        self.p0 = motion_law.padded_positions(setups, self.count)
        count = len(self.p0)
        self.t0, self.w0 = np.zeros(count), np.zeros((count, 3))
        self.v0, self.acceleration, self.angular = (np.zeros((count, 2)) for _ in range(3))
        self.state = np.full(count, REST, dtype=np.intp)
        self.duration, self.change_time = np.full(count, np.inf), np.full(count, np.inf)

    def kinematics_at(self, balls: IntArray | slice, time: float | FloatArray) -> Kinematics:
        """Positions, velocities and spins of `balls` at `time` (one, or one a ball)."""
        return spin_state(
            self.p0[balls],
            self.v0[balls],
            self.w0[balls],
            self.acceleration[balls],
            self.angular[balls],
            self.t0[balls],
            self.duration[balls],
            at_rows(self.spin_decel, balls),
            time,
        )

    def state_at(self, balls: IntArray, time: float | FloatArray) -> Dynamics:
        positions, velocities, spins = self.kinematics_at(balls, time)
        # Zero once the state has run out (the ball waits for its change event).
        running = time - self.t0[balls] < self.duration[balls]
        accelerations = np.where(running[:, None], self.acceleration[balls], 0.0)
        return positions, velocities, spins, accelerations

    def anchor(
        self, balls: IntArray, time: float | FloatArray, kinematics: Kinematics
    ) -> FloatArray:
        positions, velocities, spins = kinematics
        radius = at_rows(self.radius, balls)
        states, velocities, spins = classify(velocities, spins, radius)
        acceleration, angular, duration = state_laws(
            states,
            velocities,
            spins,
            radius,
            at_rows(self.slide_decel, balls),
            at_rows(self.decel, balls),
            at_rows(self.spin_decel, balls),
        )
        self.t0[balls], self.p0[balls], self.v0[balls] = time, positions, velocities
        self.w0[balls], self.state[balls] = spins, states
        self.acceleration[balls], self.angular[balls] = acceleration, angular
        self.duration[balls] = duration
        self.change_time[balls] = np.where(states == REST, np.inf, time + duration)
        times = np.full(len(balls), time)[:, None]
        return np.concatenate((times, positions, velocities, spins, states[:, None]), axis=1)

    def state_changes(self, balls: IntArray, times: float | FloatArray) -> Kinematics:
        positions, velocities, spins, _ = self.state_at(balls, times)
        state = self.state[balls]
        sliding = state == SLIDING
        # The slip is zero now by construction: roll (rounding removed).
        spins[sliding, :2] = rolling_spin(velocities[sliding], at_rows(self.radius, balls[sliding]))
        stopping = ~sliding
        velocities[stopping] = 0.0
        spins[stopping, :2] = 0.0
        spins[stopping & (state != ROLLING), 2] = 0.0  # spinning in place: to rest
        return positions, velocities, spins

    def slipping(self, balls: IntArray) -> BoolArray:
        return np.asarray(self.state[balls] == SLIDING)

    def states_of(self, balls: IntArray) -> IntArray:
        return np.asarray(self.state[balls], dtype=np.intp)

    def edge_times(
        self, balls: IntArray, skip: Skips, starts: IntArray
    ) -> tuple[FloatArray, IntArray]:
        reach = None
        if self.pockets is not None:  # the jaws' rounding level, run by run
            largest = np.abs(self.p0[balls]).max(axis=1)
            ends = np.concatenate((starts[1:], [len(balls)]))
            reach = np.repeat(np.maximum.reduceat(largest, starts), ends - starts)
        bounds = self.bounds if self.bounds.ndim == 1 else self.bounds[balls]
        pockets = None if self.pockets is None else self.pockets.at(balls)
        return cushion_contacts(
            self.p0[balls],
            self.v0[balls],
            self.acceleration[balls],
            self.t0[balls],
            self.duration[balls],
            self.state[balls],
            bounds,
            pockets,
            at_rows(self.max_time, balls),
            skip,
            reach,
        )

    def pair_times(
        self, pairs: Pairs, now: FloatArray, ends: FloatArray, parting: bool, runs: IntArray
    ) -> FloatArray:
        first, second = pairs
        balls, times, row_first, row_second, run_of_pair = motion_law.run_rows(
            runs, now, first, second, self.count
        )
        position, velocity, _ = self.kinematics_at(balls, times)
        reach = np.abs(position).reshape(len(runs), -1).max(axis=1)
        rows_of = (row_first, row_second, motion_law.per_pair(reach, run_of_pair))
        return pair_contacts(
            first,
            second,
            motion_law.per_pair(now, run_of_pair),
            position,
            velocity,
            self.acceleration[balls],
            self.state[balls],
            self.change_time,
            ends,
            at_rows(self.radius, first),
            at_rows(self.max_time, first),
            parting,
            rows_of,
        )

    def latest_stop(self, run: int) -> float:
        """When the run's last ball came to rest, or the end of its latest state still
        running (so it is past any step's end until every ball rests)."""
        own = slice(run * self.count, (run + 1) * self.count)
        t0 = self.t0[own]
        ends = np.where(self.state[own] == REST, t0, t0 + self.duration[own])
        return float(ends.max(initial=0.0))

    def latest_stops(self, runs: IntArray) -> FloatArray:
        t0 = self.t0.reshape(-1, self.count)[runs]
        duration = self.duration.reshape(-1, self.count)[runs]
        rest = self.state.reshape(-1, self.count)[runs] == REST
        return np.asarray(np.where(rest, t0, t0 + duration).max(axis=1, initial=0.0))

    def recorded(self, setup: Setup, balls: IntArray, rows: FloatArray, count: int) -> SpinMotion:
        return logged_spin_motion(setup, balls, rows, count)
