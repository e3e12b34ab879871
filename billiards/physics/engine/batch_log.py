"""What happened in every run of a batch: contacts, motion-state changes and anchors.

A pass appends one chunk (the runs, and each run's entry), not one call a run; runs'
entries interleave, each run's in its time order. `by_run` sorts them apart once,
stably: each run's log is then exactly the one it writes alone.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from operator import itemgetter
from typing import TypeVar

import numpy as np

from billiards.physics.numerics.arrays import FloatArray, IntArray

# A contact as logged: time, kind, balls (the run's own indices), impact speed, pocket.
Contact = tuple[float, str, tuple[int, ...], float, str | None]
Entry = TypeVar("Entry")


@dataclass
class ContactLog:
    """One run's log: contacts that changed velocities, motion-state changes (time,
    ball, state), and every anchor (path segment) as the motion law's rows."""

    contacts: list[Contact] = field(default_factory=list)
    transitions: list[tuple[float, int, int]] = field(default_factory=list)
    segment_balls: IntArray = field(default_factory=lambda: np.zeros(0, dtype=np.intp))
    segment_rows: FloatArray = field(default_factory=lambda: np.zeros((0, 0)))


class BatchLog:
    """The log of every run of a batch, appended a pass at a time."""

    def __init__(self, runs: int) -> None:
        self.runs = runs
        self._contact_runs: list[int] = []
        self._contacts: list[Contact] = []
        self._transition_runs: list[int] = []
        self._transitions: list[tuple[float, int, int]] = []
        # Anchors: one chunk a flush of (run of each row, ball of its run, rows).
        self._segments: list[tuple[IntArray, IntArray, FloatArray]] = []

    def contact(self, run: int, contact: Contact) -> None:
        self._contact_runs.append(run)
        self._contacts.append(contact)

    def contacts(
        self, runs: IntArray, times: FloatArray, kind: str, balls: IntArray, speeds: FloatArray
    ) -> None:
        """One contact of `kind` for each of `runs` (no pocket): balls (k, 1 or 2)."""
        if len(runs) == 0:
            return
        self._contact_runs.extend(runs.tolist())
        named = [tuple(row) for row in balls.tolist()]
        count = len(named)
        self._contacts.extend(
            zip(times.tolist(), [kind] * count, named, speeds.tolist(), [None] * count, strict=True)
        )

    def transitions(
        self, runs: IntArray, times: FloatArray, balls: IntArray, states: IntArray
    ) -> None:
        """Each of `balls` (its run's own index) took motion state `states` at `times`."""
        self._transition_runs.extend(runs.tolist())
        self._transitions.extend(zip(times.tolist(), balls.tolist(), states.tolist(), strict=True))

    def segments(self, runs: IntArray, balls: IntArray, rows: FloatArray) -> None:
        """New anchors: the motion law's `rows` of `balls` (their runs' own indices)."""
        self._segments.append((runs, balls, rows))

    def of(self, run: int) -> ContactLog:
        """One run's log, as it stands (for a run alone, and tests)."""
        return self.by_run([run])[run]

    def by_run(self, wanted: list[int] | None = None) -> dict[int, ContactLog]:
        """Each run's log (of `wanted`, or of all), its entries in the order they came."""
        wanted = list(range(self.runs)) if wanted is None else wanted
        contacts = _split(self._contact_runs, self._contacts, self.runs)
        transitions = _split(self._transition_runs, self._transitions, self.runs)
        runs, balls, rows = (np.concatenate(part) for part in zip(*self._segments, strict=True))
        order = np.lexsort((runs,))  # stable
        ends = np.searchsorted(runs[order], np.arange(self.runs + 1)).tolist()
        logs = {}
        for run in wanted:
            own = order[ends[run] : ends[run + 1]]
            logs[run] = ContactLog(contacts[run], transitions[run], balls[own], rows[own])
        return logs


def _split(runs: list[int], entries: list[Entry], count: int) -> list[list[Entry]]:
    """entries by run (a run's in the order they came): a stable sort, then slices."""
    if not entries:
        return [[] for _ in range(count)]
    keys = np.array(runs)
    order = np.lexsort((keys,))  # stable
    ordered = list(itemgetter(*order.tolist())(entries)) if len(entries) > 1 else list(entries)
    ends = np.searchsorted(keys[order], np.arange(count + 1)).tolist()
    return [ordered[ends[run] : ends[run + 1]] for run in range(count)]
