"""Output files and folders that appear whole or not at all.

Every file the package writes (film, still, picture, sound, trajectory) is written to
a temporary file beside its target and renamed over it only when complete, and a
sweep's folder likewise, so an error, Ctrl-C or a terminating signal never leaves a
half-written output behind.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

# Read once: os.umask can only be read by setting it, which is not thread-safe.
_UMASK = os.umask(0)
os.umask(_UMASK)


class OutputError(OSError):
    """An output file could not be written; str() is one line naming the target."""


class AtomicFile:
    """A temporary file beside `path` that becomes `path` on commit(), or is removed on
    discard(). Either may be called any number of times; the first decides."""

    def __init__(self, path: str | Path, suffix: str = ".tmp") -> None:
        self.target = Path(path)
        directory = self.target.parent
        try:
            handle, name = tempfile.mkstemp(
                prefix=f".{self.target.name}.", suffix=suffix, dir=directory
            )
        except OSError as error:
            raise OutputError(f"{self.target}: cannot write there ({error.strerror})") from None
        os.close(handle)
        self.temporary = Path(name)
        self._done = False

    def commit(self) -> Path:
        """Move the finished file into place; on failure remove it and raise OutputError
        naming the target (never the temporary name)."""
        if self._done:
            return self.target
        self._done = True
        try:
            # mkstemp makes the file private; give the result the usual permissions.
            os.chmod(self.temporary, 0o666 & ~_UMASK)
            os.replace(self.temporary, self.target)
        except OSError as error:
            self.temporary.unlink(missing_ok=True)
            raise OutputError(f"{self.target}: cannot write it ({error.strerror})") from None
        return self.target

    def discard(self) -> None:
        """Remove the unfinished file; the target is left as it was."""
        if not self._done:
            self._done = True
            self.temporary.unlink(missing_ok=True)


@contextmanager
def atomic_output(path: str | Path, suffix: str = ".tmp") -> Iterator[Path]:
    """Yield a temporary path beside `path`; rename it to `path` if the block succeeds,
    delete it if the block raises (KeyboardInterrupt included)."""
    output = AtomicFile(path, suffix)
    try:
        yield output.temporary
    except BaseException:
        output.discard()
        raise
    output.commit()


class AtomicFolder:
    """A temporary folder beside `path` that becomes `path` on commit(), or is removed
    on discard(); the first of them decides."""

    def __init__(self, path: str | Path) -> None:
        self.target = Path(path)
        parent = self.target.absolute().parent
        try:
            name = tempfile.mkdtemp(prefix=f".{self.target.name}.", suffix=".tmp", dir=parent)
        except OSError as error:
            raise OutputError(f"{self.target}: cannot write there ({error.strerror})") from None
        self.temporary = Path(name)
        self._done = False

    def commit(self) -> Path:
        if self._done:
            return self.target
        self._done = True
        old = None
        try:
            os.chmod(self.temporary, 0o777 & ~_UMASK)  # mkdtemp's folder is private
            if self.target.is_dir():  # empty, or --force: moved aside, then removed
                old = Path(
                    tempfile.mkdtemp(prefix=f".{self.target.name}.", dir=self.temporary.parent)
                )
                os.replace(self.target, old / "old")
            os.replace(self.temporary, self.target)
        except OSError as error:
            if old is not None and (old / "old").exists():
                os.replace(old / "old", self.target)  # put the old folder back
            shutil.rmtree(self.temporary, ignore_errors=True)
            raise OutputError(f"{self.target}: cannot write it ({error.strerror})") from None
        finally:
            if old is not None:
                shutil.rmtree(old, ignore_errors=True)
        return self.target

    def discard(self) -> None:
        if not self._done:
            self._done = True
            shutil.rmtree(self.temporary, ignore_errors=True)
