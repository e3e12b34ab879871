"""The scene file's [render] table and [[camera]] shots, as frozen dataclasses.

Parsed with the scene's TableReader so errors read like every other scene error.
Imports no GL: the simulator reads scene files too.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from billiards.scene import TableReader


@dataclass(frozen=True)
class RenderSettings:
    width: int = 1280
    height: int = 720
    fps: float = 30.0
    quality: int = 23  # x264 crf: lower is better and larger
    output: str = "break.mp4"


def parse_render_settings(root: TableReader, source: str) -> RenderSettings:
    reader = root.table("render")
    settings = RenderSettings(
        width=reader.integer("width", RenderSettings.width, low=16),
        height=reader.integer("height", RenderSettings.height, low=16),
        fps=reader.number("fps", RenderSettings.fps, low=1.0, high=240.0),
        quality=reader.integer("quality", RenderSettings.quality, low=0),
        output=reader.string("output", RenderSettings.output),
    )
    reader.finish()
    return settings
