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

from billiards.physics.engine.result import SimulationResult
from billiards.scene.reader import default_scene_path, load_scene
from billiards.simulation import simulate_scene

# (scene, method, dt or None for the scene's own) -> sha256 prefix of the run.
PINS = {
    ("bank_shot", "event", None): "21d3853f512973cfc75f3ce71deb382c",
    ("bank_shot", "exact", None): "21d3853f512973cfc75f3ce71deb382c",
    ("bank_shot", "exact", 1 / 30): "21d3853f512973cfc75f3ce71deb382c",
    ("bank_shot", "exact", 1 / 1000): "21d3853f512973cfc75f3ce71deb382c",
    ("bank_shot", "naive", None): "02dd3cab7846b1bb39c8fe4e856cbf04",
    ("break", "event", None): "5d8d9b72468ba364d84e01b29546ba94",
    ("break", "exact", None): "5d8d9b72468ba364d84e01b29546ba94",
    ("break", "exact", 1 / 30): "5d8d9b72468ba364d84e01b29546ba94",
    ("break", "exact", 1 / 1000): "5d8d9b72468ba364d84e01b29546ba94",
    ("break", "naive", None): "4d3d63b29e8d0f552c8da3ca2525afd7",
    ("hard_break", "event", None): "2a72254f0a331bcc324e1557ab5e1f52",
    ("hard_break", "exact", None): "2a72254f0a331bcc324e1557ab5e1f52",
    ("hard_break", "exact", 1 / 30): "2a72254f0a331bcc324e1557ab5e1f52",
    ("hard_break", "exact", 1 / 1000): "2a72254f0a331bcc324e1557ab5e1f52",
    ("newtons_cradle", "event", None): "fb8c3797a56ffad78ae38af0332cb4d4",
    ("newtons_cradle", "exact", None): "fb8c3797a56ffad78ae38af0332cb4d4",
    ("newtons_cradle", "exact", 1 / 30): "fb8c3797a56ffad78ae38af0332cb4d4",
    ("newtons_cradle", "exact", 1 / 1000): "fb8c3797a56ffad78ae38af0332cb4d4",
    ("newtons_cradle", "naive", None): "c2de540ca0edf094d09bce80ccf79a8d",
    # The spin model's scenes.
    ("draw_shot", "event", None): "568de67ee59bb4ef405e12e2cd63c937",
    ("draw_shot", "exact", None): "568de67ee59bb4ef405e12e2cd63c937",
    ("draw_shot", "exact", 1 / 30): "568de67ee59bb4ef405e12e2cd63c937",
    ("draw_shot", "exact", 1 / 1000): "568de67ee59bb4ef405e12e2cd63c937",
    ("draw_shot", "naive", None): "242e7808fc45a4d66b5030f519365771",
    ("english_bank", "event", None): "9996758c6078fca713d1a29e7d10aaa4",
    ("english_bank", "exact", None): "9996758c6078fca713d1a29e7d10aaa4",
    ("english_bank", "exact", 1 / 30): "9996758c6078fca713d1a29e7d10aaa4",
    ("english_bank", "exact", 1 / 1000): "9996758c6078fca713d1a29e7d10aaa4",
    ("english_bank", "naive", None): "64ec29098f2ed126e52edba602679fd6",
    ("follow_shot", "event", None): "84a40673cbc27362eb2002f3ae9d13c0",
    ("follow_shot", "exact", None): "84a40673cbc27362eb2002f3ae9d13c0",
    ("follow_shot", "exact", 1 / 30): "84a40673cbc27362eb2002f3ae9d13c0",
    ("follow_shot", "exact", 1 / 1000): "84a40673cbc27362eb2002f3ae9d13c0",
    ("follow_shot", "naive", None): "e1673ee22b12b7f231b4d9a982c16508",
    ("spin_break", "event", None): "6ecca2966d6194d229fd0090a961cdb0",
    ("spin_break", "exact", None): "6ecca2966d6194d229fd0090a961cdb0",
    ("spin_break", "exact", 1 / 30): "6ecca2966d6194d229fd0090a961cdb0",
    ("spin_break", "exact", 1 / 1000): "6ecca2966d6194d229fd0090a961cdb0",
    ("spin_break", "naive", None): "d01fa8e582f92b5574a3d7e8fb315d27",
    ("stun_shot", "event", None): "55743add7d0ccf430472d020b0d747e4",
    ("stun_shot", "exact", None): "55743add7d0ccf430472d020b0d747e4",
    ("stun_shot", "exact", 1 / 30): "55743add7d0ccf430472d020b0d747e4",
    ("stun_shot", "exact", 1 / 1000): "55743add7d0ccf430472d020b0d747e4",
    ("stun_shot", "naive", None): "e41053fa9bf86ea1530eb2d9694f4f09",
    # A stroke (`cue = {...}`): a massé round a ball.
    ("masse_shot", "event", None): "91a3f767cc4ee1d49de122399fdb6357",
    ("masse_shot", "exact", None): "91a3f767cc4ee1d49de122399fdb6357",
    ("masse_shot", "exact", 1 / 30): "91a3f767cc4ee1d49de122399fdb6357",
    ("masse_shot", "exact", 1 / 1000): "91a3f767cc4ee1d49de122399fdb6357",
    ("masse_shot", "naive", None): "a877498b894437cc9f98edb576df90af",
    # Tables with pockets.
    ("pocket_shot", "event", None): "dbd7c9d00402f3e33338e3e8835cb49a",
    ("pocket_shot", "exact", None): "dbd7c9d00402f3e33338e3e8835cb49a",
    ("pocket_shot", "exact", 1 / 30): "dbd7c9d00402f3e33338e3e8835cb49a",
    ("pocket_shot", "exact", 1 / 1000): "dbd7c9d00402f3e33338e3e8835cb49a",
    ("pocket_shot", "naive", None): "afec0d2de49644da137e0909d44d5c15",
    # Re-pinned on purpose (issue 30): the 9-8 glancing pair was pressed by the hair rule
    # in the old break (docs/touching.md, section 8); then a real pool break (issue 33): the
    # cue ball on the head string aimed at the head ball.
    ("pool_break", "event", None): "9616d2e28a1d896e7a26f92c6ba0bc29",
    ("pool_break", "exact", None): "9616d2e28a1d896e7a26f92c6ba0bc29",
    ("pool_break", "exact", 1 / 30): "9616d2e28a1d896e7a26f92c6ba0bc29",
    ("pool_break", "exact", 1 / 1000): "9616d2e28a1d896e7a26f92c6ba0bc29",
    ("pool_break", "naive", None): "f0849236f3b46bc755fe423b3209cd20",
    # The frictional ball-ball law (issue 20): a cut that drops only by its throw.
    ("throw_shot", "event", None): "e277f42f02151adaefae883d51618a2d",
    ("throw_shot", "exact", None): "e277f42f02151adaefae883d51618a2d",
    ("throw_shot", "exact", 1 / 30): "e277f42f02151adaefae883d51618a2d",
    ("throw_shot", "exact", 1 / 1000): "e277f42f02151adaefae883d51618a2d",
    ("throw_shot", "naive", None): "1f82ee0675426aad68e4e7810b16af25",
    # The carom table (issue 31): the fitted constants of docs/validation.md.
    ("three_cushion", "event", None): "f88ffad26ef6cdf833a56177496fb2e4",
    ("three_cushion", "exact", None): "f88ffad26ef6cdf833a56177496fb2e4",
    ("three_cushion", "exact", 1 / 30): "f88ffad26ef6cdf833a56177496fb2e4",
    ("three_cushion", "exact", 1 / 1000): "f88ffad26ef6cdf833a56177496fb2e4",
    ("three_cushion", "naive", None): "32e3b008a1bd3d86599450f43adb8c3d",
    # Off the cloth (issue 45): a jump shot over a blocker (no naive: flight is the
    # compiled loop's only).
    ("jump_shot", "event", None): "f803b65ff1b0fee97dd726f2ff1d47fb",
    ("jump_shot", "exact", None): "f803b65ff1b0fee97dd726f2ff1d47fb",
    ("jump_shot", "exact", 1 / 30): "f803b65ff1b0fee97dd726f2ff1d47fb",
    ("jump_shot", "exact", 1 / 1000): "f803b65ff1b0fee97dd726f2ff1d47fb",
    # A hopping break (physics.airborne): the cue ball hops into the rack and the 1 flies.
    ("hop_break", "event", None): "82d2bece57ea3f6c658f23f162b5d314",
    ("hop_break", "exact", None): "82d2bece57ea3f6c658f23f162b5d314",
    ("hop_break", "exact", 1 / 30): "82d2bece57ea3f6c658f23f162b5d314",
    ("hop_break", "exact", 1 / 1000): "82d2bece57ea3f6c658f23f162b5d314",
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
