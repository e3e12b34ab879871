"""Triangle meshes as numpy arrays (no GL here) and the solids they are built from:
boxes, quads, discs, cylinders and convex solids, flat-shaded but for the cylinders'
sides. Frame: the physics frame, z up, the cloth at z = 0."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from billiards.stage.materials import Material

FloatArray = npt.NDArray[np.float64]


@dataclass
class Mesh:
    """Triangles as flat vertex arrays: three consecutive vertices per triangle."""

    positions: FloatArray = field(default_factory=lambda: np.zeros((0, 3)))
    normals: FloatArray = field(default_factory=lambda: np.zeros((0, 3)))
    colours: FloatArray = field(default_factory=lambda: np.zeros((0, 3)))
    materials: FloatArray = field(default_factory=lambda: np.zeros((0, 4)))

    def __len__(self) -> int:
        return len(self.positions)

    def add(self, positions: FloatArray, normals: FloatArray, material: Material) -> None:
        count = len(positions)
        self.positions = np.concatenate([self.positions, positions])
        self.normals = np.concatenate([self.normals, normals])
        self.colours = np.concatenate([self.colours, np.tile(material.colour, (count, 1))])
        values = (material.specular, material.shininess, material.emissive, material.pattern)
        self.materials = np.concatenate([self.materials, np.tile(values, (count, 1))])

    def extend(self, other: Mesh) -> None:
        self.positions = np.concatenate([self.positions, other.positions])
        self.normals = np.concatenate([self.normals, other.normals])
        self.colours = np.concatenate([self.colours, other.colours])
        self.materials = np.concatenate([self.materials, other.materials])

    def interleaved(self) -> npt.NDArray[np.float32]:
        """Per vertex: in_position 3f, in_normal 3f, in_color 3f, in_material 4f."""
        data = np.hstack([self.positions, self.normals, self.colours, self.materials])
        return np.ascontiguousarray(data, dtype=np.float32)

    def bounds(self) -> tuple[FloatArray, FloatArray]:
        return self.positions.min(axis=0), self.positions.max(axis=0)


def convex_solid(
    mesh: Mesh, corners: FloatArray, faces: list[list[int]], material: Material
) -> None:
    """Add a convex solid given its corners and faces (corner indices around each face).

    Faces are fanned into triangles; each gets the flat normal that points away from
    the solid's centre, so winding does not matter.
    """
    centre = corners.mean(axis=0)
    triangles = []
    for face in faces:
        for k in range(1, len(face) - 1):
            triangles.append((face[0], face[k], face[k + 1]))
    tri = corners[np.array(triangles)]  # (T, 3, 3)
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    keep = lengths[:, 0] > 1e-12
    tri, normals = tri[keep], normals[keep] / lengths[keep]
    outward = np.einsum("ij,ij->i", normals, tri.mean(axis=1) - centre) >= 0
    normals[~outward] *= -1
    mesh.add(tri.reshape(-1, 3), np.repeat(normals, 3, axis=0), material)


# The unit cube's corners and its 12 triangles, wound outwards (trimesh.creation.box's,
# written out: importing trimesh costs the film 0.4 s at its start, before any frame).
CUBE_CORNERS = np.array(
    [(x, y, z) for x in (0.0, 1.0) for y in (0.0, 1.0) for z in (0.0, 1.0)], dtype=np.float64
)
CUBE_TRIANGLES = np.array(
    [[1, 3, 0], [4, 1, 0], [0, 3, 2], [2, 4, 0], [1, 7, 3], [5, 1, 4],
     [5, 7, 1], [3, 7, 2], [6, 4, 2], [2, 7, 6], [6, 5, 4], [7, 5, 6]]
)  # fmt: skip


def box(mesh: Mesh, low: tuple[float, ...], high: tuple[float, ...], material: Material) -> None:
    """An axis-aligned box from corner `low` to corner `high`, flat-shaded."""
    start = np.array(low, dtype=np.float64)
    corners = start + CUBE_CORNERS * (np.array(high, dtype=np.float64) - start)
    triangles = corners[CUBE_TRIANGLES]  # (12, 3, 3)
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    mesh.add(triangles.reshape(-1, 3), np.repeat(normals, 3, axis=0), material)


def quad(mesh: Mesh, corners: FloatArray, normal: tuple[float, float, float], m: Material) -> None:
    """A one-sided rectangle (corners in order around it) facing `normal`."""
    tri = corners[[0, 1, 2, 0, 2, 3]]
    mesh.add(tri, np.tile(normal, (6, 1)), m)


def upright_quads(
    mesh: Mesh,
    sides: list[tuple[tuple[float, float], tuple[float, float], tuple[float, float, float]]],
    bands: list[tuple[float, float, Material]],
) -> None:
    """Vertical rectangles over each side ((ax, ay), (bx, by), its normal): one a band
    (z from low to high, material), the bands of a side in turn."""
    for (ax, ay), (bx, by), normal in sides:
        for low, high, material in bands:
            corners = np.array([(ax, ay, low), (bx, by, low), (bx, by, high), (ax, ay, high)])
            quad(mesh, corners, normal, material)


def disc(
    mesh: Mesh,
    centre: tuple[float, float, float],
    radius: float,
    material: Material,
    inner: float = 0.0,
    segments: int = 40,
) -> None:
    """A horizontal disc (or ring when inner > 0) facing up."""
    angles = np.linspace(0.0, 2 * math.pi, segments + 1)
    ring = np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)], axis=1)
    c = np.array(centre)
    outer_pts = c + radius * ring
    if inner > 0:
        inner_pts = c + inner * ring
        tris = []
        for k in range(segments):
            tris += [inner_pts[k], outer_pts[k], outer_pts[k + 1]]
            tris += [inner_pts[k], outer_pts[k + 1], inner_pts[k + 1]]
    else:
        tris = []
        for k in range(segments):
            tris += [c, outer_pts[k], outer_pts[k + 1]]
    positions = np.array(tris)
    mesh.add(positions, np.tile((0.0, 0.0, 1.0), (len(positions), 1)), material)


def cylinder(
    mesh: Mesh,
    bottom: tuple[float, float, float],
    height: float,
    radius_bottom: float,
    radius_top: float,
    material: Material,
    segments: int = 32,
) -> None:
    """A vertical (truncated) cone's side with smooth normals, plus its two caps."""
    # The side: a quad (two triangles) per section between the bottom and top rings.
    angles = np.linspace(0.0, 2 * math.pi, segments + 1)
    ring = np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)], axis=1)
    low = radius_bottom * ring
    high = radius_top * ring + np.array([0.0, 0.0, height])
    side = np.stack([low[:-1], low[1:], high[:-1], high[:-1], low[1:], high[1:]], axis=1).reshape(
        -1, 3, 3
    )
    triangles = side + np.array(bottom)  # (T, 3, 3)
    # Smooth normals in closed form: outward from the axis, tilted by the side's slope.
    outward = triangles[..., :2] - np.array(bottom[:2])
    outward /= np.linalg.norm(outward, axis=-1, keepdims=True)
    slope = (radius_bottom - radius_top) / height
    normals = np.concatenate([outward, np.full((*outward.shape[:-1], 1), slope)], axis=-1)
    normals /= np.linalg.norm(normals, axis=-1, keepdims=True)
    mesh.add(triangles.reshape(-1, 3), normals.reshape(-1, 3), material)
    b = np.array(bottom)
    disc(mesh, (b[0], b[1], b[2] + height), radius_top, material, segments=segments)
    cap = Mesh()
    disc(cap, (b[0], b[1], b[2]), radius_bottom, material, segments=segments)
    cap.normals[:] = (0.0, 0.0, -1.0)
    mesh.extend(cap)
