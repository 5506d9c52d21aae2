"""The plugin in the real ParaView client: `paraview` under an Xvfb of its own loads the plugin
and the mesh (--script), then plays a test script (--test-script) that picks "Volume (SPT)" in
the representation toolbar, sets Repetition Level and Seed in the Properties panel, and keeps
the whole window and the view. The view must show a volume, the settings must have reached the
representation, and paraview must exit cleanly (--exit).
"""

import json
import shutil

import numpy as np
import pytest

import paraview_support as pvs

SCREEN = "1280x1024"


@pytest.fixture(scope="module")
def session(tmp_path_factory):
    """One GUI session; its output directory."""
    if not shutil.which("xvfb-run"):
        pytest.skip("xvfb-run (package xvfb) is not installed")
    directory = tmp_path_factory.mktemp("gui")
    framebuffer = directory / "framebuffer"
    framebuffer.mkdir()
    mesh = pvs.write_mesh(directory / "mesh.vtk")
    env = pvs.environment(
        SPT_PARAVIEW_PLUGIN=str(pvs.plugin_path()), SPT_GUI_DATA=str(mesh),
        SPT_GUI_OUTPUT=str(directory), SPT_GUI_CAPTURE=str(pvs.SCRIPTS / "gui_capture.py"),
        SPT_GUI_FRAMEBUFFER=str(framebuffer / "Xvfb_screen0"))
    result = pvs.run(
        [pvs.executable("xvfb-run"), "-a", "-s",
         f"-screen 0 {SCREEN}x24 -noreset -fbdir {framebuffer}",
         pvs.executable("paraview"), "-geometry", f"{SCREEN}+0+0", "--dr",
         f"--script={pvs.SCRIPTS / 'gui_setup.py'}",
         f"--test-script={pvs.SCRIPTS / 'gui_pick_spt.xml'}", "--exit"],
        env=env)
    (directory / "paraview.log").write_text(result.stdout + result.stderr)
    return directory


def test_paraview_played_the_test_script_and_exited(session):
    log = (session / "paraview.log").read_text()
    assert "Success =  true" in log, log[-3000:]


def test_spt_was_picked_and_set_in_the_gui(session):
    state = json.loads((session / "state.json").read_text())
    assert state["representation"] == "Volume (SPT)"
    assert (state["RepetitionLevel"], state["Seed"]) == (6, 7)
    assert state["mapper_class"] == "vtkSPTVolumeMapper"


def test_view_shows_a_volume(session):
    image = pvs.read_png(session / "view.png")
    pvs.keep(session / "view.png", "gui_view.png")
    # The background of the color palette, as drawn: the color of the view's corners.
    corners = np.array([image[0, 0], image[0, -1], image[-1, 0], image[-1, -1]])[:, :3]
    assert np.ptp(corners, axis=0).max() < 2.0 / 255.0, corners
    covered = pvs.footprint(image, background=corners[0], threshold=8.0 / 255.0)
    assert 0.05 < covered.mean() < 0.8, f"{covered.mean():.3f} of the view differs from the background"
    assert image[covered][:, :3].std(axis=0).max() > 0.05, "a flat color, not a volume"


def test_window_screenshot(session):
    """The whole window (toolbar, Properties panel with the SPT settings, view), kept as
    gui_window.png for a person to look at; here only checked to be a drawn window."""
    window = pvs.read_xwd(session / "window.xwd")
    assert window.shape == (1024, 1280, 3)
    if pvs.artifacts():
        from spt import metrics

        metrics.write_png(pvs.artifacts() / "gui_window.png", window)
    colors = np.unique(window.reshape(-1, 3)[::7], axis=0)
    assert len(colors) > 500, "an empty screen, not ParaView's window"
