"""The break from above, as an image: every ball's path, its contacts, start and rest.

The drawing behind `python -m billiards.plot` (billiards.plot, the command). Like the source report's 2D figures: the table seen from above (x to the right,
y up), each ball's path drawn in its colour (stripes dashed with white), a hollow
ring where each ball started and the ball itself where it came to rest, a dot at
each ball-ball contact point and a cross at each cushion (or jaw) contact; white dots
over a path where its ball is in the air (a jump, issue 45). A table
with pockets is drawn with its six holes and the cushions stopping at the mouths
(one without has none); a pocketed ball's path runs into its hole, and the ball is
drawn in the hole, ringed, instead of at rest; a ball that left the table (issue 45)
has its path run off it, dotted, and is not drawn at rest. Drawn with
Pillow at 3x and downsampled with a Lanczos filter, so lines are antialiased.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt
from PIL import Image, ImageDraw, ImageFont

from billiards.record.drop import off_table_end
from billiards.record.pocket_shapes import PocketShapes
from billiards.record.sampling import sample_trajectory
from billiards.record.trajectory import RecordedMotion, Trajectory
from billiards.shell.atomic import atomic_output
from billiards.stage.ball_colors import RGB, STRIPE_WHITE, ball_color, ball_label
from billiards.stage.table_plan import CORNER_JAW_SLOPE, SIDE_JAW_SLOPE

FloatArray = npt.NDArray[np.float64]
Font = ImageFont.FreeTypeFont | ImageFont.ImageFont

DEFAULT_WIDTH = 1600  # px
SUPERSAMPLE = 3  # draw this many times larger, then downsample
# The largest side of a picture, in px: drawn 3 times larger, a 4096 px wide break
# took 0.6 GB and 5 s (8192 px: 2.3 GB, 15 s; 100,000 px was killed at 24 GB).
MAX_SIDE = 4096

# Table furniture, in metres (the playing area is [0, L] x [0, W] between cushion noses).
CUSHION_DEPTH = 0.045
RAIL_DEPTH = 0.095  # wide enough to hold a side pocket's hole (0.127 m behind the nose)
MARGIN = 0.03
STRIPE_DASH = (0.03, 0.02)  # m of colour, m of white along a striped ball's path
# A curved path (RecordedMotion.curved_paths) is drawn from samples this far apart: the
# chords stay within a Delta t^2 / 8 = 6 um of the parabola at mu_s g = 2 m/s^2, below
# a pixel of any top view.
CURVE_SPACING = 0.005  # s
# A ball is drawn in the air where its centre is this share of a radius above the cloth.
FLIGHT_SHARE = 1e-6
FLIGHT_DOT_SPACING = 0.02  # m between the dots over a path in the air

BACKGROUND: RGB = (28, 30, 34)
RAIL: RGB = (96, 56, 30)
CUSHION: RGB = (20, 96, 60)
CLOTH: RGB = (36, 132, 82)
POCKET: RGB = (10, 10, 10)
POCKET_SHELF: RGB = (52, 40, 32)  # the leather around a hole, where the cushion stops
SIGHT: RGB = (232, 220, 190)
INK: RGB = (16, 18, 20)  # outlines under paths and around balls
TEXT: RGB = (236, 236, 236)
MUTED: RGB = (170, 174, 180)
CONTACT: RGB = (255, 255, 255)


@dataclass(frozen=True)
class Layout:
    """Where the table sits in the final image (pixels; y down)."""

    width: int
    height: int
    scale: float  # px per metre
    header: int  # px of title band above the table
    footer: int  # px of legend band below it
    table_size: tuple[float, float]

    @classmethod
    def fit(cls, table_size: tuple[float, float], width_px: int) -> Layout:
        length, width = table_size
        border = CUSHION_DEPTH + RAIL_DEPTH + MARGIN
        scale = width_px / (length + 2 * border)
        header = max(24, round(0.055 * width_px))
        footer = max(16, round(0.03 * width_px))
        height = header + round((width + 2 * border) * scale) + footer
        return cls(
            width=width_px,
            height=height,
            scale=scale,
            header=header,
            footer=footer,
            table_size=table_size,
        )

    def to_pixels(self, x: FloatArray, y: FloatArray, zoom: float = 1.0) -> FloatArray:
        """Table coordinates (m) -> pixel centres (n x 2), in an image `zoom` times larger."""
        border = CUSHION_DEPTH + RAIL_DEPTH + MARGIN
        column = (np.asarray(x) + border) * self.scale
        row = self.header + (self.table_size[1] + border - np.asarray(y)) * self.scale
        return np.stack([column, row], axis=-1) * zoom


def draw_top_view(
    trajectory: Trajectory, width_px: int = DEFAULT_WIDTH, title: str = ""
) -> Image.Image:
    """The break from above: table, paths, contacts, start and rest positions (RGB image).

    Uses the samples at times >= 0 (a film's lead-in before the shot is left out);
    the trajectory's times need not be evenly spaced, so a caller can add a sample at
    every contact to make the corners of the paths exact.
    """
    layout = Layout.fit(trajectory.table_size, width_px)
    canvas = _Canvas(layout, SUPERSAMPLE)
    canvas.table(trajectory.pockets)
    times, positions = _from_the_shot(trajectory)
    for index, ball_id in enumerate(trajectory.ball_ids):
        canvas.path(positions[:, index, :2], ball_id)
    flights = [
        _flights(positions[:, index], trajectory.radius)
        for index in range(len(trajectory.ball_ids))
    ]
    for pieces in flights:
        for piece in pieces:
            canvas.flight(piece, trajectory.radius)
    _mark_contacts(canvas, trajectory, times, positions)
    for index, ball_id in enumerate(trajectory.ball_ids):
        canvas.start_ring(positions[0, index, :2], ball_id, trajectory.radius)
    marks = pocketed_marks(trajectory)
    sunk = {mark.ball_id for mark in marks} | set(left_the_table(trajectory))
    for index, ball_id in enumerate(trajectory.ball_ids):
        if ball_id not in sunk:
            canvas.ball(positions[-1, index, :2], ball_id, trajectory.radius)
    for mark in marks:
        canvas.pocketed(mark, trajectory.radius)
    canvas.header(title or "break", _summary(trajectory, marks, left_the_table(trajectory)))
    canvas.legend(pockets=trajectory.pockets is not None, flight=any(flights))
    return canvas.image.resize((layout.width, layout.height), Image.Resampling.LANCZOS)


@dataclass(frozen=True)
class PocketedMark:
    """Where the picture shows a pocketed ball: in its pocket's hole (the second and
    later balls of one pocket a ball's width further out each, so none hides another)."""

    ball_id: str
    pocket: str
    time: float  # s, when it dropped
    centre: tuple[float, float]  # m, table coordinates of the mark


def pocketed_marks(trajectory: Trajectory) -> list[PocketedMark]:
    """One mark per pocketed ball (an event of kind "pocket"), in the order they dropped."""
    shapes = trajectory.pockets
    length, width = trajectory.table_size
    marks: list[PocketedMark] = []
    for event in sorted(trajectory.events, key=lambda e: e.time):
        if event.kind != "pocket" or not event.balls or event.balls[0] not in trajectory.ball_ids:
            continue
        if event.pocket is None:  # it left the table: no hole holds it
            continue
        ball_id = event.balls[0]
        pocket = event.pocket or ""
        if shapes is not None and pocket in shapes.names:
            x, y, _ = (float(v) for v in shapes.holes[shapes.names.index(pocket)])
        else:  # no hole to put it in: where its path ends
            index = trajectory.ball_ids.index(ball_id)
            x, y = (float(v) for v in trajectory.positions[-1, index, :2])
        # Further balls in the same pocket: outwards, away from the table's middle.
        earlier = sum(mark.pocket == pocket for mark in marks)
        outward = np.array((x - length / 2, y - width / 2))
        outward = np.sign(outward) * (np.abs(outward) > 0.25 * min(length, width))
        norm = float(np.linalg.norm(outward))
        step = outward / norm if norm > 0 else np.zeros(2)
        shift = 2.2 * trajectory.radius * earlier * step
        marks.append(
            PocketedMark(ball_id, pocket, event.time, (x + float(shift[0]), y + float(shift[1])))
        )
    return marks


def _from_the_shot(trajectory: Trajectory) -> tuple[FloatArray, FloatArray]:
    """Samples from t = 0 (inserted by interpolation if the film starts earlier)."""
    times = np.asarray(trajectory.times, dtype=np.float64)
    positions = np.asarray(trajectory.positions, dtype=np.float64)
    if len(times) == 0 or times[0] >= 0 or times[-1] <= 0:
        return times, positions
    after = times > 0
    at_zero = _positions_at(times, positions, 0.0)
    return (
        np.concatenate([[0.0], times[after]]),
        np.concatenate([at_zero[None], positions[after]]),
    )


def _positions_at(times: FloatArray, positions: FloatArray, time: float) -> FloatArray:
    """Every ball's centre (N x 3) at `time`, linear between samples, clamped at the ends."""
    return np.stack(
        [
            np.stack([np.interp(time, times, positions[:, n, k]) for k in range(3)])
            for n in range(positions.shape[1])
        ]
    )


def _mark_contacts(
    canvas: _Canvas, trajectory: Trajectory, times: FloatArray, positions: FloatArray
) -> None:
    """A dot at each ball-ball contact point, a cross at each cushion contact."""
    column = {ball_id: index for index, ball_id in enumerate(trajectory.ball_ids)}
    for event in trajectory.events:
        if len(times) == 0 or event.time < times[0] or event.time > times[-1]:
            continue
        indices = [column[ball] for ball in event.balls if ball in column]
        if not indices:
            continue
        centres = _positions_at(times, positions[:, indices, :], event.time)[:, :2]
        if event.kind == "ball":
            canvas.ball_contact(centres.mean(axis=0), trajectory.radius)
        elif event.kind == "pocket":
            continue  # the ball is drawn in its hole (pocketed_marks)
        else:
            for centre in centres:
                canvas.cushion_contact(centre, trajectory.radius)


def _flights(points: FloatArray, radius: float) -> list[FloatArray]:
    """The stretches of one ball's path (its samples' x, y, z) where it is off the cloth
    (issue 45's jumps): each run of sample-to-sample steps with either end above it, as
    its x, y; none for a ball that never leaves the cloth."""
    above = points[:, 2] > radius * (1.0 + FLIGHT_SHARE)
    steps = above[:-1] | above[1:]
    pieces: list[FloatArray] = []
    start: int | None = None
    for index, flying in enumerate([*steps.tolist(), False]):
        if flying and start is None:
            start = index
        elif not flying and start is not None:
            pieces.append(points[start : index + 1, :2])
            start = None
    return pieces


def left_the_table(trajectory: Trajectory) -> list[str]:
    """The balls that left the table (an event of kind "pocket" with no pocket), in the
    order they left."""
    events = sorted(trajectory.events, key=lambda e: e.time)
    return [e.balls[0] for e in events if e.kind == "pocket" and e.pocket is None and e.balls]


def _summary(
    trajectory: Trajectory, marks: Sequence[PocketedMark] = (), left: Sequence[str] = ()
) -> str:
    ball_contacts = sum(event.kind == "ball" for event in trajectory.events)
    cushion_contacts = sum(event.kind == "cushion" for event in trajectory.events)
    text = (
        f"{len(trajectory.ball_ids)} balls, at rest after {trajectory.rest_time:.2f} s, "
        f"{ball_contacts} ball-ball and {cushion_contacts} cushion contacts"
    )
    if marks:
        names = ", ".join(f"{ball_label(m.ball_id) or m.ball_id} in {m.pocket}" for m in marks)
        text += f"; pocketed: {names}"
    if left:
        text += "; off the table: " + ", ".join(ball_label(ball) or ball for ball in left)
    return text


def _dashes(points: FloatArray, on: float, off: float) -> list[FloatArray]:
    """The pieces of a polyline that lie in the `on` parts of an on/off dash pattern."""
    steps = np.linalg.norm(np.diff(points, axis=0), axis=1)
    distance = np.concatenate([[0.0], np.cumsum(steps)])
    total = float(distance[-1])
    period = on + off
    starts = np.arange(0.0, total, period)
    cuts = np.unique(np.concatenate([distance, starts, np.minimum(starts + on, total)]))
    cut_points = np.stack([np.interp(cuts, distance, points[:, k]) for k in range(2)], axis=1)
    middle = 0.5 * (cuts[:-1] + cuts[1:])
    inside = np.mod(middle, period) < on
    pieces: list[FloatArray] = []
    run_start: int | None = None
    for index, flag in enumerate(inside):
        if flag and run_start is None:
            run_start = index
        if not flag and run_start is not None:
            pieces.append(cut_points[run_start : index + 1])
            run_start = None
    if run_start is not None:
        pieces.append(cut_points[run_start:])
    return pieces


def _font(size: float) -> Font:
    try:
        return ImageFont.load_default(size=max(6, round(size)))
    except (TypeError, OSError):  # Pillow < 10.1 or without FreeType: the small bitmap font
        return ImageFont.load_default()


class _Canvas:
    """A supersampled RGB image with drawing in table coordinates."""

    def __init__(self, layout: Layout, zoom: int) -> None:
        self.layout = layout
        self.zoom = zoom
        self.image = Image.new("RGB", (layout.width * zoom, layout.height * zoom), BACKGROUND)
        self.draw = ImageDraw.Draw(self.image)

    def px(self, point: Sequence[float] | FloatArray) -> tuple[float, float]:
        xy = self.layout.to_pixels(np.asarray(point[0]), np.asarray(point[1]), self.zoom)
        return (float(xy[0]), float(xy[1]))

    def metres(self, length: float) -> float:
        """A length in table metres as supersampled pixels."""
        return length * self.layout.scale * self.zoom

    def points(self, xy: FloatArray) -> list[tuple[float, float]]:
        pixels = self.layout.to_pixels(xy[:, 0], xy[:, 1], self.zoom)
        return [(float(c), float(r)) for c, r in pixels]

    def box(self, lower: Sequence[float], upper: Sequence[float]) -> list[float]:
        (left, bottom), (right, top) = self.px(lower), self.px(upper)
        return [left, top, right, bottom]

    def disc(self, centre: Sequence[float] | FloatArray, radius: float, **style: object) -> None:
        c, r = self.px(centre), self.metres(radius)
        self.draw.ellipse([c[0] - r, c[1] - r, c[0] + r, c[1] + r], **style)  # type: ignore[arg-type]

    # --- the table ---------------------------------------------------------------------

    def table(self, pockets: PocketShapes | None = None) -> None:
        """Rail, cushions, cloth and sights; with `pockets`, the holes and the gaps
        the cushions leave at their mouths (without, no pocket is drawn)."""
        length, width = self.layout.table_size
        outer = CUSHION_DEPTH + RAIL_DEPTH
        self.draw.rounded_rectangle(
            self.box((-outer, -outer), (length + outer, width + outer)),
            radius=self.metres(0.04),
            fill=RAIL,
        )
        self.draw.rectangle(
            self.box(
                (-CUSHION_DEPTH, -CUSHION_DEPTH), (length + CUSHION_DEPTH, width + CUSHION_DEPTH)
            ),
            fill=CUSHION,
        )
        self.draw.rectangle(self.box((0.0, 0.0), (length, width)), fill=CLOTH)
        if pockets is not None:
            for opening in pocket_openings(pockets, (length, width), CUSHION_DEPTH):
                self.draw.polygon(self.points(opening), fill=POCKET_SHELF)
            # Each hole's edge on its capture line, as the film draws it: a ball's
            # path reaches the hole where the physics lets it drop, not before.
            for (x, y, _), radius in zip(pockets.holes, pockets.edge_radii(), strict=True):
                self.disc((x, y), radius, fill=POCKET)
        # Sights (diamonds) on the rails: quarters of a diamond spacing W/4 = L/8.
        sight_line = CUSHION_DEPTH + 0.5 * RAIL_DEPTH
        for k in range(1, 8):
            if k != 4:
                for y in (-sight_line, width + sight_line):
                    self.disc((k * length / 8, y), 0.007, fill=SIGHT)
        for k in range(1, 4):
            for x in (-sight_line, length + sight_line):
                self.disc((x, k * width / 4), 0.007, fill=SIGHT)

    # --- balls and paths -------------------------------------------------------------------

    def path(self, xy: FloatArray, ball_id: str) -> None:
        moved = np.concatenate([[True], np.any(np.diff(xy, axis=0) != 0, axis=1)])
        xy = xy[moved]
        if len(xy) < 2 or np.sum(np.linalg.norm(np.diff(xy, axis=0), axis=1)) < 1e-4:
            return
        look = ball_color(ball_id)
        line = max(2.0, self.metres(0.0055))
        edge = max(1.0, self.metres(0.0014))
        self.draw.line(self.points(xy), fill=INK, width=round(line + 2 * edge), joint="curve")
        if not look.striped:
            self.draw.line(self.points(xy), fill=look.rgb, width=round(line), joint="curve")
            return
        self.draw.line(self.points(xy), fill=STRIPE_WHITE, width=round(line), joint="curve")
        for piece in _dashes(xy, *STRIPE_DASH):
            self.draw.line(self.points(piece), fill=look.rgb, width=round(line), joint="curve")

    def start_ring(self, centre: FloatArray, ball_id: str, radius: float) -> None:
        look = ball_color(ball_id)
        ring = max(2, round(self.metres(0.16 * radius)))
        self.disc(centre, radius * 1.06, outline=INK, width=ring + 2 * self.zoom)
        self.disc(centre, radius, outline=look.rgb, width=ring)

    def ball(self, centre: FloatArray, ball_id: str, radius: float) -> None:
        look = ball_color(ball_id)
        c, r = self.px(centre), self.metres(radius)
        bounds = [c[0] - r, c[1] - r, c[0] + r, c[1] + r]
        self.draw.ellipse(bounds, fill=look.rgb)
        if look.striped:  # white caps above and below a band of colour
            self.draw.chord(bounds, 215, 325, fill=STRIPE_WHITE)
            self.draw.chord(bounds, 35, 145, fill=STRIPE_WHITE)
        self.draw.ellipse(bounds, outline=INK, width=max(1, round(0.07 * r)))
        label = ball_label(ball_id)
        if not label:
            return
        spot = 0.52 * r
        self.draw.ellipse([c[0] - spot, c[1] - spot, c[0] + spot, c[1] + spot], fill=STRIPE_WHITE)
        font = _font(0.78 * r if len(label) < 3 else 1.4 * r / len(label))
        self.draw.text(c, label, fill=INK, font=font, anchor="mm")

    def pocketed(self, mark: PocketedMark, radius: float) -> None:
        """The ball in its pocket, ringed in white: it dropped there."""
        centre = np.array(mark.centre)
        self.disc(centre, 1.45 * radius, fill=INK)
        self.disc(
            centre, 1.35 * radius, outline=CONTACT, width=max(1, round(self.metres(0.2 * radius)))
        )
        self.ball(centre, mark.ball_id, radius)

    def flight(self, xy: FloatArray, radius: float) -> None:
        """Dots along a stretch of path in the air, over the path's colour."""
        steps = np.linalg.norm(np.diff(xy, axis=0), axis=1)
        along = np.concatenate([[0.0], np.cumsum(steps)])
        for distance in np.arange(0.0, float(along[-1]) + 1e-12, FLIGHT_DOT_SPACING):
            centre = np.array([np.interp(distance, along, xy[:, k]) for k in range(2)])
            self.disc(centre, 0.22 * radius, fill=INK)
            self.disc(centre, 0.14 * radius, fill=CONTACT)

    def ball_contact(self, point: FloatArray, radius: float) -> None:
        self.disc(point, 0.3 * radius, fill=INK)
        self.disc(point, 0.2 * radius, fill=CONTACT)

    def cushion_contact(self, centre: FloatArray, radius: float) -> None:
        c, arm = self.px(centre), self.metres(0.3 * radius)
        for width, colour in (
            (self.metres(0.17 * radius), INK),
            (self.metres(0.08 * radius), CONTACT),
        ):
            for sign in (1, -1):
                self.draw.line(
                    [(c[0] - arm, c[1] - sign * arm), (c[0] + arm, c[1] + sign * arm)],
                    fill=colour,
                    width=max(1, round(width)),
                )

    # --- words -------------------------------------------------------------------------

    def header(self, title: str, summary: str) -> None:
        band = self.layout.header * self.zoom
        left = self.metres(MARGIN)
        self.draw.text((left, 0.38 * band), title, fill=TEXT, font=_font(0.42 * band), anchor="lm")
        self.draw.text(
            (left, 0.8 * band), summary, fill=MUTED, font=_font(0.26 * band), anchor="lm"
        )

    def legend(self, pockets: bool = False, flight: bool = False) -> None:
        band = self.layout.footer * self.zoom
        row = self.image.height - 0.5 * band
        font = _font(0.5 * band)
        unit = 0.5 * band  # size of a legend symbol, px
        x = self.metres(MARGIN)
        entries: tuple[str, ...] = ("start", "rest", "ball-ball contact", "cushion contact")
        entries += ("pocketed",) if pockets else ()
        entries += ("path (stripes dashed)",)
        entries += ("in the air",) if flight else ()
        for name in entries:
            self._legend_symbol(name, x + unit, row, unit)
            x += 2.4 * unit
            self.draw.text((x, row), name, fill=MUTED, font=font, anchor="lm")
            x += self.draw.textlength(name, font=font) + 2.0 * unit

    def _legend_symbol(self, name: str, x: float, y: float, size: float) -> None:
        r = 0.8 * size
        box = [x - r, y - r, x + r, y + r]
        if name == "start":
            self.draw.ellipse(box, outline=TEXT, width=max(1, round(0.25 * r)))
        elif name == "rest":
            self.draw.ellipse(box, fill=TEXT)
        elif name == "pocketed":
            self.draw.ellipse(box, outline=CONTACT, width=max(1, round(0.2 * r)))
            inner = 0.6 * r
            self.draw.ellipse([x - inner, y - inner, x + inner, y + inner], fill=TEXT)
        elif name == "in the air":
            for step in (-1.0, 0.0, 1.0):
                dot = 0.25 * r
                centre = x + step * r
                self.draw.ellipse([centre - dot, y - dot, centre + dot, y + dot], fill=CONTACT)
        elif name == "ball-ball contact":
            self.draw.ellipse([x - 0.4 * r, y - 0.4 * r, x + 0.4 * r, y + 0.4 * r], fill=CONTACT)
        elif name == "cushion contact":
            for sign in (1, -1):
                self.draw.line(
                    [(x - 0.5 * r, y - sign * 0.5 * r), (x + 0.5 * r, y + sign * 0.5 * r)],
                    fill=CONTACT,
                    width=max(1, round(0.25 * r)),
                )
        else:
            self.draw.line(
                [(x - 1.4 * r, y), (x + 1.4 * r, y)], fill=TEXT, width=max(1, round(0.3 * r))
            )


def pocket_openings(
    pockets: PocketShapes, table_size: tuple[float, float], depth: float
) -> list[FloatArray]:
    """Each pocket's gap in the cushions (K, 2), from one mouth back through the
    cushions' depth to the other mouth: the corner's jaws run back at 45 degrees, a
    side pocket's lean away from it."""
    length, width = table_size
    openings = []
    for (x, y, _), mouth in zip(pockets.holes, pockets.mouths, strict=True):
        hole = np.array((x, y))
        backs = []
        same_wall = bool(np.any(np.abs(mouth[0] - mouth[1]) < 1e-9))  # a side pocket
        for point in mouth:
            # The nose line the mouth lies on, and outward from the table across it.
            along_y = abs(point[0]) < 1e-9 or abs(point[0] - length) < 1e-9
            outward = (
                np.array((-1.0 if point[0] < length / 2 else 1.0, 0.0))
                if along_y
                else np.array((0.0, -1.0 if point[1] < width / 2 else 1.0))
            )
            along = np.array((0.0, 1.0)) if along_y else np.array((1.0, 0.0))
            towards = along * np.sign((hole - point) @ along)
            slope = SIDE_JAW_SLOPE if same_wall else CORNER_JAW_SLOPE
            backs.append(point + depth * outward + slope * depth * towards)
        polygon = [mouth[0], backs[0]]
        if not same_wall:  # a corner: its gap reaches the band's corner behind the hole
            outward_corner = np.sign(hole - np.array((length / 2, width / 2)))
            polygon.append(hole + depth * outward_corner)
        polygon += [backs[1], mouth[1]]
        openings.append(np.array(polygon))
    return openings


def sample_path_bends(motion: RecordedMotion, table_size: tuple[float, float]) -> Trajectory:
    """A trajectory sampled at t = 0, at every time a path may bend, and at rest.

    Between contacts every rolling path is a straight line, so these samples draw each
    path exactly, corners included, and put every contact mark at its true place; the
    spin model's curved paths add samples dense enough to draw them.
    """
    end = motion.rest_time
    breaks = np.asarray(motion.path_breaks(), dtype=np.float64)
    times = np.unique(np.concatenate([[0.0, end], breaks[(breaks > 0) & (breaks < end)]]))
    # A ball that left the table flies on over the rail (record.drop.fly_off_table).
    times = np.union1d(times, [max(end, off_table_end(motion))])
    # The spin model's paths curve between breaks (parabolas while sliding).
    if motion.curved_paths:
        times = np.union1d(times, np.arange(0.0, end, CURVE_SPACING))
    return sample_trajectory(motion, times, table_size, turn=False)


# The picture formats a top view can be written in, by file name suffix (Pillow's names).
PICTURE_FORMATS = {".png": "PNG", ".jpg": "JPEG", ".jpeg": "JPEG", ".webp": "WEBP"}


def save_picture(image: Image.Image, path: str | Path) -> None:
    """Write the picture whole or not at all, in the format its suffix names."""
    target = Path(path)
    kind = PICTURE_FORMATS[target.suffix.lower()]
    with atomic_output(target, target.suffix) as temporary:
        if kind == "PNG":
            image.save(temporary, format=kind, optimize=True)
        else:
            image.convert("RGB").save(temporary, format=kind, quality=92)
