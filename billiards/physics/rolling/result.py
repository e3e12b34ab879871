"""The rolling model's motion as a result: each ball's anchors, evaluated in closed form
(a straight line, slowing at mu g, to rest)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from itertools import accumulate

import numpy as np

from billiards.physics.engine.result import AnchoredMotion, SimulationResult, last_at_or_before
from billiards.physics.numerics.arrays import FloatArray, IntArray
from billiards.physics.rolling.motion import rest_duration, rolling_state, unit_directions


@dataclass(frozen=True)
class RollingMotion(AnchoredMotion):
    """Anchors of the rolling model: one per contact."""

    def segment_state(
        self, rows: IntArray, times: FloatArray | float
    ) -> tuple[FloatArray, FloatArray]:
        speed, direction = unit_directions(self.v0[rows])
        rest_after = rest_duration(speed, self.decel)
        positions, velocities, _ = rolling_state(
            self.p0[rows], direction, speed, self.t0[rows], rest_after, self.decel, times
        )
        return positions, velocities

    @classmethod
    def keep_final_positions(cls, results: Sequence[SimulationResult]) -> None:
        """Many rolling results' final positions found at once (one set of numpy calls
        costs about what one run's does), bit for bit final_positions' own."""
        chosen = [result for result in results if type(result.motion) is cls]
        if not chosen:
            return
        try:
            # A run whose arithmetic warns finds its own when asked, and warns there.
            with np.errstate(all="raise"):
                _keep_final_positions(chosen)
        except FloatingPointError:
            for result in chosen:
                result.__dict__.pop("_final_positions", None)


def _keep_final_positions(chosen: Sequence[SimulationResult]) -> None:
    motions = [result.motion for result in chosen if isinstance(result.motion, RollingMotion)]
    counts = np.array([motion.count for motion in motions], dtype=np.intp)
    sizes = [len(motion.t0) for motion in motions]
    starts = [0, *accumulate(counts.tolist()[:-1])]  # each run's first (run, ball) group
    group = np.concatenate(
        [motion.ball + start for motion, start in zip(motions, starts, strict=True)]
    )
    t0 = np.concatenate([motion.t0 for motion in motions])
    p0 = np.concatenate([motion.p0 for motion in motions])
    v0 = np.concatenate([motion.v0 for motion in motions])
    rest = np.array([result.rest_time for result in chosen])
    total = starts[-1] + int(counts[-1])
    order, first, found = last_at_or_before(group, t0 <= np.repeat(rest, sizes), total)
    rows = order[np.maximum(found, first)]
    speed, direction = unit_directions(v0[rows])
    decel = np.repeat(np.array([motion.decel for motion in motions], dtype=np.float64), counts)
    positions, _, _ = rolling_state(
        p0[rows],
        direction,
        speed,
        t0[rows],
        rest_duration(speed, decel),
        decel,
        np.repeat(rest, counts),
    )
    # SimulationResult.positions_at's clamp to the cushion lines, where no pockets.
    clamped = np.repeat(np.array([result.pockets is None for result in chosen]), counts)
    if clamped.any():
        radius = np.array([result.radius for result in chosen])
        length = np.array([result.table_size[0] - result.radius for result in chosen])
        width = np.array([result.table_size[1] - result.radius for result in chosen])
        low, high_x, high_y = (
            np.repeat(values, counts)[clamped] for values in (radius, length, width)
        )
        positions[clamped, 0] = np.clip(positions[clamped, 0], low, high_x)
        positions[clamped, 1] = np.clip(positions[clamped, 1], low, high_y)
    for result, start, count in zip(chosen, starts, counts.tolist(), strict=True):
        object.__setattr__(result, "_final_positions", positions[start : start + count])
