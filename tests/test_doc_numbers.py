"""What the README and the site say that the code can tell: the test counts, the installed
commands, and every command line's options, computed here so that none goes stale
(issue 42: the quick check was 192 tests where the README said 185, the site said
1,365, the first film's page listed four of six commands).

Measured figures (seconds, loads, speeds) are dated where they stand; these are not."""

from __future__ import annotations

import importlib
import re
import shlex
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from scripts.docs_hooks import command_modules
from tests.conftest import SMOKE_MODULES
from tests.test_docs import PAGES

ROOT = Path(__file__).resolve().parent.parent
README = ROOT / "README.md"

# Where a count of the tests is stated: (file, pattern with the count, which suite).
STATED_COUNTS = [
    (README, r"is the default suite \(([\d,]+) tests", "full"),
    (README, r"this README \(([\d,]+) tests", "smoke"),
    (ROOT / "docs" / "development.md", r"the default suite: ([\d,]+) tests", "full"),
    (ROOT / "docs" / "development.md", r"the quick check: ([\d,]+) tests", "smoke"),
]


def collected_tests() -> list[str]:
    """The node ids `python -m pytest` runs (its default selection), collected alone."""
    out = subprocess.run(
        [sys.executable, "-m", "pytest", "--collect-only", "-q", "-n0", "-p", "no:cacheprovider"],
        capture_output=True,
        text=True,
        check=True,
        cwd=ROOT,
    )
    return [line for line in out.stdout.splitlines() if "::" in line]


def test_the_stated_test_counts_are_the_suites() -> None:
    ids = collected_tests()
    counts = {
        "full": len(ids),
        "smoke": sum(1 for node in ids if Path(node.split("::")[0]).name in SMOKE_MODULES),
    }
    assert counts["full"] > 1000 and counts["smoke"] > 100  # the suite was found
    stale = []
    for path, pattern, suite in STATED_COUNTS:
        found = re.search(pattern, path.read_text(encoding="utf-8"))
        assert found, f"{path.name}: no count matches {pattern!r}"
        stated = int(found.group(1).replace(",", ""))
        if stated != counts[suite]:
            stale.append(f"{path.name} says {stated:,} ({suite}); write {counts[suite]:,}")
    assert stale == []


def installed_commands() -> list[str]:
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    return sorted(pyproject["project"]["scripts"])


@pytest.mark.parametrize(
    "page", [README, ROOT / "docs" / "tutorials" / "first-film.md"], ids=lambda page: page.name
)
def test_a_page_that_lists_the_installed_commands_lists_them_all(page: Path) -> None:
    text = page.read_text(encoding="utf-8")
    commands = installed_commands()
    assert len(commands) >= 6
    assert [command for command in commands if f"`{command}`" not in text] == []


COMMAND_LINE = re.compile(r"^\s*(?:\.venv/bin/)?python -m billiards\.(\w+)\b(.*)$")


def command_lines(text: str) -> list[tuple[str, list[str]]]:
    """(module, arguments) of each command line in a page's indented blocks, continuation
    lines joined, comments dropped."""
    found = []
    lines = text.splitlines()
    index = 0
    while index < len(lines):
        line = lines[index]
        index += 1
        if not line.startswith("    "):
            continue
        while line.endswith("\\") and index < len(lines):
            line = line[:-1] + lines[index].strip()
            index += 1
        match = COMMAND_LINE.match(line)
        if match:
            words = shlex.split(match.group(2), comments=True)
            shell = [n for n, word in enumerate(words) if word in (">", "|", "&&", ";")]
            found.append((match.group(1), words[: shell[0]] if shell else words))
    return found


def test_every_command_line_of_the_readme_and_the_site_is_one_its_command_takes(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """Each example's options exist, with values its parser takes: an option renamed or
    removed would make the page's example fail."""
    modules = {module.split(".")[1]: module for module in command_modules().values()}
    refused = []
    lines = [
        (page, module, arguments)
        for page in [README, *PAGES]
        for module, arguments in command_lines(page.read_text(encoding="utf-8"))
    ]
    assert len(lines) > 30  # the examples were found
    for page, name, arguments in lines:
        if name not in modules:
            refused.append(f"{page.name}: python -m billiards.{name}: no such command")
            continue
        if "--help" in arguments or "--version" in arguments or "--list-scenes" in arguments:
            continue
        parser = importlib.import_module(modules[name]).build_parser()
        try:
            parser.parse_args(_joined(arguments))
        except SystemExit:
            refused.append(
                f"{page.name}: {name} {shlex.join(arguments)}: {capsys.readouterr().err}"
            )
    assert refused == []


def _joined(arguments: list[str]) -> list[str]:
    """`--nudge -1:1`-style values as the commands themselves join them before parsing."""
    out: list[str] = []
    words = iter(arguments)
    for word in words:
        joined = word in ("--nudge", "--vary", "--times")
        out.append(f"{word}={next(words, '')}" if joined else word)
    return out


def test_no_command_says_it_simulates_only_a_break() -> None:
    """Every command takes any scene: its --help says so, not "a pool break"."""
    for module in command_modules().values():
        description = importlib.import_module(module).build_parser().description or ""
        assert "break" not in description.lower(), (module, description)
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert "break" not in pyproject["project"]["description"]
