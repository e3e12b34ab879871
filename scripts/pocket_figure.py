"""The labelled top view of a corner and a side pocket in docs/explanation/pockets.md.

    python scripts/pocket_figure.py [--out docs/pockets.png]

Draws the geometry billiards.physics.pockets builds for the default table (WPA
mouths, 8 mm jaws, r = 28.6 mm): the cushion noses, the jaws, the lines a ball's
centre cannot cross (r inside the noses, r + rho around each jaw), the capture lines
and the holes, with a ball dropping and one striking a jaw.
"""

from __future__ import annotations

import argparse
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.axes import Axes
from matplotlib.patches import Circle

from billiards.physics.pockets import PocketTable, pocket_table
from billiards.record.pocket_shapes import PocketShapes
from billiards.rules.seed import RADIUS, TABLE_SIZE


def draw(
    axes: Axes, pockets: PocketTable, pocket: int, view: tuple[float, float, float, float]
) -> None:
    left, right, bottom, top = view
    r = pockets.radius
    length, width = TABLE_SIZE
    # The cloth and the cushions (beyond the noses), the hole.
    axes.add_patch(plt.Rectangle((left, bottom), right - left, top - bottom, color="#8d6e63"))
    axes.add_patch(plt.Rectangle((0.0, 0.0), length, width, color="#e8f1e8"))
    shapes = PocketShapes.of(pockets)
    # The hole as the film and the plot draw it: its edge on the capture line.
    hole_x, hole_y, _ = shapes.holes[pocket]
    hole_radius = shapes.edge_radii()[pocket]
    axes.add_patch(Circle((hole_x, hole_y), hole_radius, color="#555555", zorder=1))
    # Cushion noses: the segments between the mouths, drawn on their nose lines.
    lines = ((0, 0.0), (0, length), (1, 0.0), (1, width))
    for wall, ((axis, nose), segments) in enumerate(zip(lines, pockets.segments, strict=True)):
        for low, high in segments:
            if axis == 0:
                axes.plot([nose, nose], [low, high], color="#1b5e20", lw=3, zorder=3)
                centre = nose + (r if wall == 0 else -r)
                axes.plot([centre, centre], [low, high], color="#1b5e20", lw=1, ls="--", zorder=3)
            else:
                axes.plot([low, high], [nose, nose], color="#1b5e20", lw=3, zorder=3)
                centre = nose + (r if wall == 2 else -r)
                axes.plot([low, high], [centre, centre], color="#1b5e20", lw=1, ls="--", zorder=3)
    for jaw in pockets.jaws:
        axes.add_patch(Circle(tuple(jaw), pockets.jaw_radius, color="#1b5e20", zorder=4))
        axes.add_patch(
            Circle(tuple(jaw), pockets.jaw_reach, fill=False, ls="--", color="#1b5e20", zorder=4)
        )
    # The capture line through the pocket's two jaw centres.
    first, second = pockets.jaws[pockets.jaw_pocket == pocket]
    axes.plot(*zip(first, second, strict=True), color="#c62828", lw=2, zorder=5)
    mouth = shapes.mouths[pocket]
    axes.plot(*zip(*mouth, strict=True), color="#1565c0", lw=1, ls=":", zorder=5)
    axes.set_xlim(left, right)
    axes.set_ylim(bottom, top)
    axes.set_aspect("equal")
    axes.set_xlabel("x (m)")
    axes.set_ylabel("y (m)")
    axes.set_title(f"{pockets.names[pocket]} pocket")


def draw_corner(corner: Axes, pockets: PocketTable) -> None:
    """The head-left corner pocket, its parts labelled, a ball heading in."""
    mouths = PocketShapes.of(pockets).mouths
    r = RADIUS
    draw(corner, pockets, 0, (-0.07, 0.21, -0.07, 0.21))
    a = mouths[0][0][0]
    corner.annotate("cushion nose", (0.19, 0.0), (0.15, -0.062), arrowprops={"arrowstyle": "->"})
    corner.annotate(
        "centre line: r inside the nose", (0.17, r), (0.09, 0.09), arrowprops={"arrowstyle": "->"}
    )
    corner.annotate(
        "jaw: radius rho, centre\nrho behind the nose end",
        tuple(pockets.jaws[0]),
        (0.1, -0.04),
        arrowprops={"arrowstyle": "->"},
    )
    corner.annotate(
        "jaw reach r + rho",
        (
            pockets.jaws[0][0] + pockets.jaw_reach * math.cos(2.0),
            pockets.jaws[0][1] + pockets.jaw_reach * math.sin(2.0),
        ),
        (0.1, 0.135),
        arrowprops={"arrowstyle": "->"},
    )
    corner.annotate(
        "capture line\n(through the jaw centres)",
        (0.03, 0.042),
        (-0.065, 0.17),
        color="#c62828",
        arrowprops={"arrowstyle": "->", "color": "#c62828"},
    )
    corner.annotate(
        f"mouth w_c = {mouths[0][0][0] * math.sqrt(2) * 1000:.1f} mm\n(nose end to nose end)",
        (a / 2, a / 2),
        (0.1, 0.045),
        color="#1565c0",
        arrowprops={"arrowstyle": "->", "color": "#1565c0"},
    )
    corner.text(-0.02, -0.02, "hole", color="white")
    corner.text(-0.065, 0.115, "cushion\nand rail", color="white")
    corner.add_patch(Circle((0.16, 0.165), r, fill=False, color="black", zorder=6))
    corner.plot([0.16], [0.165], "k.", zorder=6)
    corner.annotate(
        "a ball heading in", (0.16, 0.165), (0.04, 0.195), arrowprops={"arrowstyle": "->"}
    )


def draw_side(side: Axes, pockets: PocketTable) -> None:
    """A side pocket, a ball striking its jaw."""
    mouths = PocketShapes.of(pockets).mouths
    r = RADIUS
    length = TABLE_SIZE[0]
    draw(side, pockets, 1, (length / 2 - 0.17, length / 2 + 0.17, -0.13, 0.13))
    jaw = pockets.jaws[3]
    struck = (
        jaw[0] + pockets.jaw_reach * math.cos(2.2),
        jaw[1] + pockets.jaw_reach * math.sin(2.2),
    )
    side.add_patch(Circle(struck, r, fill=False, color="black", zorder=6))
    side.plot([struck[0]], [struck[1]], "k.", zorder=6)
    side.annotate(
        "a ball striking the jaw:\nits centre on the jaw's reach",
        struck,
        (length / 2 + 0.0, 0.09),
        arrowprops={"arrowstyle": "->"},
    )
    side.annotate(
        "capture line y = -rho",
        (length / 2, -pockets.jaw_radius),
        (length / 2 - 0.16, -0.1),
        color="#c62828",
        arrowprops={"arrowstyle": "->", "color": "#c62828"},
    )
    side.annotate(
        f"mouth w_s = {(mouths[1][1][0] - mouths[1][0][0]) * 1000:.1f} mm",
        (length / 2, 0.0),
        (length / 2 - 0.16, 0.06),
        color="#1565c0",
        arrowprops={"arrowstyle": "->", "color": "#1565c0"},
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default="docs/pockets.png")
    args = parser.parse_args()
    pockets = pocket_table(TABLE_SIZE, RADIUS)
    figure, (corner, side) = plt.subplots(1, 2, figsize=(12, 5.6))
    draw_corner(corner, pockets)
    draw_side(side, pockets)
    figure.suptitle(
        "Pockets seen from above (the default table): a ball's centre bounces off the dashed "
        "lines and drops across the red one",
        fontsize=11,
    )
    figure.tight_layout()
    figure.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
