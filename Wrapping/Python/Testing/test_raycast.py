"""The project's exact ray caster (spt.raycast), the reference of the statistical tests.

It is checked three ways: against an integral identity that holds for any mesh (the optical
depth summed over the pixels, times the pixel area, is the volume integral of the attenuation),
against VTK's ray caster on a small mesh, and on bad input.
"""

import numpy as np
import pytest
import vtk
from scipy import ndimage
from vtkmodules.util.numpy_support import vtk_to_numpy

from spt import data, metrics, raycast, render

from robustness_support import (UNIT_TETRAHEDRON, split_image, tetrahedra, volume_property,
                                with_point_scalars)
from scene_support import draw_once, moved_copy, with_moved_copy

SIZE = 96


def _linear_property(low, high, unit):
    """Opacity rising linearly over [low, high] (so the attenuation is linear in the scalar)."""
    return volume_property([(low, 0.2, 0.4, 1.0), (high, 1.0, 0.6, 0.2)],
                           [(low, 0.05), (high, 0.6)], unit)


def _parallel_camera(grid, size):
    window, renderer = render.make_window(size, size)
    render.place_camera(renderer, grid.GetBounds(), render.View(30.0, 25.0, parallel=True))
    camera = vtk.vtkCamera()
    camera.DeepCopy(renderer.GetActiveCamera())
    window.Finalize()
    return camera


def _volume_integral_of_attenuation(grid, prop):
    """Sum over the tetrahedra of volume x attenuation at the centroid (exact when the
    attenuation is linear in a linearly interpolated scalar)."""
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    scalars = vtk_to_numpy(grid.GetPointData().GetScalars()).astype(float)
    v = points[cells]
    volume = np.abs(np.linalg.det(v[:, 1:] - v[:, :1])) / 6.0
    centroid_scalar = scalars[cells].mean(axis=1)
    opacity = prop.GetScalarOpacity()
    unit = prop.GetScalarOpacityUnitDistance()
    tau = np.array([opacity.GetValue(s) for s in centroid_scalar]) / unit
    return float((volume * tau).sum())


def test_optical_depth_integrates_the_attenuation_over_the_volume():
    """For a parallel view, sum over pixels of -ln(1 - alpha) x pixel area = integral of tau
    over the volume, for any mesh, convex or not. This checks the chords, the scalars and the
    integration at once, independently of the ray caster's own geometry."""
    grid = data.make_default_mesh()
    low, high = grid.GetPointData().GetScalars().GetRange()
    prop = _linear_property(low, high, unit=2.0)
    size = 160
    camera = _parallel_camera(grid, size)
    image = raycast.render(grid, prop, camera, (size, size))
    assert image[..., 3].max() > 0.2, "the image is empty"
    assert image[..., 3].max() < 0.999, "the volume saturates; the identity needs no clamping"
    pixel_area = (2.0 * camera.GetParallelScale() / size) ** 2
    optical_depth = -np.log1p(-image[..., 3])
    expected = _volume_integral_of_attenuation(grid, prop)
    measured = float(optical_depth.sum() * pixel_area)
    # Pixel sampling of a smooth footprint: about a percent at this size.
    assert measured == pytest.approx(expected, rel=0.02)


def test_single_tetrahedron_chord():
    """A ray through a corner tetrahedron, straight down the z axis at (x, y), crosses a chord
    of length 1 - x - y: alpha = 1 - exp(-tau (1 - x - y))."""
    grid = tetrahedra(UNIT_TETRAHEDRON, [(0, 1, 2, 3)], np.full(4, 0.5))
    prop = _linear_property(0.0, 1.0, unit=0.5)
    camera = vtk.vtkCamera()
    camera.ParallelProjectionOn()
    camera.SetFocalPoint(0.5, 0.5, 0.0)
    camera.SetPosition(0.5, 0.5, 5.0)
    camera.SetViewUp(0.0, 1.0, 0.0)
    camera.SetParallelScale(0.5)  # the view spans [0, 1] x [0, 1]
    camera.SetClippingRange(1.0, 10.0)
    size = 64
    image = raycast.render(grid, prop, camera, (size, size))
    centres = (np.arange(size) + 0.5) / size
    x, y = np.meshgrid(centres, centres[::-1])  # row 0 at the top
    chord = np.clip(1.0 - x - y, 0.0, None)
    tau = prop.GetScalarOpacity().GetValue(0.5) / 0.5
    expected = -np.expm1(-tau * chord)
    assert np.abs(image[..., 3] - expected).max() < 1e-6
    color = np.array(prop.GetRGBTransferFunction().GetColor(0.5))
    assert np.allclose(image[..., :3], expected[..., None] * color, atol=1e-6)


def _tetrahedron_around_the_eye():
    """A regular-ish tetrahedron around the origin, a constant field, and a perspective camera
    at the origin looking down -z with its near plane at 0.05."""
    corners = np.array([(1.0, 1.0, 1.0), (1.0, -1.0, -1.0), (-1.0, 1.0, -1.0), (-1.0, -1.0, 1.0)])
    grid = tetrahedra(corners * 2.0, [(0, 1, 2, 3)], np.full(4, 0.5))
    camera = vtk.vtkCamera()
    camera.SetPosition(0.0, 0.0, 0.0)
    camera.SetFocalPoint(0.0, 0.0, -1.0)
    camera.SetViewUp(0.0, 1.0, 0.0)
    camera.SetViewAngle(60.0)
    camera.SetClippingRange(0.05, 10.0)
    return grid, camera, corners * 2.0


def _alpha_from_the_near_plane(camera, corners, prop, size):
    """Per pixel centre, 1 - exp(-tau chord) of the ray's chord inside the tetrahedron from
    the near plane on (the field is constant, of attenuation tau)."""
    _, origin, direction = raycast._camera_rays(camera, size, size)
    leave = np.full(len(origin), np.inf)
    for k in range(4):
        a, b, c = (corners[(k + i) % 4] for i in (1, 2, 3))
        normal = np.cross(b - a, c - a)
        if np.dot(normal, corners[k] - a) > 0:
            normal = -normal
        approach = direction @ normal
        t = (a - origin) @ normal / np.where(approach > 0, approach, 1.0)
        leave = np.where(approach > 0, np.minimum(leave, t), leave)
    chord = (np.clip(leave, 0.0, 1.0) * np.linalg.norm(direction, axis=1)).reshape(size, size)
    assert chord.min() > 0.5, "every ray should cross the cell"
    tau = prop.GetScalarOpacity().GetValue(0.5) / prop.GetScalarOpacityUnitDistance()
    return -np.expm1(-tau * chord[::-1])


@pytest.mark.parametrize("method, tolerance", [("exact", 1e-6), ("spt", 3.0 / 255.0)])
def test_chord_from_the_near_plane_inside_one_tetrahedron(method, tolerance):
    """The eye inside the cell: every ray starts at the near plane, inside, and its chord runs
    from there to the exit face, alpha = 1 - exp(-tau chord). SPT draws the same chords
    (constant field: the pre-integrated opacity is exact up to the table's sampling and the
    8-bit read-back)."""
    grid, camera, corners = _tetrahedron_around_the_eye()
    prop = _linear_property(0.0, 1.0, unit=2.0)
    size = 48
    if method == "exact":
        image = raycast.render(grid, prop, camera, (size, size))
    else:
        window, renderer = render.make_window(size, size)
        render.add_volume(renderer, grid, prop, render.spt_mapper(4, seed=1))
        renderer.GetActiveCamera().DeepCopy(camera)
        image = draw_once(window)
    expected = _alpha_from_the_near_plane(camera, corners, prop, size)
    assert not np.isnan(image).any()
    error = np.abs(image[..., 3] - expected).max()
    assert error < tolerance, f"alpha off by {error:.4f}"


def _box_mesh():
    """A convex mesh: a tetrahedralized 7 x 6 x 5 box with a smooth analytic field."""
    image = vtk.vtkImageData()
    image.SetDimensions(8, 7, 6)
    image.SetSpacing(0.3, 0.35, 0.4)
    x, y, z = np.meshgrid(*(np.arange(n) for n in (8, 7, 6)), indexing="ij")
    field = np.sin(0.6 * x) * np.cos(0.5 * y) + 0.2 * z
    return split_image(with_point_scalars(image, field.ravel(order="F"), "field"))


def test_agrees_with_vtk_ray_caster_inside_the_silhouette():
    """On a convex mesh the two ray casters agree away from the silhouette (where VTK's
    misses or doubles grazing segments), to about the 8-bit quantization of VTK's image."""
    grid = _box_mesh()
    prop = data.transfer_function(grid)
    view = render.View(azimuth=30.0, elevation=30.0)
    exact = render.reference(grid, prop, view, (SIZE, SIZE)).image
    theirs = render.reference(grid, prop, view, (SIZE, SIZE), method="vtk").image
    assert exact[..., 3].max() > 0.3, "the exact image is empty"
    inside = ndimage.binary_erosion(exact[..., 3] > 0.0, iterations=2)
    assert inside.sum() > 0.3 * SIZE * SIZE
    difference = np.abs(exact - theirs)[inside].max(axis=-1)
    # VTK's image is 8-bit, truncated, and its rays stop at alpha 0.99; its grazing rays along
    # the box's edges (inside the footprint) are off by more, hence percentiles.
    assert np.median(difference) < 2.0 / 255.0, f"median {np.median(difference):.4f}"
    assert np.percentile(difference, 90) < 0.02, f"90 % {np.percentile(difference, 90):.4f}"
    assert abs((exact - theirs)[inside].mean()) < 0.003
    assert metrics.rmse(exact, theirs) < 0.02


def test_bad_input_raises_with_the_reason():
    grid = data.make_default_mesh()
    prop = data.default_transfer_function(grid)
    camera = vtk.vtkCamera()
    no_scalars = vtk.vtkUnstructuredGrid()
    no_scalars.DeepCopy(grid)
    no_scalars.GetPointData().SetScalars(None)
    with pytest.raises(ValueError, match="scalars"):
        raycast.render(no_scalars, prop, camera, (8, 8))
    zero_unit = vtk.vtkVolumeProperty()
    zero_unit.DeepCopy(prop)
    zero_unit.SetScalarOpacityUnitDistance(0.0)
    with pytest.raises(ValueError, match="UnitDistance"):
        raycast.render(grid, zero_unit, camera, (8, 8))
    with pytest.raises(ValueError, match="method"):
        render.reference(grid, prop, method="nonsense")


def test_several_volumes_are_the_image_of_their_union():
    """Two interpenetrating volumes with one property: every ray's segments of both,
    composited together, are the image of the two meshes appended into one grid; a second
    volume with another, transparent property leaves the first as it is alone."""
    grid = data.make_default_mesh()
    b = grid.GetBounds()
    offset = (0.3 * (b[1] - b[0]), 0.2 * (b[3] - b[2]), 0.1 * (b[5] - b[4]))
    moved, union = moved_copy(grid, offset), with_moved_copy(grid, offset)
    prop = data.default_transfer_function(grid)
    camera = _parallel_camera(union, SIZE)
    both = raycast.render_volumes([(grid, prop), (moved, prop)], camera, (SIZE, SIZE))
    whole = raycast.render(union, prop, camera, (SIZE, SIZE))
    assert both[..., 3].max() > 0.2
    np.testing.assert_allclose(both, whole, atol=1e-9)
    clear = data.default_transfer_function(grid)
    clear.GetScalarOpacity().RemoveAllPoints()
    clear.GetScalarOpacity().AddPoint(0.0, 0.0)
    alone = raycast.render(grid, prop, camera, (SIZE, SIZE))
    with_clear = raycast.render_volumes([(grid, prop), (moved, clear)], camera, (SIZE, SIZE))
    np.testing.assert_allclose(with_clear, alone, atol=1e-9)
