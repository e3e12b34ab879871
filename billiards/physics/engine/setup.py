"""What a run needs, as plain numbers and arrays: the physics never sees a scene."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from billiards.physics.numerics.arrays import FloatArray
from billiards.physics.pockets import PocketTable

# Every default is the seed's number, at home in billiards.rules.seed (as the scene reader's).
from billiards.rules import seed


@dataclass(frozen=True)
class Setup:
    """Everything the physics needs, as plain numbers and arrays (no scene types)."""

    positions: FloatArray  # (N, 2) m
    velocities: FloatArray  # (N, 2) m/s
    masses: FloatArray  # (N,) kg
    radius: float = seed.RADIUS  # m
    table_size: tuple[float, float] = seed.TABLE_SIZE  # (L, W) m between cushion noses
    decel: float = seed.ROLLING_FRICTION * seed.GRAVITY  # m/s^2, mu g
    restitution: float = seed.RESTITUTION  # ball-ball
    retention: float = seed.RETENTION  # cushion: share of kinetic energy kept
    max_time: float = seed.MAX_TIME  # s
    max_events: int = seed.MAX_EVENTS
    ball_law: str = "frictionless"  # a name in physics.laws.BALL_LAWS
    cushion_law: str = "mirror"  # a name in physics.laws.CUSHION_LAWS
    # The spin model (billiards.physics.spin.motion); the rolling model ignores these.
    model: str = "rolling"  # a name in physics.motion_law.MOTION_LAWS
    spins: FloatArray | None = None  # (N, 3) rad/s, world axes; None: no spin
    slide_decel: float = seed.SLIDING_FRICTION * seed.GRAVITY  # m/s^2, mu_s g
    spin_decel: float = 5 * seed.SPINNING_FRICTION * seed.GRAVITY / (2 * seed.RADIUS)  # rad/s^2
    cushion_restitution: float = seed.CUSHION_RESTITUTION  # han2005's e, mathavan2010's e_e
    cushion_friction: float = seed.CUSHION_FRICTION  # han2005's mu, mathavan2010's mu_w
    cushion_height: float = seed.CUSHION_HEIGHT  # m, the cushion nose's height (both)
    # mu_s itself, for a law that needs the cloth's grip during an impact (mathavan2010).
    sliding_friction: float = seed.SLIDING_FRICTION
    # mathavan2010_ev's v_c: its e_e = cushion_restitution / sqrt(1 + (v_n / v_c)^4).
    cushion_restitution_speed: float = seed.MATHAVAN_EV_SPEED  # m/s
    # The ball law "frictional": mu = a + b exp(-c s) at the slip speed s (m/s).
    ball_friction: tuple[float, float, float] = (
        seed.BALL_FRICTION_A,
        seed.BALL_FRICTION_B,
        seed.BALL_FRICTION_C,
    )
    # Six pockets (billiards.physics.pockets.pocket_table); None: closed cushions.
    pockets: PocketTable | None = None
    # Off the cloth (issue 45; the compiled loop's spin model only): how fast each ball
    # is driven into the bed at t = 0 (N,) m/s, a jump stroke's v sin(elevation)
    # (billiards.scene.stroke.Strike.drive_down), the bed throwing it up at e_t of that;
    # None: no ball ever leaves the cloth (and nothing below is read).
    drives: FloatArray | None = None
    gravity: float = seed.GRAVITY  # m/s^2, a flying ball's
    table_restitution: float = seed.TABLE_RESTITUTION  # the bed's e_t (its mu_t: mu_s)
    settle_height: float = seed.SETTLE_HEIGHT  # m: a bounce rising less ends the hopping

    @classmethod
    def of(
        cls,
        positions: npt.ArrayLike,
        velocities: npt.ArrayLike | None = None,
        masses: npt.ArrayLike | None = None,
        *,
        spins: npt.ArrayLike | None = None,
        drives: npt.ArrayLike | None = None,
        **constants: Any,
    ) -> Setup:
        """A setup of these balls with the seed's defaults (the fields') for every constant
        not given: at rest unless `velocities`, each of mass seed.MASS unless `masses`."""
        placed = np.asarray(positions, dtype=np.float64).reshape(-1, 2)
        count = len(placed)
        velocities = np.zeros((count, 2)) if velocities is None else velocities
        masses = np.full(count, seed.MASS) if masses is None else masses
        return cls(
            positions=placed,
            velocities=np.asarray(velocities, dtype=np.float64).reshape(count, 2),
            masses=np.asarray(masses, dtype=np.float64).reshape(count),
            spins=None if spins is None else np.asarray(spins, dtype=np.float64).reshape(count, 3),
            drives=None if drives is None else np.asarray(drives, dtype=np.float64).reshape(count),
            **constants,
        )

    @property
    def bounds(self) -> FloatArray:
        """The lines a ball centre cannot cross: (r, L - r, r, W - r)."""
        length, width = self.table_size
        r = self.radius
        return np.array([r, length - r, r, width - r])
