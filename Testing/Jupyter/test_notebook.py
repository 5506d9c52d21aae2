"""A notebook in JupyterLab, run in headless Chromium, as a user runs it: ``spt.pyvista.add_volume``
and ``plotter.show()`` with PyVista's default (trame) backend. The output cell shows SPT's image,
rendered by the kernel's VTK and sent to the browser as a JPEG: within the error of SPT's target,
the 8-bit rounding and that JPEG of the exact reference of the kernel's camera. One drag in the
browser turns the camera; the image changes and is again SPT's, at the camera read back from
the kernel. The cell's screenshots go to SPT_JUPYTER_OUTPUT (default out/jupyter)."""

import base64
import io
import json
import os
import time
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import lab

TARGET_ERROR = 0.005
QUALITY = 98  # trame's still-image JPEG quality (trame_vtk's VtkRemoteView still_quality)
OUTPUT = Path(os.environ.get("SPT_JUPYTER_OUTPUT",
                             Path(__file__).resolve().parents[2] / "out" / "jupyter"))

CELLS = ["""import pyvista as pv
import spt.pyvista
from spt import data

mesh = pv.wrap(data.make_default_mesh())
plotter = pv.Plotter(window_size=(400, 400))
plotter.background_color = "black"
actor = spt.pyvista.add_volume(plotter, mesh, cmap="viridis", show_scalar_bar=False,
                               target_error=%r)
plotter.camera_position = "iso"
""" % TARGET_ERROR, "plotter.show()"]

# Read back from the kernel: the camera's position and the size of the image it last rendered,
# and into the file named here, the exact image of the notebook's scene at that camera and size
# (premultiplied RGBA, its RGB the color over the black background).
STATE = """import json
import numpy as np
from spt import raycast
_size = tuple(plotter.render_window.GetSize())
np.save(%r, raycast.render(actor.mapper.GetInput(), actor.prop,
                           plotter.renderer.GetActiveCamera(), _size))
print(json.dumps({"position": plotter.camera.position, "size": _size}))
"""

EXECUTE = """const [code, done] = arguments;
const kernel = jupyterapp.shell.currentWidget.sessionContext.session.kernel;
const future = kernel.requestExecute({code});
let text = "";
future.onIOPub = (m) => {
  if (m.header.msg_type === "stream" && m.content.name === "stdout") text += m.content.text;
  if (m.header.msg_type === "error") text += "ERROR " + m.content.evalue;
};
future.done.then(() => done(text), (e) => done("ERROR " + e));"""

# The frame inside the output cell's iframe: its image, decoded by the browser, as a PNG.
FRAME = """const img = [...document.querySelectorAll("img")].find(
    (i) => i.src.startsWith("blob:") && i.naturalWidth > 0);
if (!img) return null;
const canvas = document.createElement("canvas");
canvas.width = img.naturalWidth; canvas.height = img.naturalHeight;
canvas.getContext("2d").drawImage(img, 0, 0);
return [img.src, canvas.toDataURL("image/png")];"""


def _wait(condition, what, timeout=300.0, step=0.5):
    deadline = time.monotonic() + timeout
    while True:
        value = condition()
        if value:
            return value
        if time.monotonic() > deadline:
            raise AssertionError(f"not within {timeout:.0f} s: {what}")
        time.sleep(step)


def _kernel(driver, code):
    text = driver.execute_async_script(EXECUTE, code)
    assert not text.startswith("ERROR"), text
    return text


def _frame(driver, frame_element, previous=None, settle=3.0):
    """The output's image once a new one (not ``previous``'s source) has stayed for
    ``settle`` seconds: trame sends interactive frames, then the still one."""
    def current():
        driver.switch_to.frame(frame_element)
        try:
            return driver.execute_script(FRAME)
        finally:
            driver.switch_to.default_content()
    seen = _wait(lambda: (lambda f: f if f and f[0] != previous else None)(current()),
                 "an image in the output cell")
    since = time.monotonic()
    while time.monotonic() - since < settle:
        time.sleep(0.5)
        now = current()
        if now and now[0] != seen[0]:
            seen, since = now, time.monotonic()
    png = base64.b64decode(seen[1].split(",", 1)[1])
    return seen[0], np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))


def _jpeg_error(rgb8: np.ndarray, mask: np.ndarray) -> float:
    """The RMSE that a JPEG of ``rgb8`` at trame's quality adds, encoded as trame encodes it
    (VTK's vtkJPEGWriter, through vtkWebApplication) and decoded."""
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOImage import vtkJPEGWriter
    height, width = rgb8.shape[:2]
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    image.GetPointData().SetScalars(numpy_to_vtk(rgb8[::-1].reshape(-1, 3).copy()))
    writer = vtkJPEGWriter()
    writer.SetInputData(image)
    writer.SetQuality(QUALITY)
    writer.WriteToMemoryOn()
    writer.Write()
    encoded = vtk_to_numpy(writer.GetResult()).tobytes()
    decoded = np.asarray(Image.open(io.BytesIO(encoded)).convert("RGB"))
    return _rmse(decoded / 255.0, rgb8 / 255.0, mask)


def _rmse(a, b, mask):
    difference = (a - b)[mask]
    return float(np.sqrt(np.mean(difference * difference)))


def _state(driver, directory, name):
    """The kernel's camera position and image size, and the exact image of its scene."""
    path = directory / f"{name}-exact.npy"
    state = json.loads(_kernel(driver, STATE % str(path)))
    return state, np.load(path)


def _check_is_spt(image, state, exact, name):
    assert image.shape[:2] == exact.shape[:2], (image.shape, state["size"])
    mask = exact[..., 3] > 0.5 / 255.0
    assert mask.mean() > 0.05, "the exact image is (nearly) empty"
    rgb8 = np.clip(np.round(exact[..., :3] * 255.0), 0, 255).astype(np.uint8)
    jpeg = _jpeg_error(rgb8, mask)
    error = _rmse(image / 255.0, exact[..., :3], mask)
    # SPT's error target is an RMSE over premultiplied RGBA: over RGB alone at most sqrt(4/3)
    # of it; the 8-bit image's rounding (uniform, 1/255/sqrt(12)); the JPEG's error, measured
    # on the exact image. The three add at most (triangle inequality).
    tolerance = TARGET_ERROR * np.sqrt(4.0 / 3.0) + 1.0 / 255.0 / np.sqrt(12.0) + jpeg
    Image.fromarray(rgb8).save(OUTPUT / f"{name}-exact.png")
    print(f"{name}: RMSE {error:.4f} against the exact image, tolerance {tolerance:.4f} "
          f"(JPEG {jpeg:.4f}), {image.shape[1]}x{image.shape[0]}")
    assert error <= tolerance, (name, error, tolerance)
    return mask


@pytest.fixture
def notebook_page(tmp_path):
    path = lab.notebook(tmp_path / "spt.ipynb", CELLS)
    with lab.jupyter_lab(tmp_path) as url, lab.chromium() as driver:
        driver.get(url(f"lab/tree/{path.name}"))
        _wait(lambda: driver.execute_script(
            "const w = window.jupyterapp && jupyterapp.shell.currentWidget;"
            "return !!(w && w.sessionContext && w.sessionContext.session"
            " && w.sessionContext.session.kernel"
            " && w.sessionContext.session.kernel.connectionStatus === 'connected');"),
            "the notebook open with its kernel")
        yield driver


def test_notebook_shows_spt_and_turns_with_the_camera(notebook_page, tmp_path):
    driver = notebook_page
    OUTPUT.mkdir(parents=True, exist_ok=True)
    driver.execute_script("jupyterapp.commands.execute('notebook:run-all-cells');")
    iframe = _wait(lambda: driver.find_elements("css selector", ".jp-OutputArea-output iframe"),
                   "the output cell's frame", timeout=600)[0]
    source, first = _frame(driver, iframe)
    cell = iframe  # the output cell's view, as the page shows it (trame's menu included)
    cell.screenshot(str(OUTPUT / "notebook.png"))
    Image.fromarray(first).save(OUTPUT / "frame.png")
    before, exact = _state(driver, tmp_path, "frame")
    _check_is_spt(first, before, exact, "frame")

    # One drag across the image: the camera turns, trame asks the kernel for new images.
    from selenium.webdriver import ActionChains
    driver.switch_to.frame(iframe)
    image = driver.find_element("css selector", "img[src^='blob:']")
    chain = ActionChains(driver).move_to_element(image).click_and_hold()
    for _ in range(8):
        chain = chain.move_by_offset(10, 4).pause(0.05)
    chain.release().perform()
    driver.switch_to.default_content()
    _, turned = _frame(driver, iframe, previous=source)
    cell.screenshot(str(OUTPUT / "notebook-dragged.png"))
    Image.fromarray(turned).save(OUTPUT / "frame-dragged.png")
    after, exact = _state(driver, tmp_path, "frame-dragged")
    assert not np.allclose(after["position"], before["position"]), "the camera did not turn"
    mask = _check_is_spt(turned, after, exact, "frame-dragged")
    # The image changed, by more than the tolerance of either comparison.
    moved = _rmse(first / 255.0, turned / 255.0, mask | (first.max(axis=2) > 0))
    print(f"the drag changed the image by an RMSE of {moved:.4f}")
    assert moved > 4 * TARGET_ERROR, moved
