"""A context older than the mappers need is refused with a message that names what is missing
and what to do, never a crash and never a shader compile error. Mesa makes the context old:
MESA_GL_VERSION_OVERRIDE=3.1 (the mappers need OpenGL 3.2). Through X, VTK accepts the 3.1
context and each mapper refuses it; through EGL, the window cannot make its OpenGL 3.2 context
and says so, and spt.render stops with that message instead of reading back pixels that were
never drawn.
"""

import os
import pathlib
import subprocess
import sys

import pytest

import spt

# The child renders the default mesh with one mapper and prints the image's largest alpha.
CHILD = """
import sys
from spt import data, render
grid = data.make_default_mesh()
mapper = render.MAPPERS[sys.argv[1]]()
image = render.render(grid, data.default_transfer_function(grid), mapper, size=(32, 32)).image
print("alpha", image[..., 3].max())
"""


def run_with_gl_version(version: str, kind: str, x: bool) -> subprocess.CompletedProcess:
    env = dict(os.environ, MESA_GL_VERSION_OVERRIDE=version)
    if not x:
        env.pop("DISPLAY", None)
    package_parent = str(pathlib.Path(spt.__file__).resolve().parent.parent)
    env["PYTHONPATH"] = os.pathsep.join([package_parent, env.get("PYTHONPATH", "")])
    return subprocess.run([sys.executable, "-c", CHILD, kind], capture_output=True, text=True,
                          env=env, check=False, timeout=600)


@pytest.mark.parametrize("kind", ["spt", "havs", "pbvr"])
def test_through_x_each_mapper_names_the_version_it_needs(kind):
    if not os.environ.get("DISPLAY"):
        pytest.skip("no X display: VTK's X window is what accepts a 3.1 context")
    result = run_with_gl_version("3.1", kind, x=True)
    assert result.returncode == 0, result.stderr[-2000:]
    assert "alpha 0.0" in result.stdout
    assert "needs OpenGL 3.2 or later" in result.stderr
    assert "this context is OpenGL 3.1" in result.stderr
    assert "Update the graphics driver" in result.stderr
    assert "Could not compile" not in result.stderr


def test_through_egl_the_window_names_the_version_it_needs():
    result = run_with_gl_version("3.1", "spt", x=False)
    assert result.returncode == 1 and "alpha" not in result.stdout
    assert "RuntimeError: no DISPLAY, and no OpenGL through EGL either" in result.stderr
    assert "could not make an OpenGL 3.2 core profile context" in result.stderr
    assert "Use a driver that offers it" in result.stderr
    assert "Could not compile" not in result.stderr and "Segmentation" not in result.stderr


def test_a_new_enough_context_renders_without_a_message():
    result = run_with_gl_version("3.3", "spt", x=bool(os.environ.get("DISPLAY")))
    assert result.returncode == 0, result.stderr[-2000:]
    assert result.stderr == ""
    assert float(result.stdout.split()[-1]) > 0.2
