"""The plugin in the real ParaView client: `paraview` under an Xvfb of its own loads the plugin
and the mesh (--script), then plays a test script (--test-script) that picks "Volume (SPT)" in
the representation toolbar and sets Repetition Level and Seed in the Properties panel, then
"Volume (HAVS-like)" and its K-buffer Size, then "Volume (PBVR)" and its Repetition Level and
Seed, keeping the whole window and the view after each. Each view must show a volume, the
settings must have reached the representation's mapper, and paraview must exit cleanly (--exit).

The screenshots are kept for a person to look at; test_screenshots_for_a_person prints where.
"""

import json
import shutil

import numpy as np
import pytest

import paraview_support as pvs

SCREEN = "1280x1024"
#: What the test script sets in the GUI for each method, by step.
METHODS = {"spt": (pvs.SPT, {"RepetitionLevel": 6, "Seed": 7}),
           "havs": (pvs.HAVS, {"KBufferSize": 4}),
           "pbvr": (pvs.PBVR, {"PBVRRepetitionLevel": 5, "PBVRSeed": 2})}


@pytest.fixture(scope="module")
def session(have_x_display, tmp_path_factory):
    """One GUI session; its output directory. It starts an Xvfb of its own, but only where X
    is available at all (have_x_display): the run without X starts no X server."""
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
         f"--test-script={pvs.SCRIPTS / 'gui_pick_methods.xml'}", "--exit"],
        env=env)
    (directory / "paraview.log").write_text(result.stdout + result.stderr)
    # The whole window after each step (toolbar, Properties panel with the method's settings,
    # view) as PNG next to its dump, and in the artifacts as gui_window_STEP.png.
    from spt import metrics

    for step in METHODS:
        dump = directory / f"window_{step}.xwd"
        if dump.exists():
            metrics.write_png(dump.with_suffix(".png"), pvs.read_xwd(dump))
            pvs.keep(dump.with_suffix(".png"), f"gui_window_{step}.png")
    return directory


def test_paraview_played_the_test_script_and_exited(session):
    log = (session / "paraview.log").read_text()
    assert "Success =  true" in log, log[-3000:]
    errors = sorted(session.glob("error_*.txt"))
    assert not errors, "\n".join(path.read_text() for path in errors)


@pytest.mark.parametrize("step", METHODS)
def test_method_was_picked_and_set_in_the_gui(session, step):
    representation, settings = METHODS[step]
    state = json.loads((session / f"state_{step}.json").read_text())
    assert state["representation"] == representation
    # The combo box lists all three.
    assert set(pvs.MAPPERS) <= set(state["representation_types"])
    assert state["settings"] == state["mapper_settings"] == settings
    assert state["mapper_class"] == pvs.MAPPERS[representation]


@pytest.mark.parametrize("step", METHODS)
def test_view_shows_a_volume(session, step):
    image = pvs.read_png(session / f"view_{step}.png")
    pvs.keep(session / f"view_{step}.png", f"gui_view_{step}.png")
    # The background of the color palette, as drawn: the color of the view's corners.
    corners = np.array([image[0, 0], image[0, -1], image[-1, 0], image[-1, -1]])[:, :3]
    assert np.ptp(corners, axis=0).max() < 2.0 / 255.0, corners
    pvs.check_volume_image(image, background=corners[0], threshold=8.0 / 255.0)


@pytest.mark.parametrize("step", METHODS)
def test_window_screenshot(session, step):
    """Only checked to be a drawn window here; a person looks at it (the Representation combo
    box and the method's group in the Properties panel)."""
    window = pvs.read_xwd(session / f"window_{step}.xwd")
    assert window.shape == (1024, 1280, 3)
    colors = np.unique(window.reshape(-1, 3)[::7], axis=0)
    assert len(colors) > 500, "an empty screen, not ParaView's window"


def test_panels_differ_between_methods(session):
    """Switching the method changes the Properties panel (each method shows its own group)."""
    windows = {step: pvs.read_xwd(session / f"window_{step}.xwd") for step in METHODS}
    panel = slice(0, 1024), slice(0, 400)  # the left-hand dock, where the Properties panel is
    assert not np.array_equal(windows["spt"][panel], windows["havs"][panel])
    assert not np.array_equal(windows["havs"][panel], windows["pbvr"][panel])


def test_screenshots_for_a_person(session, capsys):
    """Say where the screenshots are, past pytest's capture."""
    directory = pvs.artifacts() or session
    with capsys.disabled():
        print(f"\nGUI screenshots: {directory}/gui_window_{{spt,havs,pbvr}}.png (whole window) "
              f"and gui_view_{{spt,havs,pbvr}}.png (view); also in {session}")
