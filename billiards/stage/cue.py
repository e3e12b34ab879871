"""The cue in the film: its shape (a lathe mesh in numpy) and where it is at each moment.

The stick lies along the stroke's line (billiards.record.trajectory.CueStrike): its axis
passes the struck ball's centre at the tip offset (side, height) r, as
billiards.scene.stroke models the hit, along c = cos(el) d - sin(el) z. It addresses
the ball, draws back, pauses, and comes through so that its tip meets the ball's
surface at t = 0 at the cue's speed (the instant the ball leaves), follows through
at the speed the hit leaves it, holds, and is drawn away out of the picture.

Drawn only: nothing here feeds the motion. A cue at the stroke's own elevation
would pass through the rail behind a ball near it, so the drawing tilts it up as a
player must (`drawn_elevation`), never below the stroke's elevation. No GL here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from billiards.record.trajectory import CueStrike
from billiards.rules import seed
from billiards.stage.materials import Material, linear_rgb
from billiards.stage.meshes import Mesh
from billiards.stage.table_plan import TableShape

FloatArray = npt.NDArray[np.float64]

# The stick, from the tip's face (0) to the butt's end: a 58 in (1.47 m) pool cue.
# (distance from the tip's face in m, radius in m) rings, each section one material.
TIP = Material(linear_rgb("#3d6f9c"), specular=0.05, shininess=8.0)  # chalked leather
FERRULE = Material(linear_rgb("#efece2"), specular=0.6, shininess=90.0)
SHAFT = Material(linear_rgb("#dcc293"), specular=0.35, shininess=60.0)  # maple
COLLAR = Material(linear_rgb("#c9c4b8"), specular=0.9, shininess=120.0)  # the joint
FOREARM = Material(linear_rgb("#4a2412"), specular=0.5, shininess=70.0)  # dark wood
WRAP = Material(linear_rgb("#141414"), specular=0.08, shininess=10.0)  # linen
BUTT_CAP = Material(linear_rgb("#0a0a0a"), specular=0.5, shininess=60.0)
# (start, end, radius at start, radius at end, material) along the stick, m
SECTIONS: tuple[tuple[float, float, float, float, Material], ...] = (
    (0.000, 0.006, 0.0062, 0.0064, TIP),
    (0.006, 0.031, 0.0064, 0.0065, FERRULE),
    (0.031, 0.735, 0.0065, 0.0102, SHAFT),  # the taper, 13 mm to 20.5 mm
    (0.735, 0.755, 0.0104, 0.0104, COLLAR),
    (0.755, 1.010, 0.0106, 0.0128, FOREARM),
    (1.010, 1.260, 0.0128, 0.0136, WRAP),
    (1.260, 1.450, 0.0136, 0.0148, FOREARM),
    (1.450, 1.470, 0.0148, 0.0146, BUTT_CAP),
)
CUE_LENGTH = SECTIONS[-1][1]
RING_SEGMENTS = 24

# The stroke's timing (s) and lengths (m).
ADDRESS_GAP = 0.02  # the tip this far from the ball while the player addresses it
BACKSWING_TIME = 0.3  # drawing back
PAUSE = 0.1  # at the back of the stroke
FOLLOW_HOLD = 0.35  # after the follow-through, before it is drawn away
WITHDRAW_TIME = 0.6  # drawn back and up out of the picture
WITHDRAW_DISTANCE = 1.6  # m along its axis
RAIL_CLEARANCE = 0.004  # m the stick's underside keeps above the rail's top


def backswing(speed: float) -> float:
    """m the tip is drawn back from the ball: longer for a harder stroke."""
    return min(0.08 + 0.025 * speed, 0.3)


def follow_through(speed: float) -> float:
    """m the tip goes on past where it met the ball."""
    return min(0.05 + 0.02 * speed, 0.22)


def speed_after(strike: CueStrike) -> float:
    """m/s the cue keeps after an elastic hit on the ball (TP A-30's e = 1), its
    share along the line through the centres: V (M - m_eff) / (M + m_eff) with the
    seed ball's effective mass m / (1 + (5/2) b^2 / r^2) at the offset b."""
    side, height = strike.tip
    effective = seed.MASS / (1.0 + 2.5 * (side * side + height * height))
    return strike.speed * (seed.STICK_MASS - effective) / (seed.STICK_MASS + effective)


def cue_mesh() -> Mesh:
    """The stick along local +x from its tip's face (x = 0) to the butt (CUE_LENGTH),
    round the x axis; triangles wound counter-clockwise seen from outside, with smooth
    normals on the sides and flat end caps."""
    mesh = Mesh()
    angles = np.linspace(0.0, 2 * math.pi, RING_SEGMENTS + 1)
    ring = np.stack([np.zeros_like(angles), np.cos(angles), np.sin(angles)], axis=1)
    for start, end, r0, r1, material in SECTIONS:
        low = ring * r0 + np.array([start, 0.0, 0.0])
        high = ring * r1 + np.array([end, 0.0, 0.0])
        # Seen from outside (+radial), x along and the angle turning: (low k, high k,
        # low k+1) turns counter-clockwise.
        triangles = np.stack(
            [low[:-1], high[:-1], low[1:], low[1:], high[:-1], high[1:]], axis=1
        ).reshape(-1, 3, 3)
        slope = (r0 - r1) / (end - start)  # outward normal tilts towards the thinner end
        radial = triangles.copy()
        radial[..., 0] = 0.0
        radial /= np.linalg.norm(radial, axis=-1, keepdims=True)
        normals = radial + np.array([slope, 0.0, 0.0])
        normals /= np.linalg.norm(normals, axis=-1, keepdims=True)
        mesh.add(triangles.reshape(-1, 3), normals.reshape(-1, 3), material)
    for x, radius, facing, material in (
        (0.0, SECTIONS[0][2], -1.0, TIP),
        (CUE_LENGTH, SECTIONS[-1][3], 1.0, BUTT_CAP),
    ):
        rim = ring * radius + np.array([x, 0.0, 0.0])
        centre = np.array([x, 0.0, 0.0])
        fan = [(centre, rim[k], rim[k + 1]) for k in range(RING_SEGMENTS)]
        triangles = np.array(fan)
        if facing < 0:  # seen from -x the ring turns the other way
            triangles = triangles[:, ::-1]
        mesh.add(
            triangles.reshape(-1, 3),
            np.tile((facing, 0.0, 0.0), (triangles.size // 3, 1)),
            material,
        )
    return mesh


@dataclass(frozen=True)
class CuePlacement:
    """Where the stick is: its tip's face centre (m) and its unit axis `forward` (the
    way it strikes, from butt to tip); `right` and `up` complete its frame."""

    tip: FloatArray
    forward: FloatArray
    right: FloatArray
    up: FloatArray

    def model_matrix(self) -> npt.NDArray[np.float32]:
        """Local (x from the tip back along the stick, y, z round it) to world, for
        `v_row @ M` (the layout the shaders' raw uploads take, as pyrr's)."""
        matrix = np.eye(4)
        matrix[0, :3] = -self.forward
        matrix[1, :3] = self.right
        matrix[2, :3] = self.up
        matrix[3, :3] = self.tip
        return matrix.astype(np.float32)

    def bounds(self) -> FloatArray:
        """The 8 corners (8, 3) of a box holding the whole stick, m."""
        butt = self.tip - CUE_LENGTH * self.forward
        thickness = max(radius for _, _, _, radius, _ in SECTIONS) + 0.002
        low = np.minimum(self.tip, butt) - thickness
        high = np.maximum(self.tip, butt) + thickness
        return np.array(
            [
                (x, y, z)
                for x in (low[0], high[0])
                for y in (low[1], high[1])
                for z in (low[2], high[2])
            ]
        )


@dataclass(frozen=True)
class CueStroke:
    """The cue's motion through one strike: `placement(t)` at any film time."""

    strike: CueStrike
    centre: FloatArray  # m, the struck ball's centre before it leaves
    radius: float  # m, the ball's
    elevation: float  # degrees, as drawn (drawn_elevation)

    @classmethod
    def of(
        cls, strike: CueStrike, centre: FloatArray, radius: float, table: TableShape
    ) -> CueStroke:
        elevation = drawn_elevation(strike, centre, radius, table)
        return cls(strike, np.asarray(centre, dtype=np.float64), radius, elevation)

    def frame(self) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The stick's unit axis (towards the ball), its right and its up."""
        direction = math.radians(self.strike.direction)
        elevation = math.radians(self.elevation)
        level = np.array([math.cos(direction), math.sin(direction), 0.0])
        forward = math.cos(elevation) * level - math.sin(elevation) * np.array([0.0, 0.0, 1.0])
        right = np.cross(level, np.array([0.0, 0.0, 1.0]))  # d x z, the shooter's right
        up = np.cross(right, forward)
        return forward, right, up

    def contact(self) -> FloatArray:
        """Where the tip meets the ball: on its surface, where the axis (the centre
        offset by (side right + height up) r) enters it."""
        forward, right, up = self.frame()
        side, height = self.strike.tip
        offset = self.radius * (side * right + height * up)
        depth = self.radius * math.sqrt(max(1.0 - side * side - height * height, 0.0))
        return np.asarray(self.centre + offset - depth * forward)

    def gap(self, time: float) -> float | None:
        """m from the tip's face back to the contact point along the axis at film time
        `time` (negative: past it, following through), or None once drawn away."""
        speed = self.strike.speed
        back = backswing(speed)
        # Forward stroke: a cubic from rest at `back` to 0 at the cue's speed, in 2 back / V
        # (no overshoot while V T <= 3 back).
        forward_time = 2.0 * back / speed
        start_forward = -forward_time
        start_pause = start_forward - PAUSE
        start_back = start_pause - BACKSWING_TIME
        if time <= start_back:
            return ADDRESS_GAP
        if time <= start_pause:
            share = (time - start_back) / BACKSWING_TIME
            eased = share * share * (3.0 - 2.0 * share)
            return ADDRESS_GAP + (back - ADDRESS_GAP) * eased
        if time <= start_forward:
            return back
        if time <= 0.0:
            s = (time - start_forward) / forward_time  # Hermite: g(0)=back, g'(0)=0,
            h00 = 2 * s**3 - 3 * s**2 + 1  # g(1) = 0, g'(1) = -V T
            h11 = s**3 - s**2
            return back * h00 - h11 * speed * forward_time
        after = speed_after(self.strike)
        reach = self.follow_reach()
        follow_time = 2.0 * reach / max(after, 1e-3)  # decelerating from `after` to rest
        if time <= follow_time:
            s = time / follow_time
            return -reach * (2 * s - s * s)
        hold_end = follow_time + FOLLOW_HOLD
        if time <= hold_end:
            return -reach
        share = (time - hold_end) / WITHDRAW_TIME
        if share >= 1.0:
            return None
        return -reach + WITHDRAW_DISTANCE * share * share * (3.0 - 2.0 * share)

    def follow_reach(self) -> float:
        """m the tip follows through: follow_through's, or less for a raised cue, whose
        tip stops on the cloth (its face's rim at the cloth)."""
        reach = follow_through(self.strike.speed)
        drop = math.sin(math.radians(self.elevation))
        if drop > 0:
            above = float(self.contact()[2]) - SECTIONS[0][2] * math.cos(
                math.radians(self.elevation)
            )
            reach = min(reach, max(above, 0.0) / drop)
        return reach

    def placement(self, time: float) -> CuePlacement | None:
        """Where the stick is at film time `time` (None: not in the picture)."""
        gap = self.gap(time)
        if gap is None:
            return None
        forward, right, up = self.frame()
        tip = self.contact() - gap * forward
        return CuePlacement(tip, forward, right, up)


def drawn_elevation(
    strike: CueStrike, centre: FloatArray, radius: float, table: TableShape
) -> float:
    """Degrees: the stroke's elevation, or more where the stick must rise to pass over
    the rail behind the ball (its underside RAIL_CLEARANCE above the rail's top where
    it crosses the cushion's nose, with the tip drawn back its whole backswing)."""
    direction = math.radians(strike.direction)
    back_x, back_y = -math.cos(direction), -math.sin(direction)
    x, y = float(centre[0]), float(centre[1])
    length, width = table.length, table.width
    # How far back along the line, on the cloth, the cushion's nose is.
    reaches = []
    if back_x < 0:
        reaches.append(x / -back_x)
    if back_x > 0:
        reaches.append((length - x) / back_x)
    if back_y < 0:
        reaches.append(y / -back_y)
    if back_y > 0:
        reaches.append((width - y) / back_y)
    to_nose = min(reaches) - radius - backswing(strike.speed)
    thickness = max(r for _, _, _, r, _ in SECTIONS)
    height = radius * (1.0 + strike.tip[1])  # the tip's height over the cloth
    rise = table.rail_top + RAIL_CLEARANCE + thickness - height
    needed = math.degrees(math.atan2(rise, max(to_nose, 0.05)))
    return max(strike.elevation, min(needed, 60.0))
