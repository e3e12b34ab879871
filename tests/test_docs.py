"""The documentation site (docs/, mkdocs.yml) cannot drift from the code: every Python
example on it runs as written, its internal links lead somewhere, and its generated
reference holds every command option and every scene key the code has."""

from __future__ import annotations

import argparse
import ast
import contextlib
import importlib
import io
import os
import re
from pathlib import Path

import pytest

from scripts.docs_hooks import (
    GENERATED,
    command_modules,
    commands_markdown,
    layout_markdown,
    scene_keys,
    scene_keys_markdown,
)

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
PAGES = sorted(DOCS.rglob("*.md"))
PYTHON_BLOCK = re.compile(r"^```python\n(.*?)^```", re.MULTILINE | re.DOTALL)
LINK = re.compile(r"\]\(([^)\s]+)\)")


def python_blocks(text: str) -> list[str]:
    return PYTHON_BLOCK.findall(text)


def test_the_python_blocks_are_found() -> None:
    text = "intro\n```python\nx = 1\n```\n\n    indented\n```python\nprint(x)\n```\n"
    assert python_blocks(text) == ["x = 1\n", "print(x)\n"]


PAGES_WITH_PYTHON = [page for page in PAGES if python_blocks(page.read_text(encoding="utf-8"))]


@pytest.mark.parametrize("page", PAGES_WITH_PYTHON, ids=lambda page: str(page.relative_to(DOCS)))
def test_every_python_example_on_a_page_runs_in_order(
    page: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A page's blocks run one after another in one namespace, as a reader pastes them
    into one notebook, in a fresh folder (what they write lands there)."""
    monkeypatch.chdir(tmp_path)
    namespace: dict[str, object] = {"__name__": "__docs__"}
    for index, block in enumerate(python_blocks(page.read_text(encoding="utf-8"))):
        code = compile(block, f"{page.relative_to(ROOT)} block {index + 1}", "exec")
        with contextlib.redirect_stdout(io.StringIO()):
            exec(code, namespace)


def test_the_site_has_python_examples_on_its_tutorials_and_guides() -> None:
    names = {str(page.relative_to(DOCS)) for page in PAGES_WITH_PYTHON}
    assert {"index.md", "tutorials/first-simulation.md", "how-to/python.md"} <= names


def test_every_internal_link_leads_to_a_file_of_the_site() -> None:
    broken = []
    for page in PAGES:
        for target in LINK.findall(page.read_text(encoding="utf-8")):
            if re.match(r"[a-z]+:", target) or target.startswith("#"):
                continue  # the web, or an anchor of the page (mkdocs --strict checks those)
            path = (page.parent / target.split("#")[0]).resolve()
            if not path.is_file() or DOCS not in path.parents:
                broken.append(f"{page.relative_to(ROOT)}: {target}")
    assert broken == []


def test_every_page_is_in_the_sites_navigation() -> None:
    nav = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    listed = set(re.findall(r":\s*(\S+\.md)\s*$", nav, re.MULTILINE))
    assert {str(page.relative_to(DOCS)) for page in PAGES} == listed


def test_each_generated_marker_is_on_a_reference_page() -> None:
    text = "".join(page.read_text(encoding="utf-8") for page in PAGES)
    for marker in GENERATED:
        assert text.count(marker) == 1, marker


# --- the generated reference -------------------------------------------------------------


def test_every_installed_command_builds_its_parser_for_the_reference() -> None:
    modules = command_modules()
    assert set(modules) >= {"billiards-render", "billiards-simulate", "billiards-plot"}
    for module in modules.values():
        assert isinstance(importlib.import_module(module).build_parser(), argparse.ArgumentParser)


def test_every_option_of_every_command_is_in_the_reference() -> None:
    page = commands_markdown()
    for name, module in command_modules().items():
        assert f"## {name}" in page
        section = page.split(f"## {name}", 1)[1].split("\n## ", 1)[0]
        for action in importlib.import_module(module).build_parser()._actions:
            for option in action.option_strings:
                assert option in section, f"{name} {option}"


def test_the_reference_help_is_the_commands_own() -> None:
    """The page shows what `--help` prints, at a fixed width whatever the terminal."""
    columns = os.environ.get("COLUMNS")
    page = commands_markdown()
    assert os.environ.get("COLUMNS") == columns
    assert "usage: python -m billiards.simulate" in page
    assert "--vary" in page.split("## billiards-sweep", 1)[1]


def _keys_in_code(path: Path) -> set[str]:
    """Every key name the reader's code asks a TableReader for: a string constant as the
    first argument of its reading methods, or the second of a helper given the reader
    (`bounded(reader, "length", ...)`)."""
    methods = {"number", "integer", "string", "boolean", "vector", "table", "tables", "raw", "has"}
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if not isinstance(node, ast.Call):
            continue
        if isinstance(node.func, ast.Attribute) and node.func.attr in methods and node.args:
            key = node.args[0]
        elif isinstance(node.func, ast.Name) and len(node.args) > 1:
            key = node.args[1]
        else:
            continue
        if isinstance(key, ast.Constant) and isinstance(key.value, str) and key.value:
            found.add(key.value)
    return found


def test_every_key_the_reader_asks_for_is_in_the_reference() -> None:
    documented = {path.split(".")[-1].removesuffix("[]") for path in scene_keys()}
    code = _keys_in_code(ROOT / "billiards" / "scene" / "reader.py")
    code |= _keys_in_code(ROOT / "billiards" / "scene" / "render_table.py")
    assert len(code) > 50  # the reader's keys were found
    # render_settings' _limited reads its keys by variable: LIMITS names them.
    from billiards.scene.render_table import LIMITS

    assert code | set(LIMITS) <= documented


def test_each_key_says_what_it_accepts() -> None:
    silent = [path for path, read in scene_keys().items() if not read.expected]
    assert silent == []


def test_the_scene_keys_page_has_every_table_and_its_defaults() -> None:
    page = scene_keys_markdown()
    for heading in ("[table]", "[physics]", "[[ball]]", "[rack]", "[render]", "[[camera]]"):
        assert f"## `{heading}`" in page
    assert "| `table.cushion_retention` | `0.75` | a number in [0, 1] |" in page
    assert "| `ball[].id` | required |" in page


def test_the_layout_page_names_every_module_under_its_floor() -> None:
    """docs/development.md's layout is made from the tree: every module of the package
    is listed once, each folder and module under the floor tests/test_floors.py gives it."""
    page = layout_markdown()
    modules = sorted((ROOT / "billiards").rglob("*.py"))
    for path in modules:
        shown = path.relative_to(ROOT).as_posix().replace("/__init__.py", "/")
        assert page.count(f"`{shown}`:") == 1, shown
    floors = page.split("- **")
    rules = next(floor for floor in floors if floor.startswith("rules**"))
    assert "`billiards/rules/seed.py`:" in rules and "`billiards/stage/" not in rules
    assert "<!-- generated: layout -->" in (DOCS / "development.md").read_text()
