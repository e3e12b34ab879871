"""Recorded shots: each ball's centre over time, read from a file and checked.

Three formats, told apart by the file (or `format=`):

- "json" (the format of ../shared/data/carom_tracks/train.json): a list of shots,
  `[{"id": N, "balls": {"1": {"t": [...], "x": [...], "y": [...]}, ...}}, ...]`, with
  `t` in s from the shot's first sample and `x`, `y` in m on the table, origin at a
  cushion-nose corner, x along the length, y along the width.
- "tailuge": tailuge/billiards' `dist/fit/trajectories.json` as published: the same
  structure, but centred on the table's middle and scaled by 1.06507 (x) and 1.06508
  (y) to its larger-ball table (the data README); reading undoes both. A .json file
  whose coordinates go negative is taken for this one.
- "csv": a plain table with the header `shot,ball,t,x,y`, one sample a row, in the
  "json" format's units and frame.

A bad recording (a ball missing, times that go back, a position off the table) is a
RecordingError: one line naming the file, the shot, the ball and the sample.

The project's own recordings (122 three-cushion shots, train.json, 1.2 MB) are not in
the repository: `recordings_path` finds them where the user says (a path, or the
BILLIARDS_RECORDINGS environment variable), else in ../shared/data/carom_tracks beside
the repository; MissingRecordings (one line) says where it looked and how to give them.
"""

from __future__ import annotations

import csv
import json
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]

FORMATS = ("auto", "json", "tailuge", "csv")
# tailuge/billiards' scaling of the recordings to its table (the data README).
TAILUGE_SCALE = (1.06507, 1.06508)
# A recorded centre may sit this far beyond where a centre can be (the recordings are
# rounded to 1 mm before de-scaling) before it counts as off the table.
OFF_TABLE_TOLERANCE = 0.003  # m
# The cue ball is the first ball to leave its first recorded position by this much
# (a few times the recordings' 1 mm resolution).
MOVED = 0.005  # m

# Where the project's recordings are looked for when no path is given: the file (or
# the folder holding RECORDINGS_FILE) the environment variable names, else the shared
# data folder beside the repository, as the CI machine has it.
RECORDINGS_ENV = "BILLIARDS_RECORDINGS"
RECORDINGS_FILE = "train.json"
SHARED_RECORDINGS = (
    Path(__file__).resolve().parents[3] / "shared" / "data" / "carom_tracks" / RECORDINGS_FILE
)


class RecordingError(ValueError):
    """A recording a person must fix; str() is one line naming the shot, ball and sample."""


class MissingRecordings(RecordingError):
    """No recordings file where they were looked for; str() is one line naming the path,
    where it came from and how to give the recordings."""


def recordings_path(given: str | Path | None = None) -> Path:
    """The recordings file: `given` (a file, or a folder holding train.json), else the
    one BILLIARDS_RECORDINGS names (the same), else ../shared/data/carom_tracks/train.json
    beside the repository. MissingRecordings if there is no such file."""
    if given is not None:
        path, origin = Path(given), "the path given"
    elif os.environ.get(RECORDINGS_ENV):
        path, origin = Path(os.environ[RECORDINGS_ENV]), f"from {RECORDINGS_ENV}"
    else:
        path, origin = SHARED_RECORDINGS, "the default: the shared data beside the repository"
    if path.is_dir():
        path = path / RECORDINGS_FILE
    if not path.is_file():
        raise MissingRecordings(
            f"recordings: no file {path} ({origin}); expected the recorded shots: give "
            f"their path (TRACKS) or set {RECORDINGS_ENV} to the file or its folder (the "
            f"project's 122 three-cushion shots, {RECORDINGS_FILE}, are not in the "
            'repository: docs/validation.md, "Recorded shots", says where they come from)'
        )
    return path


@dataclass(frozen=True)
class Track:
    """One ball's recorded centre: times (s, non-decreasing) and positions (m)."""

    t: FloatArray  # (S,)
    xy: FloatArray  # (S, 2)

    @property
    def start_time(self) -> float:
        """When the ball first leaves its first position by MOVED (inf: it never does)."""
        moved = np.hypot(*(self.xy - self.xy[0]).T) > MOVED
        return float(self.t[np.argmax(moved)]) if moved.any() else math.inf


@dataclass(frozen=True)
class Recording:
    """One shot: each ball's track, by the recording's ball id."""

    id: str
    balls: dict[str, Track]

    @property
    def cue_ball(self) -> str:
        """The first ball to move (ties: the first id in the recording's order)."""
        return min(self.balls, key=lambda ball: self.balls[ball].start_time)

    @property
    def duration(self) -> float:
        return max(float(track.t[-1]) for track in self.balls.values())


def read_recordings(path: str | Path, format: str = "auto", *, balls: int = 3) -> list[Recording]:
    """Every shot of a recordings file, checked (RecordingError: one line)."""
    file = Path(path)
    if format not in FORMATS:
        raise RecordingError(f"--format {format!r}: expected one of {', '.join(FORMATS)}")
    try:
        text = file.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise RecordingError(f"{file}: cannot read the recordings ({error})") from None
    if format == "auto":
        format = "csv" if file.suffix.lower() == ".csv" else "json"
    if format == "csv":
        shots = _csv_shots(text, str(file))
    else:
        shots = _json_shots(text, str(file))
        if format == "json" and _centred(shots):
            format = "tailuge"
        if format == "tailuge":
            shots = [_descaled(shot) for shot in shots]
    return [_checked(shot, str(file), balls) for shot in shots]


def check_on_table(
    recordings: Sequence[Recording], size: tuple[float, float], radius: float, source: str
) -> None:
    """RecordingError for the first sample whose centre is off the table (a centre
    stays in [R, L - R] x [R, W - R], within OFF_TABLE_TOLERANCE)."""
    low = radius - OFF_TABLE_TOLERANCE
    high = np.array(size) - radius + OFF_TABLE_TOLERANCE
    for shot in recordings:
        for ball, track in shot.balls.items():
            off = ((track.xy < low) | (track.xy > high)).any(axis=1)
            if off.any():
                index = int(np.argmax(off))
                x, y = track.xy[index]
                raise RecordingError(
                    f'{source}: shot {shot.id} ball "{ball}" sample {index} (t = '
                    f"{track.t[index]:g} s) at ({x:.4f}, {y:.4f}) m: off the table; expected "
                    f"a centre in [{radius:g}, {size[0] - radius:g}] x "
                    f"[{radius:g}, {size[1] - radius:g}] m"
                )


# A shot as read, before checks: id and, by ball, (t, x, y) lists.
_RawShot = tuple[str, dict[str, tuple[list[Any], list[Any], list[Any]]]]


def _json_shots(text: str, source: str) -> list[_RawShot]:
    try:
        data = json.loads(text)
    except json.JSONDecodeError as error:
        raise RecordingError(f"{source}: not JSON ({error})") from None
    expected = 'a list of shots {"id": N, "balls": {"1": {"t": [...], "x": [...], "y": [...]}}}'
    if not isinstance(data, list) or not data:
        raise RecordingError(f"{source}: expected {expected}")
    shots: list[_RawShot] = []
    for index, shot in enumerate(data):
        if not isinstance(shot, dict) or not isinstance(shot.get("balls"), dict):
            raise RecordingError(f"{source}: shot {index}: expected {expected}")
        shot_id = str(shot.get("id", index))
        balls = {}
        for ball, track in shot["balls"].items():
            if not isinstance(track, dict) or not all(key in track for key in "txy"):
                raise RecordingError(
                    f'{source}: shot {shot_id} ball "{ball}": expected {{"t": [...], '
                    '"x": [...], "y": [...]}'
                )
            balls[str(ball)] = (track["t"], track["x"], track["y"])
        shots.append((shot_id, balls))
    return shots


def _csv_shots(text: str, source: str) -> list[_RawShot]:
    rows = csv.DictReader(text.splitlines())
    if rows.fieldnames is None or not {"shot", "ball", "t", "x", "y"} <= set(rows.fieldnames):
        raise RecordingError(f"{source}: expected a CSV header naming shot,ball,t,x,y")
    shots: dict[str, dict[str, tuple[list[Any], list[Any], list[Any]]]] = {}
    for row in rows:
        track = shots.setdefault(row["shot"], {}).setdefault(row["ball"], ([], [], []))
        for column, value in zip(track, (row["t"], row["x"], row["y"]), strict=True):
            column.append(value)
    return list(shots.items())


def _centred(shots: list[_RawShot]) -> bool:
    """Whether the coordinates go negative: tailuge's frame, centred on the table."""
    for _, balls in shots:
        for _, xs, ys in balls.values():
            with_numbers = [v for v in (*xs, *ys) if isinstance(v, int | float)]
            if with_numbers and min(with_numbers) < 0:
                return True
    return False


def _descaled(shot: _RawShot) -> _RawShot:
    """tailuge's frame to the table's: undo the scaling, move the origin to a corner.
    The table's size there is 92.36 x 46.18 of its radius 0.03275 m, i.e. 2.84 x 1.42 m
    once descaled; its half is added."""
    shot_id, balls = shot
    half = (1.42, 0.71)
    out = {}
    for ball, (ts, xs, ys) in balls.items():
        out[ball] = (
            ts,
            [_number(x) / TAILUGE_SCALE[0] + half[0] for x in xs],
            [_number(y) / TAILUGE_SCALE[1] + half[1] for y in ys],
        )
    return shot_id, out


def _number(value: Any) -> float:
    return float(value) if isinstance(value, int | float) else math.nan


def _checked(shot: _RawShot, source: str, count: int) -> Recording:
    shot_id, balls = shot
    where = f"{source}: shot {shot_id}"
    if len(balls) != count:
        names = ", ".join(f'"{ball}"' for ball in balls) or "none"
        raise RecordingError(
            f"{where}: {len(balls)} balls recorded ({names}); expected {count}, one a "
            "ball of the scene (a ball missing?)"
        )
    tracks = {}
    for ball, (ts, xs, ys) in balls.items():
        try:
            t, x, y = (np.array(column, dtype=np.float64) for column in (ts, xs, ys))
        except (TypeError, ValueError):
            raise RecordingError(f'{where} ball "{ball}": expected numbers in t, x, y') from None
        if not (t.ndim == 1 and len(t) == len(x) == len(y) and len(t) > 0):
            raise RecordingError(
                f'{where} ball "{ball}": expected t, x, y of one equal length > 0, got '
                f"{len(t)}, {len(x)}, {len(y)}"
            )
        bad = ~(np.isfinite(t) & np.isfinite(x) & np.isfinite(y))
        if bad.any():
            index = int(np.argmax(bad))
            raise RecordingError(f'{where} ball "{ball}" sample {index}: expected finite t, x, y')
        back = np.diff(t) < 0
        if back.any():
            index = int(np.argmax(back)) + 1
            raise RecordingError(
                f'{where} ball "{ball}" sample {index}: t = {t[index]:g} s after '
                f"{t[index - 1]:g} s; expected times that never go back"
            )
        if t[0] < 0:
            raise RecordingError(
                f'{where} ball "{ball}" sample 0: t = {t[0]:g} s; expected times from 0'
            )
        tracks[ball] = Track(t, np.stack([x, y], axis=1))
    return Recording(shot_id, tracks)
