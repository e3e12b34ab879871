"""A headless OpenGL 3.3 context: EGL first, OSMesa as the fallback.

EGL gives the GPU's driver where one exists and Mesa's llvmpipe on a CPU. glcontext
(moderngl's loader) has no OSMesa backend, so the fallback makes an OSMesa context
current itself through ctypes and hands moderngl a loader that resolves GL entry
points with OSMesaGetProcAddress. Any failure is one line naming what to install.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import threading
from typing import Any

import moderngl

from billiards.shell.cli import first_line

GL_VERSION = 330
INSTALL_HINT = (
    "install Mesa's EGL and its software rasterizer "
    "(Debian/Ubuntu: sudo apt-get install libegl1 libgl1-mesa-dri; "
    "or libosmesa6 for the OSMesa fallback)"
)


class ContextError(RuntimeError):
    """No OpenGL context could be made; str() is one line saying what to install."""


# What GL raises while drawing, named here so that no module outside render.gl imports GL.
GLError = moderngl.Error


def create_context() -> moderngl.Context:
    """A standalone context on EGL, or on OSMesa where EGL cannot make one."""
    forced = os.environ.get("BILLIARDS_GL_BACKEND", "").lower()
    errors: list[str] = []
    if forced in ("", "egl"):
        try:
            return moderngl.create_standalone_context(require=GL_VERSION, **_backend("egl"))
        except Exception as error:  # glcontext raises bare Exceptions
            errors.append(f"EGL: {first_line(error)}")
    if forced in ("", "osmesa"):
        try:
            return _osmesa_context()
        except Exception as error:
            errors.append(f"OSMesa: {first_line(error)}")
    if not errors:
        errors.append(f"BILLIARDS_GL_BACKEND={forced!r} is not egl or osmesa")
    raise ContextError(
        f"no headless OpenGL {GL_VERSION // 100}.{GL_VERSION // 10 % 10} context "
        f"({'; '.join(errors)}): {INSTALL_HINT}"
    )


def _backend(name: str) -> dict[str, Any]:
    """Keyword arguments naming a glcontext backend (typed loosely, as moderngl takes them)."""
    return {"backend": name}


# --- OSMesa ------------------------------------------------------------------------------

_OSMESA_RGBA = 0x1908
_OSMESA_DEPTH_BITS = 0x30
_OSMESA_STENCIL_BITS = 0x31
_OSMESA_ACCUM_BITS = 0x32
_OSMESA_PROFILE = 0x33
_OSMESA_CORE_PROFILE = 0x34
_OSMESA_CONTEXT_MAJOR_VERSION = 0x36
_OSMESA_CONTEXT_MINOR_VERSION = 0x37
_OSMESA_FORMAT = 0x22
_GL_UNSIGNED_BYTE = 0x1401

_osmesa_lock = threading.Lock()


class _OSMesaContext:
    """What moderngl asks of a glcontext backend, over an OSMesa context.

    OSMesa renders into a client buffer; the package draws into its own
    framebuffer objects, so a 1x1 buffer is enough to make the context current.
    """

    def __init__(self, library: ctypes.CDLL) -> None:
        self.lib = library
        library.OSMesaCreateContextAttribs.restype = ctypes.c_void_p
        library.OSMesaCreateContextAttribs.argtypes = [
            ctypes.POINTER(ctypes.c_int),
            ctypes.c_void_p,
        ]
        library.OSMesaMakeCurrent.restype = ctypes.c_ubyte
        library.OSMesaMakeCurrent.argtypes = [
            ctypes.c_void_p,
            ctypes.c_void_p,
            ctypes.c_uint,
            ctypes.c_int,
            ctypes.c_int,
        ]
        library.OSMesaGetProcAddress.restype = ctypes.c_void_p
        library.OSMesaGetProcAddress.argtypes = [ctypes.c_char_p]
        library.OSMesaDestroyContext.argtypes = [ctypes.c_void_p]
        settings = (
            (_OSMESA_FORMAT, _OSMESA_RGBA),
            (_OSMESA_DEPTH_BITS, 24),
            (_OSMESA_STENCIL_BITS, 8),
            (_OSMESA_ACCUM_BITS, 0),
            (_OSMESA_PROFILE, _OSMESA_CORE_PROFILE),
            (_OSMESA_CONTEXT_MAJOR_VERSION, 3),
            (_OSMESA_CONTEXT_MINOR_VERSION, 3),
        )
        attributes = [*(value for pair in settings for value in pair), 0]  # 0 ends the list
        array = (ctypes.c_int * len(attributes))(*attributes)
        self.handle = library.OSMesaCreateContextAttribs(array, None)
        if not self.handle:
            raise RuntimeError("OSMesaCreateContextAttribs failed (no core 3.3 profile)")
        self.buffer = (ctypes.c_ubyte * 4)()
        self.make_current()

    def make_current(self) -> None:
        if not self.lib.OSMesaMakeCurrent(self.handle, self.buffer, _GL_UNSIGNED_BYTE, 1, 1):
            raise RuntimeError("OSMesaMakeCurrent failed")

    def load_opengl_function(self, name: str) -> int:
        return int(self.lib.OSMesaGetProcAddress(name.encode()) or 0)

    def load(self, name: str) -> int:
        return self.load_opengl_function(name)

    def release(self) -> None:
        if self.handle:
            self.lib.OSMesaDestroyContext(self.handle)
            self.handle = None

    def __enter__(self) -> None:
        self.make_current()

    def __exit__(self, *args: Any) -> None:
        return None


def _osmesa_context() -> moderngl.Context:
    import glcontext

    name = ctypes.util.find_library("OSMesa") or "libOSMesa.so.8"
    try:
        library = ctypes.CDLL(name)
    except OSError:
        raise RuntimeError("libOSMesa is not installed") from None
    backend = _OSMesaContext(library)

    def factory(*args: Any, **kwargs: Any) -> _OSMesaContext:
        return backend

    # moderngl asks glcontext for a backend by name; lend it ours for this one call.
    with _osmesa_lock:
        original = glcontext.get_backend_by_name
        glcontext.get_backend_by_name = lambda name: factory
        try:
            return moderngl.create_context(
                require=GL_VERSION, standalone=True, **_backend("osmesa")
            )
        finally:
            glcontext.get_backend_by_name = original
