"""Which OpenGL window VTK makes where there is no X display.

VTK 9.4 and later (PyPI's vtk wheels are built so) choose the class of a new
``vtkRenderWindow`` when it is made, from ``VTK_DEFAULT_OPENGL_WINDOW``: unset, VTK tries X
first, which without a display prints ``vtkXOpenGLRenderWindow ... bad X server connection``
before it falls back to EGL, on every window, off screen plots included. Importing ``spt``
sets the variable where there is no display and the user has not set it, to the first
display-less window whose library this machine can load, so that a script, a notebook's kernel
or a server without X renders through EGL (or OSMesa) with nothing printed. A user's own setting
always wins, and where there is a display nothing changes.
"""

from __future__ import annotations

import ctypes
import os
import sys
from typing import Mapping, MutableMapping, Optional

#: The environment variable ``vtkOpenGLRenderWindow::New`` reads (VTK 9.4 on).
VARIABLE = "VTK_DEFAULT_OPENGL_WINDOW"

#: The windows that need no display, in VTK's own order of preference, with the libraries
#: they open at run time.
WITHOUT_DISPLAY = (
    ("vtkEGLRenderWindow", ("libEGL.so.1",)),
    ("vtkOSOpenGLRenderWindow", ("libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so")),
)


def _loadable(library: str) -> bool:
    try:
        ctypes.CDLL(library)
    except OSError:
        return False
    return True


def chooses_at_run_time(vtk_version: str) -> bool:
    """Whether a VTK of this version (``'9.5.0'``) reads :data:`VARIABLE`: 9.4 and later."""
    major, minor = (int(part) for part in vtk_version.split(".")[:2])
    return (major, minor) >= (9, 4)


def default_window(environment: Mapping[str, str], platform: str = sys.platform
                   ) -> Optional[str]:
    """The window class to name in :data:`VARIABLE`, or None to leave VTK's choice: None where
    the user has set it, where there is an X display (``DISPLAY``), off Linux, or where no
    display-less window's library loads."""
    if environment.get(VARIABLE) or environment.get("DISPLAY"):
        return None
    if not platform.startswith("linux"):
        return None
    for window, libraries in WITHOUT_DISPLAY:
        if any(_loadable(library) for library in libraries):
            return window
    return None


def choose(vtk_version: str, environment: MutableMapping[str, str] = os.environ
           ) -> Optional[str]:
    """Set :data:`VARIABLE` in ``environment`` to :func:`default_window` where VTK reads it and
    that names one; returns what it set, or None where it left the environment as it was."""
    if not chooses_at_run_time(vtk_version):
        return None
    window = default_window(environment)
    if window is not None:
        environment[VARIABLE] = window
    return window
