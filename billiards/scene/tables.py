"""TOML tables read with one-line errors: the bottom floor of every input file.

The scene reader (billiards.scene.reader) and its render settings (billiards.scene.render_table)
read their tables with the same TableReader, so every error reads alike:
`<file>: <key path> = <value>: expected <what>`. Standard library only.
"""

from __future__ import annotations

import contextlib
import difflib
import math
import re
from collections.abc import Iterator, Sequence
from contextvars import ContextVar
from dataclasses import dataclass
from typing import Any


class SceneError(ValueError):
    """A scene file a person must fix; str() is one line naming key, value, expectation."""


def shown(value: Any) -> str:
    """A Python value in a one-line message (an argument the library was given): its
    repr on one line, cut short."""
    text = " ".join(repr(value).split())
    return text if len(text) <= 60 else text[:57] + "..."


def _show(value: Any) -> str:
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, dict):
        return "a table"
    return str(value)


@dataclass(frozen=True)
class KeyRead:
    """A key the reader asked for: its path (an array of tables' items as `[]`), the
    default it was given, and what it accepts (empty when the caller checks it)."""

    path: str
    default: Any
    expected: str
    # A number's range, as the reader checks it (None: unbounded on that side).
    low: float | None = None
    high: float | None = None
    low_open: bool = False


# The default noted for a key the reader requires (when it finds it missing).
REQUIRED = "<required>"

# The keys asked for inside keys_read(); None outside it (the reader records nothing).
_KEYS_READ: ContextVar[list[KeyRead] | None] = ContextVar("keys_read", default=None)


@contextlib.contextmanager
def keys_read() -> Iterator[list[KeyRead]]:
    """Every key each TableReader asks for within the with-block, in order: the
    reader's own table of keys, from which the site's reference of scene keys is made."""
    found: list[KeyRead] = []
    token = _KEYS_READ.set(found)
    try:
        yield found
    finally:
        _KEYS_READ.reset(token)


class TableReader:
    """Reads one TOML table, checking types and ranges; finish() rejects unknown keys.

    Shared by every section of a scene file (the render settings use it too).
    """

    def __init__(self, data: Any, path: str, source: str) -> None:
        self.path = path
        self.source = source
        if not isinstance(data, dict):
            raise SceneError(f"{source}: {path} = {_show(data)}: expected a table")
        self.data: dict[str, Any] = data
        self.known: set[str] = set()

    def key_path(self, key: str) -> str:
        return f"{self.path}.{key}" if self.path else key

    def fail(self, key: str, value: Any, expected: str) -> SceneError:
        self.note(key, None, expected)
        return SceneError(
            f"{self.source}: {self.key_path(key)} = {_show(value)}: expected {expected}"
        )

    def missing(self, key: str, expected: str) -> SceneError:
        self.note(key, REQUIRED, expected)
        return SceneError(f"{self.source}: {self.key_path(key)}: missing; expected {expected}")

    def has(self, key: str) -> bool:
        self.known.add(key)
        self.note(key, None, "")
        return key in self.data

    def raw(self, key: str, default: Any = None) -> Any:
        self.known.add(key)
        self.note(key, default, "")
        return self.data.get(key, default)

    def note(self, key: str, default: Any, expected: str, **bounds: Any) -> None:
        """Record the key within keys_read() (nothing otherwise), with its bounds as
        KeyRead takes them (low, high, low_open)."""
        found = _KEYS_READ.get()
        if found is not None:
            path = re.sub(r"\[\d+\]", "[]", self.key_path(key))
            found.append(KeyRead(path, default, expected, **bounds))

    def number(
        self,
        key: str,
        default: float,
        *,
        low: float | None = None,
        high: float | None = None,
        low_open: bool = False,
        what: str | None = None,
    ) -> float:
        value = self.raw(key, default)
        expected = what or _range_text(low, high, low_open)
        self.note(key, default, expected, low=low, high=high, low_open=low_open)
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.fail(key, value, expected)
        number = float(value)
        if not math.isfinite(number):
            raise self.fail(key, value, expected)
        if low is not None and (number < low or (low_open and number == low)):
            raise self.fail(key, value, expected)
        if high is not None and number > high:
            raise self.fail(key, value, expected)
        return number

    def integer(self, key: str, default: int, *, low: int | None = None) -> int:
        value = self.raw(key, default)
        expected = "a whole number" + (f" >= {low}" if low is not None else "")
        self.note(key, default, expected, low=low)
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.fail(key, value, expected)
        if low is not None and value < low:
            raise self.fail(key, value, expected)
        return value

    def string(self, key: str, default: str, choices: Sequence[str] | None = None) -> str:
        value = self.raw(key, default)
        if choices is not None:
            expected = "one of " + ", ".join(f'"{c}"' for c in choices)
        else:
            expected = "a string"
        self.note(key, default, expected)
        if not isinstance(value, str) or (choices is not None and value not in choices):
            raise self.fail(key, value, expected)
        return value

    def boolean(self, key: str, default: bool) -> bool:
        value = self.raw(key, default)
        self.note(key, default, "true or false")
        if not isinstance(value, bool):
            raise self.fail(key, value, "true or false")
        return value

    def vector(self, key: str, default: Sequence[float], size: int = 2) -> tuple[float, ...]:
        value = self.raw(key, list(default))
        expected = f"an array of {size} finite numbers"
        self.note(key, tuple(default), expected)
        if not isinstance(value, list) or len(value) != size:
            raise self.fail(key, value, expected)
        if any(isinstance(v, bool) or not isinstance(v, int | float) for v in value):
            raise self.fail(key, value, expected)
        numbers = tuple(float(v) for v in value)
        if not all(math.isfinite(v) for v in numbers):
            raise self.fail(key, value, expected)
        return numbers

    def table(self, key: str) -> TableReader:
        data = self.raw(key, {})
        self.note(key, None, "a table")
        return TableReader(data, self.key_path(key), self.source)

    def tables(self, key: str) -> list[TableReader]:
        """An array of tables ([[key]] in TOML), each with an indexed key path."""
        value = self.raw(key, [])
        self.note(key, None, f"an array of tables ([[{key}]])")
        if not isinstance(value, list):
            raise self.fail(key, value, f"an array of tables ([[{key}]])")
        return [
            TableReader(item, f"{self.key_path(key)}[{index}]", self.source)
            for index, item in enumerate(value)
        ]

    def finish(self) -> None:
        """Reject keys nobody asked for, suggesting the nearest known one."""
        for key in self.data:
            if key in self.known:
                continue
            near = difflib.get_close_matches(key, sorted(self.known), n=1)
            hint = f' (did you mean "{near[0]}"?)' if near else ""
            known = ", ".join(sorted(self.known)) or "no keys"
            raise SceneError(
                f"{self.source}: {self.key_path(key)}: unknown key{hint}; expected one of: {known}"
            )


def _range_text(low: float | None, high: float | None, low_open: bool) -> str:
    if low is not None and high is not None:
        return f"a number in {'(' if low_open else '['}{low:g}, {high:g}]"
    if low is not None:
        return f"a number {'>' if low_open else '>='} {low:g}"
    if high is not None:
        return f"a number <= {high:g}"
    return "a finite number"
