"""The race's bookkeeping on made-up rows (time to an error, "not reached", the summary, the
merge of races run scene by scene), and one small race on the embedded default scene. No
timing is asserted: the race reports speed, tests check that it is measured and accounted
for."""

import math

import numpy as np
import pytest

from spt.experiments.bench import race
from spt.experiments.bench.sections import race as race_section
from spt.experiments.bench.settings import Settings
from spt.progress import Progress


ROWS = [(1, 0.040, 0.10), (2, 0.020, 0.12), (4, 0.011, 0.15), (8, 0.006, 0.22),
        (16, 0.004, 0.35)]


@pytest.mark.parametrize("rows, target, expected", [
    (ROWS, 0.020, (2, 0.12)),  # exactly at the target counts
    (ROWS, 0.019, (4, 0.15)), (ROWS, 0.5, (1, 0.10)), (ROWS[::-1], 0.005, (16, 0.35)),
    (ROWS, 0.002, None), ([], 0.1, None)])  # None: not reached
def test_time_to_error_takes_the_smallest_level_at_or_below_the_target(rows, target, expected):
    assert race.time_to_error(rows, target) == expected


def test_levels_double_up_to_the_cap():
    assert race.levels(1) == [1]
    assert race.levels(20) == [1, 2, 4, 8, 16]
    assert race.levels(64)[-1] == 64


def race_row(method, level, rmse, seconds, stochastic=True, floor=0.00113, scene="s"):
    return {"scene": scene, "method": method, "label": method, "stochastic": stochastic,
            "repetitions": level, "rmse": rmse, "seconds": seconds, "cpu_seconds": seconds,
            "host_seconds": level * 1e-3, "read_back_floor": floor}


def test_summary_as_multiples_of_vtk_pt():
    rows = [race_row("pt", 1, 0.011, 0.05, False), race_row("havs6", 1, 0.004, 0.5, False)]
    rows += [race_row("spt", level, rmse, seconds) for level, rmse, seconds in ROWS]
    (summary,) = race.summarize(rows)
    reached = summary["reached"]
    assert reached["VTK PT's error"] == {"repetitions": 4, "ratio": pytest.approx(3.0)}
    assert reached["HAVS-like k=6's error"] == {"repetitions": 16, "ratio": pytest.approx(7.0)}
    assert reached["RMSE 0.005"]["repetitions"] == 16
    assert reached["RMSE 0.002"] is None
    # host time where VTK PT's error is reached
    assert summary["host_repetitions"] == 4 and summary["host_seconds"] == pytest.approx(4e-3)


def test_the_report_gives_each_scenes_read_back_floor_where_it_was_recorded():
    result = _race(["spx", "torus"], [race_row("pt", 1, 0.01, 0.1, False, floor=0.0011),
                                      race_row("spt", 1, 0.005, 0.2, floor=0.0011)])
    text = "\n".join(race_section.race_full(result))
    assert "rounded to 8 bits: spx 0.0011, torus 0.0011." in text
    # rows of a race measured before the floor was recorded
    for row in result["rows"]:
        del row["read_back_floor"]
    assert "rounded to 8 bits" not in "\n".join(race_section.race_full(result))


def test_summary_when_vtk_pt_is_never_reached_reports_the_largest_level():
    rows = [race_row("pt", 1, 0.001, 0.05, False), race_row("pbvr", 1, 0.1, 0.1),
            race_row("pbvr", 2, 0.08, 0.2)]
    (summary,) = race.summarize(rows)
    assert summary["reached"]["VTK PT's error"] is None
    assert summary["host_repetitions"] == 2


def _race(scenes, rows_per_scene=None, **changes):
    rows = []
    for scene in scenes:
        for row in rows_per_scene or [race_row("pt", 1, 0.01, 0.1, False),
                                      race_row("spt", 1, 0.005, 0.2)]:
            rows.append(dict(row, scene=scene))
    result = {"size": 256, "azimuth": race.AZIMUTH, "elevation": race.ELEVATION,
              "frames": race.FRAMES, "max_repetitions": 256, "host_source": "perf",
              "rows": rows, "summary": race.summarize(rows)}
    result.update(changes)
    return result


def test_a_race_of_some_scenes_keeps_the_other_scenes_of_the_earlier_race():
    earlier = _race(["spx", "torus", "drill-1M"])
    later = _race(["drill-3M", "torus"], [race_row("pt", 1, 0.02, 0.3, False),
                                          race_row("spt", 1, 0.01, 0.6)])
    merged = race.merge_runs(later, earlier)
    # the race's order of scenes; torus's rows are the later run's only
    assert [row["scene"] for row in merged["rows"]] == [
        "spx", "spx", "torus", "torus", "drill-1M", "drill-1M", "drill-3M", "drill-3M"]
    torus = [row for row in merged["rows"] if row["scene"] == "torus"]
    assert [row["seconds"] for row in torus] == [0.3, 0.6]
    assert [s["scene"] for s in merged["summary"]] == ["spx", "torus", "drill-1M", "drill-3M"]
    torus_summary = next(s for s in merged["summary"] if s["scene"] == "torus")
    assert torus_summary["reached"]["VTK PT's error"]["ratio"] == pytest.approx(2.0)
    assert merged["runs"] == [{"scenes": ["spx", "drill-1M"]}, {"scenes": ["torus", "drill-3M"]}]
    # a third run that races spx again leaves drill-1M as the first run's only scene
    again = race.merge_runs(_race(["spx"]), merged)
    assert again["runs"] == [{"scenes": ["spx"]}, {"scenes": ["torus", "drill-3M"]},
                             {"scenes": ["drill-1M"]}]
    assert len(again["rows"]) == 8


@pytest.mark.parametrize("key, value", [("size", 128), ("frames", 3), ("max_repetitions", 64),
                                        ("host_source", "thread_time")])
def test_an_earlier_race_measured_otherwise_is_dropped(key, value):
    earlier = _race(["spx", "torus"], **{key: value})
    merged = race.merge_runs(_race(["drill-3M"]), earlier)
    assert {row["scene"] for row in merged["rows"]} == {"drill-3M"}
    assert merged["runs"] == [{"scenes": ["drill-3M"]}]
    assert race.merge_runs(_race(["drill-3M"]), None)["runs"] == [{"scenes": ["drill-3M"]}]


def test_a_small_race_on_the_default_scene(tmp_path):
    settings = Settings(race_scenes=("default",), race_size=48, race_max_repetitions=2)
    progress = Progress(race.steps(settings), "race", stream=None)
    result = race.race(settings, progress, tmp_path)
    rows = result["rows"]
    methods = {row["method"] for row in rows}
    assert {"pt", "havs2", "havs3", "havs4", "havs5", "havs6", "spt", "spt-paper-sampling",
            "spt-slabs", "pbvr"} <= methods
    assert result["host_source"] in ("perf", "thread_time")
    floor = rows[0]["read_back_floor"]
    assert 0.0005 < floor < 0.002  # about 1 / 255 / sqrt(12)
    for row in rows:
        assert 0.0 <= row["rmse"] < 0.5 and row["seconds"] > 0.0, row
        # every image is read back through 8 bits: no error is below the exact image's own
        assert row["read_back_floor"] == floor and row["rmse"] >= floor, row
        assert math.isfinite(row["host_seconds"]) and row["host_seconds"] >= 0.0, row
        # the objects named are a part of the host time
        assert sum(row["host_objects"].values()) <= row["host_seconds"] + 1e-9, row
    # SPT converges: its error at the largest level measured is below its error at L=1
    spt = sorted((r for r in rows if r["method"] == "spt"), key=lambda r: r["repetitions"])
    assert spt[-1]["rmse"] < spt[0]["rmse"]
    # the cached reference is what the race compared with, and a second race reads it
    (cached,) = (tmp_path / "references").glob("default-48-*.npy")
    reference = np.load(cached)
    assert reference.shape == (48, 48, 4) and reference[..., 3].max() > 0.1
    again = race.cached_reference(race.race_scene("default"), 48, tmp_path / "references")
    assert np.array_equal(again, reference)
    assert len(result["summary"]) == 4 + 3
    for name in ("spt-target", "spt-target-turned", "spt-slabs-target"):
        target = next(r for r in rows if r["method"] == name)
        assert target["target_error"] == pytest.approx(rows[0]["rmse"])
    assert (tmp_path / "default_pt_1.png").stat().st_size > 100
