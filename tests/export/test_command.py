"""python -m billiards.export as a user runs it: files written whole, bad input refused."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from tests.commands import run_module


@pytest.mark.long
def test_the_command_writes_a_glb_named_after_the_scene_and_says_so(tmp_path: Path) -> None:
    done = run_module("billiards.export", cwd=tmp_path)  # the seed break, as every command
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "break.glb").read_bytes()[:4] == b"glTF"
    assert "wrote break.glb" in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["break.glb"]


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["-o", "shot.obj"], "shot.obj: expected a .glb or .gltf file name"),
        (["-o", "missing/shot.glb"], "the folder missing does not exist"),
        (["--html", "shot.txt"], "shot.txt: expected an .html file name"),
        (["no_such_scene"], "no_such_scene"),
        (["--trajectory", "nothing.npz"], "nothing.npz: no such trajectory file"),
        (["--trajectory", "bad.npz"], "bad.npz: not a trajectory file"),
        (["--angle-error", "0"], "--angle-error 0: expected degrees in (0, 90]"),
        (["--texture-width", "300"], "--texture-width"),
        (["--linear", "-1"], "--linear -1: expected millimetres above 0"),
        (["-o", "here.glb"], "here.glb: already exists (pass --force to replace it)"),
    ],
)
def test_bad_input_is_one_line_exit_2_and_no_file(
    args: list[str], message: str, tmp_path: Path
) -> None:
    (tmp_path / "bad.npz").write_bytes(b"not a zip")
    (tmp_path / "here.glb").write_bytes(b"kept")
    before = sorted(p.name for p in tmp_path.iterdir())
    done = run_module("billiards.export", *args, cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert message in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == before
    assert (tmp_path / "here.glb").read_bytes() == b"kept"


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes in a read-only folder")
def test_an_unwritable_folder_is_refused(tmp_path: Path) -> None:
    folder = tmp_path / "locked"
    folder.mkdir()
    folder.chmod(0o500)
    done = run_module("billiards.export", "-o", str(folder / "shot.glb"))
    assert done.returncode == 2
    assert "cannot write in the folder" in done.stderr


def test_without_pygltflib_the_command_says_which_extra_in_one_line(tmp_path: Path) -> None:
    blocker = tmp_path / "sitecustomize.py"  # pygltflib made unimportable
    blocker.write_text("import sys\nsys.modules['pygltflib'] = None\n")
    done = run_module(
        "billiards.export", "-o", "shot.glb", cwd=tmp_path, env={"PYTHONPATH": str(tmp_path)}
    )
    assert done.returncode == 1
    assert done.stderr.strip() == (
        "error: the export needs pygltflib: pip install 'billiards[export]'"
    )
    assert not (tmp_path / "shot.glb").exists()
