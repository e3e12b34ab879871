"""The static meshes' edges that a moving camera's picture smooths (edge_lines.py)."""

from __future__ import annotations

import numpy as np

from billiards.stage.edge_lines import edge_lines
from billiards.stage.materials import Material
from billiards.stage.meshes import Mesh, box, cylinder, quad

PLAIN = Material((0.5, 0.5, 0.5))
RED = Material((0.6, 0.1, 0.1))


def ends(lines: np.ndarray) -> set[tuple[tuple[float, ...], ...]]:
    """Each line's two ends (rounded, in either order), and its `always` flag last."""
    found: set[tuple[tuple[float, ...], ...]] = set()
    for start, end in zip(lines[0::2], lines[1::2], strict=True):
        assert np.array_equal(start[:3], end[3:6]) and np.array_equal(start[3:6], end[:3])
        a, b = tuple(np.round(start[:3], 6)), tuple(np.round(start[3:6], 6))
        found.add((min(a, b), max(a, b), (float(start[12]),)))
    return found


def test_a_box_has_its_twelve_creases_and_no_face_diagonals() -> None:
    mesh = Mesh()
    box(mesh, (0.0, 0.0, 0.0), (1.0, 2.0, 3.0), PLAIN)
    lines = edge_lines(mesh)
    found = ends(lines)
    assert len(found) == 12
    for a, b, (always,) in found:
        assert always == 1.0
        assert sum(x != y for x, y in zip(a, b, strict=True)) == 1  # along one axis
    # each line's two faces are the crease's two sides, at right angles
    assert np.allclose(np.sum(lines[:, 6:9] * lines[:, 9:12], axis=1), 0.0)


def test_a_flat_square_keeps_its_border_and_a_colour_change() -> None:
    corners = np.array([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], dtype=np.float64)
    one = Mesh()
    quad(one, corners, (0.0, 0.0, 1.0), PLAIN)
    assert len(ends(edge_lines(one))) == 4  # the diagonal between its halves is not seen
    two = Mesh()
    quad(two, corners, (0.0, 0.0, 1.0), PLAIN)
    quad(two, corners + np.array([1.0, 0.0, 0.0]), (0.0, 0.0, 1.0), RED)
    found = ends(edge_lines(two))
    assert ((1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (1.0,)) in found  # where the colour changes
    assert len(found) == 7


def test_a_smooth_cylinders_side_lines_are_drawn_only_as_its_silhouette() -> None:
    mesh = Mesh()
    cylinder(mesh, (0.0, 0.0, 0.0), 1.0, 0.5, 0.5, PLAIN, segments=16)
    found = ends(edge_lines(mesh))
    upright = {(a, b) for a, b, (always,) in found if a[2] != b[2]}
    rims = [(a, b, always) for a, b, (always,) in found if a[2] == b[2] and a[:2] != (0.0, 0.0)]
    assert len(upright) == 16
    assert all(always == 0.0 for a, b, (always,) in found if a[2] != b[2])  # silhouettes
    assert len(rims) == 32 and all(always == 1.0 for *_, always in rims)  # creases
