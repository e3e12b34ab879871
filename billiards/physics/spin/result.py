"""The spin model's motion as a result: each ball's anchors, evaluated in closed form."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from billiards.physics.engine.result import AnchoredMotion
from billiards.physics.numerics.arrays import FloatArray, IntArray
from billiards.physics.spin.motion import spin_state, state_laws


@dataclass(frozen=True)
class SpinMotion(AnchoredMotion):
    """Anchors of the spin model: one per contact or motion-state change."""

    w0: FloatArray  # (S, 3) rad/s
    state: IntArray  # (S,) spin.motion.SLIDING .. REST
    radius: float
    slide_decel: float
    spin_decel: float

    def segment_state(
        self, rows: IntArray, times: FloatArray | float
    ) -> tuple[FloatArray, FloatArray]:
        positions, velocities, _ = self.segment_spin_state(rows, times)
        return positions, velocities

    def segment_spin_state(
        self, rows: IntArray, times: FloatArray | float
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        acceleration, angular, duration = state_laws(
            self.state, self.v0, self.w0, self.radius, self.slide_decel, self.decel, self.spin_decel
        )
        return spin_state(
            self.p0[rows], self.v0[rows], self.w0[rows], acceleration[rows], angular[rows],
            self.t0[rows], duration[rows], self.spin_decel, times,
        )  # fmt: skip

    def spins_at(self, times: FloatArray) -> FloatArray:
        """Angular velocities (T, N, 3); at an event's own time, just after it."""
        times = np.asarray(times, dtype=np.float64)
        return self.segment_spin_state(self.segments_at(times), times[:, None])[2]
