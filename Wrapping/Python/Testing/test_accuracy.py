"""Tests of spt.experiments.accuracy: the stochastic estimator is unbiased and its
error falls like 1/sqrt(L)."""

import numpy as np
import pytest

import spt.experiments.accuracy as accuracy


def test_exact_brightness_known_values():
    alpha = np.array([[0.5, 0.5], [1.0, 0.3], [0.0, 0.0]])
    color = np.array([[1.0, 1.0], [0.2, 0.9], [1.0, 1.0]])
    expected = [0.5 + 0.5 * 0.5, 0.2, 0.0]
    np.testing.assert_allclose(
        accuracy.exact_brightness(alpha, color), expected)


def test_opaque_first_segment_is_exact():
    rng = np.random.default_rng(1)
    alpha = np.array([[1.0, 0.7, 0.2]])
    color = np.array([[0.35, 0.9, 0.1]])
    estimate = accuracy.stochastic_brightness(alpha, color, 64, rng)
    np.testing.assert_allclose(estimate, [0.35])


def test_chunked_walk_matches_shape():
    rng = np.random.default_rng(3)
    alpha, color = accuracy.random_rays(5, 7, 0.4, rng)
    estimate = accuracy.stochastic_brightness(alpha, color, 3, rng)
    assert estimate.shape == (5,)
    assert np.all((estimate >= 0.0) & (estimate <= 1.0))


def test_estimator_is_unbiased():
    result = accuracy.check_unbiased(n_segments=16, repetitions=4,
                                     n_trials=20000, n_rays=8, seed=11)
    # Within 4 standard errors of the exact brightness, for every ray.
    assert result["max_abs_z"] < 4.0
    tolerance = 4.0 * result["stderr"]
    assert np.all(np.abs(result["mean"] - result["exact"]) < tolerance)


def test_error_slope_is_minus_one_half():
    result = accuracy.run(n_segments=16, levels=[2 ** k for k in range(10)],
                          n_rays=800, seed=5)
    assert result["slope"] == pytest.approx(-0.5, abs=0.05)
    assert np.all(np.diff(result["error"]) < 0.0)


def test_run_is_deterministic_and_plots_a_png(tmp_path):
    first = accuracy.run(n_segments=8, levels=(1, 4, 16), n_rays=50, seed=9)
    second = accuracy.run(n_segments=8, levels=(1, 4, 16), n_rays=50, seed=9)
    np.testing.assert_array_equal(first["error"], second["error"])
    path = tmp_path / "accuracy.png"
    accuracy.plot(first, path)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
