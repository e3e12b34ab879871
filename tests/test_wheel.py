"""The wheel holds every module and data file of the tree (scripts/check_wheel.py
installs it and runs the commands; .ci/run calls that after the tests)."""

from __future__ import annotations

import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from scripts.check_wheel import ROOT, tree_files, wheel_problems

# What a build reads: the configuration, the package and its data folders.
BUILD_INPUTS = ["pyproject.toml", "setup.py", "README.md", "LICENSE"]


@pytest.mark.long
def test_the_wheel_holds_every_module_and_data_file_of_the_tree(tmp_path: Path) -> None:
    source = tmp_path / "source"  # a copy, so no stale build/ of the tree's is reused
    for folder in ("billiards", "shaders", "assets"):
        shutil.copytree(ROOT / folder, source / folder)
    for name in BUILD_INPUTS:
        if (ROOT / name).exists():
            shutil.copy(ROOT / name, source / name)
    (source / "assets" / "__pycache__").mkdir(exist_ok=True)
    (source / "assets" / "__pycache__" / "stray.cpython-311.pyc").write_bytes(b"")
    built = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(tmp_path), str(source)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert built.returncode == 0, built.stderr
    (wheel,) = tmp_path.glob("billiards-*.whl")
    assert wheel_problems(wheel) == []
    assert (
        "billiards/physics/laws/held.py" in tree_files()
    )  # a subpackage module (issue 17 lost one)


def test_the_check_names_a_file_missing_from_a_wheel_and_one_it_should_not_hold(
    tmp_path: Path,
) -> None:
    wheel = tmp_path / "billiards-0-py3-none-any.whl"
    with zipfile.ZipFile(wheel, "w") as archive:
        for name in tree_files() - {"billiards/physics/laws/held.py"}:
            archive.writestr(name, "")
        archive.writestr("billiards/assets/__pycache__/x.pyc", "")
        archive.writestr("billiards-0.dist-info/RECORD", "")
    assert wheel_problems(wheel) == [
        "missing from the wheel: billiards/physics/laws/held.py",
        "in the wheel but not of the tree: billiards/assets/__pycache__/x.pyc",
    ]


def test_the_tree_lists_shaders_scenes_and_modules_where_the_wheel_puts_them() -> None:
    files = tree_files()
    assert "billiards/shaders/ball.frag" in files
    assert "billiards/assets/scenes/break.toml" in files
    assert "billiards/render/__main__.py" in files
    # The measured sets the reports read, with their sources (issue 44, item 6).
    assert "billiards/fit/data/mathavan2009_cut_shots.csv" in files
    assert "billiards/fit/data/SOURCES.md" in files
    assert not any("__pycache__" in name for name in files)
