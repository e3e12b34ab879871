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


def from_rotation_matrix(matrix: FloatArray) -> FloatArray:
    """The unit quaternion (4,) of a rotation matrix (3, 3) (Shepperd's method: from
    the largest of the four squared components, so it stays accurate near 180
    degrees)."""
    m = np.asarray(matrix, dtype=np.float64)
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    squares = np.array(
        [1 + 2 * m[0, 0] - trace, 1 + 2 * m[1, 1] - trace, 1 + 2 * m[2, 2] - trace, 1 + trace]
    )
    largest = int(np.argmax(squares))
    q = np.empty(4)
    q[largest] = 0.5 * np.sqrt(squares[largest])
    s = 0.25 / q[largest]
    if largest == 3:
        q[:3] = ((m[2, 1] - m[1, 2]) * s, (m[0, 2] - m[2, 0]) * s, (m[1, 0] - m[0, 1]) * s)
    elif largest == 0:
        q[1:] = ((m[0, 1] + m[1, 0]) * s, (m[0, 2] + m[2, 0]) * s, (m[2, 1] - m[1, 2]) * s)
    elif largest == 1:
        q[[0, 2, 3]] = ((m[0, 1] + m[1, 0]) * s, (m[1, 2] + m[2, 1]) * s, (m[0, 2] - m[2, 0]) * s)
    else:
        q[[0, 1, 3]] = ((m[0, 2] + m[2, 0]) * s, (m[1, 2] + m[2, 1]) * s, (m[1, 0] - m[0, 1]) * s)
    return q / np.linalg.norm(q)


def slerp(first: FloatArray, second: FloatArray, weight: float) -> FloatArray:
    """Spherical linear interpolation (4,) from `first` (weight 0) to `second` (1):
    the turn between them at a constant rate, along the shorter way round."""
    dot = float(first @ second)
    if dot < 0:
        second, dot = -second, -dot
    if dot > 0.9995:  # nearly the same: the chord is the arc
        return blend(first[None], second[None], weight)[0]
    angle = np.arccos(min(dot, 1.0))
    blended = (np.sin((1 - weight) * angle) * first + np.sin(weight * angle) * second) / np.sin(
        angle
    )
    return np.asarray(blended / np.linalg.norm(blended))
