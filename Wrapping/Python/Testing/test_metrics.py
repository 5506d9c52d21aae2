"""Tests of spt.metrics on small synthetic images with known answers."""

import math

import numpy as np
import pytest

import spt.metrics as metrics


def _images():
    a = np.zeros((4, 5, 4))
    a[1:3, 1:4] = (0.2, 0.4, 0.6, 0.8)          # 6 covered pixels
    b = a.copy()
    b[1, 1] += (0.1, 0.1, 0.1, 0.1)             # one pixel off by 0.1
    return a, b


def test_footprint():
    a, b = _images()
    mask = metrics.footprint(a, b)
    assert mask.shape == (4, 5)
    assert mask.sum() == 6
    b[0, 0, 3] = 0.5                            # only b covers (0, 0)
    assert metrics.footprint(a, b).sum() == 7
    b[0, 0, 3] = 0.5 / 255.0                    # below the threshold
    assert metrics.footprint(a, b).sum() == 6


def test_errors_known_values():
    a, b = _images()
    # 4 channels x 6 pixels, 4 values differ by 0.1.
    expected = math.sqrt(4 * 0.01 / 24)
    assert metrics.rmse(a, b) == pytest.approx(expected)
    assert metrics.rmse(a, a) == 0.0
    full = np.ones((4, 5), dtype=bool)
    assert metrics.rmse(a, b, full) == pytest.approx(math.sqrt(4 * 0.01 / 80))
    assert metrics.psnr(a, b) == pytest.approx(-20.0 * math.log10(expected))
    assert metrics.psnr(a, a) == math.inf
    assert metrics.fraction_off(a, b) == pytest.approx(1.0 / 6.0)
    assert metrics.fraction_off(a, b, threshold=0.2) == 0.0
    empty = np.zeros((3, 3, 4))
    assert metrics.rmse(empty, empty) == 0.0
    assert metrics.fraction_off(empty, empty) == 0.0
    with pytest.raises(ValueError):
        metrics.rmse(np.zeros((2, 2, 4)), np.zeros((2, 3, 4)))


def test_uint8_and_float_agree():
    a, b = _images()
    a8, b8 = metrics.to_uint8(a), metrics.to_uint8(b)
    assert a8.dtype == np.uint8
    assert metrics.rmse(a8, b8) == pytest.approx(metrics.rmse(a, b), abs=2e-3)


def test_read_back_floor():
    # values spread over the 8-bit steps: the rounding error is uniform in half a step
    rng = np.random.default_rng(2009)
    image = rng.uniform(0.1, 0.9, (64, 64, 4))
    floor = metrics.read_back_floor(image)
    assert floor == pytest.approx(1.0 / 255.0 / math.sqrt(12.0), rel=0.03)
    # rounding to the nearest step is each value's least error: any other 8-bit image of it
    # is further away
    truncated = np.floor(image * 255.0).astype(np.uint8)
    assert metrics.rmse(truncated, image) > 1.5 * floor
    # an image on the 8-bit steps loses nothing
    assert metrics.read_back_floor(metrics.as_float(metrics.to_uint8(image))) == 0.0


def test_difference_image():
    a, b = _images()
    diff = metrics.difference_image(a, b)
    assert diff.shape == (4, 5, 3)
    assert diff.dtype == np.uint8
    assert diff[1, 1].sum() > diff[2, 2].sum()


def test_png_round_trip(tmp_path):
    from vtkmodules.vtkIOImage import vtkPNGReader

    a, _ = _images()
    for image in (a, a[..., :3], metrics.to_uint8(a)):
        path = tmp_path / "image.png"
        metrics.write_png(path, image)
        reader = vtkPNGReader()
        reader.SetFileName(str(path))
        reader.Update()
        back = metrics.from_vtk_image(reader.GetOutput())
        np.testing.assert_array_equal(back, metrics.to_uint8(image))


def test_side_by_side():
    a, b = _images()
    out = metrics.side_by_side([a, b, metrics.difference_image(a, b)],
                               ["a", "b", "diff"], gap=2, label_height=10)
    assert out.dtype == np.uint8
    assert out.shape == (4 + 10 + 4, 3 * 5 + 4 * 2, 3)
