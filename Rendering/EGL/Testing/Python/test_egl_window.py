"""Rendering without X: spt.vtkHeadlessEGLRenderWindow, and its automatic choice when there is no
DISPLAY. The renders without X run in a child process whose environment has no DISPLAY; the
image is compared with the same scene rendered through X when this process has a display, and
with the exact reference (spt.raycast) in any case.
"""

import json
import os

import numpy as np
import pytest

import spt
from spt import metrics, render

from scene_support import reference, scene_image
from spt_pytest_fixtures import run_python

SIZE = 96
LEVEL = 64

# The child: the default scene through SPT in render.make_window's window, with no DISPLAY.
CHILD = """
import json, sys
import numpy as np
from spt import render, scenes
window, _ = render.make_window(8, 8)
s = scenes.scene("default")
image = render.render(s.grid, s.property, render.spt_mapper({level}, seed=1), s.view,
                      ({size}, {size})).image
np.save(sys.argv[1], image)
window.Render()
print(json.dumps({{"class": window.GetClassName(), "platform": window.GetPlatformName()}}))
"""


@pytest.fixture(scope="module")
def without_x(tmp_path_factory):
    """The child's image and what it reported of its window."""
    path = tmp_path_factory.mktemp("egl") / "image.npy"
    result = run_python(CHILD.format(level=LEVEL, size=SIZE), str(path), without_display=True)
    assert result.returncode == 0, result.stderr
    return np.load(path), json.loads(result.stdout.strip().splitlines()[-1]), result.stderr


def test_without_display_the_egl_window_is_chosen_and_prints_nothing(without_x):
    _, window, stderr = without_x
    assert window in ({"class": "vtkHeadlessEGLRenderWindow", "platform": platform}
                      for platform in ("surfaceless", "device")), window
    # No spurious message (GLEW's "could not be initialized" among them): nothing at all.
    assert stderr == ""


def test_without_display_the_image_is_the_volume(without_x):
    image, _, _ = without_x
    assert 0.05 < (image[..., 3] > 0.05).mean() < 0.95
    assert metrics.rmse(image, reference("default", SIZE)) < 0.05


def test_without_display_the_image_is_the_one_x_renders(without_x):
    if not os.environ.get("DISPLAY"):
        pytest.skip("no X display to render the same scene through X (GLX)")
    image, _, _ = without_x
    with_x = scene_image("default", render.spt_mapper(LEVEL, seed=1), SIZE)
    # The same driver (Mesa) draws both, with the same seed: the same image up to rounding.
    assert np.abs(image - with_x).max() <= 2.0 / 255.0


def test_settings_and_print_self():
    window = spt.vtkHeadlessEGLRenderWindow()
    assert window.GetDeviceIndex() == -1
    window.SetDeviceIndex(100)
    assert window.GetDeviceIndex() == 63
    window.SetDeviceIndex(-5)
    assert window.GetDeviceIndex() == -1
    assert window.GetPlatformName() == ""
    assert "DeviceIndex: -1" in str(window)


BAD_DEVICE = """
from spt import vtkHeadlessEGLRenderWindow
window = vtkHeadlessEGLRenderWindow()
window.SetDeviceIndex(63)
window.Render()
print("supported", window.SupportsOpenGL())
"""


X_INTERACTOR = """
import vtk
from spt import vtkHeadlessEGLRenderWindow
window = vtkHeadlessEGLRenderWindow()
interactor = vtk.vtkRenderWindowInteractor()
interactor.SetRenderWindow(window)
window.Render()
print("rendered", window.GetInteractor() is None)
"""


@pytest.mark.parametrize("code, printed, error", [
    (BAD_DEVICE, "supported 0", "EGL device 63 does not exist"),
    (X_INTERACTOR, "rendered True", "cannot drive a window without X"),
], ids=["a missing device", "an X interactor"])
def test_a_misuse_is_a_clear_error_not_a_crash(code, printed, error):
    result = run_python(code, without_display=True)
    assert result.returncode == 0, result.stderr
    assert printed in result.stdout
    assert error in result.stderr
