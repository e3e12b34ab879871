"""The pockets as drawn: the holes, the mouths and the jaws a pocketed table has, laid
out from the physics' pockets (the film, the glTF file and the top view draw them)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from billiards.rules.pocket_rule import corner_reach, pocket_places

if TYPE_CHECKING:  # the renderer loads the trajectory, never the physics' geometry
    from billiards.physics.pockets import PocketTable

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class PocketShapes:
    """A pocketed table's shapes, for drawing (billiards.physics.pockets.PocketTable).

    Table coordinates in m (the cushion noses along x = 0, L and y = 0, W)."""

    names: tuple[str, ...]  # (P,) e.g. "foot-left", "side-top"
    holes: FloatArray  # (P, 3) each hole's centre x, y and its radius
    mouths: FloatArray  # (P, 2, 2) the two points where the cushion noses end
    jaws: FloatArray  # (J, 2) centres of the noses' rounded ends
    jaw_radius: float  # m

    @classmethod
    def of(cls, pockets: PocketTable) -> PocketShapes:
        """The shapes of the physics' pockets: its jaws, and the holes and mouths laid
        out from the same places and widths (billiards.rules.pocket_rule.pocket_places). A
        corner's hole is centred on its corner, w_c / 2 across; a side's, w_s / 2
        behind the nose, as wide."""
        a = corner_reach(pockets.corner_width)
        half = pockets.side_width / 2.0
        holes: list[tuple[float, float, float]] = []
        mouths: list[tuple[tuple[float, float], tuple[float, float]]] = []
        for x, y, sx, sy in pocket_places(pockets.table_size):
            if sx:
                holes.append((x, y, pockets.corner_width / 2.0))
                mouths.append(((x + sx * a, y), (x, y + sy * a)))
            else:
                holes.append((x, y - sy * half, half))
                mouths.append(((x - half, y), (x + half, y)))
        return cls(
            names=pockets.names,
            holes=np.array(holes),
            mouths=np.array(mouths),
            jaws=pockets.jaws,
            jaw_radius=pockets.jaw_radius,
        )

    def edge_radii(self) -> FloatArray:
        """(P,) m: each hole's radius as drawn, the distance from its centre to its
        capture line (the line through the pocket's two jaw centres, where a ball's
        centre drops: billiards.physics.pockets), so that the hole's edge is where the
        physics lets a ball fall, not a few millimetres past it."""
        first, second = self.jaws[0::2], self.jaws[1::2]  # two jaws per pocket, in order
        along = second - first
        normal = np.column_stack((-along[:, 1], along[:, 0]))
        normal /= np.linalg.norm(normal, axis=1, keepdims=True)
        offset = self.holes[:, :2] - first
        return np.abs(np.einsum("ij,ij->i", offset, normal))
