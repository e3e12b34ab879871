"""The glTF 2.0 document of a shot: table, numbered balls, their animation, cameras.

Written with pygltflib (the Khronos schema as dataclasses, and .glb packing), so the
structure is checked by its types and this module only lays out the binary data.

Frame: glTF's, +Y up, metres, the table's centre at the origin with its cloth at
y = 0: a physics point (x, y, z) is at (x - L/2, z, W/2 - y). The balls' body frame
turns the same way, so a ball's rotation key is its physics quaternion with its
vector part turned likewise (textures: billiards.stage.textures' mapping).
"""

from __future__ import annotations

import base64
import io
import json
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt
import pygltflib as gl
from PIL import Image

from billiards.export.tracks import BallTrack, Tracks
from billiards.record.pocket_shapes import PocketShapes
from billiards.stage.cameras import CameraPose
from billiards.stage.meshes import Mesh
from billiards.stage.table import build_table
from billiards.stage.table_plan import TableShape
from billiards.stage.textures import ball_texture

FloatArray = npt.NDArray[np.float64]

# Physics frame to glTF frame: x stays, z becomes y, y becomes -z (a turn about x).
TURN = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])
SPHERE_SEGMENTS = (48, 24)  # a ball's longitudes and latitudes
BALL_ROUGHNESS = 0.12  # polished phenolic resin
CAMERA_ASPECT = 16 / 9  # the film's
NEAR, FAR = 0.01, 100.0  # m
TOP_MARGIN = 0.05  # m round the rails in the top camera's view


@dataclass(frozen=True)
class ShotCamera:
    """A film camera to export: its name and its pose (physics frame)."""

    name: str
    pose: CameraPose
    start: float  # s: when the film cuts to it


@dataclass(frozen=True)
class CameraPath:
    """The film's camera over the shot (its director's cuts, eases and orbits), sampled:
    a pose (physics frame) at each time."""

    times: FloatArray  # (K,) s, increasing
    poses: tuple[CameraPose, ...]


@dataclass
class _Builder:
    """The document being built and its one binary buffer."""

    document: gl.GLTF2 = field(default_factory=gl.GLTF2)
    blob: bytearray = field(default_factory=bytearray)

    def view(self, data: bytes, target: int | None = None) -> int:
        while len(self.blob) % 4:
            self.blob.append(0)
        self.document.bufferViews.append(
            gl.BufferView(buffer=0, byteOffset=len(self.blob), byteLength=len(data), target=target)
        )
        self.blob.extend(data)
        return len(self.document.bufferViews) - 1

    def accessor(
        self,
        array: npt.NDArray[Any],
        kind: str,
        target: int | None = None,
        bounds: bool = False,
    ) -> int:
        """An accessor over `array` (float32 or uint16/uint32 indices), in its own view."""
        if array.dtype == np.float32:
            component = gl.FLOAT
        elif array.dtype == np.uint16:
            component = gl.UNSIGNED_SHORT
        else:
            component = gl.UNSIGNED_INT
        data = np.ascontiguousarray(array)
        accessor = gl.Accessor(
            bufferView=self.view(data.tobytes(), target),
            componentType=component,
            count=len(data),
            type=kind,
        )
        if bounds:
            flat = data.reshape(len(data), -1)
            accessor.min = [float(v) for v in flat.min(axis=0)]
            accessor.max = [float(v) for v in flat.max(axis=0)]
        self.document.accessors.append(accessor)
        return len(self.document.accessors) - 1

    def node(self, node: gl.Node) -> int:
        self.document.nodes.append(node)
        return len(self.document.nodes) - 1


def to_gltf_points(points: FloatArray, table_size: tuple[float, float]) -> FloatArray:
    """Physics-frame points (..., 3) in glTF's frame (table centred, +Y up)."""
    length, width = table_size
    centred = np.asarray(points, dtype=np.float64) - np.array([length / 2, width / 2, 0.0])
    return np.asarray(centred @ TURN.T)


def to_gltf_vectors(vectors: FloatArray) -> FloatArray:
    """Physics-frame directions or velocities (..., 3) in glTF's frame."""
    return np.asarray(np.asarray(vectors, dtype=np.float64) @ TURN.T)


def to_gltf_rotations(quaternions: FloatArray) -> FloatArray:
    """Physics-frame unit quaternions (..., 4) x, y, z, w as glTF-frame ones."""
    q = np.asarray(quaternions, dtype=np.float64)
    return np.concatenate([to_gltf_vectors(q[..., :3]), q[..., 3:]], axis=-1)


def matrix_quaternion(matrix: FloatArray) -> tuple[float, float, float, float]:
    """A rotation matrix (3, 3) as a unit quaternion x, y, z, w (Shepperd's method)."""
    m = matrix
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    if trace > 0:
        s = 2 * math.sqrt(trace + 1)
        q = ((m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, s / 4)
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = 2 * math.sqrt(1 + m[0, 0] - m[1, 1] - m[2, 2])
        q = (s / 4, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s, (m[2, 1] - m[1, 2]) / s)
    elif m[1, 1] > m[2, 2]:
        s = 2 * math.sqrt(1 + m[1, 1] - m[0, 0] - m[2, 2])
        q = ((m[0, 1] + m[1, 0]) / s, s / 4, (m[1, 2] + m[2, 1]) / s, (m[0, 2] - m[2, 0]) / s)
    else:
        s = 2 * math.sqrt(1 + m[2, 2] - m[0, 0] - m[1, 1])
        q = ((m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, s / 4, (m[1, 0] - m[0, 1]) / s)
    norm = math.sqrt(sum(c * c for c in q))
    x, y, z, w = (c / norm for c in q)
    return (x, y, z, w)


# --- meshes and materials ---------------------------------------------------------------


def _roughness(material: tuple[float, ...]) -> float:
    """PBR roughness from the film's Blinn-Phong highlight (specular, shininess):
    Walter et al.'s sqrt(2 / (n + 2)); a surface with no highlight is fully rough."""
    specular, shininess = material[0], material[1]
    if specular <= 0:
        return 1.0
    return float(min(max(math.sqrt(2 / (shininess + 2)), 0.05), 1.0))


def _add_table(builder: _Builder, tracks: Tracks, pockets: PocketShapes | None) -> int:
    """The film's table (billiards.stage.table), one primitive per material."""
    length, width = tracks.table_size
    mesh = build_table(TableShape(length, width), pockets)
    _wind_along_normals(mesh)
    keys = np.hstack([mesh.colours, mesh.materials])
    looks, which = np.unique(keys.round(6), axis=0, return_inverse=True)
    which = which.reshape(-1)
    primitives = []
    document = builder.document
    for look_index, look in enumerate(looks):
        corners = np.flatnonzero(which == look_index)
        positions = to_gltf_points(mesh.positions[corners], tracks.table_size).astype(np.float32)
        normals = to_gltf_vectors(mesh.normals[corners]).astype(np.float32)
        normals /= np.linalg.norm(normals, axis=1, keepdims=True)
        vertices = np.hstack([positions, normals])
        unique, indices = np.unique(vertices, axis=0, return_inverse=True)
        index_type = np.uint16 if len(unique) < 65536 else np.uint32
        attributes = gl.Attributes(
            POSITION=builder.accessor(
                np.ascontiguousarray(unique[:, :3]), gl.VEC3, gl.ARRAY_BUFFER, bounds=True
            ),
            NORMAL=builder.accessor(np.ascontiguousarray(unique[:, 3:]), gl.VEC3, gl.ARRAY_BUFFER),
        )
        colour = [float(c) for c in look[:3]]
        emissive = float(look[5])
        document.materials.append(
            gl.Material(
                name=f"table-{look_index}",
                pbrMetallicRoughness=gl.PbrMetallicRoughness(
                    baseColorFactor=[*colour, 1.0],
                    metallicFactor=0.0,
                    roughnessFactor=_roughness(tuple(look[3:])),
                ),
                emissiveFactor=[c * emissive for c in colour] if emissive > 0 else None,
            )
        )
        primitives.append(
            gl.Primitive(
                attributes=attributes,
                indices=builder.accessor(
                    indices.reshape(-1).astype(index_type), gl.SCALAR, gl.ELEMENT_ARRAY_BUFFER
                ),
                material=len(document.materials) - 1,
            )
        )
    document.meshes.append(gl.Mesh(name="table", primitives=primitives))
    return builder.node(gl.Node(name="table", mesh=len(document.meshes) - 1))


def _wind_along_normals(mesh: Mesh) -> None:
    """Turn each triangle (in place) to wind counter-clockwise about its normal: the
    film draws both sides, but glTF's materials are single-sided by default, and a
    viewer culls the faces it sees from behind."""
    corners = mesh.positions.reshape(-1, 3, 3)
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normal = mesh.normals.reshape(-1, 3, 3).mean(axis=1)
    backwards = np.einsum("ij,ij->i", cross, normal) < 0
    for array in (mesh.positions, mesh.normals, mesh.colours, mesh.materials):
        triangles = array.reshape(len(corners), 3, -1)
        triangles[backwards] = triangles[backwards][:, ::-1]


def sphere(radius: float) -> tuple[FloatArray, FloatArray, FloatArray, npt.NDArray[np.uint16]]:
    """A UV sphere in glTF's frame: positions, normals, texture coordinates (V, 2) and
    triangle indices, the texture mapping billiards.stage.textures paints for."""
    longitudes, latitudes = SPHERE_SEGMENTS
    u = np.arange(longitudes + 1) / longitudes
    v = np.arange(latitudes + 1) / latitudes
    lon = 2 * math.pi * u[None, :]
    lat = math.pi * (v[:, None] - 0.5)
    body = np.stack(
        np.broadcast_arrays(np.cos(lat) * np.cos(lon), np.sin(lat), np.cos(lat) * np.sin(lon)),
        axis=-1,
    ).reshape(-1, 3)
    normals = to_gltf_vectors(body)
    uv = np.stack(np.broadcast_arrays(u[None, :], v[:, None]), axis=-1).reshape(-1, 2)
    row = longitudes + 1
    triangles = []
    for j in range(latitudes):
        for i in range(longitudes):
            a, b = j * row + i, j * row + i + 1
            c, d = a + row, b + row
            triangles += [(a, b, d), (a, d, c)]
    faces = np.array(triangles)
    # Wind each triangle counter-clockwise seen from outside (glTF's front faces).
    corners = normals[faces]
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    inward = np.einsum("ij,ij->i", cross, corners.mean(axis=1)) < 0
    faces[inward] = faces[inward][:, ::-1]
    area = np.linalg.norm(cross, axis=1) > 1e-12  # drop the poles' degenerate triangles
    return normals * radius, normals, uv, faces[area].reshape(-1).astype(np.uint16)


def _add_ball_meshes(builder: _Builder, tracks: Tracks, texture_width: int) -> list[int]:
    """A mesh per ball: the shared sphere, its own numbered texture."""
    document = builder.document
    positions, normals, uv, indices = sphere(tracks.radius)
    attributes = gl.Attributes(
        POSITION=builder.accessor(positions.astype(np.float32), gl.VEC3, gl.ARRAY_BUFFER, True),
        NORMAL=builder.accessor(normals.astype(np.float32), gl.VEC3, gl.ARRAY_BUFFER),
        TEXCOORD_0=builder.accessor(uv.astype(np.float32), gl.VEC2, gl.ARRAY_BUFFER),
    )
    index_accessor = builder.accessor(indices, gl.SCALAR, gl.ELEMENT_ARRAY_BUFFER)
    document.samplers.append(
        gl.Sampler(
            magFilter=gl.LINEAR,
            minFilter=gl.LINEAR_MIPMAP_LINEAR,
            wrapS=gl.REPEAT,
            wrapT=gl.CLAMP_TO_EDGE,
        )
    )
    meshes = []
    for ball in tracks.ball_ids:
        png = io.BytesIO()
        Image.fromarray(np.asarray(ball_texture(ball, texture_width))[..., :3]).save(
            png, format="PNG"
        )
        document.images.append(
            gl.Image(
                name=f"ball-{ball}", mimeType="image/png", bufferView=builder.view(png.getvalue())
            )
        )
        document.textures.append(gl.Texture(sampler=0, source=len(document.images) - 1))
        document.materials.append(
            gl.Material(
                name=f"ball-{ball}",
                pbrMetallicRoughness=gl.PbrMetallicRoughness(
                    baseColorTexture=gl.TextureInfo(index=len(document.textures) - 1),
                    metallicFactor=0.0,
                    roughnessFactor=BALL_ROUGHNESS,
                ),
            )
        )
        primitive = gl.Primitive(
            attributes=attributes, indices=index_accessor, material=len(document.materials) - 1
        )
        document.meshes.append(gl.Mesh(name=f"ball-{ball}", primitives=[primitive]))
        meshes.append(len(document.meshes) - 1)
    return meshes


# --- the animation -----------------------------------------------------------------------


def float32_keys(
    times: FloatArray, *rows: FloatArray | None
) -> tuple[npt.NDArray[np.float32], list[FloatArray | None]]:
    """Key times as float32, strictly increasing as glTF requires: keys whose times
    round to the same float32 are merged (the first one's in-tangent, the last's value
    and out-tangent: rows given as (in, value, out) for cubic keys, else values)."""
    stored = np.asarray(times, dtype=np.float32)
    last = np.ones(len(stored), dtype=bool)
    last[:-1] = stored[1:] != stored[:-1]
    first = np.ones(len(stored), dtype=bool)
    first[1:] = stored[1:] != stored[:-1]
    merged: list[FloatArray | None] = []
    for position, row in enumerate(rows):
        if row is None:
            merged.append(None)
        elif len(rows) == 3 and position == 0:
            merged.append(row[first])
        else:
            merged.append(row[last])
    return stored[last], merged


def _add_channels(
    builder: _Builder, track: BallTrack, node: int, table_size: tuple[float, float]
) -> tuple[list[gl.AnimationSampler], list[gl.AnimationChannel]]:
    samplers: list[gl.AnimationSampler] = []
    channels: list[gl.AnimationChannel] = []

    def add(
        path: str, times: npt.NDArray[np.float32], output: FloatArray, how: str, kind: str
    ) -> None:
        samplers.append(
            gl.AnimationSampler(
                input=builder.accessor(times, gl.SCALAR, bounds=True),
                output=builder.accessor(output.astype(np.float32), kind),
                interpolation=how,
            )
        )
        channels.append(
            gl.AnimationChannel(
                sampler=len(samplers) - 1, target=gl.AnimationChannelTarget(node=node, path=path)
            )
        )

    values = to_gltf_points(track.values, table_size)
    if track.in_tangents is None or track.out_tangents is None:
        times, (values_kept,) = float32_keys(track.times, values)
        assert values_kept is not None
        add("translation", times, values_kept, gl.ANIM_LINEAR, gl.VEC3)
    else:
        times, (in_t, kept, out_t) = float32_keys(
            track.times,
            to_gltf_vectors(track.in_tangents),
            values,
            to_gltf_vectors(track.out_tangents),
        )
        assert in_t is not None and kept is not None and out_t is not None
        # CUBICSPLINE output: per key its in-tangent, value, out-tangent.
        add(
            "translation",
            times,
            np.stack([in_t, kept, out_t], axis=1).reshape(-1, 3),
            gl.ANIM_CUBICSPLINE,
            gl.VEC3,
        )
    rotation_times, (rotations,) = float32_keys(
        track.rotation_times, to_gltf_rotations(track.rotations)
    )
    assert rotations is not None
    rotations = rotations / np.linalg.norm(rotations, axis=1, keepdims=True)
    add("rotation", rotation_times, rotations, gl.ANIM_LINEAR, gl.VEC4)
    if track.hidden_from is not None:
        hide = np.array([0.0, track.hidden_from], dtype=np.float32)
        add("scale", hide, np.array([[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]]), gl.ANIM_STEP, gl.VEC3)
    return samplers, channels


# --- cameras -----------------------------------------------------------------------------


def _add_cameras(builder: _Builder, tracks: Tracks, shots: Sequence[ShotCamera]) -> list[int]:
    """The film's cameras (perspective, at their poses), and a top view (orthographic)."""
    document = builder.document
    nodes = []
    for shot in shots:
        document.cameras.append(
            gl.Camera(
                name=shot.name,
                type=gl.PERSPECTIVE,
                perspective=gl.Perspective(
                    yfov=math.radians(shot.pose.fov),
                    aspectRatio=CAMERA_ASPECT,
                    znear=NEAR,
                    zfar=FAR,
                ),
            )
        )
        eye = to_gltf_points(np.array([shot.pose.eye]), tracks.table_size)[0]
        turn = TURN @ shot.pose.orientation()
        nodes.append(
            builder.node(
                gl.Node(
                    name=f"camera-{shot.name}",
                    camera=len(document.cameras) - 1,
                    translation=[float(c) for c in eye],
                    rotation=list(matrix_quaternion(turn)),
                    extras={"camera": shot.name, "start": shot.start},
                )
            )
        )
    half_x, half_y = top_view_half_extent(tracks.table_size)
    document.cameras.append(
        gl.Camera(
            name="top",
            type=gl.ORTHOGRAPHIC,
            orthographic=gl.Orthographic(xmag=half_x, ymag=half_y, znear=NEAR, zfar=FAR),
        )
    )
    down = math.sqrt(0.5)
    nodes.append(
        builder.node(
            gl.Node(
                name="camera-top",
                camera=len(document.cameras) - 1,
                translation=[0.0, 3.0, 0.0],
                rotation=[-down, 0.0, 0.0, down],  # looking down, +y of the table up
                extras={"camera": "top", "half_extent": [half_x, half_y]},
            )
        )
    )
    return nodes


def _add_director(
    builder: _Builder, tracks: Tracks, path: CameraPath
) -> tuple[int, list[gl.AnimationSampler], list[gl.AnimationChannel]]:
    """A camera that follows the film's camera: LINEAR translation and rotation keys
    (its field of view stays the first shot's: core glTF cannot animate it)."""
    document = builder.document
    first = path.poses[0]
    document.cameras.append(
        gl.Camera(
            name="film",
            type=gl.PERSPECTIVE,
            perspective=gl.Perspective(
                yfov=math.radians(first.fov), aspectRatio=CAMERA_ASPECT, znear=NEAR, zfar=FAR
            ),
        )
    )
    eyes = to_gltf_points(np.array([pose.eye for pose in path.poses]), tracks.table_size)
    turns = np.array([matrix_quaternion(TURN @ pose.orientation()) for pose in path.poses])
    for k in range(1, len(turns)):  # neighbours on the same side: the short way round
        if np.dot(turns[k - 1], turns[k]) < 0:
            turns[k] = -turns[k]
    node = builder.node(
        gl.Node(
            name="camera-film",
            camera=len(document.cameras) - 1,
            translation=[float(c) for c in eyes[0]],
            rotation=[float(c) for c in turns[0]],
            extras={"camera": "film", "fovs": sorted({pose.fov for pose in path.poses})},
        )
    )
    samplers = []
    channels = []
    for target, values, kind in (("translation", eyes, gl.VEC3), ("rotation", turns, gl.VEC4)):
        times, (kept,) = float32_keys(path.times, values)
        assert kept is not None
        samplers.append(
            gl.AnimationSampler(
                input=builder.accessor(times, gl.SCALAR, bounds=True),
                output=builder.accessor(kept.astype(np.float32), kind),
                interpolation=gl.ANIM_LINEAR,
            )
        )
        channels.append(
            gl.AnimationChannel(
                sampler=len(samplers) - 1,
                target=gl.AnimationChannelTarget(node=node, path=target),
            )
        )
    return node, samplers, channels


def top_view_half_extent(table_size: tuple[float, float]) -> tuple[float, float]:
    """Half the width and height (m) the top camera shows: the table, rails, a margin."""
    outer = TableShape(*table_size).outer + TOP_MARGIN
    return table_size[0] / 2 + outer, table_size[1] / 2 + outer


# --- the document ------------------------------------------------------------------------


def build_document(
    tracks: Tracks,
    *,
    events: Sequence[dict[str, Any]],
    pockets: PocketShapes | None,
    shots: Sequence[ShotCamera],
    extras: dict[str, Any],
    texture_width: int = 512,
    director: CameraPath | None = None,
) -> gl.GLTF2:
    """The whole glTF document of a shot, its binary data set as its blob."""
    builder = _Builder()
    document = builder.document
    document.asset = gl.Asset(version="2.0", generator="billiards.export")
    table = _add_table(builder, tracks, pockets)
    meshes = _add_ball_meshes(builder, tracks, texture_width)
    balls = []
    samplers: list[gl.AnimationSampler] = []
    channels: list[gl.AnimationChannel] = []
    for mesh, track in zip(meshes, tracks.balls, strict=True):
        start = to_gltf_points(track.values[:1], tracks.table_size)[0]
        node = builder.node(
            gl.Node(
                name=f"ball-{track.ball}",
                mesh=mesh,
                translation=[float(c) for c in start],
                extras={"ball": track.ball},
            )
        )
        balls.append(node)
        more_samplers, more_channels = _add_channels(builder, track, node, tracks.table_size)
        for channel in more_channels:
            channel.sampler += len(samplers)
        samplers += more_samplers
        channels += more_channels
    cameras = _add_cameras(builder, tracks, shots)
    if director is not None:
        node, more_samplers, more_channels = _add_director(builder, tracks, director)
        for channel in more_channels:
            channel.sampler += len(samplers)
        samplers += more_samplers
        channels += more_channels
        cameras.append(node)
    document.animations.append(
        gl.Animation(
            name="shot",
            samplers=samplers,
            channels=channels,
            extras={"events": list(events), "duration": tracks.end},
        )
    )
    document.scenes.append(gl.Scene(name="shot", nodes=[table, *balls, *cameras], extras=extras))
    document.scene = 0
    document.buffers.append(gl.Buffer(byteLength=len(builder.blob)))
    document.set_binary_blob(bytes(builder.blob))
    return document


def glb_bytes(document: gl.GLTF2) -> bytes:
    """The document as a binary .glb file."""
    chunks = document.save_to_bytes()
    return b"".join(chunks)


def gltf_text(document: gl.GLTF2) -> str:
    """The document as one .gltf JSON file, its buffer embedded as a base64 data URI."""
    blob = document.binary_blob() or b""
    record = json.loads(document.to_json())
    record["buffers"] = [
        {
            "byteLength": len(blob),
            "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode(),
        }
    ]
    return json.dumps(record, separators=(",", ":"))
