"""SPT works only where its volumes are on screen: a group's depth keys are cleared, sorted
and read in the samples that the projection of the volumes' bounding boxes covers.

The keys outside that footprint keep whatever an earlier frame left there. The tests check
that nothing reads them: a mapper that has just drawn a view filled by the volume draws a view
where the volume is small, off centre and partly outside the view, exactly as a mapper that
draws that view first, bit for bit; two volumes far apart, after views that leave keys under
each of them, the same; and where the view's edges cut the volume, its image is as unbiased
against the exact reference as the centred view's.
"""

import math

import numpy as np
import pytest

import image_statistics
import scene_support
from statistics_checks import BIAS_FLOOR, Z
from spt import raycast, render

SIZE = 192
REPETITIONS = 16


def _volumes(renderer, grid, prop, apart, seed=3):
    """The mesh as one volume in ``renderer``, or as two volumes far apart (the second, of
    seed 4, moved by its own transform): the volumes and the bounds of what they show."""
    bounds = list(grid.GetBounds())
    volumes = [render.add_volume(renderer, grid, prop, render.spt_mapper(REPETITIONS, seed=each))
               for each in ((seed, 4) if apart else (seed,))]
    if apart:
        shift = 3.0 * (bounds[1] - bounds[0])
        volumes[1].SetPosition(shift, 0.0, 0.0)
        bounds[1] += shift
    return volumes, bounds


def _draw(window, renderer, bounds, view, zoom, centre):
    render.place_camera(renderer, bounds, view)
    camera = renderer.GetActiveCamera()
    camera.Zoom(zoom)
    camera.SetWindowCenter(*centre)
    renderer.ResetCameraClippingRange(bounds)
    window.Render()
    return render.read_rgba(window)


def _small_view(apart, first_fills):
    """The image of the small view, after views that leave depth keys where the small view's
    footprint does not reach, where `first_fills`: one filled by the volume; with two volumes,
    the small view with both volumes on the place of the second, then of the first, so that
    each one's pixels hold keys of the same depths as its own."""
    s = scene_support.scene("default")
    window, renderer = render.make_window(SIZE, SIZE)
    volumes, bounds = _volumes(renderer, s.grid, s.property, apart)
    zoom = 0.5 if apart else 0.45
    if first_fills and not apart:
        filled = _draw(window, renderer, s.grid.GetBounds(), s.view, 4.0, (0.0, 0.0))
        assert (filled[..., 3] > 0.0).mean() > 0.9, "the first view is not filled"
    if first_fills and apart:
        places = [volume.GetPosition() for volume in volumes]
        for place in reversed(places):
            for volume in volumes:
                volume.SetPosition(place)
            _draw(window, renderer, bounds, s.view, zoom, (0.0, 0.0))
        for volume, place in zip(volumes, places):
            volume.SetPosition(place)
    # Small, off centre, cut by the view's left and bottom edges where one volume shows.
    centre = (0.0, 0.0) if apart else (0.875, 0.75)
    image = _draw(window, renderer, bounds, s.view, zoom, centre)
    window.Finalize()
    return image


@pytest.mark.parametrize("apart", [False, True], ids=["one off centre", "two apart"])
def test_keys_outside_the_footprint_are_never_read(apart):
    after = _small_view(apart, first_fills=True)
    first = _small_view(apart, first_fills=False)
    covered = (first[..., 3] > 0.0).mean()
    assert 0.005 < covered < 0.5, f"the volumes cover {covered:.3f} of the view"
    if apart:
        half = SIZE // 2
        for side, part in (("left", first[:, :half]), ("right", first[:, half:])):
            assert part[..., 3].max() > 0.2, f"no volume in the view's {side} half"
    assert np.array_equal(after, first), (
        f"max difference {np.abs(after - first).max():.4f} after the views before")


def _unbiased_estimate(centre):
    """Two seeds' images of the small view against the exact reference of the same camera
    (spt.raycast)."""
    s = scene_support.scene("default")
    images = []
    for seed in (3, 5):
        window, renderer = render.make_window(SIZE, SIZE)
        _, bounds = _volumes(renderer, s.grid, s.property, False, seed)
        images.append(_draw(window, renderer, bounds, s.view, 0.45, centre))
        exact = raycast.render(s.grid, s.property, renderer.GetActiveCamera(), (SIZE, SIZE))
        window.Finalize()
    assert images[0][..., 3].max() > 0.2, "the image is (almost) empty"
    return image_statistics.estimate(images[0], images[1], exact, REPETITIONS)


def test_volume_cut_by_the_view_is_unbiased():
    """Where the view's edges cut the volume, and its footprint with it, the image is as
    unbiased against the exact reference as the same view centred."""
    centred, cut = _unbiased_estimate((0.0, 0.0)), _unbiased_estimate((0.875, 0.75))
    tolerance = Z * math.hypot(centred.bias2_error, cut.bias2_error)
    assert cut.bias2 <= centred.bias2 + tolerance, (
        f"bias {cut.bias:.4f}, centred {centred.bias:.4f}")
    assert cut.bias <= BIAS_FLOOR, f"bias {cut.bias:.4f}"
