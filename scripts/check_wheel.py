"""The package as a user installs it: the sdist and the wheel, in a fresh venv.

    python scripts/check_wheel.py [--keep FOLDER]

Builds the sdist and, from it, the wheel (`python -m build`), checks that the wheel
holds every module of billiards/, the export's page files and every file of shaders/
and assets/ (and nothing else of the tree, no .pyc), installs the wheel with its
`sweep` and `export` extras into a fresh venv, and from an unrelated folder runs every
command as installed (billiards-render, -simulate, -plot, -sweep, -export and their
`python -m` forms): `--version`, `--list-scenes`, a shipped scene simulated by name,
a 2-second 160x90 film, a top view, a glTF export with its page and a 20-run sweep
with `--workers 0`. Every module of the installed package must import. Prints
one line per step and exits 1 if any failed. .ci/run calls it after the tests; it
takes about a minute, most of it installing the dependencies.

The film needs a headless OpenGL context: where none can be made the film step is
skipped with the command's own reason, as the GL tests are.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import zipfile
from collections.abc import Iterable
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
# The source folders of the wheel's packages: billiards/ itself and the data folders
# that setup.py maps into it.
SOURCE_FOLDERS = {
    "billiards": "billiards",
    "shaders": "billiards/shaders",
    "assets": "billiards/assets",
}
COMMANDS = ["render", "simulate", "plot", "sweep", "export"]
# The extras installed with the wheel: every module of the package then imports.
EXTRAS = "sweep,export"
# Data folders inside billiards/ (not .py) that travel in the wheel as package data.
PACKAGE_DATA = ("export/web", "export/vendor", "fit/data")
# A 2-second film: the seed break cut at 1 s, with half a second before and after.
SHORT_FILM_SCENE = "[simulation]\nmax_time = 1.0\n\n[render]\nlead = 0.5\ntail = 0.5\n"
NO_GL = "no headless OpenGL context"


def _skipped(path: Path) -> bool:
    return "__pycache__" in path.parts or path.suffix == ".pyc"


def tree_files(root: Path = ROOT) -> set[str]:
    """What the wheel must hold, as paths inside it: billiards/**/*.py, and every
    file of shaders/ and assets/ under billiards/shaders and billiards/assets."""
    expected = set()
    for folder, inside in SOURCE_FOLDERS.items():
        for path in (root / folder).rglob("*"):
            relative = path.relative_to(root / folder)
            if not path.is_file() or _skipped(relative):
                continue
            data = relative.as_posix().startswith(tuple(f"{d}/" for d in PACKAGE_DATA))
            if folder == "billiards" and path.suffix != ".py" and not data:
                continue
            expected.add(f"{inside}/{relative.as_posix()}")
    return expected


def wheel_files(wheel: Path) -> set[str]:
    """The package's files in a wheel (its .dist-info left out)."""
    with zipfile.ZipFile(wheel) as archive:
        names = archive.namelist()
    return {name for name in names if not name.split("/")[0].endswith(".dist-info")}


def wheel_problems(wheel: Path, root: Path = ROOT) -> list[str]:
    """One line per file of the tree missing from the wheel, or in it unasked."""
    expected, held = tree_files(root), wheel_files(wheel)
    return [f"missing from the wheel: {name}" for name in sorted(expected - held)] + [
        f"in the wheel but not of the tree: {name}" for name in sorted(held - expected)
    ]


def _run(command: list[str], cwd: Path, env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        command, cwd=cwd, env=env, capture_output=True, text=True, check=False, timeout=600
    )


class Checker:
    """Runs the steps, printing one line each, and counts the failures."""

    def __init__(self, cwd: Path, env: dict[str, str]) -> None:
        self.cwd, self.env, self.failures = cwd, env, 0

    def step(
        self, name: str, command: list[str], expect: Iterable[str] = (), may_skip: bool = False
    ) -> bool:
        done = _run(command, self.cwd, self.env)
        output = done.stdout + done.stderr
        if done.returncode != 0 and may_skip and NO_GL in output:
            print(f"skip  {name}: {output.strip().splitlines()[-1]}")
            return False
        missing = [text for text in expect if text not in output]
        if done.returncode == 0 and not missing:
            print(f"ok    {name}")
            return True
        self.failures += 1
        why = f"exit {done.returncode}" if done.returncode else f"no {missing!r} in the output"
        print(f"FAIL  {name}: {why}\n      $ {' '.join(command)}")
        print("".join(f"      | {line}\n" for line in output.strip().splitlines()[-15:]), end="")
        return False

    def expect(self, name: str, fact: bool) -> None:
        print(f"{'ok  ' if fact else 'FAIL'}  {name}")
        self.failures += not fact


def build(folder: Path) -> tuple[Path, Path]:
    """The sdist, and the wheel built from it, in `folder`."""
    done = subprocess.run(
        [sys.executable, "-m", "build", "--outdir", str(folder), str(ROOT)],
        capture_output=True,
        text=True,
        check=False,
    )
    if done.returncode != 0:
        sys.exit(f"FAIL  python -m build:\n{done.stdout[-3000:]}{done.stderr[-3000:]}")
    (sdist,), (wheel,) = folder.glob("*.tar.gz"), folder.glob("*.whl")
    print(f"ok    built {sdist.name} and, from it, {wheel.name}")
    return sdist, wheel


def install(wheel: Path, venv: Path) -> Path:
    """A fresh venv with the wheel and its sweep extra; its bin folder."""
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    done = subprocess.run(
        [str(venv / "bin" / "python"), "-m", "pip", "install", "-q", f"{wheel}[{EXTRAS}]"],
        capture_output=True,
        text=True,
        check=False,
    )
    if done.returncode != 0:
        sys.exit(f"FAIL  pip install {wheel.name}[{EXTRAS}]:\n{done.stderr[-3000:]}")
    print(f"ok    installed {wheel.name}[{EXTRAS}] into a fresh venv")
    return venv / "bin"


# Imports every module of the installed package and says where billiards came from.
IMPORT_ALL = """
import importlib, pkgutil, billiards
names = [m.name for m in pkgutil.walk_packages(billiards.__path__, "billiards.")]
for name in names:
    importlib.import_module(name)
print(billiards.__file__, len(names))
"""


# The library as a notebook uses it (billiards.api), from the installed wheel.
LIBRARY_EXAMPLE = (
    "import billiards; result = billiards.run('pocket_shot'); print(result); "
    "billiards.plot_top_view(result, 'pocket.png', width=200)"
)


def check_installed(bin_folder: Path, work: Path) -> int:
    """Every command as installed, from an unrelated folder; the number of failures."""
    env = {key: value for key, value in os.environ.items() if not key.startswith("PYTHON")}
    env["PATH"] = f"{bin_folder}{os.pathsep}{env.get('PATH', '')}"
    work.mkdir()
    python = str(bin_folder / "python")
    check = Checker(work, env)

    done = _run([python, "-c", IMPORT_ALL], work, env)
    where = done.stdout.split()
    check.expect(
        f"every module imports from the venv ({where[-1] if where else '?'} modules)",
        done.returncode == 0 and bool(where) and where[0].startswith(str(bin_folder.parent)),
    )
    if done.returncode != 0:
        print(done.stderr.strip()[-3000:])

    for command in COMMANDS:
        for form in ([f"billiards-{command}"], [python, "-m", f"billiards.{command}"]):
            shown = " ".join(form[-1:] if len(form) == 1 else ["python -m", form[-1]])
            check.step(f"{shown} --version", [*form, "--version"], ["0.1.0"])
            check.step(f"{shown} --list-scenes", [*form, "--list-scenes"], ["pocket_shot"])

    # The fitter takes recordings, not a scene: its version and help, as installed.
    for form in (["billiards-fit"], [python, "-m", "billiards.fit"]):
        shown = " ".join(form[-1:] if len(form) == 1 else ["python -m", form[-1]])
        check.step(f"{shown} --version", [*form, "--version"], ["0.1.0"])
        check.step(f"{shown} score --help", [*form, "score", "--help"], ["TRACKS"])

    check.step("billiards-simulate pocket_shot", ["billiards-simulate", "pocket_shot"])
    check.step(
        "python -m billiards.simulate hard_break --json",
        [python, "-m", "billiards.simulate", "hard_break", "--json"],
        ['"complete": true'],
    )
    (work / "short.toml").write_text(SHORT_FILM_SCENE, encoding="utf-8")
    film = ["short.toml", "-o", "short.mp4", "--width", "160", "--height", "90", "--quiet"]
    if check.step(
        "billiards-render: a 2 s film at 160x90", ["billiards-render", *film], may_skip=True
    ):
        check.expect("the film is written", (work / "short.mp4").stat().st_size > 1000)
    check.step(
        "the library: billiards.run('pocket_shot') and its top view",
        [python, "-c", LIBRARY_EXAMPLE],
        ["pocketed: 1 (foot-left)"],
    )
    check.step("billiards-plot bank_shot", ["billiards-plot", "bank_shot", "-o", "bank.png"])
    check.expect("the top view is a PNG", (work / "bank.png").read_bytes()[:4] == b"\x89PNG")
    check.step(
        "billiards-export bank_shot: a .glb and its page",
        ["billiards-export", "bank_shot", "-o", "bank.glb", "--html", "bank.html", "--quiet"],
    )
    check.expect(
        "the glb and the page are written",
        (work / "bank.glb").exists() and (work / "bank.html").exists(),
    )
    sweep = ["--runs", "20", "--workers", "0", "--quiet", "-o", "sweep"]
    sweep += ["--vary", "ball.cue.position.y=0.5325~0.001"]
    check.step("billiards-sweep break: 20 runs, --workers 0", ["billiards-sweep", "break", *sweep])
    runs = (
        (work / "sweep" / "runs.csv").read_text().splitlines() if (work / "sweep").exists() else []
    )
    check.expect(
        "the sweep wrote 20 ok runs",
        len(runs) == 21 and all(",ok," in row for row in runs[1:]),
    )
    return check.failures


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--keep", type=Path, help="work in this (new) folder and keep it")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="check-wheel-") as temporary:
        folder = args.keep or Path(temporary)
        folder.mkdir(parents=True, exist_ok=args.keep is None)
        _, wheel = build(folder / "dist")
        problems = wheel_problems(wheel)
        for problem in problems:
            print(f"FAIL  {problem}")
        if not problems:
            print(f"ok    the wheel holds the tree's {len(tree_files())} files and nothing else")
        failures = len(problems) + check_installed(install(wheel, folder / "venv"), folder / "run")
    print(f"check_wheel: {'all ok' if failures == 0 else f'{failures} failed'}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
