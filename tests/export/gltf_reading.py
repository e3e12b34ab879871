"""Reading an exported glTF back as a viewer would: its accessors, and each animated
node's translation, rotation and scale at any time (glTF 2.0's interpolation rules,
evaluated in float64 from the file's float32 data)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pygltflib as gl

FloatArray = npt.NDArray[np.float64]
TYPE_WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
COMPONENTS = {gl.FLOAT: np.float32, gl.UNSIGNED_SHORT: np.uint16, gl.UNSIGNED_INT: np.uint32}


def accessor_array(document: gl.GLTF2, index: int) -> npt.NDArray[np.generic]:
    accessor = document.accessors[index]
    assert accessor.bufferView is not None
    view = document.bufferViews[accessor.bufferView]
    blob = document.binary_blob()
    assert blob is not None
    dtype = np.dtype(COMPONENTS[accessor.componentType])
    width = TYPE_WIDTH[accessor.type]
    start = (view.byteOffset or 0) + (accessor.byteOffset or 0)
    data = np.frombuffer(blob, dtype=dtype, count=accessor.count * width, offset=start)
    return data.reshape(accessor.count, width) if width > 1 else data


@dataclass(frozen=True)
class Channel:
    times: FloatArray  # (K,) from float32
    output: FloatArray  # (K, w) or (3K, w) for CUBICSPLINE
    interpolation: str

    def at(self, time: float) -> FloatArray:
        times = self.times
        cubic = self.interpolation == "CUBICSPLINE"
        values = self.output[1::3] if cubic else self.output
        if time <= times[0]:
            return values[0]
        if time >= times[-1]:
            return values[-1]
        k = int(np.searchsorted(times, time, side="right")) - 1
        h = times[k + 1] - times[k]
        s = (time - times[k]) / h
        if self.interpolation == "STEP":
            return values[k]
        if cubic:
            p0, m0 = self.output[3 * k + 1], self.output[3 * k + 2] * h
            p1, m1 = self.output[3 * k + 4], self.output[3 * k + 3] * h
            return (
                (2 * s**3 - 3 * s**2 + 1) * p0
                + (s**3 - 2 * s**2 + s) * m0
                + (-2 * s**3 + 3 * s**2) * p1
                + (s**3 - s**2) * m1
            )
        first, second = values[k], values[k + 1]
        if len(first) == 4:  # quaternions: slerp along the shorter arc
            dot = float(np.dot(first, second))
            if dot < 0:
                second, dot = -second, -dot
            angle = np.arccos(min(dot, 1.0))
            if angle < 1e-9:
                return first
            mixed = (np.sin((1 - s) * angle) * first + np.sin(s * angle) * second) / np.sin(angle)
            return mixed / np.linalg.norm(mixed)
        return first + (second - first) * s


def read_document(path: str | Path) -> gl.GLTF2:
    document = gl.GLTF2().load(str(path))
    assert document is not None
    if str(path).endswith(".gltf"):
        document.convert_buffers(gl.BufferFormat.BINARYBLOB)
    return document


def node_channels(document: gl.GLTF2) -> dict[str, dict[str, Channel]]:
    """Each animated node's channels, by node name and path."""
    animation = document.animations[0]
    found: dict[str, dict[str, Channel]] = {}
    for channel in animation.channels:
        sampler = animation.samplers[channel.sampler]
        name = document.nodes[channel.target.node].name
        found.setdefault(name, {})[channel.target.path] = Channel(
            np.asarray(accessor_array(document, sampler.input), dtype=np.float64),
            np.asarray(accessor_array(document, sampler.output), dtype=np.float64),
            sampler.interpolation,
        )
    return found
