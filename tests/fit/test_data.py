"""The data the fitter's reports read (issue 44, item 6): the published measurements
travel with the package, with their sources; the recordings are found where the user
says (a path, BILLIARDS_RECORDINGS) or beside the repository, and when they are absent
every command says so in one line, exit 2, no traceback."""

from __future__ import annotations

from pathlib import Path

import pytest

from billiards.fit.measured import MEASURED, MEASURED_SETS, read_rows
from billiards.fit.recordings import (
    RECORDINGS_ENV,
    SHARED_RECORDINGS,
    MissingRecordings,
    read_recordings,
    recordings_path,
)


def project_recordings() -> Path | None:
    """The project's recordings where the commands look by default, or None."""
    try:
        return recordings_path()
    except MissingRecordings:
        return None


needs_recordings = pytest.mark.skipif(
    project_recordings() is None,
    reason=f"no recordings: set {RECORDINGS_ENV} to train.json (or its folder), or put it "
    f"at {SHARED_RECORDINGS}",
)


def test_the_measured_sets_travel_inside_the_package_with_their_sources() -> None:
    assert MEASURED.parts[-3:] == ("billiards", "fit", "data")
    sources = (MEASURED / "SOURCES.md").read_text(encoding="utf-8")
    assert "Licence" in sources
    for name in MEASURED_SETS.values():
        path = MEASURED / name
        assert path.stat().st_size < 4096  # small: a table from a paper
        assert path.read_text(encoding="utf-8").startswith("# ")  # its source first
        assert read_rows(path)  # and rows below
        assert f"`{name}`" in sources


def test_the_measured_report_names_a_missing_set_in_one_line_and_exits_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    pytest.importorskip("scipy")
    from scripts.validation_measured import main

    assert main(["--data", str(tmp_path)]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err.count("\n") == 1
    assert "mathavan2010_cushion_rebounds.csv" in captured.err and str(tmp_path) in captured.err


def test_the_recordings_are_the_path_given_else_the_variable_s_else_the_shared_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    given, named = tmp_path / "given", tmp_path / "named"
    for folder in (given, named):
        folder.mkdir()
        (folder / "train.json").write_text("[]")
    monkeypatch.setenv(RECORDINGS_ENV, str(named))
    assert recordings_path(given) == given / "train.json"  # a folder: its train.json
    assert recordings_path(given / "train.json") == given / "train.json"
    assert recordings_path() == named / "train.json"
    monkeypatch.delenv(RECORDINGS_ENV)
    if SHARED_RECORDINGS.is_file():
        assert recordings_path() == SHARED_RECORDINGS
    else:
        with pytest.raises(MissingRecordings, match="the shared data beside the repository"):
            recordings_path()


def test_missing_recordings_are_one_line_naming_the_path_and_how_to_give_them(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv(RECORDINGS_ENV, str(tmp_path))
    with pytest.raises(MissingRecordings) as raised:
        recordings_path()
    message = str(raised.value)
    assert "\n" not in message
    assert str(tmp_path / "train.json") in message
    assert RECORDINGS_ENV in message and "TRACKS" in message


@pytest.mark.parametrize("command", ["billiards-fit", "validation_tracks", "bench_cushion_laws"])
def test_every_command_without_its_recordings_says_so_in_one_line_and_exits_2(
    command: str,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    pytest.importorskip("scipy")
    monkeypatch.setenv(RECORDINGS_ENV, str(tmp_path))  # an empty folder: no train.json
    if command == "billiards-fit":
        from billiards.fit.__main__ import main as fit_main

        status = fit_main(["score", "-o", str(tmp_path / "out"), "--quiet"])
    elif command == "validation_tracks":
        from scripts.validation_tracks import main as tracks_main

        status = tracks_main([])
    else:
        from scripts.bench_cushion_laws import main as bench_main

        status = bench_main([])
    captured = capsys.readouterr()
    assert status == 2
    assert captured.err.count("\n") == 1, captured.err
    assert f"no file {tmp_path / 'train.json'}" in captured.err
    assert RECORDINGS_ENV in captured.err and "Traceback" not in captured.err
    assert not (tmp_path / "out").exists()


@needs_recordings
def test_the_project_recordings_are_found_and_read_by_default() -> None:
    path = project_recordings()
    assert path is not None
    recordings = read_recordings(path)
    assert len(recordings) == 122
    assert all(len(recording.balls) == 3 for recording in recordings)
