"""`python -m billiards.sweep` on Dask: a local cluster gives the serial bytes; an
existing cluster (`dask scheduler` and `dask worker` on loopback) runs the sweep; a
worker killed mid-sweep has its batch rerun, every run once; Ctrl-C leaves nothing.

Each test starts its processes in a session of their own and checks that none of
them is left alive."""

from __future__ import annotations

import contextlib
import csv
import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import psutil
import pytest

from billiards.sweep.runs import VaryPlan, run_rows
from billiards.sweep.variations import Variations, load_scene_data, parse_vary
from tests.commands import run_module
from tests.physics.test_machine_independence import VARIANTS

DASK = str(Path(sys.executable).parent / "dask")
SHORT = "simulation.max_time=0.4"  # a few milliseconds a run


def _default_sigint() -> None:
    # Children of a background job may inherit an ignored SIGINT; a terminal's is default.
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def start(
    args: list[str], log: Path, environment: dict[str, str] | None = None
) -> subprocess.Popen[bytes]:
    """A process in a session of its own (so its children can be found), logging to a file."""
    with open(log, "wb") as file:
        return subprocess.Popen(
            args,
            stdout=file,
            stderr=subprocess.STDOUT,
            start_new_session=True,
            preexec_fn=_default_sigint,
            env={**os.environ, **environment} if environment else None,
        )


def sweep(*args: str, log: Path) -> subprocess.Popen[bytes]:
    return start([sys.executable, "-m", "billiards.sweep", *args], log)


def alive_in_session(session: int) -> list[str]:
    """Processes of a session that still run (a zombie has already exited)."""
    found = []
    for process in psutil.process_iter(["pid", "status", "cmdline"]):
        with contextlib.suppress(psutil.Error, ProcessLookupError):
            if os.getsid(process.pid) == session and process.status() != psutil.STATUS_ZOMBIE:
                found.append(" ".join(process.info["cmdline"] or []))
    return found


def wait_for(condition: object, seconds: float, what: str) -> None:
    assert callable(condition)
    deadline = time.monotonic() + seconds
    while not condition():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.05)


def rows_written(output: Path) -> int:
    """Rows in the unfinished folder's runs.csv (the folder is hidden until done)."""
    files = list(output.parent.glob(f".{output.name}.*.tmp/runs.csv"))
    return max((len(file.read_bytes().splitlines()) - 1 for file in files), default=0)


@contextlib.contextmanager
def loopback_cluster(
    tmp_path: Path, workers: int, environments: list[dict[str, str]] | None = None
) -> Iterator[tuple[str, list[subprocess.Popen[bytes]]]]:
    """`dask scheduler` on a free loopback port and `dask worker`s joined to it (worker
    i with environments[i] added to its environment); all stopped, and checked gone,
    on the way out."""
    scheduler_file = tmp_path / "scheduler.json"
    processes = [
        start(
            [DASK, "scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
             "--scheduler-file", str(scheduler_file)],
            tmp_path / "scheduler.log",
        )
    ]  # fmt: skip
    worker_processes: list[subprocess.Popen[bytes]] = []
    try:
        wait_for(scheduler_file.exists, 30, "the scheduler's address")
        wait_for(lambda: scheduler_file.read_text().strip().endswith("}"), 5, "its file")
        address = json.loads(scheduler_file.read_text())["address"]
        for index in range(workers):
            worker_processes.append(
                start(
                    [DASK, "worker", address, "--nthreads", "1", "--no-nanny", "--no-dashboard",
                     "--name", f"w{index}", "--local-directory", str(tmp_path / f"w{index}")],
                    tmp_path / f"w{index}.log",
                    environments[index] if environments else None,
                )
            )  # fmt: skip
        processes += worker_processes
        for index in range(workers):
            log = tmp_path / f"w{index}.log"
            wait_for(lambda log=log: b"Registered to" in log.read_bytes(), 30, "a worker")
        yield address, worker_processes
    finally:
        # Workers first: a worker closing while its scheduler goes waits for it.
        for process in reversed(processes):
            if process.poll() is None:
                process.terminate()
            try:
                process.wait(timeout=15)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
        for process in processes:
            assert alive_in_session(process.pid) == [], "a cluster process outlived the test"


def serial_rows(scene: str, vary: list[str], runs: list[int]) -> dict[int, tuple[str, ...]]:
    """Run a few of the runs here, as CSV fields (inputs and positions) to compare."""
    scene_data = load_scene_data(scene)
    plan_runs = max(runs) + 1
    plan = VaryPlan(scene_data, Variations(tuple(parse_vary(v) for v in vary), 0), plan_runs)
    out = {}
    for run in runs:
        (row,) = run_rows(plan, range(run, run + 1))
        out[run] = tuple(repr(float(v)) for v in (*row.inputs, *row.positions.ravel()))
    return out


def positions(row: dict[str, str]) -> tuple[str, ...]:
    return tuple(value for column, value in row.items() if column.endswith(("_x", "_y")))


@pytest.mark.long
def test_a_two_worker_local_sweep_equals_the_serial_sweep_byte_for_byte(tmp_path: Path) -> None:
    args = ["--runs", "60", "--vary", "ball.cue.velocity=2.5:3.5",
            "--vary", "ball.cue.position.y=0.5325~0.001", "--vary", SHORT, "--quiet"]  # fmt: skip
    local = sweep(*args, "--workers", "2", "--batch", "4", "-o", str(tmp_path / "local"),
                  log=tmp_path / "local.log")  # fmt: skip
    serial = run_module("billiards.sweep", *args, "--workers", "0", "-o", str(tmp_path / "serial"))
    assert serial.returncode == 0, serial.stderr
    assert local.wait(timeout=120) == 0, (tmp_path / "local.log").read_text()
    assert (tmp_path / "local.log").read_text() == ""
    local_csv = (tmp_path / "local" / "runs.csv").read_bytes()
    assert local_csv == (tmp_path / "serial" / "runs.csv").read_bytes()
    assert local_csv.count(b"\n") == 61
    summary = (tmp_path / "local" / "summary.json").read_bytes()
    assert summary == (tmp_path / "serial" / "summary.json").read_bytes()
    time.sleep(0.5)  # the workers' exits are reaped by the cluster before the command ends
    assert alive_in_session(local.pid) == []


@pytest.mark.long
def test_a_sweep_runs_on_an_existing_scheduler_and_worker(tmp_path: Path) -> None:
    vary = ["ball.cue.velocity=2.5:3.5", SHORT]
    with loopback_cluster(tmp_path, workers=1) as (address, _):
        run = run_module(
            "billiards.sweep", "--runs", "12", "--vary", vary[0], "--vary", vary[1],
            "--scheduler", address, "-o", str(tmp_path / "out"), "--quiet",
        )  # fmt: skip
    assert run.returncode == 0, run.stderr
    with open(tmp_path / "out" / "runs.csv", newline="") as file:
        rows = list(csv.DictReader(file))
    assert [row["run"] for row in rows] == [str(i) for i in range(12)]
    expected = serial_rows("break", vary, [0, 11])
    for run_index in (0, 11):
        row = rows[run_index]
        got = (row["ball.cue.velocity"], row["simulation.max_time"], *positions(row))
        assert got == expected[run_index]


@pytest.mark.long
def test_workers_on_different_cpu_kernels_write_the_serial_sweeps_bytes(tmp_path: Path) -> None:
    # Two workers computing as two different machines would (other BLAS kernels, numpy
    # without AVX2): a 10 m/s break, chaotic at rounding, gives the same runs.csv as one
    # process. Before the physics dropped BLAS, 23 of 40 such runs ended > 1 cm apart.
    args = ["hard_break", "--runs", "24", "--vary", "ball.cue.position.y=0.5325~0.001",
            "--vary", "simulation.max_time=3", "--batch", "2", "--quiet"]  # fmt: skip
    environments = [
        {**VARIANTS["openblas-Prescott"], **VARIANTS["numpy-no-avx2"]},
        VARIANTS["openblas-Haswell"],
    ]
    with loopback_cluster(tmp_path, workers=2, environments=environments) as (address, _):
        cluster = run_module(
            "billiards.sweep", *args, "--scheduler", address, "-o", str(tmp_path / "cluster")
        )
    serial = run_module("billiards.sweep", *args, "--workers", "0", "-o", str(tmp_path / "serial"))
    assert cluster.returncode == 0, cluster.stderr
    assert serial.returncode == 0, serial.stderr
    assert (tmp_path / "cluster" / "runs.csv").read_bytes() == (
        tmp_path / "serial" / "runs.csv"
    ).read_bytes()


@pytest.mark.long
def test_a_killed_worker_has_its_batch_rerun_and_every_run_appears_once(tmp_path: Path) -> None:
    vary = ["ball.cue.velocity=2.5:3.5"]  # the full break: about 12 ms a run
    output = tmp_path / "out"
    with loopback_cluster(tmp_path, workers=2) as (address, workers):
        run = sweep("--runs", "200", "--vary", vary[0], "--batch", "3", "--scheduler", address,
                    "-o", str(output), "--quiet", log=tmp_path / "sweep.log")  # fmt: skip
        wait_for(lambda: rows_written(output) >= 30, 60, "the first rows")
        workers[1].kill()  # SIGKILL: no goodbye to the scheduler, its batches are lost
        workers[1].wait()
        assert rows_written(output) < 200, "the sweep ended before the worker was killed"
        assert run.wait(timeout=120) == 0, (tmp_path / "sweep.log").read_text()
    with open(output / "runs.csv", newline="") as file:
        rows = list(csv.DictReader(file))
    assert [row["run"] for row in rows] == [str(i) for i in range(200)]
    assert all(row["status"] == "ok" for row in rows)
    expected = serial_rows("break", vary, [0, 199])
    for index in (0, 199):
        assert (rows[index]["ball.cue.velocity"], *positions(rows[index])) == expected[index]


@pytest.mark.long
def test_ctrl_c_stops_the_cluster_and_leaves_no_output(tmp_path: Path) -> None:
    output = tmp_path / "out"
    run = sweep("hard_break", "--runs", "2000", "--vary", "ball.cue.velocity=9.5:10.5",
                "--workers", "2", "-o", str(output), log=tmp_path / "sweep.log")  # fmt: skip
    wait_for(lambda: rows_written(output) >= 4, 60, "the first rows")
    os.killpg(run.pid, signal.SIGINT)  # as a terminal's Ctrl-C: the whole process group
    assert run.wait(timeout=30) == 130
    log = (tmp_path / "sweep.log").read_text()
    assert log.rstrip().splitlines()[-1] == "interrupted: stopped, no output written"
    assert "Traceback" not in log
    assert os.listdir(tmp_path) == ["sweep.log"]  # neither the folder nor its temporary
    wait_for(lambda: alive_in_session(run.pid) == [], 10, "the workers to stop")
