"""The README is a front door (at most 200 lines) whose Python example runs as written,
and its examples and each site page's run in order as written: no command stops at an
output an earlier one wrote (every output is refused when it exists, unless `--force`)."""

from __future__ import annotations

import contextlib
import io
import re
import shlex
from pathlib import Path

import pytest

import billiards.render.__main__ as render_command
import billiards.sweep.__main__ as sweep_command
from billiards import plot
from billiards.shell.cli import default_output
from tests.render.fixtures import needs_gl
from tests.test_docs import PAGES, python_blocks

README = Path(__file__).resolve().parent.parent / "README.md"
README_LINES_MAX = 200  # the rest lives on the site (docs/)
# How each command's output is named without an output option: after its scene.
DEFAULT_ENDING = {"render": ".mp4", "plot": ".png", "sweep": "_sweep"}
COMMAND = re.compile(r"^(?:\.venv/bin/)?python -m billiards\.(render|simulate|plot|sweep)\b")


def readme_commands(text: str) -> list[tuple[int, str, list[str]]]:
    """(line, command, arguments) of each package command in the README's code blocks
    (indented four spaces), continuation lines joined, comments dropped."""
    commands = []
    lines = text.splitlines()
    index = 0
    while index < len(lines):
        line, number = lines[index], index + 1
        index += 1
        if not line.startswith("    "):
            continue
        words = line.strip()
        while words.endswith("\\") and index < len(lines):
            words = words[:-1] + lines[index].strip()
            index += 1
        match = COMMAND.match(words)
        if match:
            arguments = shlex.split(words, comments=True)[3:]
            commands.append((number, match.group(1), arguments))
    return commands


def output_of(command: str, arguments: list[str]) -> str | None:
    """The file or folder a command writes (its default, or its option's value)."""
    if "--list-scenes" in arguments or "--help" in arguments:
        return None  # prints, writes nothing
    options = {"simulate": ["--trajectory"], "render": ["--sound-only", "-o"]}
    for option in options.get(command, ["-o"]):
        if option in arguments:
            return arguments[arguments.index(option) + 1].rstrip("/")
    if command not in DEFAULT_ENDING:
        return None
    scene = scene_argument(command, arguments)
    if command == "render" and scene is None and "--trajectory" in arguments:
        scene = Path(arguments[arguments.index("--trajectory") + 1]).stem
    ending = ".png" if command == "render" and "--frame" in arguments else DEFAULT_ENDING[command]
    return default_output(scene, ending)


def scene_argument(command: str, arguments: list[str]) -> str | None:
    """The SCENE a command was given, as the command's own parser reads it."""
    if command == "render":
        return render_command.build_parser().parse_args(arguments).scene
    parser = {"plot": plot.build_parser, "sweep": sweep_command.build_parser}[command]()
    scene: str | None = parser.parse_args(arguments).scene
    return scene


def clashes(commands: list[tuple[int, str, list[str]]]) -> list[str]:
    """Each command that would stop at an output an earlier command wrote."""
    written: dict[str, int] = {}
    found = []
    for line, command, arguments in commands:
        output = output_of(command, arguments)
        if output is None:
            continue
        if output in written and "--force" not in arguments:
            found.append(f"line {line}: {output} exists (written at line {written[output]})")
        written[output] = line
    return found


@pytest.mark.parametrize("page", [README, *PAGES], ids=lambda page: page.name)
def test_a_pages_examples_in_order_never_stop_at_an_existing_output(page: Path) -> None:
    assert clashes(readme_commands(page.read_text(encoding="utf-8"))) == []


def test_the_commands_of_the_readme_and_the_site_are_found() -> None:
    found = [readme_commands(page.read_text(encoding="utf-8")) for page in [README, *PAGES]]
    assert len(found[0]) >= 5
    assert sum(len(commands) for commands in found) > 25


def test_the_readme_is_a_front_door() -> None:
    lines = README.read_text(encoding="utf-8").splitlines()
    assert len(lines) <= README_LINES_MAX
    assert lines[0] == "# billiards"


@pytest.mark.gl
@needs_gl
def test_the_readmes_python_example_runs_as_written(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (block,) = python_blocks(README.read_text(encoding="utf-8"))
    monkeypatch.chdir(tmp_path)
    with contextlib.redirect_stdout(io.StringIO()) as out:
        exec(compile(block, "README.md", "exec"), {"__name__": "__readme__"})
    assert "pocketed: 12 (side-top)" in out.getvalue()
    assert (tmp_path / "pool_break.png").is_file()
    assert (tmp_path / "pool_break_1s.png").is_file()


def test_the_check_finds_a_second_film_of_the_same_name() -> None:
    text = (
        "    python -m billiards.render   # a film\n"
        "    python -m billiards.simulate --trajectory break.npz\n"
        "    python -m billiards.render --trajectory break.npz   # break.mp4 too\n"
        "    python -m billiards.sweep break --runs 2 \\\n        -o out/\n"
        "    python -m billiards.sweep hard_break -o out/ --force\n"
    )
    commands = readme_commands(text)
    assert [command for _, command, _ in commands] == [
        "render",
        "simulate",
        "render",
        "sweep",
        "sweep",
    ]
    assert clashes(commands) == ["line 3: break.mp4 exists (written at line 1)"]


def test_default_outputs_are_named_after_the_scene() -> None:
    text = (
        "    python -m billiards.plot\n"
        "    python -m billiards.plot masse_shot   # no clash: masse_shot.png\n"
        "    python -m billiards.render pool_break --width 640 --height 360\n"
        "    python -m billiards.render scenes/my.toml --frame 1\n"
        "    python -m billiards.sweep hard_break --runs 2\n"
        "    python -m billiards.plot break.toml   # the seed break again\n"
    )
    commands = readme_commands(text)
    assert [output_of(command, arguments) for _, command, arguments in commands] == [
        "break.png",
        "masse_shot.png",
        "pool_break.mp4",
        "my.png",
        "hard_break_sweep",
        "break.png",
    ]
    assert clashes(commands) == ["line 6: break.png exists (written at line 1)"]


def test_the_cluster_example_stays_on_this_machine() -> None:
    text = (README.parent / "docs" / "how-to" / "sweeps.md").read_text(encoding="utf-8")
    assert "dask scheduler --host 127.0.0.1 --port 8786" in text
    assert "--scheduler tcp://127.0.0.1:8786" in text
    assert "sweep ..." not in text  # no placeholder read as a scene name


def test_every_link_of_the_readme_leads_to_a_file() -> None:
    targets = re.findall(r"\]\(([^)\s]+)\)", README.read_text(encoding="utf-8"))
    local = [target for target in targets if not re.match(r"[a-z]+:", target)]
    assert len(local) > 20
    missing = [t for t in local if not (README.parent / t.split("#")[0]).is_file()]
    assert missing == []


def test_the_readmes_sweep_varies_something_within_its_bounds() -> None:
    """A sweep of one shot run 200 times taught nothing (issue 42): the README's
    varies a number, and its ranges pass the checks a run would meet first."""
    sweeps = [
        arguments
        for _, command, arguments in readme_commands(README.read_text(encoding="utf-8"))
        if command == "sweep"
    ]
    assert sweeps
    for arguments in sweeps:
        plan = sweep_command.make_plan(sweep_command.build_parser().parse_args(arguments))
        assert not sweep_command.same_shot(plan), arguments
