"""The README's pictures: the race plot's points come from the benchmark's rows, and the
pictures are written as small palette PNGs."""

import numpy as np
import pytest
from PIL import Image

from spt.experiments import readme


def _race():
    rows = [{"scene": "a", "cells": 100, "method": "pt", "stochastic": False, "seconds": 2.0},
            {"scene": "a", "cells": 100, "method": "havs6", "stochastic": False,
             "seconds": 3.0},
            {"scene": "b", "cells": 900, "method": "pt", "stochastic": False, "seconds": 4.0},
            {"scene": "b", "cells": 900, "method": "havs6", "stochastic": False,
             "seconds": 1.0}]
    summary = [{"scene": "a", "method": "spt",
                "reached": {"VTK PT's error": {"repetitions": 4, "ratio": 1.5}}},
               {"scene": "b", "method": "spt",
                "reached": {"VTK PT's error": {"repetitions": 64, "ratio": 0.5}}},
               {"scene": "a", "method": "spt-slabs", "reached": {"VTK PT's error": None}},
               {"scene": "b", "method": "pbvr",
                "reached": {"VTK PT's error": {"repetitions": 1, "ratio": 9.0}}}]
    return {"rows": rows, "summary": summary}


def test_race_curves_are_the_benchmarks_ratios():
    curves = readme.race_curves(_race())
    assert curves["SPT"] == [(100, 1.5, "a"), (900, 0.5, "b")]
    assert curves["SPT, 8 depth slabs"] == []  # not reached: no point
    havs = curves[readme.HAVS_LABEL]
    assert havs == [(100, pytest.approx(1.5), "a"), (900, pytest.approx(0.25), "b")]
    assert not any(9.0 in point for points in curves.values() for point in points)


def test_small_png_keeps_the_picture_in_a_palette(tmp_path):
    rng = np.random.default_rng(0)
    image = (rng.random((64, 96, 3)) * 255).astype(np.uint8)
    image[:32] = (200, 30, 40)
    path = tmp_path / "picture.png"
    readme.write_small_png(path, image, colors=16)
    with Image.open(path) as written:
        assert written.mode == "P" and written.size == (96, 64)
        rgb = np.asarray(written.convert("RGB"))
    assert len(np.unique(rgb.reshape(-1, 3), axis=0)) <= 16
    assert np.abs(rgb[:32].astype(int) - (200, 30, 40)).max() <= 8
