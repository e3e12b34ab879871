"""The same bits on every machine (README, "The model"): the physics uses only
arithmetic that IEEE 754 fixes, and gives the same bytes under every CPU kernel.

numpy's wheel picks BLAS kernels (OPENBLAS_CORETYPE) and SIMD loops
(NPY_DISABLE_CPU_FEATURES) by CPU; forcing each of them in a subprocess makes this one
machine compute as others do. The static test keeps out what those choices change.
"""

from __future__ import annotations

import ast
import functools
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests import machine_digest
from tests.test_fingerprints import PINS

ROOT = Path(__file__).resolve().parents[2]
# What a run's result depends on: the physics, the bridge from a scene, a sweep's draws.
CHECKED = [
    *sorted((ROOT / "billiards" / "physics").rglob("*.py")),
    ROOT / "billiards" / "simulation.py",
    ROOT / "billiards" / "sweep" / "draws.py",
    ROOT
    / "billiards"
    / "rules"
    / "pocket_rule.py",  # which tables the physics builds (and the reader)
    ROOT / "billiards" / "scene" / "stroke.py",  # a stroke's velocity and spin (the reader's)
]

# numpy names whose results IEEE 754 fixes bit for bit (elementwise + - * / sqrt, exact
# operations such as abs, min/max, comparisons, sorting, copies), or that hold no value.
ALLOWED_NUMPY = {
    "abs", "add", "arange", "argmax", "argmin", "array", "asarray", "atleast_1d",
    "atleast_2d", "bool_", "clip", "concatenate", "copysign", "count_nonzero", "empty",
    "errstate", "finfo",
    "float64", "full", "inf", "int64", "intp", "isfinite", "isinf", "isnan", "ldexp",
    "lexsort", "maximum", "minimum", "multiply", "nan", "ndarray", "nonzero", "ones",
    "ones_like", "random", "ravel", "repeat", "searchsorted", "sign", "sort", "spacing",
    "sqrt", "stack", "triu", "triu_indices", "uint64", "unique", "where", "zeros",
    "zeros_like",
}  # fmt: skip
# (nextafter and ulp are IEEE 754's nextUp/nextDown: exact; comb is integer arithmetic.)
ALLOWED_MATH = {
    "ceil", "comb", "copysign", "fabs", "floor", "frexp", "fsum", "inf", "isfinite", "isinf",
    "isnan", "ldexp", "nan", "nextafter", "sqrt", "ulp",
}  # fmt: skip
# Array reductions and products in numpy's own order (or BLAS's): written out instead.
FORBIDDEN_METHODS = {"dot", "sum", "mean", "prod", "cumsum", "cumprod", "std", "var", "trace"}


def offences(source: str) -> list[str]:
    """Every use in `source` of an operation whose bits can depend on the machine."""
    found = []
    for node in ast.walk(ast.parse(source)):
        line = getattr(node, "lineno", 0)
        if isinstance(node, ast.BinOp | ast.AugAssign) and isinstance(
            node.op, ast.MatMult | ast.Pow
        ):
            found.append(f"{line}: {'@' if isinstance(node.op, ast.MatMult) else '**'}")
        elif isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
            module, name = node.value.id, node.attr
            if module in ("np", "numpy") and name not in ALLOWED_NUMPY:
                found.append(f"{line}: np.{name}")
            elif module == "math" and name not in ALLOWED_MATH:
                found.append(f"{line}: math.{name}")
        if (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Attribute)
            and node.func.attr in FORBIDDEN_METHODS
        ):
            found.append(f"{line}: .{node.func.attr}()")
        if isinstance(node, ast.ImportFrom) and node.module in ("numpy", "math", "numpy.linalg"):
            allowed = ALLOWED_MATH if node.module == "math" else ALLOWED_NUMPY
            found += [f"{line}: from {node.module} import {a.name}" for a in node.names
                      if a.name not in allowed]  # fmt: skip
        if isinstance(node, ast.Import):
            found += [f"{line}: import {a.name}" for a in node.names
                      if a.name.startswith(("numpy.linalg", "scipy", "cmath"))]  # fmt: skip
    return sorted(found, key=lambda offence: int(offence.split(":")[0]))


def test_the_offence_finder_finds_what_it_forbids() -> None:
    source = (
        "import numpy as np\nimport math\nfrom numpy.linalg import eigvals\n"
        "a @ b\nx ** 2\nnp.linalg.eigvals(m)\nnp.hypot(x, y)\nnp.exp(x)\nmath.atan2(y, x)\n"
        "v.sum()\nnp.einsum('i,i', a, b)\nnp.sqrt(x * x + y * y)\nmath.sqrt(2.0)\n"
    )
    assert [o.split(": ")[1] for o in offences(source)] == [
        "from numpy.linalg import eigvals", "@", "**", "np.linalg", "np.hypot", "np.exp",
        "math.atan2", ".sum()", "np.einsum",
    ]  # fmt: skip


@pytest.mark.parametrize("path", CHECKED, ids=lambda p: str(p.relative_to(ROOT)))
def test_the_physics_uses_only_arithmetic_that_ieee_754_fixes(path: Path) -> None:
    assert offences(path.read_text()) == []


def _dispatched() -> list[str]:
    try:
        from numpy._core._multiarray_umath import __cpu_dispatch__
    except ImportError:  # numpy 1.x
        from numpy.core._multiarray_umath import __cpu_dispatch__  # type: ignore[no-redef]
    return list(__cpu_dispatch__)


def _without(*prefixes: str) -> str:
    """NPY_DISABLE_CPU_FEATURES naming every dispatched target from these on (numpy
    refuses names it does not dispatch; on a CPU without a target, masking it is a no-op)."""
    return " ".join(name for name in _dispatched() if name.startswith(prefixes))


AVX512 = ("AVX512", "X86_V4")
VARIANTS = {
    **{f"openblas-{core}": {"OPENBLAS_CORETYPE": core}
       for core in ("Haswell", "Zen", "SkylakeX", "Sandybridge", "Prescott")},
    "numpy-no-avx512": {"NPY_DISABLE_CPU_FEATURES": _without(*AVX512)},
    "numpy-no-avx2": {"NPY_DISABLE_CPU_FEATURES": _without(*AVX512, "X86_V3", "AVX2", "FMA3")},
}  # fmt: skip


@functools.cache
def here(every_pin: bool) -> dict[str, str]:
    return machine_digest.digests(every_pin)


def _digest_under(variables: dict[str, str], every_pin: bool) -> dict[str, str]:
    environment = {
        key: value
        for key, value in os.environ.items()
        if key not in ("OPENBLAS_CORETYPE", "NPY_DISABLE_CPU_FEATURES")
    }
    environment.update(variables, PYTHONWARNINGS="error")
    done = subprocess.run(
        [sys.executable, "-m", "tests.machine_digest", *(["--all"] if every_pin else [])],
        cwd=ROOT, env=environment, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    digests: dict[str, str] = json.loads(done.stdout)
    return digests


def _check(variant: str, every_pin: bool) -> None:
    got = _digest_under(VARIANTS[variant], every_pin)
    # The shipped scenes' pins hold under this kernel as on the machine that made them ...
    for name, method, dt in machine_digest.PINS if every_pin else machine_digest.SAMPLE_PINS:
        assert got[machine_digest.pin_key(name, method, dt)] == PINS[name, method, dt], (
            f"{name} by {method} (dt {dt}) differs under {variant}"
        )
    # ... and so do the hard cases and the sweep's draws, bit for bit with this process.
    assert got == here(every_pin)


@pytest.mark.long
@pytest.mark.parametrize("variant", VARIANTS)
def test_every_cpu_kernel_gives_the_same_bytes(variant: str) -> None:
    _check(variant, every_pin=False)


@pytest.mark.hard
@pytest.mark.parametrize("variant", VARIANTS)
def test_every_cpu_kernel_gives_the_same_bytes_for_every_pin(variant: str) -> None:
    _check(variant, every_pin=True)
