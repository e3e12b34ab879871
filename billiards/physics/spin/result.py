"""The spin model's motion as a result: each ball's anchors, evaluated in closed form."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from billiards.physics.engine.result import AnchoredMotion
from billiards.physics.engine.setup import Setup
from billiards.physics.numerics.arrays import FloatArray, IntArray
from billiards.physics.spin.motion import FLYING, spin_state, state_laws


@dataclass(frozen=True)
class SpinMotion(AnchoredMotion):
    """Anchors of the spin model: one per contact or motion-state change."""

    w0: FloatArray  # (S, 3) rad/s
    state: IntArray  # (S,) spin.motion.SLIDING .. REST
    radius: float
    slide_decel: float
    spin_decel: float
    # Off the cloth (a run that lets a ball fly, issue 45): each anchor's height and
    # vertical velocity (S,), and g; None: every ball stays on the cloth.
    z0: FloatArray | None = None
    vz0: FloatArray | None = None
    gravity: float = 0.0

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
        positions, velocities, spins = spin_state(
            self.p0[rows],
            self.v0[rows],
            self.w0[rows],
            acceleration[rows],
            angular[rows],
            self.t0[rows],
            duration[rows],
            self.spin_decel,
            times,
        )
        if self.z0 is not None:  # a flying ball's spin is constant (no cloth turns it)
            flying = self.state[rows] == FLYING
            spins[..., 2] = np.where(flying, self.w0[rows][..., 2], spins[..., 2])
        return positions, velocities, spins

    def heights_at(self, times: FloatArray) -> FloatArray:
        """Ball centres' heights (T, N): R on the cloth, the parabola z0 + v_z t - g t^2 / 2
        in the air (compiled.airborne.flight's order of operations)."""
        return self._vertical_at(times)[0]

    def climbs_at(self, times: FloatArray) -> FloatArray:
        """Vertical velocities (T, N): 0 on the cloth, v_z - g t in the air; at an event's
        own time, just after it."""
        return self._vertical_at(times)[1]

    def _vertical_at(self, times: FloatArray) -> tuple[FloatArray, FloatArray]:
        times = np.asarray(times, dtype=np.float64)
        rows = self.segments_at(times)
        heights = np.full(rows.shape, self.radius)
        if self.z0 is None or self.vz0 is None:
            return heights, np.zeros(rows.shape)
        flying = self.state[rows] == FLYING
        tau = np.maximum(times[:, None] - self.t0[rows], 0.0)
        drop = 0.5 * self.gravity * (tau * tau)
        parabola = (self.z0[rows] + self.vz0[rows] * tau) - drop
        climb = self.vz0[rows] - self.gravity * tau
        return np.where(flying, parabola, heights), np.where(flying, climb, 0.0)

    def spins_at(self, times: FloatArray) -> FloatArray:
        """Angular velocities (T, N, 3); at an event's own time, just after it."""
        times = np.asarray(times, dtype=np.float64)
        return self.segment_spin_state(self.segments_at(times), times[:, None])[2]


def logged_spin_motion(
    setup: Setup, balls: IntArray, rows: FloatArray, count: int, **flight: Any
) -> SpinMotion:
    """A spin run's motion from its log's rows (t0, p0, v0, w0, state; the numpy engine's
    and the compiled loop's alike) and the setup's constants; flight: a run that lets
    balls fly gives their heights (z0, vz0, gravity)."""
    return SpinMotion.logged(
        balls,
        rows,
        setup.decel,
        count,
        w0=rows[:, 5:8].copy(),
        state=rows[:, 8].astype(np.intp),
        radius=setup.radius,
        slide_decel=setup.slide_decel,
        spin_decel=setup.spin_decel,
        **flight,
    )
