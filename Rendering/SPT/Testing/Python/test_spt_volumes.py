"""Several SPT volumes in one renderer: one ensemble, composited exactly where they overlap.

Two copies of a mesh, the second moved into the first by its vtkVolume's transform, are
rendered as two volumes. Their exact reference is that of the union (both copies appended into
one grid, the second with the transform applied to its points). The tests check that
- two SPT volumes are as close to it as one SPT mapper drawing the union as one grid, and much
  closer than VTK's projected tetrahedra with two volumes, which composites them one after the
  other;
- each volume keeps its own transfer function: a transparent second volume leaves the first
  as it is alone;
- the image is the same whichever of the volumes comes first in the renderer.
"""

import numpy as np
import pytest

from spt import metrics, render
from vtkmodules.vtkRenderingCore import vtkVolumeProperty

import image_statistics
from robustness_support import watch
from scene_support import draw_once, scene, union, union_offset, union_reference, window_with

SIZE = 128
REPETITIONS = 32
SCENES = ("default", "spx")


def _two_volumes(name, make, second_property=None, second_first=False):
    """The scene's mesh twice: as it is, and moved by the second volume's own transform."""
    s = scene(name)
    window, renderer = render.make_window(SIZE, SIZE)
    properties = [s.property, second_property or s.property]
    volumes = {index: render.add_volume(renderer, s.grid, properties[index], make())
               for index in ((1, 0) if second_first else (0, 1))}
    volumes[1].SetPosition(*union_offset(s.grid))
    render.place_camera(renderer, union(name).GetBounds(), s.view)
    return draw_once(window)


def _spt(seed=1):
    return render.spt_mapper(REPETITIONS, seed=seed)


def _check_as_close_as_the_union(name, make):
    """Two volumes through mappers of ``make(seed)`` against their union drawn as one grid
    through the same: no farther from the reference, within 4 x the noise of one render at
    this count (from two seeds of the union). Returns the two volumes' error."""
    reference = union_reference(name, SIZE)
    two = _two_volumes(name, lambda: make(1))
    assert two[..., 3].max() > 0.2, "the image is (almost) empty"
    s = scene(name)
    one, second_seed = (render.render(union(name), s.property, make(seed), s.view,
                                      (SIZE, SIZE)).image for seed in (1, 2))
    noise = image_statistics.estimate(one, second_seed, reference, REPETITIONS)
    one_error, two_error = metrics.rmse(one, reference), metrics.rmse(two, reference)
    assert two_error <= one_error + 4.0 * np.sqrt(noise.noise), (
        f"two volumes {two_error:.4f}, one grid {one_error:.4f}")
    return two_error


@pytest.mark.parametrize("name", SCENES)
def test_two_volumes_composite_as_their_union(name):
    two_error = _check_as_close_as_the_union(name, _spt)
    reference = union_reference(name, SIZE)
    sorted_one_by_one = metrics.rmse(
        _two_volumes(name, render.projected_tetrahedra_mapper), reference)
    assert two_error < 0.5 * sorted_one_by_one, (
        f"SPT {two_error:.4f}, VTK PT with two volumes {sorted_one_by_one:.4f}")


def test_two_volumes_with_depth_slabs_composite_as_their_union():
    """The slabs split the depth range of both volumes' bounds: two volumes with slabs draw
    the image of their union drawn as one grid with slabs, to within the noise."""
    _check_as_close_as_the_union(
        "default", lambda seed: render.spt_mapper(REPETITIONS, seed=seed, depth_slabs=8))


def test_one_repetition_per_pass_draws_the_groups_image():
    """Two interpenetrating volumes, one repetition per pass (each survivor found by the depth
    test over both) against groups (found from depth keys): the same image."""
    name = SCENES[0]
    one = _two_volumes(name, lambda: render.spt_mapper(4, seed=1, per_pass=1))
    groups = _two_volumes(name, lambda: render.spt_mapper(4, seed=1, per_pass=16))
    assert one[..., 3].max() > 0.2, "the image is (almost) empty"
    assert np.abs(one - groups).max() <= 1.0 / 255.0 + 1e-6


def test_each_volume_keeps_its_transfer_function():
    s = scene("default")
    transparent = vtkVolumeProperty()
    transparent.DeepCopy(s.property)
    transparent.GetScalarOpacity().RemoveAllPoints()
    transparent.GetScalarOpacity().AddPoint(-1.0e30, 0.0)
    transparent.GetScalarOpacity().AddPoint(1.0e30, 0.0)
    alone = render.render(s.grid, s.property, _spt(), s.view, (SIZE, SIZE)).image
    window, renderer = window_with(_spt(), SIZE, prop=s.property)
    render.add_volume(renderer, s.grid, transparent, _spt())
    both = draw_once(window)
    assert alone[..., 3].max() > 0.2
    assert np.abs(both - alone).max() <= 1.0 / 255.0 + 1e-6


def test_the_order_of_the_volumes_does_not_matter():
    forward = _two_volumes("default", _spt)
    backward = _two_volumes("default", _spt, second_first=True)
    # The same segments and random numbers per cell; only the cell ids' offsets swap.
    assert metrics.rmse(forward, backward) <= 0.01
    assert forward[..., 3].max() > 0.2


def test_one_mapper_drawn_by_two_volumes_draws_each_once():
    """A mapper holds one mesh, table and set of matrices: two vtkVolumes that share it are
    drawn one frame each, side by side here, each exactly as when it is the only one shown,
    with one warning."""
    s = scene("default")
    b = s.grid.GetBounds()
    mapper = _spt()
    messages = watch(mapper)
    window, renderer = render.make_window(SIZE, SIZE)
    volumes = [render.add_volume(renderer, s.grid, s.property, mapper) for _ in range(2)]
    volumes[1].SetPosition(1.5 * (b[1] - b[0]), 0.0, 0.0)
    renderer.ResetCamera()

    def shown(*visible):
        for volume, on in zip(volumes, visible):
            volume.SetVisibility(on)
        window.Render()
        return render.read_rgba(window)

    first, second = shown(True, False), shown(False, True)
    assert not messages.warnings
    both = shown(True, True)
    window.Finalize()
    assert first[..., 3].max() > 0.2 and second[..., 3].max() > 0.2
    assert not np.any((first[..., 3] > 0) & (second[..., 3] > 0)), "the volumes overlap"
    assert np.abs(both - (first + second)).max() <= 1.0 / 255.0 + 1e-6
    assert len(messages.warnings) == 1 and "drawn by 2 volumes" in messages.warnings[0]
