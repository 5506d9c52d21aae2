"""The image's sample distance: an interactive render that cannot fit even one repetition in
its time draws fewer pixels and interpolates them to the viewport
(AutoAdjustSampleDistances); a still render draws every pixel, as before.

A render at sample distance 2 in a viewport of 2n x 2n pixels draws the image a viewport of
n x n pixels draws (the same projection, the same samples and random numbers), interpolated
bilinearly: the tests compare the two exactly, up to the 8-bit framebuffer's rounding.
"""

import numpy as np
import pytest

from spt import metrics, render

from scene_support import (bilinear_upsampled, opaque_plane, render_at_still_rate, scene,
                           window_with)

SIZE = 128


def _window(mapper, size, plane=False):
    s = scene("default")
    window, renderer = window_with(mapper, size, prop=s.property)
    if plane:
        # Black and unlit, over a black background: the image is the volume's alone, where
        # the plane does not hide it.
        actor = opaque_plane(s.grid)
        actor.GetProperty().SetColor(0.0, 0.0, 0.0)
        actor.GetProperty().LightingOff()
        renderer.AddActor(actor)
    return window


def _still_image(mapper, size, plane=False):
    window = _window(mapper, size, plane)
    render_at_still_rate(window)
    image = render.read_rgba(window)
    window.Finalize()
    return image


def _fixed_distance(mapper, distance):
    mapper.AutoAdjustSampleDistancesOff()
    mapper.SetImageSampleDistance(distance)
    return mapper


def test_a_sample_distance_of_two_draws_the_image_of_half_the_pixels_interpolated(have_display):
    fine = _still_image(_fixed_distance(render.spt_mapper(16, seed=2), 2.0), 2 * SIZE)
    coarse = _still_image(render.spt_mapper(16, seed=2), SIZE)
    assert coarse[..., 3].max() > 0.2, "an empty image"
    difference = np.abs(fine - bilinear_upsampled(coarse, 2))
    # Each image is rounded to 8 bits: the interpolated rounding and the fine image's own.
    assert difference.max() <= 1.0 / 255.0 + 1e-6, f"{difference.max() * 255:.2f} / 255"


def test_the_opaque_scene_hides_the_volume_at_the_pixel_centers(have_display):
    """The opaque scene's depth is read at the center of each image pixel: behind an opaque
    plane, the image at sample distance 2 is that of half the pixels, interpolated, but where
    the plane cuts the volume (there the depth is read half a pixel of the smaller image
    apart)."""
    fine = _still_image(_fixed_distance(render.spt_mapper(16, seed=2), 2.0), 2 * SIZE, True)
    coarse = bilinear_upsampled(_still_image(render.spt_mapper(16, seed=2), SIZE, True), 2)
    without = _still_image(_fixed_distance(render.spt_mapper(16, seed=2), 2.0), 2 * SIZE)
    hidden = np.abs(fine[..., :3] - without[..., :3]).max(axis=-1) > 0.05
    assert hidden.mean() > 0.05, "the plane hides nothing"
    difference = np.abs(fine[..., :3] - coarse[..., :3]).max(axis=-1)
    assert np.median(difference[hidden]) <= 1.0 / 255.0 + 1e-6
    error, hiding = metrics.rmse(fine, coarse), metrics.rmse(fine, without)
    print(f"RMSE {error:.4f} from half the pixels, {hiding:.4f} from the image without the plane")
    assert error < 0.25 * hiding, f"RMSE {error:.4f} against {hiding:.4f}"


def test_interactive_renders_draw_fewer_pixels_and_still_renders_every_pixel(have_display):
    """With a budget of 1 us not even one repetition fits, so the sample distance is its
    maximum from the first interactive render on (planned from the still render's time, not
    drawn at every pixel first); a lower maximum caps it; a still render draws every pixel, the
    image of a mapper that never rendered interactively, bit for bit."""
    mapper = render.spt_mapper(16, seed=4)
    mapper.AutoAdjustRepetitionsOn()
    window = _window(mapper, SIZE)
    render_at_still_rate(window)
    still = render.read_rgba(window)
    assert mapper.GetImageSampleDistance() == 1.0
    window.SetDesiredUpdateRate(1.0e6)
    distances = []
    for _ in range(4):
        window.Render()
        distances.append(mapper.GetImageSampleDistance())
        assert render.read_rgba(window)[..., 3].max() > 0.2, "an empty interactive image"
    assert distances == [mapper.GetMaximumImageSampleDistance()] * 4 == [4.0] * 4, distances
    mapper.SetMaximumImageSampleDistance(2.5)
    window.Render()
    assert mapper.GetImageSampleDistance() == 2.5
    render_at_still_rate(window)
    assert mapper.GetImageSampleDistance() == 1.0
    assert mapper.GetLastRepetitionCount() == 16
    assert np.array_equal(render.read_rgba(window), still)
    window.Finalize()


def test_without_the_adjustment_the_distance_is_the_one_set(have_display):
    mapper = _fixed_distance(render.spt_mapper(4, seed=4), 3.0)
    mapper.AutoAdjustRepetitionsOn()
    window = _window(mapper, SIZE)
    render_at_still_rate(window)
    window.SetDesiredUpdateRate(1000.0)
    window.Render()
    window.Render()
    assert mapper.GetImageSampleDistance() == pytest.approx(3.0)
    mapper.SetImageSampleDistance(0.5)
    assert mapper.GetImageSampleDistance() == 1.0, "clamped to every pixel"
    window.Finalize()
