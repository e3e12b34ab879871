"""The replay page: one self-contained HTML file that plays the shot offline.

The .glb is embedded (base64) with the viewer's JavaScript: three.js 0.169.0's
renderer, GLTFLoader and OrbitControls bundled in billiards/export/vendor (MIT, its
licence beside it; scripts/vendor_three.sh says how it was made) and the page's own
script (billiards/export/web/viewer.js): orbit controls, play / pause, a time slider,
speed 0.1x-2x, the events to jump to, and a top view.
"""

from __future__ import annotations

import base64
import html
import re
from importlib import resources

THREE_VERSION = "0.169.0"
PLACEHOLDER = re.compile("@(TITLE|GLB_BASE64|THREE_BUNDLE|VIEWER)@")


def _text(folder: str, name: str) -> str:
    return resources.files("billiards.export").joinpath(folder, name).read_text(encoding="utf-8")


def page_html(glb: bytes, title: str) -> str:
    """The page holding `glb` (a .glb file's bytes), titled `title`."""
    bundle = _text("vendor", "three-viewer.min.js")
    viewer = _text("web", "viewer.js")
    # Inline scripts end at the first "</script": none may hold one.
    for name, script in (("bundle", bundle), ("viewer", viewer)):
        if "</script" in script.lower():
            raise ValueError(f"the page's {name} script holds </script")
    parts = {
        "@TITLE@": html.escape(title),
        "@GLB_BASE64@": base64.b64encode(glb).decode("ascii"),
        "@THREE_BUNDLE@": bundle,
        "@VIEWER@": viewer,
    }
    # One pass over the template: no inserted text is searched for a placeholder.
    return PLACEHOLDER.sub(lambda found: parts[found.group(0)], _text("web", "page.html"))
