"""SPT's time budget inside ParaView: dragging the mouse in a render view showing "Volume (SPT)"
draws fewer repetitions, letting go draws the full Repetition Level.

pvpython runs paraview/interactive_renders.py, which drags through ParaView's own interactor,
interactor style and interactive-render helper (what the GUI's view widget uses), and records
every render of the view. Found there, and relied upon here: ParaView's InteractiveRender() sets
the render window's desired update rate to 5 frames a second and StillRender() to 0.002, so the
renderer allots the volume 1 / (5 x renderers) seconds while the mouse moves and 1 / (0.002 x
renderers) when it is released; above the view's LOD threshold ParaView draws its
level-of-detail stand-in instead of the volume while the mouse moves.
"""

import json

import numpy as np
import pytest

import paraview_support as pvs

REPETITIONS = 16


@pytest.fixture(scope="module")
def session(have_x_display, tmp_path_factory):
    directory = tmp_path_factory.mktemp("interactive")
    mesh = pvs.write_mesh(directory / "mesh.vtk")
    pvs.run([pvs.executable("pvpython"), pvs.SCRIPTS / "interactive_renders.py",
             "--plugin", pvs.plugin_path(), "--data", mesh, "--output", directory,
             "--repetitions", REPETITIONS])
    report = json.loads((directory / "report.json").read_text())
    pvs.keep_text(json.dumps(report, indent=1), "paraview_interactive_renders.json")
    return directory, report


def renders(session, step, interactive):
    """The renders of one step of the script, interactive or still ones."""
    rate = 5.0 if interactive else 0.002
    found = [r for r in session[1]["renders"]
             if r["step"] == step and r["desired_update_rate"] == pytest.approx(rate)]
    assert found, f"no {'interactive' if interactive else 'still'} render in step {step}"
    return found


def full_level_misses_the_budget(session):
    """The precondition of a cut: the full Repetition Level takes longer than ParaView allots
    to an interactive frame (always so on llvmpipe; a fast GPU may draw it all in time)."""
    still = renders(session, "start", interactive=False)[-1]
    allotted = renders(session, "drag", interactive=True)[0]["allotted_seconds"]
    if REPETITIONS * still["seconds_per_repetition"] <= allotted:
        pytest.skip(f"{REPETITIONS} repetitions fit ParaView's {allotted * 1e3:.0f} ms here")


def test_paraview_allots_the_volume_its_interactive_and_still_times(session):
    renderers = session[1]["renderers"]
    for render in renders(session, "drag", interactive=True):
        assert render["allotted_seconds"] == pytest.approx(1.0 / (5.0 * renderers))
        assert not render["used_lod"]
    for render in renders(session, "drag", interactive=False):
        assert render["allotted_seconds"] == pytest.approx(1.0 / (0.002 * renderers))


def test_dragging_draws_fewer_repetitions_and_letting_go_all(session):
    full_level_misses_the_budget(session)
    dragged = renders(session, "drag", interactive=True)
    assert len(dragged) == 3, "one interactive render per mouse move"
    assert all(1 <= r["repetitions"] < REPETITIONS for r in dragged), dragged
    released = renders(session, "drag", interactive=False)
    assert [r["repetitions"] for r in released] == [REPETITIONS]


def test_interactive_and_still_screenshots_are_the_same_volume(session):
    """The interactive image is noisier, not different: over 7 x 7 pixels its difference from
    the still image shrinks as independent per-pixel noise does (by 1/7; measured 0.144), where
    a biased image would keep most of it (0.42 for one 20 % off)."""
    full_level_misses_the_budget(session)
    directory = session[0]
    assert renders(session, "screenshot_interactive", True)[-1]["repetitions"] < REPETITIONS
    assert renders(session, "screenshot_still", False)[-1]["repetitions"] == REPETITIONS
    interactive = pvs.read_png(directory / "interactive.png")[..., :3]
    still = pvs.read_png(directory / "still.png")[..., :3]
    pvs.keep(directory / "interactive.png", "paraview_interactive_render.png")
    pvs.keep(directory / "still.png", "paraview_still_render.png")
    pvs.check_volume_image(interactive)
    pvs.check_volume_image(still)
    difference = interactive - still
    pixel = np.sqrt((difference ** 2).mean())
    local = np.sqrt((pvs.box_filter(difference, 3) ** 2).mean())
    assert pixel > 0.0, "the interactive render drew as many repetitions as the still one"
    assert local < 2.0 / 7.0 * pixel, f"RMS {pixel:.4f} per pixel, {local:.4f} over 7 x 7"


def test_progressive_refinement_restarts_while_dragging_and_continues_after(session):
    full_level_misses_the_budget(session)
    stills = renders(session, "progressive_still", interactive=False)
    assert [r["repetitions"] for r in stills] == [REPETITIONS, 2 * REPETITIONS]
    dragged = renders(session, "progressive_drag", interactive=True)
    assert all(1 <= r["repetitions"] < REPETITIONS for r in dragged), "each move restarts"
    released = renders(session, "progressive_drag", interactive=False)[-1]
    assert released["repetitions"] == dragged[-1]["repetitions"] + REPETITIONS
    after = renders(session, "progressive_after", interactive=False)[-1]
    assert after["repetitions"] == released["repetitions"] + REPETITIONS


def test_above_the_lod_threshold_paraview_draws_its_stand_in(session):
    """The mapper is not called while ParaView's LOD is in use: had it drawn, the budget would
    have cut its repetitions (test_dragging_draws_fewer_repetitions_and_letting_go_all)."""
    full_level_misses_the_budget(session)
    dragged = renders(session, "lod_drag", interactive=True)
    assert all(r["used_lod"] and r["repetitions"] == REPETITIONS for r in dragged), dragged
    released = renders(session, "lod_drag", interactive=False)[-1]
    assert not released["used_lod"] and released["repetitions"] == REPETITIONS


def test_without_the_budget_interactive_renders_draw_all(session):
    dragged = renders(session, "unadjusted_drag", interactive=True)
    assert [r["repetitions"] for r in dragged] == [REPETITIONS]


def test_where_one_repetition_misses_the_time_dragging_draws_fewer_pixels(session):
    """With 16 samples per pixel one repetition takes longer than ParaView's interactive
    frame: while the mouse moves the image's pixels move apart (at most the default maximum of
    4 view pixels), so that a frame fits better, and the still render after it draws every
    pixel and the full Repetition Level."""
    still = renders(session, "distance_still", interactive=False)[-1]
    dragged = renders(session, "distance_drag", interactive=True)
    allotted = dragged[0]["allotted_seconds"]
    if still["seconds_per_repetition"] <= allotted:
        pytest.skip(f"one repetition fits ParaView's {allotted * 1e3:.0f} ms here")
    assert still["sample_distance"] == 1.0
    distances = [r["sample_distance"] for r in dragged]
    assert 1.0 < distances[-1] <= 4.0, distances
    assert all(1 <= r["repetitions"] <= REPETITIONS for r in dragged), dragged
    released = renders(session, "distance_drag", interactive=False)[-1]
    assert released["sample_distance"] == 1.0
    assert released["repetitions"] == REPETITIONS


def test_the_coarser_interactive_image_shows_the_same_volume(session):
    """The interactive image of fewer pixels is the still image blurred and noisier: its mean
    over 7 x 7 pixels differs from the still image's by less than a fifth of the volume's
    mean brightness, and by more than nothing per pixel."""
    directory = session[0]
    dragged = renders(session, "distance_screenshot_interactive", True)[-1]
    if dragged["sample_distance"] == 1.0:
        pytest.skip("the interactive screenshot drew every pixel here")
    interactive = pvs.read_png(directory / "distance_interactive.png")[..., :3]
    still = pvs.read_png(directory / "distance_still.png")[..., :3]
    pvs.keep(directory / "distance_interactive.png", "paraview_interactive_fewer_pixels.png")
    pvs.check_volume_image(interactive)
    pvs.check_volume_image(still)
    difference = interactive - still
    pixel = np.sqrt((difference ** 2).mean())
    local = np.abs(pvs.box_filter(difference, 3)).mean()
    covered = still.max(axis=-1) > 1.0 / 255.0
    brightness = still[covered].mean()
    assert pixel > 0.0
    assert local < 0.2 * brightness, f"{local:.4f} over 7 x 7 against a mean of {brightness:.4f}"
