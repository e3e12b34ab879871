"""An output folder that appears whole or not at all (billiards.shell.atomic, for folders).

Everything is written into a hidden temporary folder beside the target, which is
renamed into place only when complete; an error, Ctrl-C or a signal removes it.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

from billiards.shell.atomic import OutputError

# Read once: os.umask can only be read by setting it, which is not thread-safe.
_UMASK = os.umask(0)
os.umask(_UMASK)


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
