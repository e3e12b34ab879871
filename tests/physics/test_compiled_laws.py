"""The compiled contact laws (billiards.physics.compiled.laws) give the numpy laws'
results byte for byte: every cushion law and every ball law, through the dispatch by
id, on thousands of random contacts (speeds from 1e-6 to 10 m/s, spins up to 300
rad/s, normals of every direction and exactly along the axes, unequal masses, each
law's constants over the scene reader's ranges) and on the edge cases (no approach,
grazing, no spin, negative zeros), an error where the numpy law raises one; the same
bits compiled for each CPU target, with no fused multiply-add. mathavan2010's numpy
integration is slow: tens of contacts by default, thousands under -m hard."""

from __future__ import annotations

import hashlib
import math
import subprocess
import sys
from pathlib import Path
from typing import NamedTuple

import numpy as np
import pytest
from llvmlite import binding

from billiards.physics.compiled.laws import BALL_LAW_IDS, CUSHION_LAW_IDS, CushionNumbers
from billiards.physics.compiled.laws.rows import ball_rows, cushion_rows
from billiards.physics.engine.setup import Setup
from billiards.physics.laws import BALL_LAWS, CUSHION_LAWS
from billiards.physics.laws.ball_ball import PairContact
from billiards.physics.laws.cushion import CushionConstants, CushionContact
from tests.physics.test_compiled import fresh_digests, host_knows

ROOT = Path(__file__).resolve().parents[2]
hard = pytest.mark.hard
AXES = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0], [-0.0, 1.0], [1.0, -0.0]])


class CushionRows(NamedTuple):
    """k cushion contacts (CushionContact's arrays) and each one's constants (k, 7),
    CushionNumbers' columns."""

    velocities: np.ndarray
    spins: np.ndarray
    into: np.ndarray
    masses: np.ndarray
    constants: np.ndarray


class BallRows(NamedTuple):
    """k ball-ball contacts: normals (k, 2), velocities (k, 2, 2), spins (k, 2, 3),
    masses (k, 2), restitutions (k,), radii (k,), ball frictions (k, 3)."""

    normals: np.ndarray
    velocities: np.ndarray
    spins: np.ndarray
    masses: np.ndarray
    restitutions: np.ndarray
    radii: np.ndarray
    ball_frictions: np.ndarray


class BallConstants(NamedTuple):
    """What a numpy ball law reads of a run (ball_ball.BallConstants)."""

    radius: float
    ball_friction: tuple[float, float, float]


def log_uniform(rng: np.random.Generator, low: float, high: float, count: int) -> np.ndarray:
    return np.asarray(np.exp(rng.uniform(np.log(low), np.log(high), count)))


def unit_normals(rng: np.random.Generator, count: int) -> np.ndarray:
    """Half exactly along an axis (signed zeros too), half of any direction."""
    angle = rng.uniform(0.0, 2.0 * np.pi, count)
    oblique = np.stack((np.cos(angle), np.sin(angle)), axis=1)
    length = np.sqrt(oblique[:, 0] * oblique[:, 0] + oblique[:, 1] * oblique[:, 1])
    oblique /= length[:, None]
    axis = AXES[rng.integers(0, len(AXES), count)]
    return np.where((rng.random(count) < 0.5)[:, None], axis, oblique)


def motions(rng: np.random.Generator, normals: np.ndarray) -> np.ndarray:
    """Velocities (k, 2) of speeds from 1e-6 to 10 m/s: any direction; along the
    normal; along the tangent (no approach, or a rounding's); nearly along it (a graze);
    none; with negative zero components."""
    count = len(normals)
    speed = log_uniform(rng, 1e-6, 10.0, count)
    angle = rng.uniform(0.0, 2.0 * np.pi, count)
    velocity = speed[:, None] * np.stack((np.cos(angle), np.sin(angle)), axis=1)
    tangent = np.stack((-normals[:, 1], normals[:, 0]), axis=1)
    kind = rng.integers(0, 10, count)
    velocity[kind == 0] = speed[kind == 0, None] * normals[kind == 0]
    velocity[kind == 1] = -speed[kind == 1, None] * normals[kind == 1]
    velocity[kind == 2] = speed[kind == 2, None] * tangent[kind == 2]
    graze = speed[kind == 3, None] * (tangent[kind == 3] + 1e-9 * normals[kind == 3])
    velocity[kind == 3] = graze
    velocity[kind == 4] = 0.0
    velocity[kind == 5] = -0.0
    signed = kind == 6
    velocity[signed, rng.integers(0, 2)] = -0.0
    return velocity


def spins_of(
    rng: np.random.Generator, count: int, velocities: np.ndarray, radii: np.ndarray
) -> np.ndarray:
    """Spins (k, 3) up to 300 rad/s: any; none (signed zeros too); rolling; rolling
    with side spin."""
    spin = rng.uniform(-300.0, 300.0, (count, 3)) / np.sqrt(3.0)
    kind = rng.integers(0, 8, count)
    spin[kind == 0] = 0.0
    spin[kind == 1] = -0.0
    rolling = np.stack((-velocities[:, 1], velocities[:, 0]), axis=1) / radii[:, None]
    spin[kind == 2, :2] = rolling[kind == 2]
    spin[kind == 2, 2] = 0.0
    spin[kind == 3, :2] = rolling[kind == 3]
    return spin


def heights(rng: np.random.Generator, radii: np.ndarray) -> np.ndarray:
    """A cushion nose between the ball's equator and its top (the reader's range)."""
    share = rng.uniform(0.0, 1.0, len(radii))
    share[rng.random(len(radii)) < 0.1] = 0.2698  # the seed's 63.5 % of 2 r
    return np.asarray(np.minimum(radii * (1.0 + share), np.nextafter(2.0 * radii, 0.0)))


def stopping_frictions(
    rng: np.random.Generator, radii: np.ndarray, noses: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(mu_w, mu_s) over [0, 10] that let the cushion stop the ball, as the reader
    demands of the integrated laws: cos t > mu_w sin t + mu_s (sin t + mu_w cos t)."""
    count = len(radii)
    mu_w, mu_s = np.empty(count), np.empty(count)
    for row in range(count):
        sin_t = noses[row] / radii[row] - 1.0
        cos_t = math.sqrt(1.0 - sin_t * sin_t)
        w, s = rng.uniform(0.0, 10.0, 2) * rng.choice([1.0, 0.1, 0.01, 0.0])
        while not cos_t > w * sin_t + s * (sin_t + w * cos_t):
            w, s = 0.5 * w, 0.5 * s
        mu_w[row], mu_s[row] = w, s
    return mu_w, mu_s


def random_cushion_rows(seed: int, count: int) -> CushionRows:
    """`count` random cushion contacts with their run's constants (CushionRows)."""
    rng = np.random.default_rng(seed)
    into = unit_normals(rng, count)
    velocities = motions(rng, into)
    radii = log_uniform(rng, 0.001, 1.0, count)
    radii[rng.random(count) < 0.3] = 0.028575
    spins = spins_of(rng, count, velocities, radii)
    masses = log_uniform(rng, 0.001, 1000.0, count)
    noses = heights(rng, radii)
    mu_w, mu_s = stopping_frictions(rng, radii, noses)
    restitution = rng.uniform(0.0, 1.0, count)
    restitution[rng.random(count) < 0.05] = 0.0
    restitution[rng.random(count) < 0.05] = 1.0
    constants = np.stack(
        (
            radii,
            rng.uniform(0.0, 1.0, count),  # retention
            restitution,
            mu_w,
            noses,
            mu_s,
            log_uniform(rng, 0.01, 1000.0, count),  # v_c
        ),
        axis=1,
    )
    return CushionRows(velocities, spins, into, masses, constants)


def edge_cushion_rows() -> CushionRows:
    """Hand-picked contacts: square on, along the cushion (no approach), away, at rest,
    spinning in place, grazing, negative zeros, a rolling ball square on, and the stage
    that lands exactly on a zero slip (tests/physics/test_mathavan2010.py)."""
    landing = float.fromhex("-0x1.03ce0fb1418d4p+5")
    cases = [  # velocity, spin, into
        ((0.0, 2.0), (0.0, 0.0, 0.0), (0.0, 1.0)),
        ((1.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0)),
        ((1.0, -0.0), (-0.0, -0.0, -0.0), (0.0, 1.0)),
        ((0.3, -1.0), (5.0, 1.0, -2.0), (0.0, 1.0)),
        ((0.0, 0.0), (0.0, 0.0, 0.0), (1.0, 0.0)),
        ((0.0, 0.0), (10.0, -20.0, 30.0), (-1.0, 0.0)),
        ((1.0, 1e-300), (0.0, 0.0, 40.0), (0.0, 1.0)),
        ((-0.0, 1e-6), (-0.0, 0.0, -0.0), (-0.0, 1.0)),
        ((-1.0, -0.0), (0.0, 0.0, 0.0), (-1.0, -0.0)),
        ((0.0, 1.5), (-1.5 / 0.028575, 0.0, 0.0), (0.0, 1.0)),
        ((0.0, 1.0), (landing, 0.0, 0.0), (0.0, 1.0)),
        ((2.0, 2.0), (0.0, 0.0, 300.0), (math.sqrt(0.5), math.sqrt(0.5))),
    ]
    constants = [
        (0.028575, 0.75, 0.9, 0.2, 0.037, 0.2, 4.15),
        (0.03075, 0.5, 0.9, 0.14, 0.037, 0.2, 4.15),  # the landing case's numbers
    ]
    rows = [(v, w, n, constants[index == 10]) for index, (v, w, n) in enumerate(cases)]
    masses = [0.21 if index == 10 else 0.17 for index in range(len(cases))]
    return CushionRows(
        np.array([row[0] for row in rows]),
        np.array([row[1] for row in rows]),
        np.array([row[2] for row in rows]),
        np.array(masses),
        np.array([row[3] for row in rows]),
    )


def numpy_cushion(law: str, rows: CushionRows, row: int) -> list[bytes]:
    """The numpy law's results for one contact, with its run's constants (floats)."""
    constants = CushionConstants(*(float(value) for value in rows.constants[row]))
    contact = CushionContact(
        rows.velocities[row : row + 1],
        rows.spins[row : row + 1],
        rows.into[row : row + 1],
        rows.masses[row : row + 1],
    )
    velocities, spins, approaches = CUSHION_LAWS[law](contact, constants)
    return [
        np.asarray(part, dtype=np.float64).tobytes() for part in (velocities, spins, approaches)
    ]


def one_row(rows: CushionRows, row: int) -> CushionRows:
    return CushionRows(*(part[row : row + 1] for part in rows))


def cushion_outcome(law: str, rows: CushionRows, row: int, compiled: bool) -> list[bytes] | str:
    """One contact's results by the compiled law or the numpy one: their bytes, or the
    error the law raised (an impact that does not end)."""
    try:
        if not compiled:
            return numpy_cushion(law, rows, row)
        return [part.tobytes() for part in cushion_rows(CUSHION_LAW_IDS[law], *one_row(rows, row))]
    except ValueError as error:
        return str(error)


def assert_cushion_law_matches(law: str, rows: CushionRows) -> int:
    """Every contact's compiled results are the numpy law's, byte for byte (or the same
    error). Returns how many raised."""
    raised = 0
    for row in range(len(rows.velocities)):
        mine = cushion_outcome(law, rows, row, compiled=True)
        assert mine == cushion_outcome(law, rows, row, compiled=False), (law, row)
        raised += isinstance(mine, str)
    return raised


def random_ball_rows(seed: int, count: int) -> BallRows:
    """`count` random ball-ball contacts with their run's constants (BallRows)."""
    rng = np.random.default_rng(seed)
    normals = unit_normals(rng, count)
    radii = log_uniform(rng, 0.001, 1.0, count)
    radii[rng.random(count) < 0.3] = 0.028575
    velocities = np.stack((motions(rng, normals), motions(rng, -normals)), axis=1)
    velocities[rng.random(count) < 0.2, 1] = 0.0  # an object ball at rest
    spins = np.stack(
        (
            spins_of(rng, count, velocities[:, 0], radii),
            spins_of(rng, count, velocities[:, 1], radii),
        ),
        axis=1,
    )
    masses = log_uniform(rng, 0.001, 1000.0, 2 * count).reshape(count, 2)
    masses[rng.random(count) < 0.3] = (0.17, 0.165)
    restitutions = rng.uniform(0.0, 1.0, count)
    restitutions[rng.random(count) < 0.1] = 1.0
    frictions = np.stack(
        (
            rng.uniform(0.0, 10.0, count) * rng.choice([1.0, 0.01, 0.0], count),
            rng.uniform(0.0, 10.0, count) * rng.choice([1.0, 0.01, 0.0], count),
            rng.uniform(0.0, 1000.0, count) * rng.choice([1.0, 0.001, 0.0], count),
        ),
        axis=1,
    )
    frictions[rng.random(count) < 0.3] = (9.951e-3, 0.108, 1.088)
    return BallRows(normals, velocities, spins, masses, restitutions, radii, frictions)


def edge_ball_rows() -> BallRows:
    """Hand-picked pairs: head on, no closing speed, parting, at rest, negative zeros,
    a slow contact (restitution raised), spins that leave no slip (the frictionless
    law), no friction, and friction decayed past exp's range (c s >= 700)."""
    r = 0.028575
    cases = [  # normal, v1, v2, w1, w2, (a, b, c)
        ((-1.0, 0.0), (1.0, 0.0), (0.0, 0.0), (0.0,) * 3, (0.0,) * 3, (0.01, 0.1, 1.0)),
        ((-1.0, 0.0), (0.0, 1.0), (0.0, 0.0), (0.0,) * 3, (0.0,) * 3, (0.01, 0.1, 1.0)),
        ((-1.0, 0.0), (-1.0, 0.0), (0.0, 0.0), (0.0,) * 3, (0.0,) * 3, (0.01, 0.1, 1.0)),
        ((-1.0, 0.0), (0.0, 0.0), (0.0, 0.0), (5.0, 0.0, 0.0), (0.0,) * 3, (0.01, 0.1, 1.0)),
        ((-1.0, -0.0), (1.0, -0.0), (-0.0, -0.0), (-0.0,) * 3, (-0.0,) * 3, (0.01, 0.1, 1.0)),
        ((-0.0, 1.0), (-0.0, -1e-6), (0.0, 0.0), (0.0,) * 3, (-0.0,) * 3, (0.01, 0.1, 1.0)),
        ((-1.0, 0.0), (1.0, 0.0), (0.0, 0.0), (0.0, 1.0 / r, 0.0), (0.0,) * 3, (0.01, 0.1, 1.0)),
        ((-1.0, 0.0), (1.0, 0.0), (0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
        ((-0.6, -0.8), (2.0, 1.0), (0.0, 0.0), (0.0, 0.0, 50.0), (0.0,) * 3, (0.01, 5.0, 1000.0)),
        ((-0.6, -0.8), (2.0, 1.0), (0.0, 0.0), (0.0, 0.0, 50.0), (0.0,) * 3, (0.01, 5.0, 0.0)),
    ]
    count = len(cases)
    return BallRows(
        np.array([case[0] for case in cases]),
        np.array([(case[1], case[2]) for case in cases]),
        np.array([(case[3], case[4]) for case in cases]),
        np.tile([0.17, 0.165], (count, 1)),
        np.full(count, 0.95),
        np.full(count, r),
        np.array([case[5] for case in cases]),
    )


def numpy_ball(law: str, rows: BallRows, row: int) -> list[bytes]:
    """The numpy law's results for one pair."""
    pair = PairContact(rows.normals[row], rows.velocities[row], rows.spins[row], rows.masses[row])
    a, b, c = (float(value) for value in rows.ball_frictions[row])
    constants = BallConstants(float(rows.radii[row]), (a, b, c))
    velocities, spins, approach = BALL_LAWS[law](pair, float(rows.restitutions[row]), constants)
    return [np.asarray(part, dtype=np.float64).tobytes() for part in (velocities, spins, approach)]


def assert_ball_law_matches(law: str, rows: BallRows) -> None:
    """Every pair's compiled results are the numpy law's, byte for byte."""
    velocities, spins, approaches = ball_rows(BALL_LAW_IDS[law], *rows)
    for row in range(len(rows.normals)):
        mine = [part[row].tobytes() for part in (velocities, spins, approaches)]
        assert mine == numpy_ball(law, rows, row), (law, row)


def test_the_ids_are_the_numpy_registries_order() -> None:
    assert list(CUSHION_LAW_IDS) == list(CUSHION_LAWS)
    assert list(CUSHION_LAW_IDS.values()) == list(range(len(CUSHION_LAWS)))
    assert list(BALL_LAW_IDS) == list(BALL_LAWS)
    assert list(BALL_LAW_IDS.values()) == list(range(len(BALL_LAWS)))
    assert CushionNumbers._fields == tuple(CushionConstants.__dataclass_fields__)


def test_a_runs_cushion_numbers_are_its_cushion_constants_field_by_field() -> None:
    setup = Setup.of([[0.0, 0.0]], model="spin", cushion_law="han2005")
    constants = CushionConstants.of(setup)
    numbers = CushionNumbers.of(constants)
    assert numbers == tuple(getattr(constants, name) for name in CushionNumbers._fields)
    assert numbers.cushion_height == setup.cushion_height and numbers.radius == setup.radius


@pytest.mark.parametrize(("law", "count"), [("mirror", 3000), ("han2005", 5000)])
def test_the_closed_form_cushion_laws_give_the_numpy_laws_bits(law: str, count: int) -> None:
    assert_cushion_law_matches(law, random_cushion_rows(43, count))
    assert_cushion_law_matches(law, edge_cushion_rows())


@pytest.mark.parametrize("law", ["mathavan2010", "mathavan2010_ev"])
def test_the_integrated_cushion_laws_give_the_numpy_laws_bits(law: str) -> None:
    assert_cushion_law_matches(law, random_cushion_rows(2010, 60))
    assert_cushion_law_matches(law, edge_cushion_rows())


@hard
@pytest.mark.parametrize("law", ["mathavan2010", "mathavan2010_ev"])
def test_thousands_of_integrated_cushion_contacts_give_the_numpy_laws_bits(law: str) -> None:
    assert_cushion_law_matches(law, random_cushion_rows(20100, 4000))


@pytest.mark.parametrize(("law", "count"), [("frictionless", 3000), ("frictional", 5000)])
def test_the_ball_laws_give_the_numpy_laws_bits(law: str, count: int) -> None:
    assert_ball_law_matches(law, random_ball_rows(43, count))
    assert_ball_law_matches(law, edge_ball_rows())


@pytest.mark.parametrize("law", ["mathavan2010", "mathavan2010_ev"])
def test_frictions_that_hold_the_ball_raise_as_the_numpy_law_does(law: str) -> None:
    # A nose near the ball's top and frictions of 10: the impact never ends (the scene
    # reader refuses such constants; a caller that does not still gets the error).
    radius = 0.028575
    rows = CushionRows(
        np.array([[0.5, 1.0]]),
        np.zeros((1, 3)),
        np.array([[0.0, 1.0]]),
        np.array([0.17]),
        np.array([[radius, 0.75, 0.9, 10.0, 1.9 * radius, 10.0, 4.15]]),
    )
    with pytest.raises(ValueError, match="did not end") as numpy_error:
        numpy_cushion(law, rows, 0)
    with pytest.raises(ValueError, match="did not end") as compiled_error:
        cushion_rows(CUSHION_LAW_IDS[law], *rows)
    assert str(compiled_error.value) == str(numpy_error.value)


def test_an_unknown_law_id_is_refused() -> None:
    rows = edge_cushion_rows()
    with pytest.raises(ValueError, match="no cushion law"):
        cushion_rows(len(CUSHION_LAWS), *rows)
    pairs = edge_ball_rows()
    with pytest.raises(ValueError, match="no ball law"):
        ball_rows(len(BALL_LAWS), *pairs)


def test_the_laws_registry_does_not_import_numba() -> None:
    code = "import sys, billiards.physics.compiled.laws; assert 'numba' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)


# --- the same bits on every machine, compiled -------------------------------------------


def laws_digest(compiled: bool) -> str:
    """The sha256 of every law's results on random contacts (1,000 a closed-form law, 40
    an integrated one), compiled (the rows entries) or by the numpy laws, contact by
    contact: its results' bytes, or the error it raised."""
    digest = hashlib.sha256()
    for law in CUSHION_LAWS:
        rows = random_cushion_rows(7, 40 if law.startswith("mathavan") else 1000)
        for row in range(len(rows.velocities)):
            outcome = cushion_outcome(law, rows, row, compiled)
            digest.update(outcome.encode() if isinstance(outcome, str) else b"".join(outcome))
    for law in BALL_LAWS:
        pairs = random_ball_rows(7, 1000)
        results = ball_rows(BALL_LAW_IDS[law], *pairs)
        for row in range(len(pairs.normals)):
            if compiled:
                digest.update(b"".join(part[row].tobytes() for part in results))
            else:
                digest.update(b"".join(numpy_ball(law, pairs, row)))
    return digest.hexdigest()


# In a fresh process: the laws' digest and, where compiled, how many fused multiply-adds
# the rows entries' code holds (an FMA rounds a * b + c once: the bits would change).
DIGEST = """
import re
from billiards.physics.compiled.laws.rows import ball_rows, cushion_rows
from tests.physics.test_compiled_laws import laws_digest
print("laws", laws_digest(compiled=True))
if hasattr(cushion_rows, "inspect_asm"):
    listings = [text for entry in (cushion_rows, ball_rows) for text in entry.inspect_asm().values()]
    fused = re.compile(r"\\bv?f(n)?m(add|sub)", re.IGNORECASE)
    print("listings", len(listings))
    print("fma", sum(len(fused.findall(text)) for text in listings))
"""


def fresh_digest(cache: Path, **variables: str) -> dict[str, str]:
    """What DIGEST prints from a fresh process with an empty numba cache."""
    return fresh_digests(cache, DIGEST, **variables)


@hard
@pytest.mark.parametrize("cpu", ["generic", "x86-64-v2", "x86-64-v4", binding.get_host_cpu_name()])
def test_the_laws_compiled_for_each_cpu_give_the_numpy_laws_bits(cpu: str, tmp_path: Path) -> None:
    if not host_knows(cpu):
        pytest.skip(f"this host's LLVM does not know {cpu} or cannot run its code")
    expected = {"laws": laws_digest(compiled=False), "listings": "2", "fma": "0"}
    assert fresh_digest(tmp_path, NUMBA_CPU_NAME=cpu) == expected
