"""Unit quaternions (x, y, z, w), row by row over whole arrays: the package's one
quaternion module.

The order is pyrr's; a quaternion q turns body-frame vectors into world-frame ones,
v_world = q v_body q*. Written out rather than taken from pyrr so that every function
works on arrays of many balls (and frames) at once. numpy only.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]

IDENTITY = (0.0, 0.0, 0.0, 1.0)


def multiply(left: FloatArray, right: FloatArray) -> FloatArray:
    """Hamilton product, row by row: the rotation `right` first, then `left`."""
    x1, y1, z1, w1 = left[..., 0], left[..., 1], left[..., 2], left[..., 3]
    x2, y2, z2, w2 = right[..., 0], right[..., 1], right[..., 2], right[..., 3]
    product = np.stack(
        [
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
            w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
        ],
        axis=-1,
    )
    return np.asarray(product)


def about_axis(axis: int, angle: FloatArray) -> FloatArray:
    """Turns (N, 4) by `angle` (N,) radians about the coordinate axis 0, 1 or 2."""
    quaternion = np.zeros((len(angle), 4))
    quaternion[:, axis] = np.sin(0.5 * angle)
    quaternion[:, 3] = np.cos(0.5 * angle)
    return quaternion


def rotate(quaternion: FloatArray, vector: FloatArray) -> FloatArray:
    """A vector (3,) turned by a unit quaternion (4,): q v q*."""
    pure = np.array([*vector, 0.0])
    conjugate = quaternion * np.array([-1.0, -1.0, -1.0, 1.0])
    return multiply(multiply(quaternion, pure), conjugate)[:3]


def blend(first: FloatArray, second: FloatArray, weight: float) -> FloatArray:
    """Normalised linear interpolation (N, 4) from `first` (weight 0) to `second` (1).

    q and -q are the same rotation: each row blends towards the nearer of the two.
    """
    sign = np.where(np.einsum("ij,ij->i", first, second) < 0, -1.0, 1.0)[:, None]
    blended = first * (1 - weight) + sign * second * weight
    blended /= np.linalg.norm(blended, axis=1, keepdims=True)
    return blended


def rotation_matrices(quaternions: FloatArray) -> FloatArray:
    """Body-to-world rotation matrices (N x 3 x 3) of unit quaternions (N x 4)."""
    x, y, z, w = (quaternions[:, k] for k in range(4))
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
            np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
            np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
        ],
        axis=1,
    )
