"""A context manager's exit written once: what a `with` block made is closed after it,
or aborted (by default, closed) after an error in it."""

from __future__ import annotations

from types import TracebackType
from typing import Self


class Closing:
    """Closes on leaving a `with` block: close() after it ran through, abort() after an
    error (close() unless a subclass abandons its work otherwise)."""

    def __enter__(self) -> Self:
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        if kind is None:
            self.close()
        else:
            self.abort()

    def close(self) -> object:
        raise NotImplementedError

    def abort(self) -> None:
        self.close()
