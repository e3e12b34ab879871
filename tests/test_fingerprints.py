"""Pinned fingerprints of every shipped scene, by method (as Box2D pins a scene's hash).

Each digest hashes, as exact float bytes, the final positions, the rest time and the
whole contact log (time, kind, balls, impact speed) of one run. Rerunning in one process
cannot catch a change that alters every break alike; these pins do. A change that alters
a break must change its pin here on purpose, saying why in the commit.
"""

from __future__ import annotations

import hashlib
import struct

import numpy as np
import pytest

from billiards.physics.result import SimulationResult
from billiards.scene import default_scene_path, load_scene
from billiards.simulation import simulate_scene

# (scene, method, dt or None for the scene's own) -> sha256 prefix of the run.
PINS = {
    ("bank_shot", "event", None): "44636ac62c1881632c68eded1ebbabb1",
    ("bank_shot", "exact", None): "44636ac62c1881632c68eded1ebbabb1",
    ("bank_shot", "exact", 1 / 30): "44636ac62c1881632c68eded1ebbabb1",
    ("bank_shot", "exact", 1 / 1000): "44636ac62c1881632c68eded1ebbabb1",
    ("bank_shot", "naive", None): "39447b026377cb3812aa33bd34185add",
    ("break", "event", None): "0c9d640ea03145a9de45b1d9df4b2f75",
    ("break", "exact", None): "0c9d640ea03145a9de45b1d9df4b2f75",
    ("break", "exact", 1 / 30): "0c9d640ea03145a9de45b1d9df4b2f75",
    ("break", "exact", 1 / 1000): "0c9d640ea03145a9de45b1d9df4b2f75",
    ("break", "naive", None): "ffd9aa855b2311a9b2232da272adf779",
    ("hard_break", "event", None): "3bc2a21253441cf87e947f7b2d5b1729",
    ("hard_break", "exact", None): "3bc2a21253441cf87e947f7b2d5b1729",
    ("hard_break", "exact", 1 / 30): "3bc2a21253441cf87e947f7b2d5b1729",
    ("hard_break", "exact", 1 / 1000): "3bc2a21253441cf87e947f7b2d5b1729",
    ("newtons_cradle", "event", None): "fb8c3797a56ffad78ae38af0332cb4d4",
    ("newtons_cradle", "exact", None): "fb8c3797a56ffad78ae38af0332cb4d4",
    ("newtons_cradle", "exact", 1 / 30): "fb8c3797a56ffad78ae38af0332cb4d4",
    ("newtons_cradle", "exact", 1 / 1000): "fb8c3797a56ffad78ae38af0332cb4d4",
    ("newtons_cradle", "naive", None): "c2de540ca0edf094d09bce80ccf79a8d",
    # The spin model's scenes.
    ("draw_shot", "event", None): "aac7d3f8cd4f4a49580c26b6ac655915",
    ("draw_shot", "exact", None): "aac7d3f8cd4f4a49580c26b6ac655915",
    ("draw_shot", "exact", 1 / 30): "aac7d3f8cd4f4a49580c26b6ac655915",
    ("draw_shot", "exact", 1 / 1000): "aac7d3f8cd4f4a49580c26b6ac655915",
    ("draw_shot", "naive", None): "242e7808fc45a4d66b5030f519365771",
    ("english_bank", "event", None): "58fc2f604ae0e060d708269e072dbcb2",
    ("english_bank", "exact", None): "58fc2f604ae0e060d708269e072dbcb2",
    ("english_bank", "exact", 1 / 30): "58fc2f604ae0e060d708269e072dbcb2",
    ("english_bank", "exact", 1 / 1000): "58fc2f604ae0e060d708269e072dbcb2",
    ("english_bank", "naive", None): "64ec29098f2ed126e52edba602679fd6",
    ("follow_shot", "event", None): "08cd6de5f3884671c6c030647af10538",
    ("follow_shot", "exact", None): "08cd6de5f3884671c6c030647af10538",
    ("follow_shot", "exact", 1 / 30): "08cd6de5f3884671c6c030647af10538",
    ("follow_shot", "exact", 1 / 1000): "08cd6de5f3884671c6c030647af10538",
    ("follow_shot", "naive", None): "e1673ee22b12b7f231b4d9a982c16508",
    ("spin_break", "event", None): "367b919d86d088a67214448bd203355f",
    ("spin_break", "exact", None): "367b919d86d088a67214448bd203355f",
    ("spin_break", "exact", 1 / 30): "367b919d86d088a67214448bd203355f",
    ("spin_break", "exact", 1 / 1000): "367b919d86d088a67214448bd203355f",
    ("spin_break", "naive", None): "4dd51e85f7bb0cac04fd77582404a06d",
    ("stun_shot", "event", None): "07ff9d10d5ef509e04e82f1d4425b3b0",
    ("stun_shot", "exact", None): "07ff9d10d5ef509e04e82f1d4425b3b0",
    ("stun_shot", "exact", 1 / 30): "07ff9d10d5ef509e04e82f1d4425b3b0",
    ("stun_shot", "exact", 1 / 1000): "07ff9d10d5ef509e04e82f1d4425b3b0",
    ("stun_shot", "naive", None): "e41053fa9bf86ea1530eb2d9694f4f09",
    # Tables with pockets.
    ("pocket_shot", "event", None): "485e16d58972fb40c3a8b832604098c9",
    ("pocket_shot", "exact", None): "485e16d58972fb40c3a8b832604098c9",
    ("pocket_shot", "exact", 1 / 30): "485e16d58972fb40c3a8b832604098c9",
    ("pocket_shot", "exact", 1 / 1000): "485e16d58972fb40c3a8b832604098c9",
    ("pocket_shot", "naive", None): "afec0d2de49644da137e0909d44d5c15",
    ("pool_break", "event", None): "a27ab429dbac049a6f5c58c1fbe93427",
    ("pool_break", "exact", None): "a27ab429dbac049a6f5c58c1fbe93427",
    ("pool_break", "exact", 1 / 30): "a27ab429dbac049a6f5c58c1fbe93427",
    ("pool_break", "exact", 1 / 1000): "a27ab429dbac049a6f5c58c1fbe93427",
    ("pool_break", "naive", None): "3b2bd043a26a98d8e3c60f9343eccf7f",
}


def fingerprint(result: SimulationResult) -> str:
    digest = hashlib.sha256()
    digest.update(np.ascontiguousarray(result.final_positions, dtype=np.float64).tobytes())
    digest.update(struct.pack("<d", result.rest_time))
    for event in result.events:
        digest.update(struct.pack("<d", event.time))
        digest.update(event.kind.encode())
        digest.update(",".join(event.balls).encode())
        digest.update(struct.pack("<d", event.impact_speed))
        if event.pocket is not None:  # scenes with pockets only: earlier pins unchanged
            digest.update(event.pocket.encode())
    return digest.hexdigest()[:32]


@pytest.mark.parametrize(("name", "method", "dt"), list(PINS))
def test_shipped_scene_matches_its_pinned_fingerprint(
    name: str, method: str, dt: float | None
) -> None:
    result = simulate_scene(
        load_scene(default_scene_path().parent / f"{name}.toml"), method=method, dt=dt
    )
    assert fingerprint(result) == PINS[name, method, dt]


def test_every_shipped_scene_is_pinned() -> None:
    shipped = {path.stem for path in default_scene_path().parent.glob("*.toml")}
    assert shipped == {name for name, _, _ in PINS}
