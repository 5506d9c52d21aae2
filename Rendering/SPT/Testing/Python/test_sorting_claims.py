"""The claims of the sorting figure (python3 -m spt figures sorting), checked at 128 x 128.

SPT's RMSE at a repetition level it is not rendered at is predicted from two renders with
different seeds at a low level (image_statistics: bias^2 + noise x L / level); renders at 1024
repetitions measured 2 % (torus) and 12 % (default mesh) below the prediction.

- Where the centroid sort is far from the per-pixel order, the sorted renderer shows
  artifacts and SPT does not: on Blunt Fin, whose thin boundary-layer cells reach the pixels
  up to 27 places out of order, HAVS-like with k = 6 is several times farther from the
  reference than SPT at the figure's 144 repetitions.
- The issue's claim, that on the torus and on the default (non-convex) mesh SPT at 1024
  repetitions is closer to the reference than HAVS-like with k = 2 and than VTK's projected
  tetrahedra, measured against the exact reference with the mapper as users get it (the
  visibility estimator with exact coverage, stratified, 16 repetitions per pass). With the
  paper's survivor estimator (stratified) it held only against HAVS-like k = 2 on the torus:
  its noise at 1024 repetitions (0.0053 on the default mesh) was above the sorted methods'
  error there (HAVS-like k = 2 0.0042, VTK PT 0.0036).
"""

from functools import lru_cache

import pytest

from spt import metrics, render

import image_statistics
from scene_support import reference, scene

SIZE = (128, 128)


@lru_cache(maxsize=None)
def _rmse(name, method):
    s = scene(name)
    mapper = {"havs2": lambda: render.havs_mapper(2), "havs6": lambda: render.havs_mapper(6),
              "pt": render.projected_tetrahedra_mapper}[method]()
    return metrics.rmse(render.render(s.grid, s.property, mapper, s.view, SIZE).image,
                        reference(name, SIZE[0]))


@lru_cache(maxsize=None)
def _spt_estimate(name, level):
    s = scene(name)
    first, second = (render.render(s.grid, s.property,
                                   render.spt_mapper(level, seed=seed, **render.PAPER_SAMPLING),
                                   s.view, SIZE, frames=0).image for seed in (1, 2))
    return image_statistics.estimate(first, second, reference(name, SIZE[0]), level)


def test_sorting_artifacts_on_thin_cells_that_spt_does_not_have(have_display):
    """Blunt Fin: measured HAVS-like k=6 0.083 and SPT (144) 0.026 at 256 x 256."""
    spt_144 = _spt_estimate("bluntfin", 16).predicted_rmse(144)
    havs = _rmse("bluntfin", "havs6")
    assert havs > 2.0 * spt_144, f"HAVS-like k=6 {havs:.4f}, SPT at 144 {spt_144:.4f}"
    assert _rmse("bluntfin", "havs2") > havs, "k = 2 repairs less of the order than k = 6"


CLAIMS = [("torus", "havs2"), ("torus", "pt"), ("default", "havs2"), ("default", "pt")]


@lru_cache(maxsize=None)
def _spt_1024_rmse(name):
    s = scene(name)
    spt = render.render(s.grid, s.property, render.spt_mapper(1024, seed=3), s.view,
                        SIZE, frames=0).image
    return metrics.rmse(spt, reference(name, SIZE[0]))


@pytest.mark.parametrize("name, method", CLAIMS)
def test_spt_at_1024_repetitions_is_closer_than_sorted_methods(name, method, have_display):
    measured = _spt_1024_rmse(name)
    other = _rmse(name, method)
    assert measured < other, f"SPT at 1024 {measured:.4f}, {method} {other:.4f}"
