"""The compiled loop's per-ball next-contact table (billiards.physics.compiled.pair_table)
chooses what numpy's argmin over the whole pair table chooses, after every write: the
first least entry in row order, ties to the left, a NaN least of all, an all-inf table
its first entry; rows whose least grows, falls, moves or is tied again."""

from __future__ import annotations

import numpy as np
import pytest

from billiards.physics.compiled.pair_table import earliest_pair, set_pair_time
from billiards.physics.compiled.state import Calendar


def empty_calendar(count: int) -> Calendar:
    """A Calendar of `count` balls whose pair entries are all inf (as a run starts), the
    fields the table does not read left empty."""
    fields = dict.fromkeys(Calendar._fields, np.zeros(0))
    fields["pair_time"] = np.full((count, count), np.inf)
    fields["pair_least"] = np.full(count, np.inf)
    fields["pair_partner"] = np.zeros(count, dtype=np.int64)
    return Calendar(**fields)


def first_least(values: np.ndarray) -> int:
    """numpy's argmin: the first least value, the first NaN if there is one."""
    return int(np.argmin(values))


@pytest.mark.parametrize("seed", range(6))
def test_the_earliest_pair_is_the_whole_tables_first_least_after_every_write(seed: int) -> None:
    rng = np.random.default_rng(seed)
    count = int(rng.integers(2, 9))
    calendar = empty_calendar(count)
    # Few distinct values, so that ties are common; inf often (a pair that never meets);
    # NaN rarely (as a degenerate contact time would be).
    values = [0.5, 1.0, 1.0, 1.5, 2.0, np.inf, np.inf]
    if seed % 2:
        values.append(np.nan)
    for _ in range(400):
        first = int(rng.integers(0, count - 1))
        second = int(rng.integers(first + 1, count))
        set_pair_time(calendar, first, second, float(rng.choice(values)))
        flat, time = earliest_pair(calendar)
        expected = first_least(calendar.pair_time.reshape(-1))
        assert flat == expected
        assert np.array_equal(time, calendar.pair_time.reshape(-1)[expected], equal_nan=True)
        for row in range(count):
            assert calendar.pair_partner[row] == first_least(calendar.pair_time[row])


def test_a_table_of_nothing_to_meet_gives_its_first_entry_at_inf() -> None:
    calendar = empty_calendar(4)
    set_pair_time(calendar, 1, 3, 0.25)
    set_pair_time(calendar, 1, 3, np.inf)  # the least grows back to inf: the row again
    assert earliest_pair(calendar) == (0, np.inf)
    assert list(calendar.pair_partner) == [0, 0, 0, 0]
