"""The seed's motion law: every ball rolls in a straight line, slowing at mu g, from its
anchor (rolling.motion.Anchors); its contacts are roots in the distance rolled
(contact_times, pocket_times). No state ends by itself: change_time stays inf.
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
from billiards.physics.rolling.contact_times import cushion_contacts, pair_contacts
from billiards.physics.rolling.motion import Anchors, state_at
from billiards.physics.rolling.pocket_times import edge_contacts
from billiards.physics.rolling.result import RollingMotion


class RollingLaw:
    state_names: tuple[str, ...] = ("rolling",)

    def __init__(self, setups: Sequence[Setup]) -> None:
        # The runs' pockets (all or none: batch.shape_of), each run's table its own.
        tables = [setup.pockets for setup in setups if setup.pockets is not None]
        self.pockets = PocketRows.of(tables, motion_law.ball_count(setups)) if tables else None
        count = self.count = motion_law.ball_count(setups)
        positions = motion_law.padded_positions(setups, count)
        decel = motion_law.row_constant(setups, count, "decel")
        self.anchors = Anchors.start(positions, np.zeros((len(positions), 2)), decel)
        self.radius = motion_law.row_constant(setups, count, "radius")
        self.change_time = np.full(len(positions), np.inf)
        self.bounds = motion_law.row_bounds(setups, count)

    def state_at(self, balls: IntArray, time: float | FloatArray) -> Dynamics:
        positions, velocities, accelerations = state_at(self.anchors, balls, time)
        return positions, velocities, np.zeros((len(balls), 3)), accelerations

    def anchor(
        self, balls: IntArray, time: float | FloatArray, kinematics: Kinematics
    ) -> FloatArray:
        positions, velocities, _ = kinematics
        anchors = self.anchors
        anchors.set(balls, time, positions, velocities)  # no spin in this model
        times = np.full(len(balls), time)[:, None]
        return np.concatenate((times, anchors.p0[balls], anchors.v0[balls]), axis=1)

    def state_changes(self, balls: IntArray, times: float | FloatArray) -> Kinematics:
        raise AssertionError("a rolling ball has no state that ends by itself")

    def slipping(self, balls: IntArray) -> BoolArray:
        return np.zeros(len(balls), dtype=bool)

    def states_of(self, balls: IntArray) -> IntArray:
        return np.zeros(len(balls), dtype=np.intp)

    def edge_times(
        self, balls: IntArray, skip: Skips, starts: IntArray
    ) -> tuple[FloatArray, IntArray]:
        pockets = self.pockets
        bounds = self.bounds if self.bounds.ndim == 1 else self.bounds[balls]
        if pockets is None:
            return cushion_contacts(self.anchors, balls, bounds)
        return edge_contacts(self.anchors, balls, bounds, pockets.at(balls), skip)

    def pair_times(
        self, pairs: Pairs, now: FloatArray, ends: FloatArray, parting: bool, runs: IntArray
    ) -> FloatArray:
        first, second = pairs
        anchors = self.anchors
        balls, times, row_first, row_second, run_of_pair = motion_law.run_rows(
            runs, now, first, second, self.count
        )
        position, velocity, acceleration = state_at(anchors, balls, times)
        remaining = np.maximum(anchors.rest_after[balls] - (times - anchors.t0[balls]), 0.0)
        reach = np.abs(position).reshape(len(runs), -1).max(axis=1)
        # Asked only of pairs with a ball still rolling (two at rest never meet; a batch's
        # first flush asks every pair of a rack at rest).
        times = np.full(len(first), np.inf)
        asked = (~((remaining[row_first] == 0) & (remaining[row_second] == 0))).nonzero()[0]
        if asked.size == 0:
            return times
        if asked.size < len(first):
            first, second = first[asked], second[asked]
            row_first, row_second = row_first[asked], row_second[asked]
            run_of_pair = None if run_of_pair is None else run_of_pair[asked]
        states = (
            position,
            velocity,
            acceleration,
            remaining,
            row_first,
            row_second,
            motion_law.per_pair(reach, run_of_pair),
        )
        now_of, radius = motion_law.per_pair(now, run_of_pair), at_rows(self.radius, first)
        times[asked] = pair_contacts(anchors, first, second, now_of, ends, radius, parting, states)
        return times

    def latest_stop(self, run: int) -> float:
        stops = self.anchors.stop_time[run * self.count : (run + 1) * self.count]
        return float(stops.max(initial=0.0))

    def latest_stops(self, runs: IntArray) -> FloatArray:
        stops = self.anchors.stop_time.reshape(-1, self.count)[runs]
        return np.asarray(stops.max(axis=1, initial=0.0))

    def recorded(
        self, setup: Setup, balls: IntArray, rows: FloatArray, count: int
    ) -> RollingMotion:
        return RollingMotion.logged(balls, rows, setup.decel, count)
