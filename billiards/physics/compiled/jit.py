"""How the physics is compiled: numba, with the options that keep IEEE 754's bits.

- fastmath off: LLVM may then neither reorder a sum nor contract a * b + c into one
  fused multiply-add (an FMA rounds once where the numpy code rounds twice), so the same
  + - * / and sqrt in the same order give the same bits on every x86 target;
- error_model "numpy": x / 0 is inf (or NaN), as numpy gives it, instead of an exception;
- cache: compiled once, then loaded from numba's cache (`__pycache__` beside these
  modules where that is writable, else the user's cache folder: `cache_folder`). numba
  checks only the calling function's own file, not the files of the kernels compiled
  into it, so a cache older than any source of the compiled physics is emptied first
  (`forget_a_stale_cache`).

numba is imported here, by the physics' engine only: `import billiards` never loads it.
"""

from __future__ import annotations

import hashlib
import os
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar, cast, overload

Function = TypeVar("Function", bound=Callable[..., Any])


def cache_folder() -> Path | None:
    """Where numba's cache goes when the package folder is read-only: the user's cache
    ($XDG_CACHE_HOME or ~/.cache)/billiards/numba; None where numba's own default
    (`__pycache__` beside the module) is writable, or the user chose NUMBA_CACHE_DIR."""
    if os.environ.get("NUMBA_CACHE_DIR"):
        return None
    here = Path(__file__).resolve().parent
    if os.access(here, os.W_OK) or os.access(here / "__pycache__", os.W_OK):
        return None
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "billiards" / "numba"


if "numba" not in sys.modules and (_folder := cache_folder()) is not None:
    os.environ["NUMBA_CACHE_DIR"] = str(_folder)  # numba reads it once, when imported

# The file in each cache folder naming the sources its entries were compiled from.
SOURCES_STAMP = "billiards-sources.sha256"


def sources_digest() -> str:
    """The compiled physics' sources (every module under this folder), as one digest."""
    here = Path(__file__).resolve().parent
    digest = hashlib.sha256()
    for path in sorted(here.rglob("*.py")):
        digest.update(path.relative_to(here).as_posix().encode() + b"\0")
        digest.update(path.read_bytes() + b"\0")
    return digest.hexdigest()


def cache_folders() -> list[Path]:
    """Where numba keeps the cache of each folder of the compiled physics: its
    `__pycache__`, or under NUMBA_CACHE_DIR as numba names it (its
    _UserProvidedCacheLocator: the folder's name and the SHA-1 of its absolute path)."""
    here = Path(__file__).resolve().parent
    sources = sorted({path.parent for path in here.rglob("*.py")})
    chosen = os.environ.get("NUMBA_CACHE_DIR")
    if not chosen:
        return [folder / "__pycache__" for folder in sources]
    named = [
        f"{folder.name}_{hashlib.sha1(str(folder).encode()).hexdigest()}" for folder in sources
    ]
    return [Path(chosen) / name for name in named]


def forget_a_stale_cache() -> None:
    """Empty each cache folder whose stamp is not the sources' digest, then stamp it, so
    that a kernel changed in one file is never served compiled into another from the
    cache. Safe when processes start together: at worst one deletes what another just
    wrote, which is compiled again."""
    digest = sources_digest()
    for folder in cache_folders():
        stamp = folder / SOURCES_STAMP
        try:
            if stamp.is_file() and stamp.read_text() == digest:
                continue
            folder.mkdir(parents=True, exist_ok=True)
            for entry in [*folder.glob("*.nbi"), *folder.glob("*.nbc")]:
                entry.unlink(missing_ok=True)
            written = folder / f"{SOURCES_STAMP}.{os.getpid()}"
            written.write_text(digest)
            os.replace(written, stamp)  # whole or not at all
        except OSError:
            continue  # a folder numba cannot write either: it compiles every time


forget_a_stale_cache()

import numba  # noqa: E402  (after the cache folder is chosen)

OPTIONS: dict[str, Any] = {"fastmath": False, "error_model": "numpy", "cache": True}
# A kernel only other kernels call needs no wrapper for Python (nor its compile time),
# and no reference counting: it allocates nothing (the run's scratch is state.Calendar's)
# and keeps no array past its return, so the entry's arrays outlive every call. Counted,
# each array a call is handed costs two atomic operations (a third of a run's time).
INNER: dict[str, Any] = {"no_cpython_wrapper": True, "no_cfunc_wrapper": True, "_nrt": False}


@overload
def kernel(function: Function) -> Function: ...
@overload
def kernel(function: str) -> Callable[[Function], Function]: ...


def kernel(function: Function | str) -> Function | Callable[[Function], Function]:
    """A function of the compiled physics compiled as a unit of its own (called from
    other kernels); with a signature (`@kernel("f8(f8)")`) compiled for that one alone,
    as it is defined (or loaded from numba's cache)."""
    if isinstance(function, str):
        signature = function

        def signed(each: Function) -> Function:
            return cast(Function, numba.njit(signature, **INNER, **OPTIONS)(each))

        return signed
    compiled: Function = numba.njit(**INNER, **OPTIONS)(function)
    return compiled


def entry(function: Function) -> Function:
    """A kernel Python calls: the loop over runs."""
    compiled: Function = numba.njit(nogil=True, **OPTIONS)(function)
    return compiled


def inline(function: Function) -> Function:
    """A small function of the compiled physics, written into each kernel that calls it
    (numba's IR inlining: compiling it once per caller costs less than a module of its
    own, which numba would optimize and link again into every caller)."""
    compiled: Function = numba.njit(inline="always", **OPTIONS)(function)
    return compiled


def thread_count() -> int:
    """How many threads a run over many runs spreads over: numba's (NUMBA_NUM_THREADS,
    or numba.set_num_threads)."""
    return int(numba.get_num_threads())
