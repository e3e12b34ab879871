"""Where a sweep's runs are computed: in this process, on a local Dask cluster that
lives as long as the sweep, or on an existing cluster's scheduler.

Runs travel in batches of equal size (to a run), each as large as BATCH_SIZE allows
and as many as a whole number of rounds of the workers: a worker simulates its batch as
one batch of runs (billiards.simulation.simulate_batch), which costs a pass's fixed
price whatever its size, so the larger the faster up to that size (hard_break: 6-8
runs/s alone, 69-74 in a batch of 64, 128-169 in 256); and equal batches let the
workers finish together (a Dask task costs about a millisecond to schedule).
Batches come back in any order and are handed on in run order; no more than a
window of them is in flight or waiting, so memory does not grow with the runs. A batch
whose worker dies is computed again elsewhere (Dask reschedules it; `retries` covers a
task that raises), and its rows are handed on once.
"""

from __future__ import annotations

import logging
import math
import signal
import socket
import time
from collections.abc import Iterator
from typing import Any

from billiards.shell.closing import Closing
from billiards.simulation import BATCH_SIZE
from billiards.sweep.runs import Batch, Plan, run_batch

IN_FLIGHT_PER_WORKER = 2  # so a worker has its next batch while one result travels
WINDOW_PER_WORKER = 4  # batches in flight or waiting for an earlier one
RETRIES = 3
CONNECT_SECONDS = 10
WORKER_WAIT_SECONDS = 60
POLL_SECONDS = 2  # how often a sweep waiting on its batches checks that workers remain
NO_WORKERS_SECONDS = 30
INSTALL_HINT = 'the sweep needs Dask: pip install "billiards[sweep]"'


class ClusterError(RuntimeError):
    """The cluster cannot be used (Dask missing, scheduler unreachable); one line."""


class BatchError(ClusterError):
    """A batch failed on the cluster itself (a run's own failure is a row); one line."""


def dask_missing() -> str | None:
    """One line saying how to install Dask, or None if it imports."""
    try:
        import distributed  # noqa: F401
    except ImportError:
        return INSTALL_HINT
    return None


class Batcher:
    """Cuts runs 0..n-1 into consecutive batches: `size` runs each if given, else as few
    as a whole number of rounds of the workers allows with no batch over BATCH_SIZE,
    their sizes differing by one run at most."""

    def __init__(self, runs: int, workers: int, size: int | None = None) -> None:
        self.runs = runs
        if size is None:
            workers = max(1, workers)
            rounds = max(1, math.ceil(runs / (workers * BATCH_SIZE)))
            self.count = min(runs, workers * rounds)  # never an empty batch
            self.size = None
        else:
            self.count = math.ceil(runs / size)
            self.size = size
        self._taken = 0  # the spans are computed as taken: none listed up front

    def end(self, batch: int) -> int:
        """Where batch `batch` (from 0) ends: one past its last run."""
        if self.size is None:
            return (batch + 1) * self.runs // self.count
        return min(self.runs, (batch + 1) * self.size)

    def take(self) -> tuple[int, int] | None:
        if self._taken >= self.count:
            return None
        start = 0 if self._taken == 0 else self.end(self._taken - 1)
        self._taken += 1
        return start, self.end(self._taken - 1)


class Sweeper(Closing):
    """Computes a plan's batches and yields them in run order. workers = 0 computes in
    this process; otherwise a local cluster of that many worker processes is started,
    unless a scheduler address is given. A context manager: leaving it (Ctrl-C
    included) cancels the cluster's work and stops a local cluster."""

    def __init__(
        self, workers: int, scheduler: str | None = None, batch_size: int | None = None
    ) -> None:
        self.workers = workers
        self.scheduler = scheduler
        self.batch_size = batch_size
        self.client: Any = None
        self.cluster: Any = None
        self._config: Any = None  # dask.config.set, undone on close
        self.futures: set[Any] = set()
        self.worker_seconds = 0.0  # time spent in batches, on the workers
        self.run_seconds = 0.0  # wall time from the first batch sent to the last received
        self.batches = 0

    def __enter__(self) -> Sweeper:
        if self.scheduler is None and self.workers == 0:
            return self
        missing = dask_missing()
        if missing:
            raise ClusterError(missing)
        try:
            self._connect()
        except BaseException:
            self.close()
            raise
        return self

    def _connect(self) -> None:
        import dask.config
        from distributed import Client, LocalCluster

        if self.scheduler is None:
            # The scheduler lives in this process; its connections keep their last
            # messages for debugging (1,000 each by default, each task's plan among them),
            # which would be most of this process's memory. A few are enough.
            self._config = dask.config.set({"distributed.admin.low-level-log-length": 20})
            self._config.__enter__()
            # The workers ignore SIGINT (inherited through spawn): a terminal's Ctrl-C
            # reaches the whole process group, and this process alone stops them, quietly.
            handler = signal.signal(signal.SIGINT, signal.SIG_IGN)
            try:
                self.cluster = LocalCluster(
                    n_workers=self.workers,
                    threads_per_worker=1,  # one run at a time a worker (threads: --workers 0)
                    processes=True,
                    dashboard_address=":0",  # a free port: never "8787 in use"
                    # Its errors come back to the client; a closing worker's complaints
                    # (a heartbeat to a scheduler already gone) are noise on our stderr.
                    silence_logs=logging.CRITICAL,
                )
            finally:
                signal.signal(signal.SIGINT, handler)
            self.client = Client(self.cluster)
            return
        try:
            _knock(self.scheduler)
            self.client = Client(self.scheduler, timeout=f"{CONNECT_SECONDS}s")
        except (OSError, ValueError, TypeError) as error:
            raise ClusterError(
                f"--scheduler {self.scheduler}: cannot reach the scheduler "
                f"({_short(error)}); expected the address `dask scheduler` prints, "
                "e.g. tcp://127.0.0.1:8786"
            ) from None
        try:
            self.client.wait_for_workers(1, timeout=WORKER_WAIT_SECONDS)
        except TimeoutError:
            raise ClusterError(
                f"--scheduler {self.scheduler}: no worker joined within "
                f"{WORKER_WAIT_SECONDS} s; start one with `dask worker {self.scheduler}`"
            ) from None
        self.workers = len(self.client.scheduler_info()["workers"])

    def close(self) -> None:
        if self.client is not None:
            if self.futures:
                self.client.cancel(list(self.futures))
                self.futures.clear()
            self.client.close()
            self.client = None
        if self.cluster is not None:
            self.cluster.close()
            self.cluster = None
        if self._config is not None:
            self._config.__exit__(None, None, None)
            self._config = None

    def run(self, plan: Plan) -> Iterator[Batch]:
        """Every batch of the plan, in run order."""
        batcher = Batcher(plan.runs, max(1, self.workers), self.batch_size)
        began = time.perf_counter()
        try:
            if self.client is None:
                while (span := batcher.take()) is not None:
                    # This process alone: the compiled runs on its threads, one a core.
                    batch = run_batch(plan, *span, threads=True)
                    self._count(batch)
                    yield batch
            else:
                yield from self._run_on_cluster(plan, batcher)
        finally:
            self.run_seconds += time.perf_counter() - began

    def _count(self, batch: Batch) -> None:
        self.worker_seconds += batch.seconds
        self.batches += 1

    def _run_on_cluster(self, plan: Plan, batcher: Batcher) -> Iterator[Batch]:
        from distributed import wait

        client = self.client
        waiting: dict[int, Batch] = {}  # arrived before an earlier batch
        next_run = 0
        in_flight_limit = IN_FLIGHT_PER_WORKER * max(1, self.workers)
        window = WINDOW_PER_WORKER * max(1, self.workers)
        workerless_since: float | None = None

        def submit_more() -> None:
            while len(self.futures) < in_flight_limit and len(self.futures) + len(waiting) < window:
                span = batcher.take()
                if span is None:
                    return
                future = client.submit(run_batch, plan, *span, pure=False, retries=RETRIES)
                self.futures.add(future)

        submit_more()
        while self.futures:
            try:
                done, _ = wait(
                    list(self.futures), timeout=POLL_SECONDS, return_when="FIRST_COMPLETED"
                )
            except TimeoutError:
                # Dask waits for workers forever; a sweep whose cluster lost them all
                # (say, workers without billiards die unpickling a batch) says so.
                if client.scheduler_info().get("workers"):
                    workerless_since = None
                elif workerless_since is None:
                    workerless_since = time.monotonic()
                elif time.monotonic() - workerless_since > NO_WORKERS_SECONDS:
                    raise BatchError(
                        f"the cluster has had no workers for {NO_WORKERS_SECONDS} s (each "
                        'worker needs billiards installed: pip install "billiards[sweep]")'
                    ) from None
                continue
            for future in done:
                try:
                    batch: Batch = future.result()
                except Exception as error:  # a run's failure is a row: this is the cluster's
                    raise BatchError(
                        f"a batch of runs failed on the cluster: {type(error).__name__}: "
                        f"{_short(error)}"
                    ) from None
                self.futures.discard(future)
                future.release()
                self._count(batch)
                waiting[batch.start] = batch
            ready = []
            while next_run in waiting:
                ready.append(waiting.pop(next_run))
                next_run += len(ready[-1].rows)
            submit_more()  # before handing on, so the workers need not wait for us
            yield from ready


def _knock(address: str) -> None:
    """Fail at once on a refused TCP connection (Dask would retry until its timeout)."""
    from distributed.comm import parse_address
    from distributed.comm.addressing import parse_host_port

    scheme, location = parse_address(address)
    if scheme == "tcp":
        host, port = parse_host_port(location)
        with socket.create_connection((host, port), timeout=CONNECT_SECONDS):
            pass


def _short(error: BaseException) -> str:
    text = str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__
    return text if len(text) < 160 else text[:157] + "..."
