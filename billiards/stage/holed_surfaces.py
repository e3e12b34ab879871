"""Flat surfaces with round holes, as one conforming mesh of triangles, and the walls
that line the holes' cuts: the table's bed and rail top are built from these."""

from __future__ import annotations

import itertools
import math

import numpy as np
import numpy.typing as npt

from billiards.stage.materials import Material
from billiards.stage.meshes import Mesh

FloatArray = npt.NDArray[np.float64]

Rect = tuple[float, float, float, float]  # x0, y0, x1, y1

# Angular steps of a hole's circle (a multiple of 8: the tiles' corners are steps).
HOLE_SEGMENTS = 48


def _clip(polygon: FloatArray, rect: Rect) -> FloatArray:
    """A convex polygon (K, 2) clipped to an axis-aligned rectangle (Sutherland-Hodgman).

    A crossing is computed from the edge's endpoints in a fixed order, so two polygons
    sharing an edge get the very same point on the clip line (no cracks between them).
    """
    x0, y0, x1, y1 = rect
    # (axis, bound, sign): the side of each edge a point is kept on, sign * (p - bound) >= 0
    edges = ((0, x0, 1.0), (0, x1, -1.0), (1, y0, 1.0), (1, y1, -1.0))
    for axis, bound, sign in edges:
        if len(polygon) == 0:
            break
        inside = sign * (polygon[:, axis] - bound) >= 0
        kept = []
        for k in range(len(polygon)):
            j = (k + 1) % len(polygon)
            if inside[k]:
                kept.append(polygon[k])
            if inside[k] != inside[j]:
                p, q = sorted((polygon[k], polygon[j]), key=tuple)
                kept.append(p + (bound - p[axis]) / (q[axis] - p[axis]) * (q - p))
        polygon = np.array(kept).reshape(-1, 2)
    return polygon


# A hole's tile: the square around it, this many hole radii from its centre to a side
# (far enough that each side's points see the part of the hole's polygon they join).
TILE_REACH = 1.5


def _zipper(
    inner: FloatArray, inner_angles: FloatArray, outer: FloatArray, outer_angles: FloatArray
) -> list[FloatArray]:
    """Triangles filling the ring between two closed polygons around a common centre,
    each given by its points in increasing angle (radians in [0, 2 pi), the inner
    polygon's first at 0): one pass round, always advancing along the polygon whose
    next point comes first."""
    n, m = len(inner), len(outer)
    ahead_inner = np.append(inner_angles, 2 * math.pi)
    ahead_outer = np.append(outer_angles, outer_angles[0] + 2 * math.pi)
    triangles = []
    i = j = 0
    while i < n or j < m:
        if j == m or (i < n and ahead_inner[i + 1] <= ahead_outer[j + 1]):
            triangles.append(np.array([inner[i], inner[(i + 1) % n], outer[j % m]]))
            i += 1
        else:
            triangles.append(np.array([inner[i % n], outer[j], outer[(j + 1) % m]]))
            j += 1
    return triangles


def holed_surface(rects: list[Rect], holes: list[tuple[float, float, float]]) -> list[FloatArray]:
    """Triangles (T, 3, 2) covering each of some disjoint rectangles less round holes,
    one array per rectangle, all of them one conforming mesh: every edge is shared
    whole by the triangles on both sides (a vertex inside another triangle's edge
    would leave pixel cracks where the rasterizer rounds the two differently).

    Each hole sits in a square tile (TILE_REACH radii to a side); the rest is a grid
    through every rectangle's and tile's sides and each hole's centre, two triangles
    a cell. Inside a tile,
    the ring between the hole's polygon (HOLE_SEGMENTS steps, from angle 0) and the
    tile's sides (with a point wherever a grid line meets them) is zipped into
    triangles, clipped to the rectangles. The tiles must not overlap.
    """
    squares = [
        (x - TILE_REACH * r, y - TILE_REACH * r, x + TILE_REACH * r, y + TILE_REACH * r)
        for x, y, r in holes
    ]
    # Grid lines through each hole's centre too: a point mid-side on each of its tile's
    # sides, so each point of the sides joins at most an eighth of the hole.
    xs = np.unique([v for b in (*rects, *squares) for v in (b[0], b[2])] + [h[0] for h in holes])
    ys = np.unique([v for b in (*rects, *squares) for v in (b[1], b[3])] + [h[1] for h in holes])
    found: list[list[FloatArray]] = [[] for _ in rects]

    def within(box_: Rect, x: float, y: float) -> bool:
        return box_[0] < x < box_[2] and box_[1] < y < box_[3]

    for x0, x1 in itertools.pairwise(xs):
        for y0, y1 in itertools.pairwise(ys):
            middle = (0.5 * (x0 + x1), 0.5 * (y0 + y1))
            if any(within(square, *middle) for square in squares):
                continue
            for index, rect in enumerate(rects):
                if within(rect, *middle):
                    corners = np.array([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
                    found[index] += [corners[[0, 1, 2]], corners[[0, 2, 3]]]
                    break
    steps = np.linspace(0.0, 2 * math.pi, HOLE_SEGMENTS + 1)
    ray = np.column_stack((np.cos(steps), np.sin(steps)))
    for (x, y, r), square in zip(holes, squares, strict=True):
        centre = np.array((x, y))
        inner = (centre + r * ray)[:-1]  # as circle_points: the liner meets it exactly
        x0, y0, x1, y1 = square
        inside_x = [v for v in xs if x0 < v < x1]
        inside_y = [v for v in ys if y0 < v < y1]
        sides = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
        sides += [(v, y0) for v in inside_x] + [(v, y1) for v in inside_x]
        sides += [(x0, v) for v in inside_y] + [(x1, v) for v in inside_y]
        outer = np.array(sides)
        angles = np.mod(np.arctan2(outer[:, 1] - y, outer[:, 0] - x), 2 * math.pi)
        order = np.argsort(angles, kind="stable")
        ring = _zipper(inner, steps[:-1], outer[order], angles[order])
        overlapping = [
            (index, rect)
            for index, rect in enumerate(rects)
            if rect[0] < x1 and rect[2] > x0 and rect[1] < y1 and rect[3] > y0
        ]
        for triangle in ring:
            for index, rect in overlapping:
                part = _clip(triangle, rect)
                for j in range(1, len(part) - 1):
                    found[index].append(part[[0, j, j + 1]])
    out = []
    for triangles in found:
        if not triangles:
            out.append(np.zeros((0, 3, 2)))
            continue
        array = np.array(triangles)
        u, v = array[:, 1] - array[:, 0], array[:, 2] - array[:, 0]
        out.append(array[np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]) > 1e-14])
    return out


def flat_surface(
    mesh: Mesh, triangles: FloatArray, z: float, material: Material, up: bool = True
) -> None:
    """2-D triangles (T, 3, 2) laid horizontally at height z, facing up (or down)."""
    positions = np.concatenate([triangles, np.full((*triangles.shape[:2], 1), z)], axis=2)
    normal = (0.0, 0.0, 1.0 if up else -1.0)
    mesh.add(positions.reshape(-1, 3), np.tile(normal, (positions.shape[0] * 3, 1)), material)


def wall(
    mesh: Mesh, segments: FloatArray, low: float, high: float, facing: FloatArray, m: Material
) -> None:
    """Vertical quads from z = low to high over segments (S, 2, 2) in the plane, each
    facing the point `facing` (x, y). Segments of no length are left out."""
    if len(segments):
        segments = segments[np.linalg.norm(segments[:, 1] - segments[:, 0], axis=1) > 1e-12]
    if len(segments) == 0:
        return
    a, b = segments[:, 0], segments[:, 1]
    along = b - a
    normal = np.column_stack((-along[:, 1], along[:, 0]))
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    flip = np.einsum("ij,ij->i", normal, facing - 0.5 * (a + b)) < 0
    normal[flip] *= -1
    z0, z1 = np.full((len(a), 1), low), np.full((len(a), 1), high)
    p0, p1, p2, p3 = np.hstack((a, z0)), np.hstack((b, z0)), np.hstack((b, z1)), np.hstack((a, z1))
    quads = np.stack([p0, p1, p2, p0, p2, p3], axis=1)
    normals = np.repeat(np.hstack((normal, np.zeros((len(a), 1))))[:, None], 6, axis=1)
    mesh.add(quads.reshape(-1, 3), normals.reshape(-1, 3), m)


def circle_points(centre: tuple[float, float], radius: float, steps: int) -> FloatArray:
    """A closed polygon (steps + 1, 2) round a circle, from angle 0 (as holed_surface)."""
    angles = np.linspace(0.0, 2 * math.pi, steps + 1)
    return np.array(centre) + radius * np.column_stack((np.cos(angles), np.sin(angles)))


def segments_outside_rect(points: FloatArray, low: FloatArray, high: FloatArray) -> FloatArray:
    """The parts (S, 2, 2) of a polyline's segments outside an axis-aligned rectangle."""
    found = []
    for p, q in itertools.pairwise(points):
        # Liang-Barsky: the segment's parameters inside the rectangle, [enter, leave].
        enter, leave = 0.0, 1.0
        step = q - p
        for axis in (0, 1):
            if abs(step[axis]) < 1e-15:
                if not low[axis] <= p[axis] <= high[axis]:
                    enter, leave = 1.0, 0.0
                continue
            t0 = (low[axis] - p[axis]) / step[axis]
            t1 = (high[axis] - p[axis]) / step[axis]
            enter, leave = max(enter, min(t0, t1)), min(leave, max(t0, t1))
        if enter >= leave:
            found.append((p, q))
            continue
        if enter > 0:
            found.append((p, p + enter * step))
        if leave < 1:
            found.append((p + leave * step, q))
    return np.array(found).reshape(-1, 2, 2)


def segment_outside_circles(
    a: FloatArray, b: FloatArray, circles: list[tuple[float, float, float]]
) -> FloatArray:
    """The parts (S, 2, 2) of the segment a-b outside every circle (x, y, radius)."""
    step = b - a
    cuts: list[tuple[float, float]] = []
    for x, y, r in circles:
        # |a + t step - c|^2 = r^2
        f = a - np.array((x, y))
        qa, qb, qc = float(step @ step), 2.0 * float(f @ step), float(f @ f) - r * r
        disc_ = qb * qb - 4 * qa * qc
        if disc_ > 0:
            root = math.sqrt(disc_)
            cuts.append(((-qb - root) / (2 * qa), (-qb + root) / (2 * qa)))
    kept = [(0.0, 1.0)]
    for c0, c1 in cuts:
        kept = [
            piece
            for t0, t1 in kept
            for piece in ((t0, min(t1, c0)), (max(t0, c1), t1))
            if piece[1] > piece[0]
        ]
    return np.array([(a + t0 * step, a + t1 * step) for t0, t1 in kept]).reshape(-1, 2, 2)
