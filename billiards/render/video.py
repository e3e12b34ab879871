"""MP4 films: H.264 (yuv420p, faststart) through the ffmpeg bundled with imageio-ffmpeg.

Frames come as yuv420p (BT.709, limited range: the renderer converts them on the GL
side, and ffmpeg encodes them as they are) or as RGBA/RGB (ffmpeg converts them to
the same BT.709 limited range). Either way the stream is tagged BT.709 (matrix,
primaries, transfer) and limited range, so a player shows the colours the frames had:
untagged, it would guess, and swscale's default matrix (BT.601) is not what players
assume for HD (BT.709).

Frames stream through a bounded queue to a writer thread that feeds ffmpeg's stdin,
so rendering and encoding overlap and memory stays flat however long the film. The
film is written through billiards.shell.atomic (a temporary file beside the target,
renamed into place only when ffmpeg has finished cleanly); on any error or Ctrl-C
ffmpeg is killed, the temporary file is removed and the target is left as it was.

An optional mono audio track (float samples in [-1, 1] and a sample rate) is muxed
in as AAC by the same ffmpeg run (no second pass); its first sample plays with the
first frame. It is neither trimmed nor padded: pass a track as long as the film.
"""

from __future__ import annotations

import contextlib
import os
import queue
import subprocess
import tempfile
import threading
from fractions import Fraction
from pathlib import Path

import numpy as np
import numpy.typing as npt

from billiards.render.sound.voices import write_wav
from billiards.shell.atomic import AtomicFile
from billiards.shell.closing import Closing

QUEUE_FRAMES = 6  # frames in flight between the renderer and ffmpeg
# x264's superfast search with veryfast's rate control (the macroblock tree over a
# 10-frame lookahead, which superfast leaves out): on the default 720p film it takes
# about 25% less CPU than veryfast for the same picture (SSIM 0.9939 against 0.9942,
# PSNR 48.5 against 48.7 dB) in an 8% larger file. Encoding shares the CPU with
# drawing, so its time is the film's.
PRESET = "superfast"
X264_PARAMS = "mbtree=1:rc-lookahead=10"
# Bytes a pixel of each input format (yuv420p: the Y plane, then U and V at half the
# width and height).
PIXEL_BYTES = {"rgba": 4.0, "rgb24": 3.0, "yuv420p": 1.5}
# The stream's colour: BT.709's matrix, primaries and transfer, limited ("tv") range.
COLOUR_TAGS = ["-colorspace", "bt709", "-color_primaries", "bt709", "-color_trc", "bt709"]
COLOUR_TAGS += ["-color_range", "tv"]


def frame_bytes(size: tuple[int, int], pixel_format: str) -> int:
    """The bytes of one frame of `size` in `pixel_format` (one of PIXEL_BYTES)."""
    return int(size[0] * size[1] * PIXEL_BYTES[pixel_format])


class VideoError(RuntimeError):
    """ffmpeg could not write the film; str() is one line."""


def ffmpeg_exe() -> str:
    """The ffmpeg that ships with imageio-ffmpeg (or one it finds)."""
    try:
        import imageio_ffmpeg

        return str(imageio_ffmpeg.get_ffmpeg_exe())
    except (ImportError, RuntimeError) as error:
        raise VideoError(
            f"no ffmpeg ({error}); reinstall it with: pip install --force-reinstall imageio-ffmpeg"
        ) from None


class VideoWriter(Closing):
    """Streams frames (yuv420p, RGBA or RGB: `pixel_format`) to an MP4 file.

    Use as a context manager: leaving the block normally finishes and renames the
    file; leaving it with an exception (KeyboardInterrupt included) aborts, kills
    ffmpeg and removes the temporary file.
    """

    def __init__(
        self,
        path: str | Path,
        size: tuple[int, int],
        fps: float,
        *,
        quality: int = 23,
        preset: str = PRESET,
        pixel_format: str = "rgba",
        audio: npt.ArrayLike | None = None,
        sample_rate: int | None = None,
    ) -> None:
        width, height = size
        if width % 2 or height % 2:
            raise ValueError(f"H.264 with yuv420p needs an even size, not {width}x{height}")
        if pixel_format not in PIXEL_BYTES:
            raise ValueError(f"pixel_format {pixel_format!r}: expected one of {tuple(PIXEL_BYTES)}")
        if audio is not None and not sample_rate:
            raise ValueError("an audio track needs its sample_rate")
        self.path = Path(path)
        self.size = size
        self.fps = fps
        self.pixel_format = pixel_format
        self.frame_bytes = frame_bytes(size, pixel_format)
        self.frames_written = 0
        self._error: BaseException | None = None
        self._finished = False

        directory = self.path.parent if str(self.path.parent) else Path(".")
        if not directory.is_dir():
            raise VideoError(f"{self.path}: the directory {directory} does not exist")
        # Everything to undo when the film ends, whichever way: closed by close()/abort().
        self._resources = contextlib.ExitStack()
        self._output = AtomicFile(self.path, ".part.mp4")
        self._resources.callback(self._output.discard)  # a no-op once committed
        self.temporary = self._output.temporary
        self._log = self._resources.enter_context(tempfile.TemporaryFile())  # noqa: SIM115
        self._audio_file: Path | None = None
        try:
            self._process = self._start_ffmpeg(
                pixel_format, preset, quality, audio, sample_rate, directory
            )
        except BaseException:
            self._resources.close()
            raise
        self._queue: queue.Queue[bytes | None] = queue.Queue(maxsize=QUEUE_FRAMES)
        self._thread = threading.Thread(target=self._feed, name="ffmpeg-writer", daemon=True)
        self._thread.start()

    def _start_ffmpeg(
        self,
        pixel_format: str,
        preset: str,
        quality: int,
        audio: npt.ArrayLike | None,
        sample_rate: int | None,
        directory: Path,
    ) -> subprocess.Popen[bytes]:
        width, height = self.size
        rate = Fraction(self.fps).limit_denominator(1001)
        command = [ffmpeg_exe(), "-y", "-hide_banner", "-nostats", "-loglevel", "error"]
        command += ["-f", "rawvideo", "-pix_fmt", pixel_format, "-s", f"{width}x{height}"]
        command += ["-r", str(rate)]
        if pixel_format == "yuv420p":
            # Frames already BT.709 limited: said so, ffmpeg has nothing to convert.
            command += [*COLOUR_TAGS, "-i", "-"]
            video_filter = []
        else:
            # RGB with BT.709's primaries and transfer (sRGB's), converted to the same
            # BT.709 limited range (swscale's default matrix is BT.601's): one picture
            # from either input. (Untagged input leaves primaries and transfer unknown.)
            command += ["-color_primaries", "bt709", "-color_trc", "bt709", "-i", "-"]
            video_filter = ["-vf", "scale=out_color_matrix=bt709:out_range=tv"]
        if audio is not None:
            # ffmpeg reads the track from a WAV beside the film (stdin carries the frames).
            handle, audio_name = tempfile.mkstemp(prefix=".audio.", suffix=".wav", dir=directory)
            os.close(handle)
            self._audio_file = Path(audio_name)
            self._resources.callback(self._audio_file.unlink, missing_ok=True)
            write_wav(self._audio_file, audio, int(sample_rate or 0))
            command += ["-i", str(self._audio_file), "-map", "0:v:0", "-map", "1:a:0"]
            command += ["-c:a", "aac", "-b:a", "160k"]
        command += ["-c:v", "libx264", "-preset", preset, "-crf", str(quality)]
        if preset == PRESET:
            command += ["-x264-params", X264_PARAMS]
        command += [*video_filter, "-pix_fmt", "yuv420p", *COLOUR_TAGS]
        command += ["-movflags", "+faststart", "-f", "mp4", str(self.temporary)]
        try:
            # Its own session: a Ctrl-C meant for us must not make ffmpeg finish the file.
            return subprocess.Popen(
                command,
                stdin=subprocess.PIPE,
                stdout=subprocess.DEVNULL,
                stderr=self._log,
                start_new_session=True,
            )
        except OSError as error:
            raise VideoError(f"cannot start ffmpeg ({error})") from None

    # --- the writer thread -----------------------------------------------------------

    def _feed(self) -> None:
        stdin = self._process.stdin
        assert stdin is not None
        try:
            while True:
                frame = self._queue.get()
                if frame is None:
                    break
                stdin.write(frame)
        except BaseException as error:  # a broken pipe: ffmpeg died
            self._error = error
            # Keep draining so the producer never blocks on a full queue.
            while self._queue.get() is not None:
                pass

    # --- the producer side -------------------------------------------------------------

    def write(self, frame: bytes | npt.NDArray[np.uint8]) -> None:
        """Queue one frame (rows top first); blocks while the queue is full."""
        data = frame.tobytes() if isinstance(frame, np.ndarray) else frame
        if len(data) != self.frame_bytes:
            raise ValueError(f"a frame of {len(data)} bytes; expected {self.frame_bytes}")
        if self._error is not None:
            raise self._failure()
        self._queue.put(data)
        self.frames_written += 1

    def _failure(self) -> VideoError:
        self._log.seek(0)
        lines = self._log.read().decode(errors="replace").strip().splitlines()
        detail = lines[-1] if lines else str(self._error or "ffmpeg failed")
        return VideoError(f"ffmpeg could not write {self.path}: {detail}")

    def close(self) -> Path:
        """Finish the film and move it into place; returns its path."""
        if self._finished:
            return self.path
        try:
            # Finishing takes real seconds (x264's tail, the faststart rewrite): an error
            # or Ctrl-C meanwhile must still stop ffmpeg and remove the temporary file.
            self._queue.put(None)
            self._thread.join()
            stdin = self._process.stdin
            with contextlib.suppress(OSError):
                if stdin is not None:
                    stdin.close()
            code = self._process.wait()
        except BaseException:
            self.abort()
            raise
        if code != 0 or self._error is not None or self.frames_written == 0:
            failure = (
                VideoError(f"{self.path}: no frames were written")
                if self.frames_written == 0 and code == 0
                else self._failure()
            )
            self.abort()
            raise failure
        self._finished = True
        with self._resources:  # the audio and log go even if the rename fails
            self._output.commit()
        return self.path

    def abort(self) -> None:
        """Stop ffmpeg and remove the temporary file; the target is not touched."""
        if self._finished:
            return
        self._finished = True
        if self._process.poll() is None:
            self._process.kill()
        # Unblock the writer thread: with ffmpeg gone its writes fail and it drains
        # the queue until it meets this end marker.
        with contextlib.suppress(queue.Full):
            self._queue.put(None, timeout=5.0)
        self._thread.join(timeout=5.0)
        self._process.wait()
        if self._process.stdin is not None:
            # Its buffer may not flush to a dead ffmpeg: that is expected here.
            with contextlib.suppress(OSError):
                self._process.stdin.close()
        self._resources.close()  # the unfinished film, the audio track and the log go
