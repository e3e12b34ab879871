"""The pocket geometry rule: where the six pockets are, which pocket sizes a table can
hold, and when a centre is already in a corner pocket. One rule, read by both the
scene reader (billiards.scene.reader, to refuse a file in one line) and the physics
(billiards.physics.pockets, to build the table), so that every table the reader
accepts is one the physics can build; the drawing lays its holes out from the same
places (billiards.record.pocket_shapes.PocketShapes).

A leaf module of its own floor (tests/test_floors.py): the standard library only, and
no import of the package's other modules. The expressions are the physics' own
(billiards.physics.pockets.pocket_table lays the mouths, cushions and capture lines
out from the same floats; tests/test_pocket_rule.py checks it bit for bit), so the
rule decides on exactly the numbers the simulation uses, also at its boundary.
"""

from __future__ import annotations

import math
from collections.abc import Callable

POCKET_NAMES = ("head-right", "side-bottom", "foot-right", "foot-left", "side-top", "head-left")


def pocket_places(
    table_size: tuple[float, float],
) -> tuple[tuple[float, float, float, float], ...]:
    """Each pocket, in POCKET_NAMES order: its corner (X, Y) of the nose lines and its
    inward signs (sx, sy); a side pocket has sx = 0. The physics lays its jaws and
    capture lines out from these (billiards.physics.pockets), the drawing its holes and
    mouths (billiards.record.pocket_shapes.PocketShapes)."""
    length, width = table_size
    return (
        (0.0, 0.0, 1.0, 1.0),
        (length / 2, 0.0, 0.0, 1.0),
        (length, 0.0, -1.0, 1.0),
        (length, width, -1.0, -1.0),
        (length / 2, width, 0.0, -1.0),
        (0.0, width, 1.0, -1.0),
    )


def corner_reach(corner_width: float) -> float:
    """a: how far from its corner each nose ends at a corner mouth of width w_c (m)."""
    return corner_width / math.sqrt(2.0)


def cushion_segments(
    table_size: tuple[float, float], corner_width: float, side_width: float
) -> tuple[tuple[float, float], tuple[tuple[float, float], tuple[float, float]]]:
    """Where the cushions exist, (lo, hi) along their rail: a short rail's one cushion
    (along y), and a long rail's two (along x, either side of the side pocket)."""
    length, width = table_size
    a = corner_reach(corner_width)
    half = side_width / 2.0
    return (a, width - a), ((a, length / 2 - half), (length / 2 + half, length - a))


def _shown(limit: float, value: float) -> str:
    """The limit in short form, or in full where the short form hides that it differs."""
    return f"{limit:g}" if f"{limit:g}" != f"{value:g}" else repr(limit)


def _least_refused(holds: Callable[[float], bool], near: float) -> float:
    """The smallest width the cushions cannot hold, found from `near` (its value in
    exact arithmetic) by stepping float by float: rounding moves the boundary by an
    ulp or two, and the message must name the limit the rule applies."""
    width = near
    for _ in range(64):
        if holds(width):
            width = math.nextafter(width, math.inf)
        elif holds(below := math.nextafter(width, -math.inf)):
            return width
        else:
            width = below
    return near


def _cushions_hold(
    table_size: tuple[float, float], corner_width: float, side_width: float
) -> tuple[bool, bool]:
    """Whether the short and the long cushions keep a length."""
    short, long = cushion_segments(table_size, corner_width, side_width)
    return short[0] < short[1], all(lo < hi for lo, hi in long)


def pocket_problem(
    table_size: tuple[float, float],
    radius: float,
    corner_width: float,
    side_width: float,
    jaw_radius: float,
) -> tuple[str, float, str] | None:
    """What is wrong with this pocket geometry, as (key, value, what was expected), or
    None. A ball must pass between a mouth's jaws (whose centres sit jaw_radius behind
    the nose ends), and every cushion must keep a length (docs/explanation/pockets.md)."""
    length, width = table_size
    # The passage between two jaws: their centres' distance less r + rho either side.
    corner_least = 2 * radius + (2 - math.sqrt(2.0)) * jaw_radius
    side_least = 2 * (radius + jaw_radius)
    if not corner_width > corner_least:
        return (
            "corner_pocket_width",
            corner_width,
            f"a mouth a ball passes (above {_shown(corner_least, corner_width)} m)",
        )
    if not side_width > side_least:
        return (
            "side_pocket_width",
            side_width,
            f"a mouth a ball passes (above {_shown(side_least, side_width)} m)",
        )
    short_holds, long_holds = _cushions_hold(table_size, corner_width, side_width)
    if not short_holds:
        widest = _least_refused(
            lambda corner: _cushions_hold(table_size, corner, side_width)[0],
            width / math.sqrt(2.0),
        )
        return (
            "corner_pocket_width",
            corner_width,
            f"mouths the short cushions hold (below {_shown(widest, corner_width)} m)",
        )
    if not long_holds:
        widest = _least_refused(
            lambda side: _cushions_hold(table_size, corner_width, side)[1],
            length - 2 * corner_reach(corner_width),
        )
        return (
            "side_pocket_width",
            side_width,
            f"mouths the long cushions hold (below {_shown(widest, side_width)} m)",
        )
    return None


def corner_captures(
    table_size: tuple[float, float], corner_width: float, jaw_radius: float
) -> list[tuple[str, tuple[float, float], float]]:
    """Each corner pocket's capture line: its name, the unit normal n pointing into the
    pocket, and the level: a centre p with n . p > level is in the pocket. The line
    runs through the jaw centres, jaw_radius behind the nose ends."""
    a = corner_reach(corner_width)
    lines = []
    for name, (x, y, sx, sy) in zip(POCKET_NAMES, pocket_places(table_size), strict=True):
        if not sx:
            continue  # a side pocket
        normal = (-sx / math.sqrt(2.0), -sy / math.sqrt(2.0))
        jaw = (x + sx * a, y - sy * jaw_radius)
        lines.append((name, normal, normal[0] * jaw[0] + normal[1] * jaw[1]))
    return lines


def corner_pocket_of(
    table_size: tuple[float, float],
    corner_width: float,
    jaw_radius: float,
    position: tuple[float, float],
) -> str | None:
    """The corner pocket a centre is already in (past its capture line), or None."""
    x, y = position
    for name, (nx, ny), level in corner_captures(table_size, corner_width, jaw_radius):
        if nx * x + ny * y > level:
            return name
    return None
