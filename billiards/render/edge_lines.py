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

from billiards.render.geometry import Mesh

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
    keys = np.round(corners / QUANTUM).astype(np.int64)
    # Each triangle's edges by their ends' keys (in a fixed order): (triangle, the
    # corners at the edge's first end and at its second).
    found: dict[tuple[int, ...], list[tuple[int, int, int]]] = {}
    for triangle in (int(t) for t in np.flatnonzero(keep)):
        for first, second in ((0, 1), (1, 2), (2, 0)):
            a, b = tuple(keys[triangle, first]), tuple(keys[triangle, second])
            if b < a:
                a, b, first, second = b, a, second, first
            found.setdefault((*a, *b), []).append((triangle, first, second))
    rows = []
    for sides in found.values():
        triangle, first, second = sides[0]
        start, end = corners[triangle, first], corners[triangle, second]
        normal_a = face[triangle]
        if len(sides) == 1:  # an open border
            rows.append((start, end, normal_a, normal_a, 1.0))
            continue
        other, other_first, other_second = sides[1]  # (more than two faces: the first two)
        normal_b = face[other]
        mine, theirs = [first, second], [other_first, other_second]
        crease = np.any(
            np.sum(normals[triangle, mine] * normals[other, theirs], axis=1) < CREASE_COS
        )
        changed = not np.allclose(looks[triangle, mine], looks[other, theirs], atol=1e-6)
        if crease or changed:
            rows.append((start, end, normal_a, normal_b, 1.0))
        elif float(np.dot(normal_a, normal_b)) < COPLANAR_COS:
            rows.append((start, end, normal_a, normal_b, 0.0))
    lines = np.zeros((2 * len(rows), 13), dtype=np.float32)
    for index, (start, end, normal_a, normal_b, always) in enumerate(rows):
        lines[2 * index] = (*start, *end, *normal_a, *normal_b, always)
        lines[2 * index + 1] = (*end, *start, *normal_a, *normal_b, always)
    return lines
