"""A PyVista ``Plotter(off_screen=True)`` without a display, as a script runs it: importing
``spt`` names VTK's display-less window, so nothing about X is printed, the window is EGL's,
and the image is SPT's (within the target error of the exact reference). A user's own
``VTK_DEFAULT_OPENGL_WINDOW`` is left as it was."""

import json
import os
import subprocess
import sys

import numpy as np

from spt import metrics, opengl_window

SIZE = (120, 120)

SCRIPT = """
import json, os, sys
import numpy as np
import pyvista as pv
import spt.pyvista
from spt import data, raycast

plotter = pv.Plotter(off_screen=True, window_size=(%d, %d))
plotter.background_color = "black"
actor = spt.pyvista.add_volume(plotter, pv.wrap(data.make_default_mesh()), cmap="viridis",
                               show_scalar_bar=False, target_error=0.005)
plotter.camera_position = "iso"
np.save(sys.argv[1], plotter.screenshot(transparent_background=True, return_img=True))
# The same scene's exact reference, at the camera of the screenshot.
np.save(sys.argv[2], raycast.render(actor.mapper.GetInput(), actor.prop,
                                    plotter.renderer.GetActiveCamera(), (%d, %d)))
json.dump({"window": type(plotter.render_window).__name__,
           "variable": os.environ.get("VTK_DEFAULT_OPENGL_WINDOW")}, sys.stdout)
""" % (SIZE + SIZE)


def _run(tmp_path):
    environment = {k: v for k, v in os.environ.items()
                   if k not in ("DISPLAY", "XAUTHORITY", opengl_window.VARIABLE)}
    image, exact = tmp_path / "image.npy", tmp_path / "exact.npy"
    result = subprocess.run([sys.executable, "-c", SCRIPT, str(image), str(exact)],
                            capture_output=True, text=True, timeout=600, env=environment)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout), result.stderr, np.load(image), np.load(exact)


def test_off_screen_plot_without_display_prints_nothing_about_x(tmp_path):
    state, stderr, image, exact = _run(tmp_path)
    assert "X server" not in stderr and "vtkXOpenGLRenderWindow" not in stderr, stderr
    assert state["variable"] == "vtkEGLRenderWindow"
    assert state["window"] == "vtkEGLRenderWindow"
    # The image is SPT's: the same scene's exact reference, within the target error and the
    # 8-bit rounding, and not empty.
    assert exact[..., 3].max() > 0.5
    assert metrics.rmse(image / 255.0, exact) <= 0.005 + 1.0 / 255.0 / np.sqrt(12.0)


def test_the_users_window_is_left_as_chosen():
    environment = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "XAUTHORITY")}
    environment[opengl_window.VARIABLE] = "vtkOSOpenGLRenderWindow"
    result = subprocess.run(
        [sys.executable, "-c", "import os, spt; print(os.environ['%s'])" % opengl_window.VARIABLE],
        capture_output=True, text=True, timeout=300, env=environment)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "vtkOSOpenGLRenderWindow"


def test_default_window_only_without_display_and_a_users_choice():
    assert opengl_window.default_window({}) == "vtkEGLRenderWindow"  # this run has libEGL
    assert opengl_window.default_window({"DISPLAY": ":0"}) is None
    assert opengl_window.default_window({opengl_window.VARIABLE: "vtkOSOpenGLRenderWindow"}) \
        is None
    assert opengl_window.default_window({}, platform="win32") is None
    assert not opengl_window.chooses_at_run_time("9.3.1")
    assert opengl_window.chooses_at_run_time("9.5.0")
    environment = {}
    assert opengl_window.choose("9.2.6", environment) is None and environment == {}
