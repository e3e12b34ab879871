"""What a sweep keeps of its rows: runs.csv lines, and running statistics for
summary.json and the pictures, all in memory that does not grow with the runs.

Rows arrive in run order; each becomes one CSV line at once (floats as repr, the
shortest text that reads back to the same double, so equal runs give equal bytes)
and updates sums whose order is the run order (so the summary is reproducible too).
"""

from __future__ import annotations

import math
from collections import Counter
from typing import Any

import numpy as np

from billiards.physics.numerics.arrays import FloatArray
from billiards.physics.pockets import POCKET_NAMES
from billiards.sweep.runs import NudgePlan, Plan, RunRow, VaryPlan

CLOUD_RUNS = 5000  # the cloud picture shows the first runs, this many at most
FAILURE_KINDS = 10  # distinct failure reasons kept for the summary


def number(value: float | int) -> str:
    if isinstance(value, int):
        return str(value)
    return "" if math.isnan(value) else repr(float(value))


class Moments:
    """Count, mean and spread of arrays of a fixed shape (Welford's update), nan skipped."""

    def __init__(self, shape: tuple[int, ...]) -> None:
        self.count = np.zeros(shape)
        self.mean = np.zeros(shape)
        self.m2 = np.zeros(shape)
        self.low = np.full(shape, math.inf)
        self.high = np.full(shape, -math.inf)

    def add(self, values: FloatArray) -> None:
        seen = ~np.isnan(values)
        self.count += seen
        delta = np.where(seen, values - self.mean, 0.0)
        self.mean += np.where(seen, delta / np.maximum(self.count, 1), 0.0)
        self.m2 += np.where(seen, delta * (values - self.mean), 0.0)
        self.low = np.where(seen, np.minimum(self.low, values), self.low)
        self.high = np.where(seen, np.maximum(self.high, values), self.high)

    def summary(self, index: Any = ()) -> dict[str, float | None]:
        count = float(self.count[index])
        if count == 0:
            return {"mean": None, "std": None, "min": None, "max": None}
        std = math.sqrt(self.m2[index] / (count - 1)) if count > 1 else 0.0
        return {
            "mean": float(self.mean[index]),
            "std": std,
            "min": float(self.low[index]),
            "max": float(self.high[index]),
        }


class Record:
    """runs.csv's lines and the summary, for either kind of plan."""

    def __init__(self, plan: Plan) -> None:
        self.plan = plan
        self.ball_ids = plan.scene_data.scene.ball_ids
        self.runs = 0
        self.failures: Counter[str] = Counter()
        self.failed = 0
        count = len(self.ball_ids)
        self.positions = Moments((count, 2))
        self.rest_time = Moments(())
        self.contacts = Moments((2,))
        self.touched = np.zeros(count)  # runs in which each ball took part in a contact
        # A table with pockets: a column per ball naming its pocket, and drop counts.
        table = plan.scene_data.scene.table
        self.pocket_names = POCKET_NAMES if table.pockets else ()
        self.dropped = np.zeros((count, len(self.pocket_names)))
        self.cloud = np.full((min(plan.runs, CLOUD_RUNS), count, 2), math.nan)

    def header(self) -> list[str]:
        balls = [f"{ball_id}_{axis}" for ball_id in self.ball_ids for axis in "xy"]
        fixed = ["rest_time", "ball_contacts", "cushion_contacts", "stopped_by"]
        if self.pocket_names:
            fixed.append("pocketed")
            balls += [f"{ball_id}_pocket" for ball_id in self.ball_ids]
        return ["run", *self.input_header(), "status", *fixed, *balls, "reason"]

    def input_header(self) -> list[str]:
        return list(self.plan.input_names)

    def add(self, row: RunRow) -> list[str]:
        """Take the next row (in run order); return its CSV fields."""
        assert row.run == self.runs, (row.run, self.runs)
        self.runs += 1
        if row.failed is not None:
            self.failed += 1
            if row.failed in self.failures or len(self.failures) < FAILURE_KINDS:
                self.failures[row.failed] += 1
        else:
            self.positions.add(row.positions)
            self.rest_time.add(np.array(row.rest_time))
            self.contacts.add(np.array([row.ball_contacts, row.cushion_contacts], dtype=float))
            self.touched += row.contacts > 0
            for ball, pocket in enumerate(row.pockets):
                if pocket:
                    self.dropped[ball, self.pocket_names.index(pocket)] += 1
        if row.run < len(self.cloud):
            self.cloud[row.run] = row.positions
        ok = row.failed is None
        pockets: list[str] = []
        if self.pocket_names:
            names = row.pockets or ("",) * len(self.ball_ids)
            pockets = list(names)
        dropped = [str(sum(1 for name in row.pockets if name)) if ok else ""] if pockets else []
        return [
            str(row.run),
            *self.input_fields(row),
            "ok" if ok else "failed",
            number(row.rest_time),
            str(row.ball_contacts) if ok else "",
            str(row.cushion_contacts) if ok else "",
            row.stopped_by or "",
            *dropped,
            *(number(float(value)) for value in row.positions.ravel()),
            *pockets,
            row.failed or "",
        ]

    def input_fields(self, row: RunRow) -> list[str]:
        return [value if isinstance(value, str) else number(value) for value in row.inputs]

    def summary(self) -> dict[str, Any]:
        ok = self.runs - self.failed
        balls = {}
        for index, ball_id in enumerate(self.ball_ids):
            x, y = self.positions.summary((index, 0)), self.positions.summary((index, 1))
            balls[ball_id] = {
                "x": x,
                "y": y,
                # The share of runs in which the ball was touched (took part in a contact).
                "p_contact": float(self.touched[index] / ok) if ok else None,
            }
            if self.pocket_names:
                # The share of runs in which it dropped, in all and by pocket.
                drops = self.dropped[index]
                balls[ball_id]["p_pocketed"] = float(drops.sum() / ok) if ok else None
                balls[ball_id]["p_pocket"] = {
                    name: float(drops[n] / ok)
                    for n, name in enumerate(self.pocket_names)
                    if ok and drops[n]
                }
        return {
            "scene": self.plan.scene_data.source,
            "runs": self.runs,
            "failed": self.failed,
            "failures": dict(self.failures.most_common()),
            "rest_time": self.rest_time.summary(),
            "ball_contacts": self.contacts.summary(0),
            "cushion_contacts": self.contacts.summary(1),
            "balls": balls,
        }


class VaryRecord(Record):
    def __init__(self, plan: VaryPlan) -> None:
        super().__init__(plan)
        self.vary_plan = plan
        self.inputs = Moments((len(plan.variations.items),))

    def add(self, row: RunRow) -> list[str]:
        self.inputs.add(np.array(row.inputs, dtype=float))
        return super().add(row)

    def summary(self) -> dict[str, Any]:
        variations = self.vary_plan.variations
        data = super().summary()
        data["seed"] = variations.seed
        method = self.vary_plan.method or self.vary_plan.scene_data.scene.simulation.method
        data["method"] = method
        data["vary"] = {
            item.key: {"spec": item.spec, "kind": item.kind, **self.inputs.summary(n)}
            for n, item in enumerate(variations.items)
        }
        return data


class NudgeRecord(Record):
    """Adds each run's divergence: the largest distance at rest between a ball's place in
    the nudged run and in its method's unnudged run (the first of its block)."""

    def __init__(self, plan: NudgePlan) -> None:
        super().__init__(plan)
        self.nudge_plan = plan
        self.base: FloatArray | None = None
        self.curves: dict[str, list[tuple[float, float]]] = {m: [] for m in plan.methods}

    def input_header(self) -> list[str]:
        return ["method", "nudge", "divergence"]

    def input_fields(self, row: RunRow) -> list[str]:
        method, nudge = row.inputs
        assert isinstance(method, str) and isinstance(nudge, float)
        if row.run % len(self.nudge_plan.nudges) == 0:
            self.base = row.positions
            divergence = 0.0 if row.failed is None else math.nan
        else:
            assert self.base is not None
            moved = np.hypot(*(row.positions - self.base).T)
            divergence = float(np.max(moved)) if not np.isnan(moved).any() else math.nan
            self.curves[method].append((nudge, divergence))
        return [method, number(nudge), number(divergence)]

    def summary(self) -> dict[str, Any]:
        data = super().summary()
        radius = self.nudge_plan.scene_data.scene.radius
        data["nudged_ball"] = self.nudge_plan.ball
        data["divergence"] = "largest distance at rest between a ball's places (m)"
        data["methods"] = {
            method: {
                "curve": [{"nudge": d, "divergence": v} for d, v in curve],
                # How far one run can be trusted: the smallest nudge that moves some
                # ball at rest by more than its radius.
                "nudge_past_radius": next((d for d, v in curve if v > radius), None),
            }
            for method, curve in self.curves.items()
        }
        return data


def record_for(plan: Plan) -> Record:
    if isinstance(plan, NudgePlan):
        return NudgeRecord(plan)
    return VaryRecord(plan)
