"""What a run needs, as plain numbers and arrays: the physics never sees a scene."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from billiards.physics.pockets import PocketTable

FloatArray = npt.NDArray[np.float64]

# The seed report's numbers (its table 2.1), the defaults of every Setup.
RADIUS = 0.0286  # m
MASS = 0.165  # kg, an object ball
TABLE_SIZE = (2.13, 1.065)  # m between cushion noses
GRAVITY = 9.81  # m/s^2
ROLLING_FRICTION = 0.01  # mu: a rolling ball slows at mu g
RESTITUTION = 1.0  # ball-ball, 1 = elastic
RETENTION = 0.75  # share of kinetic energy a cushion keeps
SLIDING_FRICTION = 0.2  # mu_s: a sliding ball's contact point slips against mu_s g
# mu_sp, a plain number (pooltool's u_sp = 10/9 * 2/5 R, a length there, evaluated at
# R = 0.0286 m): the vertical spin decays at 5 mu_sp g / (2R) rad/s^2, so, with mu_sp
# fixed, as 1/R when the radius changes (docs/spin.md, Defaults).
SPINNING_FRICTION = 0.0127
# Han 2005 cushions (the spin model's cushion_law "han2005"; pooltool's defaults for e
# and mu): the nose at 63.5% of the ball's diameter, the WPA's specification.
CUSHION_RESTITUTION = 0.85
CUSHION_FRICTION = 0.2
CUSHION_HEIGHT = 0.635 * 2 * RADIUS  # m above the cloth
MAX_TIME = 120.0  # s
MAX_EVENTS = 100_000
# The motion models a Setup may name (billiards.scene.MODELS reads exactly these).
MODELS = ("rolling", "spin")


@dataclass(frozen=True)
class Setup:
    """Everything the physics needs, as plain numbers and arrays (no scene types)."""

    positions: FloatArray  # (N, 2) m
    velocities: FloatArray  # (N, 2) m/s
    masses: FloatArray  # (N,) kg
    radius: float  # m
    table_size: tuple[float, float]  # (L, W) m between cushion noses
    decel: float  # m/s^2, mu g
    restitution: float  # ball-ball
    retention: float  # cushion: share of kinetic energy kept
    max_time: float  # s
    max_events: int
    ball_law: str = "frictionless"  # a name in physics.laws.BALL_LAWS
    cushion_law: str = "mirror"  # a name in physics.laws.CUSHION_LAWS
    # The spin model (billiards.physics.spin_motion); the rolling model ignores these.
    model: str = "rolling"  # one of MODELS
    spins: FloatArray | None = None  # (N, 3) rad/s, world axes; None: no spin
    slide_decel: float = SLIDING_FRICTION * GRAVITY  # m/s^2, mu_s g
    spin_decel: float = 5 * SPINNING_FRICTION * GRAVITY / (2 * RADIUS)  # rad/s^2
    cushion_restitution: float = CUSHION_RESTITUTION  # han2005's e
    cushion_friction: float = CUSHION_FRICTION  # han2005's mu
    cushion_height: float = CUSHION_HEIGHT  # m, han2005's nose height
    # Six pockets (billiards.physics.pockets.pocket_table); None: closed cushions.
    pockets: PocketTable | None = None

    @classmethod
    def of(
        cls,
        positions: npt.ArrayLike,
        velocities: npt.ArrayLike | None = None,
        masses: npt.ArrayLike | None = None,
        *,
        radius: float = RADIUS,
        table_size: tuple[float, float] = TABLE_SIZE,
        decel: float = ROLLING_FRICTION * GRAVITY,
        restitution: float = RESTITUTION,
        retention: float = RETENTION,
        max_time: float = MAX_TIME,
        max_events: int = MAX_EVENTS,
        ball_law: str = "frictionless",
        cushion_law: str = "mirror",
        model: str = "rolling",
        spins: npt.ArrayLike | None = None,
        slide_decel: float = SLIDING_FRICTION * GRAVITY,
        spin_decel: float = 5 * SPINNING_FRICTION * GRAVITY / (2 * RADIUS),
        pockets: PocketTable | None = None,
    ) -> Setup:
        """A setup of these balls with the seed's defaults for everything not given:
        at rest unless `velocities`, each of mass MASS unless `masses`."""
        placed = np.asarray(positions, dtype=np.float64).reshape(-1, 2)
        count = len(placed)
        return cls(
            positions=placed,
            velocities=np.zeros((count, 2))
            if velocities is None
            else np.asarray(velocities, dtype=np.float64).reshape(count, 2),
            masses=np.full(count, MASS)
            if masses is None
            else np.asarray(masses, dtype=np.float64).reshape(count),
            radius=radius,
            table_size=table_size,
            decel=decel,
            restitution=restitution,
            retention=retention,
            max_time=max_time,
            max_events=max_events,
            ball_law=ball_law,
            cushion_law=cushion_law,
            model=model,
            spins=None if spins is None else np.asarray(spins, dtype=np.float64).reshape(count, 3),
            slide_decel=slide_decel,
            spin_decel=spin_decel,
            pockets=pockets,
        )

    @property
    def bounds(self) -> FloatArray:
        """The lines a ball centre cannot cross: (r, L - r, r, W - r)."""
        length, width = self.table_size
        r = self.radius
        return np.array([r, length - r, r, width - r])
