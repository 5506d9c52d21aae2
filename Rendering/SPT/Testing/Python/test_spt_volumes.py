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

from functools import lru_cache

import numpy as np
import pytest

import scene_support
from spt import metrics, render, scenes
from vtkmodules.vtkRenderingCore import vtkVolume, vtkVolumeProperty

import image_statistics
from spt_pytest_fixtures import load_or_skip

SIZE = 128
REPETITIONS = 32
SCENES = ("default", "spx")


@lru_cache(maxsize=None)
def _scene(name):
    if name != "default":
        load_or_skip(name)
    return scenes.scene(name)


def _offset(grid):
    b = grid.GetBounds()
    return (0.35 * (b[1] - b[0]), 0.2 * (b[3] - b[2]), 0.1 * (b[5] - b[4]))


@lru_cache(maxsize=None)
def _union(name):
    s = _scene(name)
    return scene_support.with_moved_copy(s.grid, _offset(s.grid))


@lru_cache(maxsize=None)
def _reference(name):
    s = _scene(name)
    return render.reference(_union(name), s.property, s.view, (SIZE, SIZE)).image


def _two_volumes(name, make, second_property=None, second_first=False):
    """The scene's mesh twice: as it is, and moved by the second volume's own transform."""
    s = _scene(name)
    window, renderer = render.make_window(SIZE, SIZE)
    first = vtkVolume()
    first.SetMapper(make())
    first.GetMapper().SetInputData(s.grid)
    first.SetProperty(s.property)
    second = vtkVolume()
    second.SetMapper(make())
    second.GetMapper().SetInputData(s.grid)
    second.SetProperty(second_property or s.property)
    second.SetPosition(*_offset(s.grid))
    for volume in ((second, first) if second_first else (first, second)):
        renderer.AddVolume(volume)
    render.place_camera(renderer, _union(name).GetBounds(), s.view)
    window.Render()
    image = render.read_rgba(window)
    window.Finalize()
    return image


def _spt():
    return render.spt_mapper(REPETITIONS, seed=1)


@pytest.mark.parametrize("name", SCENES)
def test_two_volumes_composite_as_their_union(name, have_display):
    reference = _reference(name)
    two = _two_volumes(name, _spt)
    assert two[..., 3].max() > 0.2, "the image is (almost) empty"
    s = _scene(name)
    one = render.render(_union(name), s.property, _spt(), s.view, (SIZE, SIZE)).image
    # The noise of one render at this count, from two seeds of the union drawn as one grid.
    second_seed = render.render(_union(name), s.property, render.spt_mapper(REPETITIONS, seed=2),
                                s.view, (SIZE, SIZE)).image
    noise = image_statistics.estimate(one, second_seed, reference, REPETITIONS)
    one_error, two_error = metrics.rmse(one, reference), metrics.rmse(two, reference)
    assert two_error <= one_error + 4.0 * np.sqrt(noise.noise), (
        f"two volumes {two_error:.4f}, one grid {one_error:.4f}")
    sorted_one_by_one = metrics.rmse(
        _two_volumes(name, render.projected_tetrahedra_mapper), reference)
    assert two_error < 0.5 * sorted_one_by_one, (
        f"SPT {two_error:.4f}, VTK PT with two volumes {sorted_one_by_one:.4f}")


def test_two_volumes_with_depth_slabs_composite_as_their_union(have_display):
    """The slabs split the depth range of both volumes' bounds: two volumes with slabs draw
    the image of their union drawn as one grid with slabs, to within the noise."""
    name = "default"
    reference = _reference(name)

    def slabs(seed=1):
        return render.spt_mapper(REPETITIONS, seed=seed, depth_slabs=8)

    two = _two_volumes(name, slabs)
    s = _scene(name)
    one = render.render(_union(name), s.property, slabs(), s.view, (SIZE, SIZE)).image
    second_seed = render.render(_union(name), s.property, slabs(2), s.view, (SIZE, SIZE)).image
    noise = image_statistics.estimate(one, second_seed, reference, REPETITIONS)
    one_error, two_error = metrics.rmse(one, reference), metrics.rmse(two, reference)
    assert two[..., 3].max() > 0.2, "the image is (almost) empty"
    assert two_error <= one_error + 4.0 * np.sqrt(noise.noise), (
        f"two volumes {two_error:.4f}, one grid {one_error:.4f}")


def test_one_repetition_per_pass_draws_the_groups_image(have_display):
    """Two interpenetrating volumes, one repetition per pass (each survivor found by the depth
    test over both) against groups (found from depth keys): the same image."""
    name = SCENES[0]
    one = _two_volumes(name, lambda: render.spt_mapper(4, seed=1, per_pass=1))
    groups = _two_volumes(name, lambda: render.spt_mapper(4, seed=1, per_pass=16))
    assert one[..., 3].max() > 0.2, "the image is (almost) empty"
    assert np.abs(one - groups).max() <= 1.0 / 255.0 + 1e-6


def test_each_volume_keeps_its_transfer_function(have_display):
    s = _scene("default")
    transparent = vtkVolumeProperty()
    transparent.DeepCopy(s.property)
    transparent.GetScalarOpacity().RemoveAllPoints()
    transparent.GetScalarOpacity().AddPoint(-1.0e30, 0.0)
    transparent.GetScalarOpacity().AddPoint(1.0e30, 0.0)
    alone = render.render(s.grid, s.property, _spt(), s.view, (SIZE, SIZE)).image
    window, renderer = render.make_window(SIZE, SIZE)
    render.add_volume(renderer, s.grid, s.property, _spt())
    render.add_volume(renderer, s.grid, transparent, _spt())
    render.place_camera(renderer, s.grid.GetBounds(), s.view)
    window.Render()
    both = render.read_rgba(window)
    window.Finalize()
    assert alone[..., 3].max() > 0.2
    assert np.abs(both - alone).max() <= 1.0 / 255.0 + 1e-6


def test_the_order_of_the_volumes_does_not_matter(have_display):
    forward = _two_volumes("default", _spt)
    backward = _two_volumes("default", _spt, second_first=True)
    # The same segments and random numbers per cell; only the cell ids' offsets swap.
    assert metrics.rmse(forward, backward) <= 0.01
    assert forward[..., 3].max() > 0.2


def test_one_mapper_drawn_by_two_volumes_draws_each_once(have_display):
    """A mapper holds one mesh, table and set of matrices: two vtkVolumes that share it are
    drawn one frame each, side by side here, each exactly as when it is the only one shown,
    with one warning."""
    from robustness_support import watch
    s = _scene("default")
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
