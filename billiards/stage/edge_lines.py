"""The static meshes' edges that can show as a step in the picture, as GL lines.

A moving camera's table and room are drawn without multisampling; their edges are
smoothed afterwards by drawing these lines over the drawing (edge_lines.vert/.frag,
after Persson's geometric post-process anti-aliasing, 2011): each pixel a line crosses
takes in its neighbour across the line by the share of the pixel that lies beyond it.
On llvmpipe, which runs every instruction of a full-screen filter for every pixel, this
costs only the few thousand pixels the lines cross.

An edge is kept if its two triangles meet at a crease or a change of colour or material
(always drawn), or could be a silhouette (two faces that are not coplanar: drawn when
one faces the eye and the other does not, decided per frame in the vertex shader), or
belongs to one triangle only (an open border: always drawn).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from billiards.stage.meshes import Mesh

FloatArray = npt.NDArray[np.float64]
# Per line vertex: its end (3f), the other end (3f), its two faces' normals (3f, 3f),
# and whether it is always drawn (1f).
LINE_FORMAT = "3f 3f 3f 3f 1f"
LINE_ATTRIBUTES = ("in_position", "in_other", "in_normal_a", "in_normal_b", "in_always")
# Vertex normals that differ more than this across an edge: a crease in the shading.
CREASE_COS = float(np.cos(np.radians(8.0)))
# Faces whose normals are this close are coplanar: never a silhouette.
COPLANAR_COS = float(np.cos(np.radians(0.5)))
QUANTUM = 1e-6  # m: positions are matched to this


def edge_lines(mesh: Mesh) -> npt.NDArray[np.float32]:
    """The mesh's edges worth smoothing, two line vertices each (LINE_FORMAT rows)."""
    count = len(mesh.positions) // 3
    if count == 0:
        return np.zeros((0, 13), dtype=np.float32)
    corners = mesh.positions[: 3 * count].reshape(count, 3, 3)
    normals = mesh.normals[: 3 * count].reshape(count, 3, 3)
    looks = np.hstack([mesh.colours, mesh.materials])[: 3 * count].reshape(count, 3, -1)
    # A face's normal: its corners' cross product, turned to agree with its vertices'.
    face = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    length = np.linalg.norm(face, axis=1, keepdims=True)
    keep = length[:, 0] > 1e-14
    face = np.where(keep[:, None], face / np.maximum(length, 1e-300), 0.0)
    face *= np.where(np.sum(face * normals.sum(axis=1), axis=1) < 0, -1.0, 1.0)[:, None]
    if not np.any(keep):
        return np.zeros((0, 13), dtype=np.float32)
    corners, normals, looks, face = corners[keep], normals[keep], looks[keep], face[keep]
    keys = np.round(corners / QUANTUM).astype(np.int64)
    # Every triangle's three edges (triangle, its corner at the edge's first end, at its
    # second), the ends put in the order of their keys, so that two triangles' copies of
    # an edge match.
    first = np.tile(np.array([0, 1, 2]), len(keys))
    second = np.tile(np.array([1, 2, 0]), len(keys))
    triangle = np.repeat(np.arange(len(keys)), 3)
    a, b = keys[triangle, first], keys[triangle, second]
    step = np.sign(b - a)
    leading = np.where(
        step[:, 0] != 0, step[:, 0], np.where(step[:, 1] != 0, step[:, 1], step[:, 2])
    )
    swap = leading < 0
    first, second = np.where(swap, second, first), np.where(swap, first, second)
    ends = np.hstack([keys[triangle, first], keys[triangle, second]])
    _, group, copies = np.unique(ends, axis=0, return_inverse=True, return_counts=True)
    order = np.argsort(group.ravel(), kind="stable")  # each edge's copies together
    starts = np.concatenate([[0], np.cumsum(copies)[:-1]])
    one = order[starts]  # an edge's first copy, and its second (if any)
    two = order[np.minimum(starts + 1, len(order) - 1)]
    shared = copies >= 2
    mine = (triangle[one], first[one], second[one])
    theirs = (triangle[two], first[two], second[two])
    start, end = corners[mine[0], mine[1]], corners[mine[0], mine[2]]
    normal_a = face[mine[0]]
    normal_b = np.where(shared[:, None], face[theirs[0]], normal_a)

    def ends_of(values: FloatArray, side: tuple[npt.NDArray[np.intp], ...]) -> FloatArray:
        """A side's per-vertex `values` at the edge's two ends (E, 2, K)."""
        return np.stack([values[side[0], side[1]], values[side[0], side[2]]], axis=1)

    bend = np.sum(ends_of(normals, mine) * ends_of(normals, theirs), axis=2)
    crease = np.any(bend < CREASE_COS, axis=1)
    mine_looks, their_looks = ends_of(looks, mine), ends_of(looks, theirs)
    changed = np.any(
        np.abs(mine_looks - their_looks) > 1e-6 + 1e-5 * np.abs(their_looks), axis=(1, 2)
    )
    always = ~shared | crease | changed  # an open border, a crease, a change of look
    silhouette = shared & ~always & (np.sum(normal_a * normal_b, axis=1) < COPLANAR_COS)
    kept = always | silhouette
    rows = np.hstack([start, end, normal_a, normal_b, always[:, None].astype(np.float64)])[kept]
    lines = np.empty((2 * len(rows), 13), dtype=np.float32)
    lines[0::2] = rows
    lines[1::2] = rows[:, [3, 4, 5, 0, 1, 2, *range(6, 13)]]  # from the other end
    return lines
