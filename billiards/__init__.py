"""billiards: an exact pool simulator that renders a shot, headless, to an MP4 film.

The library in a few lines (the functions live in billiards.api, imported on first use,
so `import billiards` stays light for the commands and the physics):

    import billiards
    scene = billiards.vary("break", {"ball.cue.velocity": 5.0})
    result = billiards.run(scene)
    result.events, result.pocketed, result.state_at(1.5).ball("cue")
    billiards.plot_top_view(result, "break.png")
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from billiards.version import __version__

if TYPE_CHECKING:
    from billiards.api import (
        BallState,
        Event,
        Pocketing,
        Result,
        Scene,
        SceneError,
        State,
        load_scene,
        plot_top_view,
        render_film,
        render_still,
        run,
        run_many,
        scene_tables,
        shipped_scenes,
        vary,
    )

__all__ = [
    "BallState",
    "Event",
    "Pocketing",
    "Result",
    "Scene",
    "SceneError",
    "State",
    "__version__",
    "load_scene",
    "plot_top_view",
    "render_film",
    "render_still",
    "run",
    "run_many",
    "scene_tables",
    "shipped_scenes",
    "vary",
]


def __getattr__(name: str) -> Any:
    """The library's names, from billiards.api on first use (PEP 562)."""
    if name in __all__:
        from billiards import api

        return getattr(api, name)
    raise AttributeError(f"module 'billiards' has no attribute {name!r}")


def __dir__() -> list[str]:
    """The library's names and the module's own dunders: not this file's helpers
    (`Any`, `annotations`, `TYPE_CHECKING`)."""
    return sorted({*__all__, *(name for name in globals() if name.startswith("__"))})
