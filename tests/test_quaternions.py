"""The one quaternion module: products, turns about axes, matrices and blends agree."""

from __future__ import annotations

import numpy as np

from billiards.record import quaternions


def test_a_quarter_turn_about_z_takes_x_to_y_by_product_and_by_matrix() -> None:
    turn = quaternions.about_axis(2, np.array([np.pi / 2]))
    assert np.allclose(quaternions.rotate(turn[0], np.array([1.0, 0.0, 0.0])), [0, 1, 0])
    matrix = quaternions.rotation_matrices(turn)[0]
    assert np.allclose(matrix @ np.array([1.0, 0.0, 0.0]), [0, 1, 0])


def test_the_product_applies_the_right_turn_first() -> None:
    about_x = quaternions.about_axis(0, np.array([np.pi / 2]))
    about_z = quaternions.about_axis(2, np.array([np.pi / 2]))
    both = quaternions.multiply(about_z, about_x)[0]  # x first, then z
    # y -> z under the turn about x; z stays under the turn about z.
    assert np.allclose(quaternions.rotate(both, np.array([0.0, 1.0, 0.0])), [0, 0, 1])


def test_a_blend_takes_the_shorter_way_and_stays_unit() -> None:
    start = quaternions.about_axis(2, np.array([0.2]))
    end = -quaternions.about_axis(2, np.array([0.6]))  # the same turn as +, written as -q
    middle = quaternions.blend(start, end, 0.5)
    assert np.isclose(np.linalg.norm(middle), 1.0)
    assert np.allclose(np.abs(middle), np.abs(quaternions.about_axis(2, np.array([0.4]))))
