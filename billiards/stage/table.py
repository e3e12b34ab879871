"""The table as a numpy triangle mesh: the cloth bed, the cushions with their rounded
jaws, the rails with their sights and pocket cuts, the apron and the legs; or a user's
own table read from a file.

Solids are built convex (boxes, prisms, discs) so flat normals can be pointed away from
their centres; the table's top is built from flat surfaces and walls with their own
normals, so that a table with pockets has real holes: through the cloth bed (each over
a dark liner, so a ball dropping in goes into darkness) and through the rail.
"""

from __future__ import annotations

import itertools
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from billiards.record.pocket_shapes import PocketShapes
from billiards.stage import materials
from billiards.stage.holed_surfaces import (
    HOLE_SEGMENTS,
    Rect,
    circle_points,
    flat_surface,
    holed_surface,
    segment_outside_circles,
    segments_outside_rect,
    wall,
)
from billiards.stage.meshes import Mesh, box, convex_solid, cylinder, quad, upright_quads
from billiards.stage.table_plan import (
    CushionRun,
    JawEnd,
    TableShape,
    cushion_runs,
    jaw_ends,
    nose_lines,
    pocket_cuts,
)

FloatArray = npt.NDArray[np.float64]

# A sight's half-diagonals (m) along and across the rail: a pearl diamond 16 x 8 mm,
# set flush in a band 1.5 mm wide.
SIGHT_HALF = (0.008, 0.004)
SIGHT_BAND = 0.0015
CUSHION_FOOT = 0.016  # m behind the nose: where the cushion's underside meets the bed


def _cushion_profile(shape: TableShape) -> list[tuple[float, float]]:
    """The cushion's cross-section as (distance behind the nose, height), convex."""
    cw = shape.cushion_width
    return [
        (cw, 0.0),
        (CUSHION_FOOT, 0.0),
        (0.0, shape.nose_height - 0.006),
        (0.003, shape.nose_height + 0.002),
        (cw, shape.rail_top - 0.002),
    ]


JAW_STEPS = 8  # steps of a cushion end's rounding


def cushion(mesh: Mesh, shape: TableShape, run: CushionRun) -> None:
    """One cushion between two pockets (or corners): its profile swept along the nose
    line over run.span, each end cut back behind the nose by its jaw slope; with a
    jaw radius, the rubber rounds from the nose into the end's face (jaw_rounding)."""
    line = nose_lines(shape)[run.wall]
    o = np.array([*line.origin, 0.0])
    t = np.array([*line.along, 0.0])
    n = np.array([*line.outward, 0.0])
    profile = _cushion_profile(shape)
    corners = []
    for s_end in (0, 1):
        for depth, height in profile:
            if s_end == 0:
                s = run.span[0] - run.jaw_slopes[0] * depth
            else:
                s = run.span[1] + run.jaw_slopes[1] * depth
            corners.append(o + s * t + depth * n + (0.0, 0.0, height))
    count = len(profile)
    faces = [list(range(count)), list(range(count, 2 * count))]
    for k in range(count):
        j = (k + 1) % count
        faces.append([k, j, count + j, count + k])
    convex_solid(mesh, np.array(corners), faces, materials.CUSHION_GREEN)
    if run.jaw_radius > 0:
        for end in jaw_ends(shape, run):
            jaw_rounding(mesh, shape, end)


def jaw_rounding(mesh: Mesh, shape: TableShape, end: JawEnd) -> None:
    """The rubber of a cushion's end rounding into the pocket: the profile swept on
    round the jaw (JawEnd.point) from the nose, where it meets the straight cushion,
    to the face, which closes it flat. Smooth normals round the turn, so the nose and
    the face are one surface; at nose height it is the physics' jaw circle."""
    cw = shape.cushion_width
    profile = np.array(_cushion_profile(shape))  # (K, 2) depth, height
    angles = np.linspace(0.0, end.turn, JAW_STEPS + 1)
    local = np.array([[end.point(d, a) for a in angles] for d, _ in profile])  # (K, A, 2)
    local[..., 1] = np.minimum(local[..., 1], cw)  # the back stays against the rail
    xy = end.place(local)
    heights = np.broadcast_to(profile[:, 1:2], local.shape[:2])
    points = np.concatenate([xy, heights[..., None]], axis=2)  # (K, A, 3)
    # Each profile edge's outward normal in (depth, height), turned with the rounding.
    centre = profile.mean(axis=0)
    count = len(profile)
    positions, normals = [], []
    for k in range(count):
        j = (k + 1) % count
        (d0, h0), (d1, h1) = profile[k], profile[j]
        edge_normal = np.array((h1 - h0, -(d1 - d0)))
        if edge_normal @ (0.5 * (profile[k] + profile[j]) - centre) < 0:
            edge_normal = -edge_normal
        edge_normal /= np.linalg.norm(edge_normal)
        for a in range(JAW_STEPS):
            quad_points = [points[k, a], points[j, a], points[j, a + 1], points[k, a + 1]]
            quad_normals = []
            for angle in (angles[a], angles[a], angles[a + 1], angles[a + 1]):
                # Behind the nose (+depth) is -normal(angle) in the plane.
                plan = -edge_normal[0] * end.normal(angle)
                world = end.place(plan[None])[0] - end.mouth
                quad_normals.append((world[0], world[1], edge_normal[1]))
            for q in (0, 1, 2, 0, 2, 3):
                positions.append(quad_points[q])
                normals.append(quad_normals[q])
    # The face: the profile laid flat where the rounding ends, facing the pocket.
    face = points[:, -1]
    outward = end.place(end.normal(end.turn)[None])[0] - end.mouth
    for k in range(1, count - 1):
        for q in (0, k, k + 1):
            positions.append(face[q])
            normals.append((outward[0], outward[1], 0.0))
    normal_array = np.array(normals)
    normal_array /= np.linalg.norm(normal_array, axis=1, keepdims=True)
    mesh.add(np.array(positions), normal_array, materials.CUSHION_GREEN)


def _ring_rects(
    low: tuple[float, float],
    high: tuple[float, float],
    inner_low: tuple[float, float],
    inner_high: tuple[float, float],
) -> list[Rect]:
    """The band between an outer rectangle and an inner one, as eight rectangles (four
    corners, four sides) that meet corner to corner, as the inner one meets them."""
    xs = (low[0], inner_low[0], inner_high[0], high[0])
    ys = (low[1], inner_low[1], inner_high[1], high[1])
    return [
        (xs[i], ys[j], xs[i + 1], ys[j + 1]) for i in range(3) for j in range(3) if (i, j) != (1, 1)
    ]


def bed_rects(shape: TableShape) -> list[Rect]:
    """The bed under the table's whole top: first the cloth, to the cushions' feet,
    then the eight pieces of the band around it (under the cushions and the rail)."""
    length, width, outer, foot = shape.length, shape.width, shape.outer, CUSHION_FOOT
    cloth: Rect = (-foot, -foot, length + foot, width + foot)
    band = _ring_rects(
        (-outer, -outer),
        (length + outer, width + outer),
        (-foot, -foot),
        (length + foot, width + foot),
    )
    return [cloth, *band]


def build_table(shape: TableShape, pockets: PocketShapes | None = None) -> Mesh:
    """Cloth bed, cushions with a nose, wooden rails with sights, apron and legs; with
    `pockets`, the six holes cut through the bed (TableShape.pocket_lip wider: the lip
    and liner below are billiards.stage.pocket_mesh's) and the rail, and the cushions
    stopping at the mouths. Without, no hole anywhere."""
    mesh = Mesh()
    cuts = pocket_cuts(shape, pockets) if pockets is not None else []
    # The bed at z = 0 under the whole top: green cloth to the cushions' feet, and
    # beyond (under the cushions and rails, seen only inside a pocket's opening) the
    # dark leather of the pocket's shelf.
    # One mesh for both, so that they meet without cracks.
    lipped = [(x, y, radius + shape.pocket_lip) for x, y, radius in (cut.hole for cut in cuts)]
    pieces = holed_surface(bed_rects(shape), lipped)
    flat_surface(mesh, pieces[0], 0.0, materials.CLOTH_GREEN)
    flat_surface(mesh, np.concatenate(pieces[1:]), 0.0, materials.POCKET_LEATHER)
    for run in cushion_runs(shape, pockets):
        cushion(mesh, shape, run)
    _rail(mesh, shape, [cut.rail for cut in cuts])
    _apron(mesh, shape)
    _sights(mesh, shape)
    _legs(mesh, shape)
    return mesh


def _rail(mesh: Mesh, shape: TableShape, rail_cuts: list[tuple[float, float, float]]) -> None:
    """The rail: its top (cut open at each of `rail_cuts`), its outer sides and
    underside, the face behind the cushions, and the leather-faced wall of each cut."""
    length, width = shape.length, shape.width
    cw, outer, top, bottom = shape.cushion_width, shape.outer, shape.rail_top, shape.rail_bottom
    inner_low, inner_high = np.array((-cw, -cw)), np.array((length + cw, width + cw))
    rail_rects = _ring_rects(
        (-outer, -outer), (length + outer, width + outer), (-cw, -cw), (length + cw, width + cw)
    )
    flat_surface(
        mesh, np.concatenate(holed_surface(rail_rects, rail_cuts)), top, materials.RAIL_WOOD
    )
    x0, y0, x1, y1 = -outer, -outer, length + outer, width + outer
    flat_surface(
        mesh,
        np.array([[(x0, y0), (x1, y0), (x1, y1)], [(x0, y0), (x1, y1), (x0, y1)]]),
        bottom,
        materials.RAIL_WOOD,
        up=False,
    )
    outside = [
        ((x0, y0), (x1, y0), (0.0, -1.0, 0.0)),
        ((x1, y0), (x1, y1), (1.0, 0.0, 0.0)),
        ((x1, y1), (x0, y1), (0.0, 1.0, 0.0)),
        ((x0, y1), (x0, y0), (-1.0, 0.0, 0.0)),
    ]
    upright_quads(mesh, outside, [(bottom, top, materials.RAIL_WOOD)])
    inner = np.array(
        [(-cw, -cw), (length + cw, -cw), (length + cw, width + cw), (-cw, width + cw), (-cw, -cw)]
    )
    middle = np.array((length / 2, width / 2))
    for a, b in itertools.pairwise(inner):
        wall(mesh, segment_outside_circles(a, b, rail_cuts), 0.0, top, middle, materials.RAIL_WOOD)
    for x, y, radius in rail_cuts:
        arc = segments_outside_rect(
            circle_points((x, y), radius, 2 * HOLE_SEGMENTS), inner_low, inner_high
        )
        wall(mesh, arc, 0.0, top, np.array((x, y)), materials.POCKET_LEATHER)


def _apron(mesh: Mesh, shape: TableShape) -> None:
    """Under the rails, the apron (the table's body), slightly set back, with a moulding
    round its foot, proud of it."""
    length, width, outer = shape.length, shape.width, shape.outer
    inset = 0.02
    box(
        mesh,
        (-outer + inset, -outer + inset, shape.apron_bottom),
        (length + outer - inset, width + outer - inset, shape.rail_bottom),
        materials.APRON_WOOD,
    )
    proud = inset - 0.008
    box(
        mesh,
        (-outer + proud, -outer + proud, shape.apron_bottom),
        (length + outer - proud, width + outer - proud, shape.apron_bottom + 0.028),
        materials.RAIL_WOOD,
    )


def _sights(mesh: Mesh, shape: TableShape) -> None:
    """Small pearl diamonds inlaid in the rail tops, each in a dark setting (flush: a
    fraction of a millimetre over the wood only against depth fighting)."""
    for x, y, along_x in shape.sights():
        for lift, grow, material in (
            (0.0002, SIGHT_BAND, materials.SIGHT_SETTING),
            (0.0003, 0.0, materials.SIGHT_PEARL),
        ):
            along, across = (half + grow for half in SIGHT_HALF)
            a_, b_ = (along, across) if along_x else (across, along)
            z = shape.rail_top + lift
            corners = np.array([(x - a_, y, z), (x, y - b_, z), (x + a_, y, z), (x, y + b_, z)])
            quad(mesh, corners, (0.0, 0.0, 1.0), material)


def _legs(mesh: Mesh, shape: TableShape) -> None:
    """Four turned posts under the apron's corners, each on a square foot."""
    outer, leg = shape.outer, 0.075
    for x in (-outer + 0.16, shape.length + outer - 0.16):
        for y in (-outer + 0.16, shape.width + outer - 0.16):
            cylinder(
                mesh,
                (x, y, shape.floor),
                shape.apron_bottom - shape.floor,
                leg,
                leg * 0.75,
                materials.LEG_WOOD,
                20,
            )
            box(
                mesh,
                (x - leg - 0.01, y - leg - 0.01, shape.floor),
                (x + leg + 0.01, y + leg + 0.01, shape.floor + 0.06),
                materials.LEG_WOOD,
            )


def load_table_mesh(path: str | Path) -> Mesh:
    """A user's own table, read with trimesh: metres, table frame, z up, cloth z = 0.

    Vertex or face colours in the file are used when present; otherwise the table
    is drawn in the rail's wood.
    """
    import trimesh  # only for a mesh of one's own (its import alone takes 0.4 s)

    try:
        loaded = trimesh.load_mesh(str(path), process=False)
    except Exception as error:  # trimesh raises many kinds for unreadable files
        raise ValueError(f"{path}: cannot read the table mesh ({error})") from None
    if isinstance(loaded, trimesh.Scene):
        parts = [g for g in loaded.dump() if isinstance(g, trimesh.Trimesh)]
        loaded = trimesh.util.concatenate(parts) if parts else None
    if not isinstance(loaded, trimesh.Trimesh) or len(loaded.faces) == 0:
        raise ValueError(f"{path}: no triangles in the table mesh")
    faces = np.asarray(loaded.faces)
    vertices = np.asarray(loaded.vertices, dtype=np.float64)
    positions = vertices[faces].reshape(-1, 3)
    normals = np.repeat(np.asarray(loaded.face_normals, dtype=np.float64), 3, axis=0)
    mesh = Mesh()
    mesh.add(positions, normals, materials.RAIL_WOOD)
    visual: Any = loaded.visual
    kind = getattr(visual, "kind", None)
    if kind in ("vertex", "face"):
        if kind == "vertex":
            rgb = np.asarray(visual.vertex_colors, dtype=np.float64)[faces].reshape(-1, 4)[:, :3]
        else:
            rgb = np.repeat(np.asarray(visual.face_colors, dtype=np.float64)[:, :3], 3, axis=0)
        mesh.colours = materials.srgb_to_linear(rgb / 255.0)
        mesh.materials[:, 3] = materials.PLAIN
    return mesh
