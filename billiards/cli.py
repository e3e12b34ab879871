"""What the package's commands share: argument errors as one line, exit status 2."""

from __future__ import annotations

import argparse
import sys
from typing import NoReturn


class OneLineParser(argparse.ArgumentParser):
    """argparse, but a bad option is one line on stderr (no usage dump) and exit 2,
    like every other input error of the package."""

    def error(self, message: str) -> NoReturn:
        print(f"error: {message} (see --help)", file=sys.stderr)
        raise SystemExit(2)


def first_line(error: BaseException) -> str:
    """An exception as one line for a person (its first line, or its type's name)."""
    text = str(error).strip() or type(error).__name__
    return text.splitlines()[0]
