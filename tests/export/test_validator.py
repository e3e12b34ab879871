"""Every exported file passes the Khronos glTF-Validator with no error and no warning.

The validator is the `gltf-validator` npm package under Node; .ci/run installs both
(Node from the system packages, the validator into .ci-node/). Where either is
missing, the test skips and says which.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

from billiards.export import export_gltf
from billiards.record.window import film_trajectory
from billiards.scene.reader import load_scene
from billiards.simulation import simulate_scene

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = Path(__file__).with_name("validate.cjs")


def validator_modules() -> Path:
    """The node_modules folder holding gltf-validator (GLTF_VALIDATOR_MODULES, or the
    one .ci/run installs), or skip saying what is missing."""
    if shutil.which("node") is None:
        pytest.skip("Node is not installed (apt-get install nodejs npm; .ci/run does)")
    folder = Path(os.environ.get("GLTF_VALIDATOR_MODULES", ROOT / ".ci-node" / "node_modules"))
    if not (folder / "gltf-validator").is_dir():
        pytest.skip(
            f"gltf-validator is not installed in {folder} "
            "(npm install --prefix .ci-node gltf-validator; .ci/run does)"
        )
    return folder


def validate(path: Path) -> dict[str, object]:
    done = subprocess.run(
        ["node", str(SCRIPT), str(validator_modules()), str(path)],
        capture_output=True,
        text=True,
        check=False,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    report: dict[str, object] = json.loads(done.stdout)
    return report


@pytest.mark.parametrize(
    ("name", "suffix"), [("break", ".glb"), ("pool_break", ".glb"), ("spin_break", ".gltf")]
)
def test_exported_files_pass_the_khronos_validator(name: str, suffix: str, tmp_path: Path) -> None:
    validator_modules()  # skip before simulating where it cannot run
    path = tmp_path / f"shot{suffix}"
    export_gltf(simulate_scene(load_scene(name)), path)
    report = validate(path)
    assert (report["errors"], report["warnings"]) == (0, 0), report["messages"]


def test_a_saved_trajectory_with_a_drop_passes_too(tmp_path: Path) -> None:
    """A film's trajectory: a lead before t = 0 (left out) and a ball taken away."""
    validator_modules()
    scene = load_scene("pool_break")
    trajectory = film_trajectory(simulate_scene(scene), scene.render)
    assert trajectory.times[0] < 0
    path = tmp_path / "saved.glb"
    export_gltf(trajectory, path)
    report = validate(path)
    assert (report["errors"], report["warnings"]) == (0, 0), report["messages"]


def test_the_validator_finds_a_broken_file(tmp_path: Path) -> None:
    """The check can fail: a file whose animation input runs backwards is refused."""
    validator_modules()
    path = tmp_path / "shot.gltf"
    export_gltf(simulate_scene(load_scene("break")), path)
    record = json.loads(path.read_text())
    record["accessors"][record["animations"][0]["samplers"][0]["input"]]["min"] = [5.0]
    path.write_text(json.dumps(record))
    assert validate(path)["errors"] != 0
