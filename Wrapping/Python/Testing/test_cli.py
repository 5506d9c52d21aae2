"""python3 -m spt: the demo and the figures run, and bad arguments are refused clearly."""

import json
import os
import pathlib
import re
import subprocess
import sys

import pytest

import spt


def environment(**overrides):
    """This process's environment, with the spt package under test first on the path."""
    env = os.environ.copy()
    package_parent = str(pathlib.Path(spt.__file__).resolve().parent.parent)
    env["PYTHONPATH"] = os.pathsep.join([package_parent, env.get("PYTHONPATH", "")])
    env.update(overrides)
    return env


def run(*arguments, cwd=None, **overrides):
    return subprocess.run([sys.executable, "-m", "spt", *arguments], cwd=cwd,
                          capture_output=True, text=True, env=environment(**overrides),
                          check=False)


def test_help():
    result = run("--help")
    assert result.returncode == 0
    assert "demo" in result.stdout and "figures" in result.stdout


# Every subcommand and every argument: a bad value is refused with a message that names it,
# and exit status 2 (argparse's), before anything is rendered.
BAD_ARGUMENTS = [
    ((), "required"),
    (("nosuch",), "invalid choice"),
    (("demo", "--nosuch"), "unrecognized arguments"),
    (("demo", "--size", "0"), "outside 1..4096"),
    (("demo", "--size", "4097"), "outside 1..4096"),
    (("demo", "--size", "big"), "not a whole number"),
    (("demo", "--repetitions", "-3"), "outside"),
    (("demo", "--repetitions", "65537"), "outside"),
    (("demo", "--dataset", "nosuch"), "unknown data set"),
    (("demo", "--target-error", "0"), "outside 0 (exclusive) .. 1"),
    (("demo", "--target-error", "lots"), "not a number"),
    (("demo", "--dataset", "spx,post"), "give one data set"),
    (("demo", "--pair-cells", "1000"), "outside 20000.."),
    (("demo", "--output"), "expected one argument"),
    (("demo", "--data-dir", "/nonexistent/spt-data"), "is not a directory"),
    (("bench", "--data-dir", "/nonexistent/spt-data"), "is not a directory"),
    (("bench", "--sections", "cells,nosuch"), "unknown section"),
    (("bench", "--sections", ","), "unknown section"),
    (("bench", "--frames", "0"), "outside"),
    (("bench", "--max-cells", "many"), "not a whole number"),
    (("bench", "--shape", "cube"), "invalid choice"),
    (("bench", "--size", "256,x"), "--size"),
    (("bench", "--size", "0"), "--size"),
    (("bench", "--size", ","), "--size"),
    (("figures", "sorting", "--data-dir", "/nonexistent/spt-data"), "is not a directory"),
    (("figures",), "required"),
    (("figures", "nosuch"), "invalid choice"),
    (("figures", "convergence", "--levels", "4,x"), "not a whole number"),
    (("figures", "convergence", "--levels", ","), "at least one repetition level"),
    (("figures", "convergence", "--levels", "0"), "outside"),
    (("figures", "convergence", "--datasets", "spx,nosuch"), "nosuch"),
    (("figures", "convergence", "--datasets", ","), "unknown data set"),
    (("figures", "convergence", "--size", "5000"), "outside 1..4096"),
    (("figures", "pbvr", "--datasets", "nosuch"), "unknown data set"),
    (("figures", "pbvr", "--datasets", "torus"), "unknown data set"),
    (("figures", "pbvr", "--repetitions", "0"), "outside"),
    (("figures", "pbvr", "--levels", "4,,-1"), "outside"),
    (("figures", "pbvr", "--size", "0"), "outside"),
    (("figures", "sampling", "--dataset", "nosuch"), "unknown data set"),
    (("figures", "sampling", "--levels", "0"), "outside"),
    (("figures", "sampling", "--size", "1.5"), "not a whole number"),
    (("figures", "sorting", "--datasets", "nosuch"), "unknown data set"),
    (("figures", "sorting", "--repetitions", "0"), "outside"),
    (("figures", "sorting", "--size", "-1"), "outside"),
    (("figures", "accuracy", "--rays", "0"), "outside 1..1000000"),
    (("figures", "accuracy", "--rays", "many"), "not a whole number"),
    (("figures", "accuracy", "--nosuch"), "unrecognized arguments"),
    (("mesh",), "required: --output"),
    (("mesh", "--output", "m.vtk", "--shape", "cube"), "invalid choice"),
    (("mesh", "--output", "m.vtk", "--cells", "0"), "outside"),
    (("mesh", "--output", "m.vtk", "--cells", "lots"), "not a whole number"),
    (("mesh", "--output", "m.vtk", "--seed", "-1"), "negative"),
] + [(command + ("--output", __file__), "exists and is not a directory")
     for command in [("demo",), ("figures", "convergence"), ("figures", "pbvr"),
                     ("figures", "sampling"), ("figures", "sorting"), ("figures", "accuracy"),
                     ("figures", "readme")]]


@pytest.mark.parametrize("arguments, message", BAD_ARGUMENTS)
def test_bad_arguments_are_refused(arguments, message):
    result = run(*arguments)
    assert result.returncode == 2
    assert message in result.stderr and "Traceback" not in result.stderr


def test_an_output_that_cannot_be_made_is_a_clear_error():
    """/proc takes no new folders, even for root."""
    result = run("figures", "accuracy", "--rays", "10", "--output", "/proc/spt-output")
    assert result.returncode == 1
    assert "/proc/spt-output" in result.stderr and "Traceback" not in result.stderr


def test_accuracy_figure(tmp_path):
    result = run("figures", "accuracy", "--rays", "200", "--output", str(tmp_path))
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "accuracy.png").stat().st_size > 1000
    slope = float(result.stdout.split("slope of the error:")[1].split()[0])
    assert -0.6 < slope < -0.4


def _check_ladder(scene, target):
    """SPT's levels grow fourfold from 1 to the cap and stop at the first whose error is at
    most the goal (VTK PT's error and the target), and the summary is what the rows say."""
    rows = scene["rows"]
    assert [row["method"] for row in rows[:2]] == ["vtk_pt", "havs6"]
    ladder = rows[2:]
    assert ladder and {row["method"] for row in ladder} == {"spt"}
    levels = [row["repetitions"] for row in ladder]
    assert levels == [1, 4, 16][:len(levels)]
    for row in rows:
        assert 0.0 < row["rmse"] < 1.0 and row["seconds"] > 0.0, row
    pt = rows[0]
    goal = min(pt["rmse"], target)
    assert all(row["rmse"] > goal for row in ladder[:-1])
    assert ladder[-1]["rmse"] <= goal or levels[-1] == 16
    summary = scene["summary"]
    assert summary["vtk_pt_rmse"] == pt["rmse"] and summary["vtk_pt_seconds"] == pt["seconds"]
    reached = summary["spt_to_vtk_pt_error"]
    first = next((row for row in ladder if row["rmse"] <= pt["rmse"]), None)
    assert (reached is None) == (first is None)
    if first is not None:
        assert reached["repetitions"] == first["repetitions"]
        assert reached["ratio"] == pytest.approx(first["seconds"] / pt["seconds"])


def test_demo_writes_images_and_the_race(tmp_path):
    """The demo at a small size: its images, and results.json consistent with itself; on
    the interpenetrating volumes, which VTK composites one after the other, SPT's image is far
    closer to the exact one than the sorted renderers'."""
    output = tmp_path / "demo"
    result = run("demo", "--dataset", "default", "--size", "64", "--pair-cells", "20000",
                 "--repetitions", "16", "--output", str(output))
    assert result.returncode == 0, result.stderr
    for scene in ("interpenetrating", "default"):
        for method in ("reference", "vtk_pt", "havs6", "spt"):
            assert (output / f"{scene}_{method}.png").stat().st_size > 100
    for name in ("comparison.png", "race.md", "results.json"):
        assert (output / name).stat().st_size > 100, name
    document = json.loads((output / "results.json").read_text())
    assert "cores" in document["machine"] and document["load_average"]["end"] >= 0.0
    scenes = {scene["scene"]: scene for scene in document["scenes"]}
    assert list(scenes) == ["interpenetrating", "default"]
    assert scenes["interpenetrating"]["volumes"] == 2 and scenes["default"]["volumes"] == 1
    for scene in scenes.values():
        _check_ladder(scene, document["target_error"])
    pair = scenes["interpenetrating"]["rows"]
    spt = min(row["rmse"] for row in pair if row["method"] == "spt")
    assert spt < 0.5 * min(pair[0]["rmse"], pair[1]["rmse"]), pair
    lines = result.stdout.splitlines()
    assert lines[0].split()[0] == "scene" and "SPT to VTK PT's error" in lines[0]
    assert lines[2].startswith("interpenetrating") and lines[3].startswith("default")
    assert "SPT loses" in result.stdout


def test_missing_data_is_a_clear_error(tmp_path):
    result = run("demo", "--dataset", "spx", "--output", str(tmp_path), cwd=tmp_path,
                 SPT_DATA_DIR=str(tmp_path / "nothing"))
    assert result.returncode == 1
    assert "SPT_DATA_DIR" in result.stderr and "Traceback" not in result.stderr


@pytest.mark.parametrize("where", ["SPT_DATA_DIR", "--data-dir"])
def test_a_damaged_data_file_is_a_clear_error(tmp_path, where):
    """A Git LFS pointer in place of a data set, in the folder that the environment or the
    option names (the option wins): the error names the file, no traceback."""
    (tmp_path / "spx.vtk").write_text(
        "version https://git-lfs.github.com/spec/v1\noid sha256:0\nsize 1\n")
    option = ["--data-dir", str(tmp_path)] if where == "--data-dir" else []
    environment_dir = tmp_path if where == "SPT_DATA_DIR" else tmp_path / "elsewhere"
    environment_dir.mkdir(exist_ok=True)
    result = run("demo", "--dataset", "spx", "--output", str(tmp_path / "out"), *option,
                 cwd=tmp_path, SPT_DATA_DIR=str(environment_dir))
    assert result.returncode == 1, result.stderr
    assert str(tmp_path / "spx.vtk") in result.stderr and "Traceback" not in result.stderr


def test_sorting_figure_writes_images_and_a_table(tmp_path):
    """The sorting figure on the default mesh only, tiny and with few repetitions."""
    output = tmp_path / "sorting"
    result = run("figures", "sorting", "--datasets", "default", "--size", "48",
                 "--repetitions", "2", "--output", str(output))
    assert result.returncode == 0, result.stderr
    for key in ("reference", "spt", "havs_k2", "havs_k6", "vtk_pt"):
        assert (output / f"default_{key}.png").stat().st_size > 100, key
        if key != "reference":
            assert (output / f"default_{key}_difference.png").stat().st_size > 100, key
    assert (output / "default_comparison.png").stat().st_size > 1000
    table = (output / "sorting.md").read_text()
    for method in ("SPT L=2", "HAVS-like k=2", "HAVS-like k=6", "VTK PT", "reference"):
        assert method in table and method in result.stdout, method
    rows = [re.split(r"\s{2,}", line.strip()) for line in result.stdout.splitlines()[2:7]]
    havs = next(row for row in rows if row[1] == "HAVS-like k=6")
    assert 0.0 < float(havs[2]) < 0.05 and float(havs[5]) > 0.0 and float(havs[6]) > 0.0


def test_pbvr_figure_writes_images_tables_and_curves(tmp_path):
    output = tmp_path / "pbvr"
    result = run("figures", "pbvr", "--datasets", "default", "--size", "48", "--repetitions", "8",
                 "--levels", "2", "--output", str(output))
    assert result.returncode == 0, result.stderr
    for name in ("default_reference.png", "default_spt_8.png", "default_pbvr_8.png",
                 "default_pbvr_cell_average_8_difference.png", "default_comparison.png",
                 "pbvr.md", "pbvr.json", "pbvr_convergence.md", "pbvr_convergence.png"):
        assert (output / name).stat().st_size > 100, name
    lines = result.stdout.splitlines()
    header = re.split(r"\s{2,}", lines[0].strip())
    rows = {cells[1]: dict(zip(header, cells))
            for cells in (re.split(r"\s{2,}", line.strip()) for line in lines[2:7])}
    assert header[:3] == ["data set", "method", "RMSE"]
    pbvr = rows["PBVR, L=8"]
    assert int(pbvr["particles"]) > 0 and float(pbvr["GPU memory [MiB]"]) > 0.0
    assert float(pbvr["particles / s"]) > 0.0 and 0.0 < float(pbvr["RMSE"]) < 0.5
    assert rows["SPT, L=8"]["particles"] == "-"
    assert rows["SPT, paper's sampling, L=8"]["particles"] == "-"
    convergence = (output / "pbvr_convergence.md").read_text()
    assert "| L=2 | L=8 |" in convergence and "PBVR, cell average" in convergence


def test_the_demos_large_scene_is_the_iron_protein_where_the_data_are(tmp_path, monkeypatch):
    """Where SPT_DATA_DIR says, and nowhere else: not in a shared/data folder above the working
    directory, which a fresh clone's machine may have for reasons of its own."""
    from spt.experiments import demo

    data_sets = tmp_path / "shared" / "data"
    data_sets.mkdir(parents=True)
    work = tmp_path / "clone" / "out"
    work.mkdir(parents=True)
    monkeypatch.chdir(work)
    monkeypatch.setenv("SPT_DATA_DIR", str(data_sets))
    assert demo.default_large_scene() == "drill-1M"
    (data_sets / "ironProt.vtk").write_text("")
    assert demo.default_large_scene() == "ironprot_full"
    monkeypatch.delenv("SPT_DATA_DIR")
    assert demo.default_large_scene() == "drill-1M"
