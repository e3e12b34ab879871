"""The quick check: `python -m pytest -m smoke` runs these modules only, in under a
minute, against the whole default suite's minutes. They touch every floor: the scene
reader, every shipped scene's pinned result, the trajectory, the library, the site's
examples and reference, the import floors and the README."""

from __future__ import annotations

from pathlib import Path

import pytest

SMOKE_MODULES = {
    "test_api.py",
    "test_docs.py",
    "test_fingerprints.py",
    "test_floors.py",
    "test_readme.py",
    "test_scene.py",
    "test_trajectory.py",
}


def pytest_ignore_collect(collection_path: Path, config: pytest.Config) -> bool | None:
    """With -m smoke, the other test modules are not even imported (collecting the
    whole suite alone takes seconds)."""
    if config.getoption("markexpr") != "smoke" or collection_path.suffix != ".py":
        return None
    is_test = collection_path.name.startswith("test_")
    return True if is_test and collection_path.name not in SMOKE_MODULES else None


@pytest.hookimpl(tryfirst=True)  # before -m selects by marker
def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        if Path(str(item.fspath)).name in SMOKE_MODULES:
            item.add_marker(pytest.mark.smoke)
