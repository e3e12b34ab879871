"""The compiled loop (billiards.physics.compiled) gives the numpy engine's results, bit
for bit and field for field: on every shipped scene it supports (both models; the spin
model's own families in test_compiled_spin), on the hard-case families, in a batch as
alone, and on threads as serially; it compiles no FMA, and `import billiards` does not
load numba."""

from __future__ import annotations

import dataclasses
import os
import subprocess
import sys
from collections.abc import Callable, Iterator
from functools import cache
from pathlib import Path

import numpy as np
import pytest
from llvmlite import binding

from billiards.physics.compiled import runner as compiled
from billiards.physics.engine.packaging import Run
from billiards.physics.engine.result import SimulationResult
from billiards.physics.engine.setup import Setup
from billiards.physics.methods import entry as methods
from billiards.scene.reader import default_scene_path, load_scene
from billiards.simulation import _run_of
from scripts.bench_compiled import random_scene
from tests.physics import test_hard_cases, test_pocket_hard_cases
from tests.test_batch import exact_form
from tests.test_fingerprints import PINS

ROOT = Path(__file__).resolve().parents[2]
hard = pytest.mark.hard


def numpy_results(items: list[Run]) -> list[SimulationResult | Exception]:
    """The numpy engine's results for `items` (the compiled loop refused every run)."""
    supports = methods.compiled.supports
    methods.compiled.supports = lambda setup, method: False
    try:
        return list(methods.run_batch(items))
    finally:
        methods.compiled.supports = supports


def assert_same_results(items: list[Run], threads: bool = False) -> None:
    """The compiled loop's result of each run is the numpy engine's, every field's bytes
    (and the final positions)."""
    fast = compiled.run_compiled(items, threads=threads)
    for item, mine, theirs in zip(items, fast, numpy_results(items), strict=True):
        assert isinstance(theirs, SimulationResult), theirs
        assert exact_form(mine) == exact_form(theirs), item[0]
        assert exact_form(mine.final_positions) == exact_form(theirs.final_positions)


def shipped_items(method: str, dt: float | None) -> list[Run]:
    """Every shipped scene's run that the compiled loop supports and the numpy engine
    runs too (not a jump's: a ball that leaves the cloth is the compiled loop's only,
    pinned in test_fingerprints and tests/physics/test_flight.py)."""
    items = []
    for path in sorted(default_scene_path().parent.glob("*.toml")):
        item = _run_of(load_scene(path), method, dt)
        if compiled.supports(item[0], item[2]) and item[0].drives is None:
            items.append(item)
    return items


def test_every_shipped_scene_is_compiled_in_both_models() -> None:
    # rolling: break, hard_break, bank_shot, newtons_cradle, pocket_shot; spin: the other
    # nine, with every cushion and ball law they name
    supported = shipped_items("event", None)
    for name in ("jump_shot", "hop_break"):
        flying = _run_of(load_scene(default_scene_path().parent / f"{name}.toml"), "event", None)
        assert compiled.supports(flying[0], "event") and flying[0].drives is not None
    assert len(supported) + 2 == len(list(default_scene_path().parent.glob("*.toml")))
    assert [setup.model for setup, *_ in supported].count("rolling") == 5
    assert [setup.model for setup, *_ in supported].count("spin") == 9
    # The rolling model takes the seed's laws only (the reader gives it no other).
    rolling = supported[0][0]
    assert rolling.model == "rolling"
    assert not compiled.supports(dataclasses.replace(rolling, cushion_law="han2005"), "event")
    assert not compiled.supports(supported[0][0], "naive")


@pytest.mark.parametrize(("method", "dt"), [("event", None), ("exact", None), ("exact", 1 / 30)])
def test_every_supported_shipped_scene_gives_the_numpy_engines_result(
    method: str, dt: float | None
) -> None:
    for item in shipped_items(method, dt):
        assert_same_results([item])


def family_runs(make: Callable[[int], Setup], indices: range) -> list[Run]:
    runs = []
    for index in indices:
        setup = make(index)
        ids = tuple(f"b{n}" for n in range(len(setup.positions)))
        runs.append((setup, ids, "event", 1 / 240))
    return runs


FAMILIES = {
    "rack": test_hard_cases.rack_case,
    "scene": test_hard_cases.scene_case,
    "pressed": test_hard_cases.pressed_case,
    "cluster": test_hard_cases.cluster_case,
    "line": test_hard_cases.line_case,
    "frozen": test_hard_cases.frozen_case,
    "pocket_rack": lambda i: test_pocket_hard_cases.on_the_table(test_hard_cases.rack_case(i)),
    "jaw_shot": test_pocket_hard_cases.jaw_shot_case,
}


@pytest.mark.parametrize("family", FAMILIES)
def test_the_hard_case_families_give_the_numpy_engines_results(family: str) -> None:
    assert_same_results(family_runs(FAMILIES[family], range(3)))


@hard
@pytest.mark.parametrize("family", FAMILIES)
def test_many_hard_cases_give_the_numpy_engines_results(family: str) -> None:
    assert_same_results(family_runs(FAMILIES[family], range(3, 40)))


@pytest.mark.parametrize("seed", [3, 4])
def test_a_crowded_table_gives_the_numpy_engines_result(seed: int) -> None:
    # 60 balls, as the many-balls benchmark draws them: most pairs an event asks are told
    # apart by their path boxes or by the gap they cannot roll across (anchoring.
    # _rolling_apart) without their pair time; the numpy engine asks every pair's, so a
    # pair told apart wrongly loses a contact here.
    assert_same_results([random_scene(60, seed)])


@cache
def seed_break_variants(count: int) -> tuple[Run, ...]:
    """The seed break with the cue ball moved sideways by up to a millimetre and its
    speed varied by 10 %, as a sweep draws them."""
    base = _run_of(load_scene(default_scene_path()), "event", None)
    rng = np.random.default_rng(43)
    runs = []
    for _ in range(count):
        setup = base[0]
        positions, velocities = setup.positions.copy(), setup.velocities.copy()
        positions[0, 1] += rng.uniform(-1e-3, 1e-3)
        velocities[0, 0] *= rng.uniform(0.9, 1.1)
        varied = Setup(**{**setup.__dict__, "positions": positions, "velocities": velocities})
        runs.append((varied, base[1], "event", base[3]))
    return tuple(runs)


def test_seed_break_variants_give_the_numpy_engines_results_in_one_call() -> None:
    assert_same_results(list(seed_break_variants(64)))


def test_a_batch_gives_each_run_its_result_alone() -> None:
    runs = list(seed_break_variants(16))
    together = compiled.run_compiled(runs)
    for item, result in zip(runs, together, strict=True):
        assert exact_form(result) == exact_form(compiled.run_compiled([item])[0])


def test_a_run_that_fails_in_the_compiled_loop_fails_alone(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """run_batch's promise holds for the compiled runs too: should the loop raise for
    one run, the others still get the results they give alone."""
    runs = list(seed_break_variants(3))
    poisoned = runs[1][0]
    run_compiled = compiled.run_compiled

    def failing(items: list[Run], threads: bool = False) -> list[SimulationResult]:
        if any(setup is poisoned for setup, *_ in items):
            raise FloatingPointError("a run the loop cannot take")
        return run_compiled(items, threads)

    monkeypatch.setattr(methods.compiled, "run_compiled", failing)
    outcomes = list(methods.run_batch(runs))
    assert isinstance(outcomes[1], FloatingPointError)
    for index in (0, 2):
        assert exact_form(outcomes[index]) == exact_form(run_compiled([runs[index]])[0])


def test_runs_on_threads_give_the_serial_loops_results() -> None:
    runs = list(seed_break_variants(32)) + family_runs(FAMILIES["pocket_rack"], range(4))
    serial = compiled.run_compiled(runs)
    before = sys.getswitchinterval()
    seen: list[float] = []
    spans = compiled._spans

    def watched(*args: object) -> Iterator[tuple[int, int]]:
        for span in spans(*args):  # type: ignore[arg-type]
            seen.append(sys.getswitchinterval())
            yield span

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(compiled, "_spans", watched)
        threaded = compiled.run_compiled(runs, threads=True)
    assert exact_form(threaded) == exact_form(serial)
    # Quick GIL handoffs while the loop threads run (runner._quick_handoffs), and
    # Python's own interval again after.
    assert seen and max(seen) <= compiled._HANDOFF_SECONDS < before
    assert sys.getswitchinterval() == before


# --- the same bits on every machine, compiled -------------------------------------------

# The pinned scenes' fingerprints (both models: two breaks, the spin break, the carom
# shot's Han 2005 cushions and throw, the pool break's pockets, the jump shot's flight, the hopping break's),
# printed by a fresh
# process (tests.test_fingerprints), and
# where compiled, how many fused multiply-adds the core kernels' code holds (an FMA
# rounds a * b + c once: the bits would change on CPUs that have it).
DIGEST = """
import re
from billiards.physics.compiled import anchoring, loop, roots
from billiards.scene.reader import default_scene_path, load_scene
from billiards.simulation import simulate_scene
from tests.test_fingerprints import fingerprint
names = ("break", "hard_break", "spin_break", "three_cushion", "pool_break", "jump_shot")
for name in (*names, "hop_break"):
    path = default_scene_path().parent / f"{name}.toml"
    print(name, fingerprint(simulate_scene(load_scene(path))))
if hasattr(loop.run_many, "inspect_asm"):
    kernels = [loop.run_many, anchoring.flush, roots.first_downward_root]
    listings = [text for kernel in kernels for text in kernel.inspect_asm().values()]
    fused = re.compile(r"\\bv?f(n)?m(add|sub)", re.IGNORECASE)
    print("listings", len(listings))
    print("fma", sum(len(fused.findall(text)) for text in listings))
"""


def fresh_digests(cache: Path, script: str = DIGEST, **variables: str) -> dict[str, str]:
    """What `script` (DIGEST: a name and a value a line) prints from a fresh process with
    an empty numba cache at `cache` and the environment's `variables`."""
    environment = {**os.environ, "NUMBA_CACHE_DIR": str(cache), **variables}
    environment.pop("PYTHONWARNINGS", None)  # NUMBA_DISABLE_JIT's numpy scalars may warn
    done = subprocess.run(
        [sys.executable, "-c", script],
        cwd=ROOT,
        env=environment,
        capture_output=True,
        text=True,
        timeout=900,
        check=True,
    )
    return dict(line.split() for line in done.stdout.splitlines())


PINNED_SCENES = (
    "break",
    "hard_break",
    "spin_break",
    "three_cushion",
    "pool_break",
    "jump_shot",
    "hop_break",
)
PINNED = {name: PINS[name, "exact", None] for name in PINNED_SCENES}


def host_knows(cpu: str) -> bool:
    """Whether this host's LLVM knows the CPU name and the host can run its code."""
    if cpu == "x86-64-v4":
        flags = Path("/proc/cpuinfo").read_text() if Path("/proc/cpuinfo").exists() else ""
        needed = ("avx512f", "avx512bw", "avx512cd", "avx512dq", "avx512vl")
        if not all(flag in flags for flag in needed):
            return False
    probe = (
        "from llvmlite import binding\nbinding.initialize_native_target()\n"
        f"binding.Target.from_default_triple().create_target_machine(cpu={cpu!r})"
    )
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True)
    return done.returncode == 0 and "not a recognized processor" not in done.stderr


@hard
@pytest.mark.parametrize("cpu", ["generic", "x86-64-v2", "x86-64-v4", binding.get_host_cpu_name()])
def test_the_breaks_compiled_for_each_cpu_give_their_pins(cpu: str, tmp_path: Path) -> None:
    if not host_knows(cpu):
        pytest.skip(f"this host's LLVM does not know {cpu} or cannot run its code")
    assert fresh_digests(tmp_path, NUMBA_CPU_NAME=cpu) == {**PINNED, "listings": "3", "fma": "0"}


def test_the_breaks_run_uncompiled_with_numba_disable_jit(tmp_path: Path) -> None:
    """NUMBA_DISABLE_JIT=1 (for debugging) runs the same loop as Python: the same bits."""
    assert fresh_digests(tmp_path, NUMBA_DISABLE_JIT="1") == PINNED


def test_import_billiards_does_not_import_numba() -> None:
    probe = "import sys, billiards, billiards.scene.reader; print('numba' in sys.modules)"
    done = subprocess.run([sys.executable, "-c", probe], cwd=ROOT, capture_output=True, text=True)
    assert done.stdout.strip() == "False", done.stderr


def test_the_cache_goes_to_the_users_cache_folder_where_the_package_is_read_only(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    from billiards.physics.compiled import jit

    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert jit.cache_folder() is None  # this checkout's package folder is writable
    monkeypatch.setattr(jit.os, "access", lambda path, mode: False)
    assert jit.cache_folder() == tmp_path / "billiards" / "numba"
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "chosen"))
    assert jit.cache_folder() is None  # the user's own choice stands


def test_a_cache_compiled_from_other_sources_is_emptied_and_a_current_one_kept(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """numba checks only a function's own file: a kernel changed in another file would
    be served stale from the cache, so the cache names the sources it was compiled from."""
    from billiards.physics.compiled import jit

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    folders = jit.cache_folders()
    assert len(folders) >= 2 and all(folder.parent == tmp_path for folder in folders)
    entries = []
    for folder in folders:
        folder.mkdir()
        (folder / jit.SOURCES_STAMP).write_text("compiled from older sources")
        entries += [folder / "loop.run_many-1.py311.nbi", folder / "loop.run_many-1.py311.1.nbc"]
        for entry in entries[-2:]:
            entry.write_bytes(b"stale")
    jit.forget_a_stale_cache()
    assert not any(entry.exists() for entry in entries)
    stamps = {(folder / jit.SOURCES_STAMP).read_text() for folder in folders}
    assert stamps == {jit.sources_digest()}
    current = folders[0] / "loop.run_many-1.py311.nbi"
    current.write_bytes(b"compiled from these sources")
    jit.forget_a_stale_cache()
    assert current.read_bytes() == b"compiled from these sources"
