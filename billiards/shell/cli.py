"""What the package's commands share: the parser (SCENE, --list-scenes, --version,
--force, --quiet), errors as one line and their exit statuses (a saved trajectory's
too), the output paths (a file, a folder, a fit's files; default names) checked before
any work, and clean exits on SIGTERM and SIGHUP."""

from __future__ import annotations

import argparse
import contextlib
import os
import signal
import sys
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from types import FrameType
from typing import Any, NoReturn

from billiards.version import __version__

# Exit statuses of every command: the shell's 128 + signal number for a signal.
EXIT_FAILED, EXIT_USAGE = 1, 2
EXIT_SIGNALLED = {signal.SIGINT: 130, signal.SIGTERM: 143, signal.SIGHUP: 129}


class OneLineParser(argparse.ArgumentParser):
    """argparse, but a bad option is one line on stderr (no usage dump) and exit 2,
    like every other input error of the package; and every command has --version."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.add_argument(
            "--version", action="version", version=f"{invoked_as(self.prog)} {__version__}"
        )

    def error(self, message: str) -> NoReturn:
        print(f"error: {message} (see --help)", file=sys.stderr)
        raise SystemExit(2)


class CommandError(Exception):
    """Ends a command from wherever it is raised: str() is the one line said on stderr,
    `status` the exit status (run_guarded says it and returns it)."""

    def __init__(self, message: object, status: int = EXIT_USAGE) -> None:
        super().__init__(str(message))
        self.status = status


def fail(message: object, status: int = EXIT_USAGE) -> int:
    """Say `message` as the command's one error line; returns the exit status."""
    print(f"error: {message}", file=sys.stderr)
    return status


@contextlib.contextmanager
def failing_on(
    *errors: type[Exception], status: int = EXIT_USAGE, one_line: bool = False
) -> Iterator[None]:
    """Any of `errors` raised in the block ends the command with `status`, said as its
    message (`one_line`: its first line, for errors that are not the package's own)."""
    try:
        yield
    except errors as error:
        raise CommandError(first_line(error) if one_line else error, status) from None


@contextlib.contextmanager
def reading_trajectory(path: str, scene_error: type[Exception]) -> Iterator[None]:
    """Loading a saved trajectory (--trajectory FILE.npz): a missing file, one whose
    [render] tables are bad (`scene_error`, the reader's: the shell sits below it) or
    one that is no trajectory ends the command in one line."""
    try:
        yield
    except FileNotFoundError:
        raise CommandError(f"{path}: no such trajectory file") from None
    except scene_error as error:  # an older file's [render] tables, read on loading
        raise CommandError(f"{path}: {error}") from None
    except (OSError, EOFError, KeyError, ValueError):  # EOFError: an empty file
        raise CommandError(
            f"{path}: not a trajectory file (one is written by "
            "python -m billiards.simulate --trajectory FILE.npz)"
        ) from None


def say(text: str) -> None:
    """A line for the person at the terminal (what was written, a warning): on stderr,
    so that stdout holds only the command's output."""
    print(text, file=sys.stderr)


def invoked_as(prog: str) -> str:
    """The command's name as it was run: the installed script's (`billiards-render`),
    else `prog` (`python -m billiards.render`)."""
    script = Path(sys.argv[0]).name
    return script if script.startswith("billiards-") else prog


def first_line(error: BaseException) -> str:
    """An exception as one line for a person (its first line, or its type's name)."""
    text = str(error).strip() or type(error).__name__
    return text.splitlines()[0]


class Terminated(BaseException):
    """SIGTERM or SIGHUP arrived: unwinds like KeyboardInterrupt, so every with-block
    (temporary files, the ffmpeg child) cleans up on the way out."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


# The signals that arrived, in order: a stop raised where something swallows it (a
# finalizer running when the signal lands prints "Exception ignored" and goes on) is
# still seen by raise_if_stopped.
_arrived: list[int] = []


def _terminate(signum: int, frame: FrameType | None) -> None:
    _arrived.append(signum)
    raise Terminated(signum)


def _interrupt(signum: int, frame: FrameType | None) -> None:
    _arrived.append(signum)
    raise KeyboardInterrupt


def _remember(signum: int, frame: FrameType | None) -> None:
    _arrived.append(signum)


def exit_cleanly_on_signals(*, deferred: bool = False) -> None:
    """Make SIGTERM and SIGHUP raise Terminated in the main thread, and SIGINT
    KeyboardInterrupt as Python's own handler does; each is also remembered. Deferred,
    they are only remembered, for the work to raise at its next raise_if_stopped: a
    stop raised inside compiled code that cannot pass it on (SciPy's Cython) is
    printed there as an ignored exception, with its traceback."""
    for signum in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(signum, _remember if deferred else _terminate)
    signal.signal(signal.SIGINT, _remember if deferred else _interrupt)


def raise_if_stopped() -> None:
    """Raise the stop of a signal that arrived, if one did: for long work to call at
    its steps and before it writes, so no swallowed signal lets it finish."""
    if _arrived:
        signum = _arrived[0]
        raise KeyboardInterrupt if signum == signal.SIGINT else Terminated(signum)


def run_guarded(command: Callable[[], int], *, deferred: bool = False) -> int:
    """A command's body run with SIGTERM and SIGHUP raising Terminated; a signal (Ctrl-C
    too) is said in one line and becomes the shell's exit status for it, as does a
    CommandError. `deferred`: the signals are raised only where the body calls
    raise_if_stopped."""
    exit_cleanly_on_signals(deferred=deferred)
    try:
        return command()
    except CommandError as error:
        return fail(error, error.status)
    except (KeyboardInterrupt, Terminated) as stop:
        return interrupted(stop)


def interrupted(error: BaseException) -> int:
    """Say that the command stopped and wrote nothing; returns its exit status."""
    signum = error.signum if isinstance(error, Terminated) else signal.SIGINT
    # After a terminal's ^C the line is not finished; in a log no blank line is wanted.
    start = "\n" if sys.stderr.isatty() else ""
    name = "interrupted" if signum == signal.SIGINT else signal.Signals(signum).name
    print(f"{start}{name}: stopped, no output written", file=sys.stderr)
    return EXIT_SIGNALLED[signal.Signals(signum)]


def output_problem(path: str | Path, *, force: bool = False) -> str | None:
    """What keeps `path` from being written as a new output file, checked before any
    work: a folder in its place, a missing or unwritable folder, or a file already
    there (replaced only with force)."""
    target = Path(path)
    folder = target.parent
    if target.is_dir():
        return f"{target}: is a folder; name a file to write"
    if not folder.is_dir():
        return f"{target}: the folder {folder} does not exist"
    if not os.access(folder, os.W_OK | os.X_OK):
        return f"{target}: cannot write in the folder {folder}"
    if target.exists() and not force:
        return f"{target}: already exists (pass --force to replace it)"
    return None


def folder_problem(path: str | Path, *, force: bool = False) -> str | None:
    """What keeps `path` from being written as a new output folder, checked before any
    work: a file in its place, a missing or unwritable parent, or a non-empty folder
    already there (replaced only with force)."""
    target = Path(path)
    parent = target.absolute().parent
    if target.exists() and not target.is_dir():
        return f"{target}: is a file; name a folder to write"
    if not parent.is_dir():
        return f"{target}: the folder {parent} does not exist"
    if not os.access(parent, os.W_OK | os.X_OK):
        return f"{target}: cannot write in the folder {parent}"
    if target.is_dir() and any(target.iterdir()) and not force:
        return f"{target}: already exists and is not empty (pass --force to replace it)"
    return None


def files_problem(folder: Path, names: list[str], *, force: bool = False) -> str | None:
    """What keeps these files from being written in `folder`, made if it is missing
    (a fit's outputs beside what the folder already holds): checked before any work."""
    if folder.exists() and not folder.is_dir():
        return f"{folder}: is a file; name a folder to write in"
    if not folder.exists():
        parent = folder.parent
        if not parent.is_dir():
            return f"{folder}: the folder {parent} does not exist"
        if not os.access(parent, os.W_OK | os.X_OK):
            return f"{folder}: cannot make it in {parent}"
        return None
    for name in names:
        problem = output_problem(folder / name, force=force)
        if problem:
            return problem
    return None


class _PrintNames(argparse.Action):
    """--list-scenes: print the shipped scenes' names, one a line, and exit 0."""

    def __init__(
        self, option_strings: list[str], dest: str, names: Callable[[], list[str]], help: str
    ) -> None:
        super().__init__(option_strings, dest, nargs=0, help=help)
        self.names = names

    def __call__(self, parser: argparse.ArgumentParser, *args: Any, **kwargs: Any) -> None:
        with contextlib.suppress(BrokenPipeError):  # `| head` may stop reading early
            print("\n".join(self.names()))
        parser.exit(0)


def command_parser(
    prog: str, description: str, scene_names: Callable[[], list[str]]
) -> OneLineParser:
    """A command's parser, with --version, the SCENE argument and --list-scenes (the
    reader's shipped_scene_names: the shell sits below the scene reader)."""
    parser = OneLineParser(prog=prog, description=description)
    parser.add_argument(
        "scene",
        nargs="?",
        help="scene TOML file, or a shipped scene's name (default: the seed break)",
    )
    parser.add_argument(
        "--list-scenes",
        action=_PrintNames,
        names=scene_names,
        help="name the shipped scenes and exit",
    )
    return parser


def add_force_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--force", action="store_true", help="replace an existing output file")


def add_quiet_argument(parser: argparse.ArgumentParser, silenced: str) -> None:
    """--quiet, its help naming what it silences."""
    parser.add_argument("--quiet", action="store_true", help=silenced)


def whole_number(
    low: int, expected: str, high: int | None = None, why: str = ""
) -> Callable[[str], int]:
    """An option's type: a whole number >= low (and <= high, `why` saying why), else
    `expected` in argparse's one line."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            value = low - 1
        if value < low:
            raise argparse.ArgumentTypeError(f"{text!r}: expected {expected}")
        if high is not None and value > high:
            raise argparse.ArgumentTypeError(
                f"{text!r}: expected {expected}, at most {high:,}{why}"
            )
        return value

    return parse


def command_words(argv: Sequence[str] | None, joined: tuple[str, ...] = ()) -> list[str]:
    """The command line's words (sys.argv's when argv is None), each option in `joined`
    glued to its value (`--times -1,2` as `--times=-1,2`): argparse would take a value
    that starts with "-" for an option and answer "expected one argument" instead of
    saying what is wrong with it."""
    out: list[str] = []
    words = iter(sys.argv[1:] if argv is None else argv)
    for word in words:
        out.append(f"{word}={next(words, '')}" if word in joined else word)
    return out


def scene_name(scene: str | None) -> str:
    """What a command's default output is named after: the scene as the command line
    gave it, a shipped scene's name or a file's without .toml (`masse_shot`,
    `scenes/my.toml` -> `my`); the seed break when none was given is `break`."""
    if scene is None:
        return "break"
    return Path(scene).name.removesuffix(".toml") or "break"


def default_output(scene: str | None, ending: str) -> str:
    """The file or folder a command writes when no output is named: in the current
    folder, after its scene (`plot masse_shot` -> masse_shot.png, `render` -> break.mp4)."""
    return scene_name(scene) + ending
