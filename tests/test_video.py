"""billiards.render.video: streamed H.264 MP4s, never a half-written file."""

from __future__ import annotations

import subprocess
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import pytest

from billiards.render.video import VideoError, VideoWriter, ffmpeg_exe
from tests.render.fixtures import decode_mp4

SIZE = (64, 48)


def frames(count: int) -> list[bytes]:
    """A bright square sliding across a dark picture, RGBA."""
    out = []
    for k in range(count):
        image = np.zeros((SIZE[1], SIZE[0], 4), dtype=np.uint8)
        image[..., 3] = 255
        image[10:30, 2 * k : 2 * k + 16, :3] = 230
        out.append(image.tobytes())
    return out


def decode(path: Path) -> tuple[dict[str, Any], list[npt.NDArray[np.uint8]]]:
    return decode_mp4(path)


def probe(path: Path) -> str:
    run = subprocess.run(
        [ffmpeg_exe(), "-hide_banner", "-i", str(path)], capture_output=True, text=True, check=False
    )
    return run.stderr


def test_a_film_has_its_size_frame_count_and_duration(tmp_path: Path) -> None:
    target = tmp_path / "film.mp4"
    with VideoWriter(target, SIZE, 25.0) as writer:
        for frame in frames(20):
            writer.write(frame)
    meta, pictures = decode(target)
    assert meta["size"] == SIZE
    assert meta["fps"] == pytest.approx(25.0)
    assert meta["duration"] == pytest.approx(20 / 25.0, abs=0.05)
    assert len(pictures) == 20
    assert pictures[5][20, 20].min() > 180 and pictures[5][40, 60].max() < 60
    info = probe(target)
    assert "h264" in info and "yuv420p" in info
    # faststart: the index (moov) comes before the media data (mdat), for browsers.
    data = target.read_bytes()
    assert data.index(b"moov") < data.index(b"mdat")
    assert list(tmp_path.iterdir()) == [target]  # no temporary left behind


def test_an_audio_track_is_muxed_as_aac(tmp_path: Path) -> None:
    target = tmp_path / "sound.mp4"
    rate = 48_000
    tone = 0.3 * np.sin(2 * np.pi * 440.0 * np.arange(rate) / rate)
    with VideoWriter(target, SIZE, 25.0, audio=tone, sample_rate=rate) as writer:
        for frame in frames(25):
            writer.write(frame)
    info = probe(target)
    assert "Audio: aac" in info and "mono" in info
    assert sorted(p.name for p in tmp_path.iterdir()) == ["sound.mp4"]


@pytest.mark.parametrize("failure", [RuntimeError, KeyboardInterrupt])
def test_an_error_or_ctrl_c_leaves_no_file_and_keeps_the_old_one(
    tmp_path: Path, failure: type[BaseException]
) -> None:
    target = tmp_path / "film.mp4"
    target.write_bytes(b"the previous film")
    with pytest.raises(failure), VideoWriter(target, SIZE, 25.0) as writer:
        for frame in frames(5):
            writer.write(frame)
        raise failure("stop")
    assert target.read_bytes() == b"the previous film"
    assert list(tmp_path.iterdir()) == [target]


def test_a_wrong_frame_or_size_is_refused(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="even size"):
        VideoWriter(tmp_path / "odd.mp4", (63, 48), 25.0)
    with (
        pytest.raises(ValueError, match="bytes"),
        VideoWriter(tmp_path / "f.mp4", SIZE, 25.0) as writer,
    ):
        writer.write(b"short")
    assert list(tmp_path.iterdir()) == []


def test_a_film_with_no_frames_is_an_error_and_no_file(tmp_path: Path) -> None:
    with (
        pytest.raises(VideoError, match="no frames"),
        VideoWriter(tmp_path / "empty.mp4", SIZE, 25.0),
    ):
        pass
    assert list(tmp_path.iterdir()) == []


def test_a_missing_directory_is_a_one_line_error(tmp_path: Path) -> None:
    with pytest.raises(VideoError, match="does not exist"):
        VideoWriter(tmp_path / "nowhere" / "film.mp4", SIZE, 25.0)


def test_a_film_that_cannot_be_moved_into_place_leaves_nothing_behind(tmp_path: Path) -> None:
    # The target is a directory: ffmpeg finishes, the rename fails. The error names the
    # target (never a temporary name), and neither the part file nor the audio stays.
    (tmp_path / "film.mp4").mkdir()
    audio = np.zeros(48_000 // 5, dtype=np.float32)
    with (
        pytest.raises(OSError, match=r"film\.mp4: cannot write it") as caught,
        VideoWriter(tmp_path / "film.mp4", SIZE, 25.0, audio=audio, sample_rate=48_000) as writer,
    ):
        for frame in frames(5):
            writer.write(frame)
    assert ".part" not in str(caught.value)
    assert [path.name for path in tmp_path.iterdir()] == ["film.mp4"]
    assert list((tmp_path / "film.mp4").iterdir()) == []


# BT.709 limited-range codes (Y, Cb, Cr) of pure green and magenta.
GREEN, MAGENTA = (173, 42, 26), (78, 214, 230)


def two_colours(pixel_format: str) -> bytes:
    """A frame green above and magenta below, in `pixel_format`."""
    width, height = SIZE
    if pixel_format == "yuv420p":
        planes = []
        for plane in range(3):
            rows = (height if plane == 0 else height // 2, width if plane == 0 else width // 2)
            values = np.empty(rows, dtype=np.uint8)
            values[: rows[0] // 2] = GREEN[plane]
            values[rows[0] // 2 :] = MAGENTA[plane]
            planes.append(values.ravel())
        return np.concatenate(planes).tobytes()
    channels = 4 if pixel_format == "rgba" else 3
    image = np.full((height, width, channels), 255, dtype=np.uint8)
    image[: height // 2, :, :3] = (0, 255, 0)
    image[height // 2 :, :, :3] = (255, 0, 255)
    return image.tobytes()


def decode_yuv420p(path: Path) -> npt.NDArray[np.uint8]:
    """The first frame's Y, U and V planes as encoded (no conversion), concatenated."""
    done = subprocess.run(
        [ffmpeg_exe(), "-v", "error", "-i", str(path), "-frames:v", "1",
         "-f", "rawvideo", "-pix_fmt", "yuv420p", "pipe:"],
        capture_output=True, check=True,
    )  # fmt: skip
    return np.frombuffer(done.stdout, dtype=np.uint8)


@pytest.mark.parametrize("pixel_format", ["yuv420p", "rgba", "rgb24"])
def test_every_input_makes_a_bt709_limited_range_film_that_decodes_to_its_colours(
    tmp_path: Path, pixel_format: str
) -> None:
    target = tmp_path / f"{pixel_format}.mp4"
    with VideoWriter(target, SIZE, 25.0, pixel_format=pixel_format) as writer:
        for _ in range(3):
            writer.write(two_colours(pixel_format))
    # Tagged: matrix, primaries, transfer BT.709, limited range.
    assert "yuv420p(tv, bt709, progressive)" in probe(target)
    # Encoded with BT.709's matrix whatever the input (RGB converted by ffmpeg).
    width, height = SIZE
    planes = decode_yuv420p(target).astype(int)
    luma = planes[: width * height].reshape(height, width)
    cb = planes[width * height : width * height * 5 // 4].reshape(height // 2, width // 2)
    cr = planes[width * height * 5 // 4 :].reshape(height // 2, width // 2)
    for codes, row in ((GREEN, height // 4), (MAGENTA, 3 * height // 4)):
        encoded = (luma[row, width // 2], cb[row // 2, width // 4], cr[row // 2, width // 4])
        assert np.abs(np.array(encoded) - codes).max() <= 2, (codes, encoded)
    # A decoder that honours the tags gives the colours back.
    _, pictures = decode(target)
    for colour, row in (((0, 255, 0), height // 4), ((255, 0, 255), 3 * height // 4)):
        got = pictures[0][row, width // 2].astype(int)
        assert np.abs(got - colour).max() <= 4, (colour, got)


def test_a_yuv420p_frame_is_its_size_in_bytes(tmp_path: Path) -> None:
    with VideoWriter(tmp_path / "f.mp4", SIZE, 25.0, pixel_format="yuv420p") as writer:
        assert writer.frame_bytes == SIZE[0] * SIZE[1] * 3 // 2
        with pytest.raises(ValueError, match="bytes"):
            writer.write(b"\0" * (SIZE[0] * SIZE[1] * 4))
        writer.write(two_colours("yuv420p"))
