"""The site's generated reference: every command's options from its own argparse parser,
every scene key from the scene reader's own reading of keys, and the package's layout
from its folders, their floors (tests/test_floors.py) and each module's docstring.

mkdocs loads this file as a hook (mkdocs.yml, `hooks:`): a page's line
`<!-- generated: commands -->`, `<!-- generated: scene-keys -->` or
`<!-- generated: layout -->` becomes the text made
here, so the reference cannot fall behind the code. tests/test_docs.py checks these
generators against the code (every option, every key the reader asks for).
"""

from __future__ import annotations

import ast
import contextlib
import importlib
import os
import re
import sys
import tomllib
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from billiards.scene.reader import SceneError, load_scene, scene_from_dict, shipped_scene_names
from billiards.scene.tables import REQUIRED, KeyRead, keys_read

ROOT = Path(__file__).resolve().parent.parent
# The floors are the floors test's (mkdocs loads this file with only the package in reach).
sys.path.insert(0, str(ROOT))
from tests.test_floors import FLOOR_OF, MAY_IMPORT, floor_of, imports_of, module_files  # noqa: E402

# The width argparse wraps help to, fixed so the page is the same on every terminal.
HELP_COLUMNS = "88"

# Scenes that take the reader down the branches no shipped scene takes (a ball given
# its spin, an orbiting camera; a required key left out, which the reader names). Each
# may fail: the keys it asked for until then are what counts.
PROBES: list[dict[str, Any]] = [
    {
        "physics": {"model": "spin", "ball_model": "frictional"},
        "ball": [{"id": "a", "position": [0.5, 0.5], "spin": [0.0, 0.0, 1.0]}],
        "camera": [{"preset": "orbit", "orbit": 0.2, "fov": 50.0}],
        "render": {"output": "probe.mp4"},
    },
    {"render": {"table_mesh": 1}},
    {"ball": [{"position": [0.5, 0.5]}]},
    {"ball": [{"id": "a"}]},
    {"physics": {"model": "spin"}, "ball": [{"id": "a", "position": [0.5, 0.5], "cue": {}}]},
    {"camera": [{"preset": "overhead", "eye": [1.0, 0.5, 2.0]}]},
]


def command_modules() -> dict[str, str]:
    """Each installed command (pyproject's [project.scripts]) and the module that
    builds its parser (`build_parser()`)."""
    scripts = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"][
        "scripts"
    ]
    return {name: target.partition(":")[0] for name, target in scripts.items()}


@contextlib.contextmanager
def _help_width() -> Iterator[None]:
    saved = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = HELP_COLUMNS
    try:
        yield
    finally:
        if saved is None:
            del os.environ["COLUMNS"]
        else:
            os.environ["COLUMNS"] = saved


def command_help(module: str) -> str:
    """The command's --help text, as its parser prints it."""
    build: Callable[[], Any] = importlib.import_module(module).build_parser
    with _help_width():
        return str(build().format_help())


def commands_markdown() -> str:
    """A section per command: how to call it, and its --help."""
    sections = []
    for name, module in command_modules().items():
        python_name = module.removesuffix(".__main__")
        help_text = "\n".join(f"    {line}".rstrip() for line in command_help(module).splitlines())
        sections.append(f"## {name}\n\n`{name}` is `python -m {python_name}`.\n\n{help_text}\n")
    return "\n".join(sections)


def scene_keys() -> dict[str, KeyRead]:
    """Every key the scene reader asks for, by path, reading every shipped scene and the
    probes: the first reading of each that says what it accepts (and its default)."""
    with keys_read() as found:
        for name in shipped_scene_names():
            load_scene(name)
        for probe in PROBES:
            with contextlib.suppress(SceneError):
                scene_from_dict(probe, "probe")
    reads: dict[str, list[KeyRead]] = {}
    for read in found:
        reads.setdefault(read.path, []).append(read)
    return {path: _merged(path, each) for path, each in reads.items()}


def _merged(path: str, reads: list[KeyRead]) -> KeyRead:
    """One key's readings as one: required if ever found missing, else the default of
    its first typed reading; what it accepts, from the first reading that says."""
    expected = next((read.expected for read in reads if read.expected), "")
    if any(read.default is REQUIRED for read in reads):
        return KeyRead(path, REQUIRED, expected)
    typed = [read for read in reads if read.expected]
    return KeyRead(path, typed[0].default if typed else None, expected)


def _shown(default: Any) -> str:
    if default is REQUIRED:
        return "required"
    if default is None or default == "":
        return ""  # optional, with no default of its own (the reader's placeholder)
    if isinstance(default, bool):
        return f"`{str(default).lower()}`"
    if isinstance(default, str):
        return f'`"{default}"`'
    if isinstance(default, tuple):
        return "`[" + ", ".join(f"{value:g}" for value in default) + "]`"
    if isinstance(default, float):
        return f"`{default:g}`"
    return f"`{default}`"


def _linked(expected: str) -> str:
    """The reader's words, with its pointer to the bounds page as a link of the site."""
    return expected.replace("docs/scene_bounds.md", "[scene bounds](../scene_bounds.md)")


def scene_keys_markdown() -> str:
    """A table per scene table: each key, its default and what it accepts."""
    keys = scene_keys()
    tables = [path for path, read in keys.items() if "." not in path]
    out = []
    for table in tables:
        kind = keys[table].expected
        heading = f"[[{table}]]" if kind.startswith("an array") else f"[{table}]"
        rows = [
            f"| `{path}` | {_shown(read.default)} | {_linked(read.expected)} |"
            for path, read in keys.items()
            if path.split(".")[0].removesuffix("[]") == table and "." in path
        ]
        out.append(
            f"## `{heading}`\n\n| key | default | accepts |\n| --- | --- | --- |\n"
            + "\n".join(rows)
            + "\n"
        )
    return "\n".join(out)


def layout_markdown() -> str:
    """Each floor bottom up (fewest floors below it first), what it may import; under it
    each folder's modules, bottom up, with the first sentence of each docstring."""
    modules = module_files(ROOT / "billiards", "billiards")
    floors = sorted(set(FLOOR_OF.values()), key=lambda floor: (len(MAY_IMPORT[floor]), floor))
    out = []
    for floor in floors:
        below = ", ".join(sorted(MAY_IMPORT[floor])) or "nothing of the package"
        out.append(f"- **{floor}** (may import: {below})")
        for entry in sorted(name for name, on in FLOOR_OF.items() if on == floor):
            out.append(f"    - {_module_line(entry, modules)}")
            inside = [
                name
                for name in modules
                if name.startswith(entry + ".")
                and floor_of(name, FLOOR_OF) == floor
                and name not in FLOOR_OF
            ]
            out.extend(f"        {line}" for line in _folder_lines(entry, inside, modules))
    return "\n".join(out) + "\n"


def _folder_lines(entry: str, inside: list[str], modules: dict[str, Path]) -> list[str]:
    """A folder's modules bottom up (each after those of the folder it imports), one list
    item each; a sub-folder's nested under its own item, where its lowest would stand."""
    needs = {name: imports_of(name, modules[name], modules) & set(inside) for name in inside}
    placed: list[str] = []
    while len(placed) < len(inside):
        left = [name for name in inside if name not in placed]
        placed.extend(sorted(name for name in left if needs[name] - {name} <= set(placed)) or left)
    lines: list[str] = []
    depth = entry.count(".") + 2
    for group in dict.fromkeys(".".join(name.split(".")[:depth]) for name in placed):
        lines.append(f"- {_module_line(group, modules)}")
        members = [name for name in inside if name.startswith(group + ".")]
        lines.extend(f"    {line}" for line in _folder_lines(group, members, modules))
    return lines


def _module_line(name: str, modules: dict[str, Path]) -> str:
    """A module's or folder's path and the first sentence of its docstring."""
    path = modules[name]
    shown = path.relative_to(ROOT).as_posix().replace("/__init__.py", "/")
    docstring = " ".join((ast.get_docstring(ast.parse(path.read_text("utf-8"))) or "").split())
    end = re.search(r"\.(\s|$)", docstring)
    return f"`{shown}`: {docstring[: end.start() + 1] if end else docstring}"


GENERATED: dict[str, Callable[[], str]] = {
    "<!-- generated: commands -->": commands_markdown,
    "<!-- generated: scene-keys -->": scene_keys_markdown,
    "<!-- generated: layout -->": layout_markdown,
}


def on_page_markdown(markdown: str, **_: Any) -> str:
    """mkdocs' hook: each marker line becomes its generated text."""
    for marker, make in GENERATED.items():
        if marker in markdown:
            markdown = markdown.replace(marker, make())
    return markdown
