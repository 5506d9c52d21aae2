"""The side-by-side comparison's arithmetic (Utilities/BenchCompare) on made-up races: each
run's ratio as the race's own summary gives it, the medians, the head's over the base's, the
spread, "not reached", the table, the order of the runs, the check that a run loaded only its
own build's libraries, and a new base's fresh sources and build. No timing is asserted; nothing
here builds or races."""

import json
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

import spt
from spt.experiments.bench import race

TOOL = pathlib.Path(__file__).resolve().parents[3] / "Utilities" / "BenchCompare"
sys.path.insert(0, str(TOOL))

import bench_compare  # noqa: E402
import comparison  # noqa: E402
from test_race import race_row  # noqa: E402

PT_SECONDS = 0.1
PT_RMSE = 0.01


def bench_json(ratios, size=256):
    """A bench.json whose race gives SPT the ratio ``ratios[scene]`` at L = 2 (None: SPT
    never reaches VTK PT's error), summarized by the race's own code."""
    rows = []
    for scene, ratio in ratios.items():
        rows.append(race_row("pt", 1, PT_RMSE, PT_SECONDS, stochastic=False, scene=scene))
        rows.append(race_row("spt", 1, 2 * PT_RMSE, 0.5 * PT_SECONDS, scene=scene))
        reached = ratio is not None
        rows.append(race_row("spt", 2, 0.9 * PT_RMSE if reached else 1.5 * PT_RMSE,
                             (ratio or 3.0) * PT_SECONDS, scene=scene))
    return {"race": {"size": size, "rows": rows, "summary": race.summarize(rows)}}


def run_record(side, index, ratios, load=1.0):
    bench = comparison.race_of(bench_json(ratios), list(ratios), 256)
    return {"side": side, "index": index, "load_average": [load, load, load],
            "scenes": {name: comparison.scene_figures(bench, name) for name in ratios}}


def compared(head, base):
    """The comparison of head and base runs, given each run's ratio on one scene "s", made
    in alternation."""
    runs = []
    for index in range(max(len(head), len(base))):
        if index < len(head):
            runs.append(run_record("head", index + 1, {"s": head[index]}, load=1.0 + index))
        if index < len(base):
            runs.append(run_record("base", index + 1, {"s": base[index]}, load=2.0))
    return comparison.comparison(runs, ["s"], {"head": "h" * 8, "base": "b" * 8}, {})


def test_each_run_takes_the_ratio_and_level_the_race_reports():
    figures = run_record("head", 1, {"s": 1.7})["scenes"]["s"]
    assert figures["ratios"]["spt"] == {"ratio": pytest.approx(1.7), "repetitions": 2}
    assert figures["pt_seconds"] == PT_SECONDS and figures["pt_rmse"] == PT_RMSE
    assert [(r["method"], r["repetitions"]) for r in figures["rows"]] == [
        ("pt", 1), ("spt", 1), ("spt", 2)]


def test_head_over_base_is_the_ratio_of_the_medians():
    result = compared([1.2, 1.6, 1.3], [2.0, 2.4])["scenes"]["s"]
    assert result["head_ratios"] == pytest.approx([1.2, 1.6, 1.3])
    assert result["head_median"] == pytest.approx(1.3)   # odd count: the middle run
    assert result["base_median"] == pytest.approx(2.2)   # even count: the mean of the middle
    assert result["head_over_base"] == pytest.approx(1.3 / 2.2)
    assert result["head_spread"] == pytest.approx(1.6 / 1.2 - 1)
    assert result["base_spread"] == pytest.approx(2.4 / 2.0 - 1)
    assert result["within_noise"] is False            # 1.6 < 2.0: the ranges are apart
    assert result["head_pt_seconds"] == [PT_SECONDS] * 3
    assert result["methods"]["spt"]["head_over_base"] == result["head_over_base"]


def test_overlapping_runs_are_within_noise():
    result = compared([1.40, 1.55], [1.50, 1.62])["scenes"]["s"]
    assert result["within_noise"] is True
    assert result["head_over_base"] == pytest.approx(1.475 / 1.56)
    assert compared([1.5], [1.5])["scenes"]["s"]["within_noise"] is True


def test_a_run_that_does_not_reach_the_error_leaves_no_median():
    result = compared([1.2, 1.3], [2.0, None])["scenes"]["s"]
    assert result["base_ratios"][1] is None
    assert result["base_median"] is None and result["head_over_base"] is None
    assert result["base_spread"] is None and result["within_noise"] is None
    assert result["head_median"] == pytest.approx(1.25)


def test_the_table_gives_every_run_the_medians_and_the_spread():
    result = compared([1.2, 1.6], [2.0, None])
    text = comparison.table(result)
    (line,) = [line for line in text.splitlines() if line.startswith("| s |")]
    assert "1.20x (L=2), 1.60x (L=2)" in line
    assert "2.00x (L=2), not reached" in line
    assert "| 33 %, - |" in line
    assert "hhhhhhhh" in text and "bbbbbbbb" in text and "1.0 to 2.0" in text
    line = comparison.table(compared([1.2, 1.6], [2.0, 2.4])).splitlines()[2]
    assert "| 0.64 |" in line and "| 33 %, 20 % |" in line and line.endswith("| no |")


def test_a_comparison_needs_both_sides_and_every_scene():
    with pytest.raises(ValueError, match="each side"):
        comparison.comparison([run_record("head", 1, {"s": 1.0})], ["s"], {}, {})
    with pytest.raises(ValueError, match="bluntfin"):
        comparison.race_of(bench_json({"spx": 1.0}), ["spx", "bluntfin"], 256)
    with pytest.raises(ValueError, match="1024 x 1024"):
        comparison.race_of(bench_json({"spx": 1.0}), ["spx"], 1024)


def test_the_runs_alternate():
    assert bench_compare.schedule(3) == [("head", 1), ("base", 1), ("head", 2), ("base", 2),
                                         ("head", 3), ("base", 3)]


def test_a_run_records_the_package_and_libraries_it_loaded(tmp_path):
    package = pathlib.Path(spt.__file__).resolve().parent
    env = dict(os.environ, PYTHONPATH=str(package.parent))
    record = tmp_path / "loaded.json"
    done = subprocess.run([sys.executable, str(TOOL / "run_race.py"), str(record), "--help"],
                          capture_output=True, text=True, env=env, cwd=tmp_path, check=False)
    assert done.returncode == 0, done.stderr
    assert "bench" in done.stdout   # spt's own command line ran
    loaded = json.loads(record.read_text())
    assert loaded["package"] == str(package)
    assert any(os.path.basename(p).startswith("libSPTRenderingSPT") for p in loaded["libraries"])
    assert any(p.startswith(str(package) + os.sep) for p in loaded["libraries"])  # extensions
    # Every file is this build's: under the folder above its libraries and its package.
    build = pathlib.Path(os.path.commonpath([str(package)] + loaded["libraries"]))
    assert build != pathlib.Path("/")
    assert bench_compare.foreign(loaded, build) == []
    assert len(bench_compare.foreign(loaded, tmp_path)) == 1 + len(loaded["libraries"])


@pytest.mark.skipif(shutil.which("git") is None
                    or not (TOOL.parents[1] / ".git").exists(), reason="not a git clone")
def test_a_base_that_names_no_commit_is_refused():
    with pytest.raises(ValueError, match="no-such-reference-anywhere names no commit"):
        bench_compare.commit_of("no-such-reference-anywhere")


@pytest.mark.skipif(shutil.which("git") is None
                    or not (TOOL.parents[1] / ".git").exists(), reason="not a git clone")
def test_a_base_of_another_commit_is_extracted_and_built_again(tmp_path):
    first, second = bench_compare.commit_of("HEAD"), bench_compare.commit_of("HEAD^")
    source = bench_compare.checkout(first, tmp_path)
    assert (source / "CMakeLists.txt").is_file()
    built = tmp_path / "build" / "object.o"
    built.parent.mkdir()
    built.write_text("built from the first commit")
    assert bench_compare.checkout(first, tmp_path) == source and built.exists()  # kept
    bench_compare.checkout(second, tmp_path)
    assert (tmp_path / "src.commit").read_text().strip() == second
    assert not built.exists() and (source / "CMakeLists.txt").is_file()
