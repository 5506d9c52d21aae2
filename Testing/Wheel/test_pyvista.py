"""spt.pyvista.add_volume in a pyvista.Plotter: the screenshot of a tetrahedral mesh within the
target error of the exact reference, PyVista's colour maps and opacity presets, the opacity unit
distance of PyVista's rule for images, any mesh PyVista holds, and the input left as it was."""

import numpy as np
import pytest
import pyvista as pv

import spt
import spt.pyvista
from spt import data, metrics, raycast

SIZE = (160, 160)
TARGET_ERROR = 0.005
# The target error, plus the 8-bit screenshot's rounding (1/255 / sqrt(12) RMSE).
TOLERANCE = TARGET_ERROR + 1.0 / 255.0 / np.sqrt(12.0)


@pytest.fixture
def mesh():
    return pv.wrap(data.make_default_mesh())


@pytest.fixture
def plotter():
    plotter = pv.Plotter(off_screen=True, window_size=SIZE)
    plotter.background_color = "black"
    yield plotter
    plotter.close()


def _screenshot(plotter) -> np.ndarray:
    image = plotter.screenshot(transparent_background=True, return_img=True)
    return image.astype(np.float64) / 255.0


@pytest.mark.parametrize("opacity, cmap", [("linear", "viridis"), ("sigmoid", "coolwarm")])
def test_screenshot_is_within_the_target_error_of_the_exact_reference(plotter, mesh, opacity, cmap):
    actor = spt.pyvista.add_volume(plotter, mesh, cmap=cmap, opacity=opacity,
                                   show_scalar_bar=False, target_error=TARGET_ERROR)
    assert isinstance(actor.mapper, spt.vtkSPTVolumeMapper)
    plotter.camera_position = "iso"
    image = _screenshot(plotter)
    exact = raycast.render(actor.mapper.GetInput(), actor.prop,
                           plotter.renderer.GetActiveCamera(), SIZE)
    assert exact[..., 3].max() > 0.5
    assert metrics.rmse(image, exact) <= TOLERANCE


def test_presets_and_colour_maps_are_pyvistas(plotter, mesh):
    low, high = mesh.get_data_range()
    actor = spt.pyvista.add_volume(plotter, mesh, cmap="coolwarm", opacity="sigmoid",
                                   n_colors=256, show_scalar_bar=False)
    expected = pv.opacity_transfer_function("sigmoid", 256) / 255.0
    opacity = actor.prop.GetScalarOpacity()
    xs = np.linspace(low, high, 256)
    got = np.array([opacity.GetValue(x) for x in xs])
    assert np.allclose(got, expected, atol=0.02)
    colours = pv.LookupTable(cmap="coolwarm", n_values=256)
    rgb = actor.prop.GetRGBTransferFunction()
    assert np.allclose(rgb.GetColor(low), np.array(colours.values[0, :3]) / 255.0, atol=0.02)
    assert np.allclose(rgb.GetColor(high), np.array(colours.values[-1, :3]) / 255.0, atol=0.02)


def test_opacity_unit_distance_follows_pyvistas_rule_for_images(plotter, mesh):
    image = pv.ImageData(dimensions=(9, 9, 9))
    image.point_data["x"] = image.points[:, 0]
    pyvistas = image.length / (np.mean(image.dimensions) - 1)
    assert spt.pyvista.default_opacity_unit_distance(image) == pytest.approx(pyvistas)
    # An image's unit distance is PyVista's, from its own cells, not from the tetrahedra.
    drawn = spt.pyvista.add_volume(plotter, image, show_scalar_bar=False)
    assert drawn.prop.GetScalarOpacityUnitDistance() == pytest.approx(pyvistas)
    actor = spt.pyvista.add_volume(plotter, mesh, show_scalar_bar=False)
    assert actor.prop.GetScalarOpacityUnitDistance() == \
        pytest.approx(mesh.length / np.cbrt(mesh.n_cells))
    given = spt.pyvista.add_volume(plotter, mesh, opacity_unit_distance=0.25,
                                   show_scalar_bar=False)
    assert given.prop.GetScalarOpacityUnitDistance() == pytest.approx(0.25)


def test_any_mesh_is_split_into_tetrahedra_and_left_as_it_was(plotter):
    image = pv.ImageData(dimensions=(6, 7, 8), spacing=(0.2, 0.2, 0.2))
    image.cell_data["heat"] = np.arange(image.n_cells, dtype=float)
    before = image.copy(deep=True)
    actor = spt.pyvista.add_volume(plotter, image, scalars="heat", show_scalar_bar=True)
    drawn = actor.mapper.GetInput()
    assert drawn.GetNumberOfCells() == 5 * image.n_cells or \
        drawn.GetNumberOfCells() == 6 * image.n_cells
    assert drawn.GetPointData().GetArray("heat") is not None
    assert image == before and list(image.cell_data.keys()) == ["heat"]
    assert list(image.point_data.keys()) == []
    shot = _screenshot(plotter)
    assert shot[..., 3].max() > 0.2, "nothing drawn"


def test_baselines_through_the_same_function(plotter, mesh):
    assert isinstance(spt.pyvista.add_volume(plotter, mesh, method="havs").mapper,
                      spt.vtkHAVSVolumeMapper)
    assert isinstance(spt.pyvista.add_volume(plotter, mesh, method="pbvr").mapper,
                      spt.vtkPBVRVolumeMapper)
    with pytest.raises(ValueError, match="unknown method"):
        spt.pyvista.add_volume(plotter, mesh, method="zsweep")


def test_bad_input_gets_a_clear_error(plotter, mesh):
    with pytest.raises(TypeError, match="no volume"):
        spt.pyvista.add_volume(plotter, pv.Sphere())
    bare = pv.ImageData(dimensions=(3, 3, 3))
    with pytest.raises(ValueError, match="no active scalars"):
        spt.pyvista.add_volume(plotter, bare)
    with pytest.raises(ValueError, match="scalars for a mesh"):
        spt.pyvista.add_volume(plotter, mesh, scalars=[1.0, 2.0])
    with pytest.raises(TypeError, match="unexpected"):
        spt.pyvista.add_volume(plotter, mesh, colour="red")


def test_pyvistas_clip_plane_widget_cuts_the_volume(plotter, mesh):
    """PyVista's add_volume_clip_plane adds a plane to the volume's mapper and moves it in place
    as the widget moves: SPT cuts the volume there exactly, without re-meshing."""
    actor = spt.pyvista.add_volume(plotter, mesh, cmap="viridis", show_scalar_bar=False,
                                   target_error=TARGET_ERROR)
    plotter.camera_position = "iso"
    widget = plotter.add_volume_clip_plane(actor, normal="-x", origin=mesh.center)
    widget.Off()  # the widget's own outline is not the volume's
    planes = actor.mapper.GetClippingPlanes()
    assert planes.GetNumberOfItems() == 1
    plane = planes.GetItemAsObject(0)
    camera = plotter.renderer.GetActiveCamera()
    for origin in (mesh.center, np.add(mesh.center, (0.4, 0.0, 0.0))):
        plane.SetOrigin(origin)  # what the widget's callback does
        plotter.render()
        image = _screenshot(plotter)
        grid = actor.mapper.GetInput()
        exact = raycast.render(grid, actor.prop, camera, SIZE, clipping_planes=[plane])
        unclipped = raycast.render(grid, actor.prop, camera, SIZE)
        assert exact[..., 3].max() > 0.3
        assert metrics.rmse(image, exact) <= TOLERANCE
        assert metrics.rmse(image, unclipped) > 3 * TOLERANCE
