"""The seed's motion law: every ball rolls in a straight line, slowing at mu g.

Each ball's anchor is billiards.physics.motion.Anchors (time, position, velocity just
after its last contact); its contacts are roots in the distance rolled
(billiards.physics.contact_times, and pocket_times on a table with pockets). A rolling
ball has no motion state that ends by itself (it stops where its last segment ends),
so change_time stays inf.
"""

from __future__ import annotations

import numpy as np

from billiards.physics.contact_times import cushion_contacts, pair_contacts
from billiards.physics.motion import Anchors, Dynamics, FloatArray, IntArray, Kinematics, state_at
from billiards.physics.motion_law import BoolArray, Pairs, Skip
from billiards.physics.pocket_times import edge_contacts
from billiards.physics.result import AnchoredMotion
from billiards.physics.setup import Setup


class RollingLaw:
    state_names: tuple[str, ...] = ("rolling",)

    def __init__(self, setup: Setup) -> None:
        count = len(setup.positions)
        self.setup = setup
        self.anchors = Anchors.start(setup.positions, np.zeros((count, 2)), setup.decel)
        self.change_time = np.full(count, np.inf)
        self.bounds = setup.bounds

    def state_at(self, balls: IntArray, time: float) -> Dynamics:
        positions, velocities, accelerations = state_at(self.anchors, balls, time)
        return positions, velocities, np.zeros((len(balls), 3)), accelerations

    def anchor(self, balls: IntArray, time: float, kinematics: Kinematics) -> FloatArray:
        positions, velocities, _ = kinematics
        anchors = self.anchors
        anchors.set(balls, time, positions, velocities)  # no spin in this model
        rows = np.empty((len(balls), 5))
        rows[:, 0] = time
        rows[:, 1:3] = anchors.p0[balls]
        rows[:, 3:5] = anchors.v0[balls]
        return rows

    def state_change(self, ball: int, time: float) -> Kinematics:
        raise AssertionError("a rolling ball has no state that ends by itself")

    def slipping(self, balls: IntArray) -> BoolArray:
        return np.zeros(len(balls), dtype=bool)

    def state_of(self, ball: int) -> int:
        return 0

    def edge_times(self, balls: IntArray, skip: Skip) -> tuple[FloatArray, IntArray]:
        pockets = self.setup.pockets
        if pockets is None:
            return cushion_contacts(self.anchors, balls, self.bounds)
        return edge_contacts(self.anchors, balls, self.bounds, pockets, skip)

    def pair_times(self, pairs: Pairs, now: float, ends: FloatArray, parting: bool) -> FloatArray:
        first, second = pairs
        return pair_contacts(
            self.anchors, first, second, now, ends, self.setup.radius, parting=parting
        )

    def latest_stop(self) -> float:
        return float(self.anchors.stop_time.max(initial=0.0))

    def recorded(self, balls: IntArray, rows: FloatArray, count: int) -> AnchoredMotion:
        return AnchoredMotion(
            ball=balls,
            t0=rows[:, 0].copy(),
            p0=rows[:, 1:3].copy(),
            v0=rows[:, 3:5].copy(),
            decel=self.setup.decel,
            count=count,
        )
