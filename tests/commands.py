"""Running the package's commands as a user would, for the CLI tests."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path


def run_module(
    module: str,
    *args: str,
    env: dict[str, str] | None = None,
    cwd: str | Path | None = None,
    timeout: float = 300,
) -> subprocess.CompletedProcess[str]:
    """`python -m module args...` with this interpreter; env adds to the environment."""
    return subprocess.run(
        [sys.executable, "-m", module, *args],
        capture_output=True,
        text=True,
        check=False,
        env={**os.environ, **(env or {})},
        cwd=cwd,
        timeout=timeout,
    )


def catches(pid: int, signums: tuple[int, ...]) -> bool:
    """Whether process pid has handlers of its own for all these signals (Linux)."""
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    mask = next(
        int(line.split()[1], 16) for line in status.splitlines() if line.startswith("SigCgt")
    )
    return all(mask >> (signum - 1) & 1 for signum in signums)


def signalled_midway(
    module: str, args: list[str], cwd: Path, signum: int, *, after_output: bool = False
) -> tuple[int, str]:
    """`python -m module args...` sent `signum` midway: once it has installed its own
    SIGTERM and SIGHUP handlers (the kernel's SigCgt mask says so, on a loaded machine
    too), with after_output once it has also written its first character to stderr (a
    forked child shows its parent's handlers until it executes Python), and a little
    later. Returns its exit status and stderr."""
    process = subprocess.Popen(
        [sys.executable, "-m", module, *args],
        cwd=cwd,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    deadline = time.monotonic() + 60
    while not catches(process.pid, (15, 1)) and time.monotonic() < deadline:
        time.sleep(0.02)
    if after_output:
        assert process.stderr is not None and process.stderr.read(1)
    time.sleep(0.3 if not after_output else 0.5)
    assert process.poll() is None, "the command ended before the signal"
    process.send_signal(signum)
    _, errors = process.communicate(timeout=60)
    return process.returncode, errors
