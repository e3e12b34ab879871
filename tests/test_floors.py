"""The package's floors: each folder is one floor, and imports only from those below.

Bottom up: billiards.rules (the rules and numbers the scene reader and the physics must
share: which tables can have pockets, the seed's numbers; numpy and the standard library
only, so that both may import them without the reader importing the physics or the
physics the reader) with billiards.version; billiards.shell (what the commands share:
the argument parser's common parts, atomic output files); billiards.scene (the reader:
TOML tables, bounds, the [render] table, the cue's stroke); billiards.physics (numpy,
numba, the standard library and its own modules only); the bridge from scenes to
physics (billiards.simulation); billiards.record (the trajectory the physics hands to
whoever draws, and the film's recording window); billiards.stage (what a film or a glTF
file shows, without GL); the outputs: billiards.render (the film: GL only under
render/gl, its sound, the video container), billiards.pictures (the top view) and
billiards.export (glTF); the many-run floors, billiards.sweep and billiards.fit; the
commands on top, and beside them the library (billiards.api, which the package's
__init__ offers as `billiards.run` and the rest: every floor but the commands'). A
module's floor is its folder's; a module left out of FLOOR_OF falls on no floor. Every
import counts, including those inside functions and under TYPE_CHECKING, and there are
no cycles, lazy ones included.
"""

from __future__ import annotations

import ast
import sys
from pathlib import Path

import billiards

# Floor of each module, by the longest matching name: one entry a folder (and the few
# modules at the top); a floor may import its own modules and those of the floors it
# lists (the commands may import anything).
FLOOR_OF = {
    "billiards.rules": "rules",
    "billiards.version": "rules",
    "billiards": "api",  # the package's __init__: the library's names, from billiards.api
    "billiards.api": "api",
    "billiards.shell": "shell",
    "billiards.scene": "scene",
    "billiards.physics": "physics",
    "billiards.simulation": "bridge",
    "billiards.record": "record",
    "billiards.stage": "stage",
    "billiards.render": "output",
    "billiards.pictures": "output",
    "billiards.export": "output",  # a shot as glTF: never the physics, never GL
    "billiards.sweep": "many",
    "billiards.fit": "many",  # many runs of the bridge against recordings
    "billiards.simulate": "command",
    "billiards.plot": "command",
    "billiards.render.__main__": "command",
    "billiards.sweep.__main__": "command",
    "billiards.fit.__main__": "command",
    "billiards.export.__main__": "command",
}
BELOW_THE_BRIDGE = {"rules", "shell", "scene", "physics"}
MAY_IMPORT = {
    "rules": set(),  # a leaf: nothing of the package
    "shell": {"rules"},
    "scene": {"rules"},
    "physics": {"rules"},  # its own modules and the shared rules only
    "bridge": BELOW_THE_BRIDGE,
    "record": BELOW_THE_BRIDGE,  # scene: the render settings a saved trajectory carries
    "stage": {"rules", "shell", "scene", "record"},  # never the physics, never GL
    "output": {"rules", "shell", "scene", "record", "stage"},  # never the physics
    "many": {*BELOW_THE_BRIDGE, "bridge", "stage"},  # many runs; never draws a film
    # The library: what the commands do, as functions (billiards.api); no command.
    "api": {*BELOW_THE_BRIDGE, "bridge", "record", "stage", "output", "many"},
    "command": {*BELOW_THE_BRIDGE, "bridge", "record", "stage", "output", "many"},
}
# Outside the package, the physics and the shared rules take numpy (and the physics
# numba) and the standard library only.
PHYSICS_THIRD_PARTY = {"numpy", "numba"}
NUMPY_AND_STDLIB_FLOORS = {"physics", "rules"}


def module_files(root: Path, package: str) -> dict[str, Path]:
    """Every module of the package under `root` (its folder), by dotted name."""
    modules = {}
    for path in sorted(root.rglob("*.py")):
        parts = [package, *path.relative_to(root).with_suffix("").parts]
        if parts[-1] == "__init__":
            parts.pop()
        modules[".".join(parts)] = path
    return modules


def imports_of(name: str, path: Path, modules: dict[str, Path]) -> set[str]:
    """Everything `name` imports anywhere in its file: the package's modules by name
    (`from a import b` names a.b when that is a module), other packages by top name."""
    found: set[str] = set()
    is_package = path.name == "__init__.py"
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = name.split(".")
                anchor = anchor[: len(anchor) - node.level + (1 if is_package else 0)]
                base = ".".join([*anchor, base] if base else anchor)
            for alias in node.names:
                child = f"{base}.{alias.name}"
                found.add(child if child in modules else base)
    return found


def floor_of(name: str, floors: dict[str, str]) -> str | None:
    """The floor of the longest listed name that `name` starts with; the package's own
    name places only the package's __init__."""
    parts = name.split(".")
    for end in range(len(parts), 0 if len(parts) == 1 else 1, -1):
        floor = floors.get(".".join(parts[:end]))
        if floor is not None:
            return floor
    return None


def floor_problems(
    root: Path,
    package: str,
    floors: dict[str, str],
    may_import: dict[str, set[str]],
    physics_third_party: set[str],
) -> list[str]:
    """Each broken rule as one line: an import up or sideways, an unplaced module, a
    command imported by another module, a physics import outside its allowance, a cycle."""
    modules = module_files(root, package)
    graph: dict[str, set[str]] = {}
    problems = []
    for name, path in modules.items():
        floor = floor_of(name, floors)
        if floor is None:
            problems.append(f"{name}: on no floor (add it to FLOOR_OF)")
            continue
        imported = imports_of(name, path, modules)
        graph[name] = {target for target in imported if target in modules}
        for target in sorted(imported):
            top = target.split(".")[0]
            if top != package:
                if (
                    floor in NUMPY_AND_STDLIB_FLOORS
                    and top not in physics_third_party | sys.stdlib_module_names
                ):
                    problems.append(f"{name} imports {target}: {floor} takes numpy and stdlib only")
                continue
            target_floor = floor_of(target, floors)
            if target_floor == "command":
                problems.append(f"{name} imports the command {target}")
            elif floor == "command" or target_floor == floor:
                continue
            elif target_floor not in may_import[floor]:
                problems.append(f"{name} ({floor}) imports {target} ({target_floor})")
    problems.extend(f"import cycle: {' -> '.join(cycle)}" for cycle in cycles(graph))
    return problems


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """One cycle through each module that can reach itself (depth-first search)."""
    found: list[list[str]] = []
    done: set[str] = set()

    def visit(name: str, path: list[str]) -> None:
        if name in path:
            found.append([*path[path.index(name) :], name])
            return
        if name in done:
            return
        for target in sorted(graph.get(name, ())):
            visit(target, [*path, name])
        done.add(name)

    for name in sorted(graph):
        visit(name, [])
    return found


def test_every_module_imports_only_from_the_floors_below() -> None:
    root = Path(billiards.__file__).parent
    problems = floor_problems(root, "billiards", FLOOR_OF, MAY_IMPORT, PHYSICS_THIRD_PARTY)
    assert problems == [], problems


def test_only_the_film_and_the_library_import_the_render_package() -> None:
    """simulate, plot, sweep and the export read [render], record the film's trajectory
    and build the stage from floors below the film: nothing outside billiards.render
    imports it but the library's render_film and render_still (billiards.api), the
    command's twins."""
    root = Path(billiards.__file__).parent
    modules = module_files(root, "billiards")
    importers = {
        name: sorted(target for target in imports_of(name, path, modules) if _in(target, "render"))
        for name, path in modules.items()
        if not _in(name, "render") and name != "billiards.api"
    }
    assert {name: found for name, found in importers.items() if found} == {}


def test_only_render_gl_imports_gl() -> None:
    """The stage (what the export shares with the film) and the rest of the film draw
    nothing with GL: moderngl and glcontext are imported under billiards.render.gl only."""
    root = Path(billiards.__file__).parent
    modules = module_files(root, "billiards")
    gl_importers = {
        name
        for name, path in modules.items()
        if imports_of(name, path, modules) & {"moderngl", "glcontext"}
    }
    assert gl_importers
    assert {name for name in gl_importers if not _in(name, "render.gl")} == set()


def _in(name: str, folder: str) -> bool:
    return name == f"billiards.{folder}" or name.startswith(f"billiards.{folder}.")


def test_the_scene_reader_and_the_physics_agree_on_the_methods() -> None:
    from billiards.physics.methods.entry import METHODS
    from billiards.scene.reader import METHODS as SCENE_METHODS

    assert SCENE_METHODS == METHODS


def _fake_package(root: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        path = root / "pkg" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return root / "pkg"


FAKE_FLOORS = {"pkg": "base", "pkg.low": "base", "pkg.physics": "physics", "pkg.cmd": "command"}
FAKE_RULES = {"base": {"base"}, "physics": set(), "command": {"base", "physics"}}


def _fake_problems(tmp_path: Path, files: dict[str, str]) -> list[str]:
    package = _fake_package(tmp_path, {"__init__.py": "", "physics/__init__.py": "", **files})
    return floor_problems(package, "pkg", FAKE_FLOORS, FAKE_RULES, {"numpy"})


def test_the_checker_passes_a_package_that_imports_downwards(tmp_path: Path) -> None:
    files = {
        "low.py": "import math\n",
        "physics/motion.py": "import numpy\nfrom . import roots\n",
        "physics/roots.py": "import math\n",
        "cmd.py": "from pkg.physics import motion\nfrom pkg import low\n",
    }
    assert _fake_problems(tmp_path, files) == []


def test_the_checker_catches_a_lazy_upward_import(tmp_path: Path) -> None:
    files = {"low.py": "def f():\n    from pkg.physics import motion\n", "physics/motion.py": ""}
    assert _fake_problems(tmp_path, files) == [
        "pkg.low (base) imports pkg.physics.motion (physics)"
    ]


def test_the_checker_catches_a_type_checking_import_of_a_command(tmp_path: Path) -> None:
    files = {
        "low.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import pkg.cmd\n",
        "cmd.py": "",
    }
    assert _fake_problems(tmp_path, files) == ["pkg.low imports the command pkg.cmd"]


def test_the_checker_catches_a_cycle_and_a_foreign_physics_import(tmp_path: Path) -> None:
    files = {
        "physics/a.py": "from .b import x\nimport moderngl\n",
        "physics/b.py": "def x():\n    from pkg.physics import a\n",
    }
    assert _fake_problems(tmp_path, files) == [
        "pkg.physics.a imports moderngl: physics takes numpy and stdlib only",
        "import cycle: pkg.physics.a -> pkg.physics.b -> pkg.physics.a",
    ]


def test_the_checker_places_every_module(tmp_path: Path) -> None:
    files = {"stray/thing.py": ""}
    floors = {name: floor for name, floor in FAKE_FLOORS.items() if name != "pkg"}
    package = _fake_package(tmp_path, {"__init__.py": "", **files})
    problems = floor_problems(package, "pkg", floors, FAKE_RULES, set())
    assert "pkg.stray.thing: on no floor (add it to FLOOR_OF)" in problems


def test_the_checker_lets_the_physics_import_a_shared_rule_that_stays_a_leaf(
    tmp_path: Path,
) -> None:
    floors = {**FAKE_FLOORS, "pkg.rule": "rules"}
    rules = {"rules": set(), "base": {"rules", "base"}, "physics": {"rules"}, "command": set()}
    files = {
        "rule.py": "import math\nimport moderngl\nfrom pkg import low\n",
        "low.py": "",
        "physics/motion.py": "import numpy\nfrom pkg import rule\n",
    }
    package = _fake_package(tmp_path, {"__init__.py": "", "physics/__init__.py": "", **files})
    assert floor_problems(package, "pkg", floors, rules, {"numpy"}) == [
        "pkg.rule imports moderngl: rules takes numpy and stdlib only",
        "pkg.rule (rules) imports pkg.low (base)",
    ]


# Inside the physics, rooms by role (README's layout): the numerics at the bottom, the
# pockets' geometry, the contact laws (which take what they read, never the engine's
# Setup), the one numpy engine (which knows the motion models only through motion_law's
# registry and AnchoredMotion), the two motion models, the compiled loop, and on top
# the methods (the entry that sends each run to its engine, the seed's stepped method). Each room
# may import its own modules and those listed (a dotted entry: that module only).
PHYSICS_ROOMS = {
    "numerics": set(),
    "pockets": {"numerics"},
    "laws": {"numerics"},
    "engine": {"numerics", "pockets", "laws"},
    "rolling": {"numerics", "pockets", "engine"},
    # The spin model shares the rolling model's walls and separation quartic.
    "spin": {"numerics", "pockets", "engine", "rolling.contact_times"},
    # Both motion models compiled: the numpy code's constants and packaging, its own loop.
    "compiled": {"numerics", "laws", "engine", "rolling", "spin"},
    # The methods: the one entry sends each run to its engine; the seed's stepped
    # method steps both models' motion explicitly.
    "methods": {"numerics", "pockets", "laws", "engine", "compiled", "spin.motion"},
}


def test_the_physics_rooms_import_only_what_their_role_allows() -> None:
    root = Path(billiards.__file__).parent
    modules = module_files(root, "billiards")
    prefix = "billiards.physics."
    problems = []
    for name, path in modules.items():
        if not name.startswith(prefix):
            continue
        own = name.removeprefix(prefix)
        room = own.split(".")[0]
        allowed = PHYSICS_ROOMS[room]
        for target in sorted(imports_of(name, path, modules)):
            if not target.startswith(prefix):
                continue
            wanted = target.removeprefix(prefix)
            if wanted.split(".")[0] == room:
                continue
            if not any(wanted == entry or wanted.startswith(entry + ".") for entry in allowed):
                problems.append(f"{own} ({room}) imports {wanted}")
    assert problems == [], problems


def test_the_physics_has_no_module_left_at_an_old_path() -> None:
    """The moves left no shims: each old flat module is gone, not re-exported."""
    import importlib

    old = "motion contact_times spin_motion spin_contact_times rolling_law spin_law result"
    old += " spin_result calendar batch batch_log stepper events setup naive motion_law roots"
    old += " arithmetic pocket_times"
    root = Path(billiards.__file__).parent / "physics"
    assert sorted(path.name for path in root.glob("*.py")) == ["__init__.py", "pockets.py"]
    for name in old.split():
        try:
            importlib.import_module(f"billiards.physics.{name}")
        except ModuleNotFoundError:
            continue
        raise AssertionError(f"billiards.physics.{name} still imports")
