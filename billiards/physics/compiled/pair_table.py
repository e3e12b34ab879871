"""Each ball's next pair contact, kept as its pair entries change, so that choosing the
next event reads N numbers instead of the N x N table (engine.batch's argmin over every
pair, the same choice: the first least entry in row order, a NaN counting as least).

Row `first` of calendar.pair_time holds the entries of the pairs (first, second > first)
and never-written inf elsewhere; calendar.pair_least[first] is that row's first least
entry and calendar.pair_partner[first] its column. Every write to a pair entry goes
through `set_pair_time`, which keeps both; a row is scanned again only when its least
entry grows.
"""

from __future__ import annotations

from billiards.physics.compiled.jit import inline, kernel
from billiards.physics.compiled.state import Calendar


@inline
def _before(value: float, column: int, least: float, partner: int) -> bool:
    """Whether entry `column` holding `value` comes before the row's least so far: less
    (a NaN least of all), or equal and further left."""
    if value != value:
        return least == least or column < partner
    if least != least:
        return False
    return value < least or (value == least and column < partner)


@kernel
def rescan(calendar: Calendar, first: int) -> None:
    """Row `first`'s least entry and its column, from the whole row."""
    row = calendar.pair_time[first]
    least, partner = row[0], 0
    for column in range(1, len(row)):
        if _before(row[column], column, least, partner):
            least, partner = row[column], column
    calendar.pair_least[first], calendar.pair_partner[first] = least, partner


@inline
def set_pair_time(calendar: Calendar, first: int, second: int, value: float) -> None:
    """pair_time[first, second] = value, the row's least entry kept."""
    calendar.pair_time[first, second] = value
    least, partner = calendar.pair_least[first], calendar.pair_partner[first]
    if second == partner:
        if value != value or value <= least:
            calendar.pair_least[first] = value  # still the first least, at the same place
        else:
            rescan(calendar, first)  # the least grew: another entry may come first now
    elif _before(value, second, least, partner):
        calendar.pair_least[first], calendar.pair_partner[first] = value, second


@inline
def earliest_pair(calendar: Calendar) -> tuple[int, float]:
    """The first least entry of the whole table, as its flat index (first * N + second)
    and its time: the first least row's least entry."""
    rows = calendar.pair_least
    best, first = rows[0], 0
    for row in range(1, len(rows)):
        value = rows[row]
        if value < best or (value != value and best == best):
            best, first = value, row
    return first * len(rows) + calendar.pair_partner[first], best
