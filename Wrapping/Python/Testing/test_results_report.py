"""The results page for readers (``build/bin/spt-python -m spt report``): generated from the
committed benchmark results it has every section and every figure with its command, the
figures are drawn again from them, the committed page is what the generator writes from them,
a run that measured nothing says how to measure each section, the race's findings follow its
rows, and bad input is refused."""

import json
import pathlib
import re
import shutil

import pytest

from spt.experiments.bench import results as report
from spt.experiments.bench.sections import race as race_section

from test_cli import run

DOCUMENTATION = pathlib.Path(__file__).resolve().parents[3] / "Documentation"
BENCH = DOCUMENTATION / "bench" / "bench.json"

needs_committed = pytest.mark.skipif(not BENCH.exists(), reason="no Documentation/bench")


def headings(text):
    return [line[3:] for line in text.splitlines() if line.startswith("## ")]


@needs_committed
def test_the_report_of_the_committed_run_has_every_section_and_figure(tmp_path):
    shutil.copy(BENCH, tmp_path / "bench.json")
    result = run("report", "--input", str(tmp_path / "bench.json"),
                 "--output", str(tmp_path / "results.md"), "--figures")
    assert result.returncode == 0, result.stderr
    text = (tmp_path / "results.md").read_text()
    assert headings(text) == list(report.HEADINGS)
    machine = json.loads(BENCH.read_text())["machine"]
    assert re.search(r"Measured in runs up to \d{4}-\d\d-\d\d on " + re.escape(machine)
                     + ": a software rasterizer, no GPU", text)
    for name, (path, caption, sections) in report.FIGURES.items():
        picture = f"![{caption}]({path})"
        assert picture in text, name
        after = text.split(picture, 1)[1][:400]
        command = f"build/bin/spt-python -m spt bench --sections {sections} --output out/bench"
        assert f"`{command}`" in after
        assert (BENCH.parent / path).exists(), f"{path} is referenced but not committed"
        assert (tmp_path / path).stat().st_size > 10_000, f"{path} not drawn from bench.json"
    assert not re.search(r"\bnan\b|\binf\b", text)
    assert "not measured" not in text and "did not measure" not in text.split("## Cell")[1]
    # the appendix is the benchmark's own table dump, written from the same file
    assert (tmp_path / "bench.md").read_text() == (BENCH.parent / "bench.md").read_text(), \
        "regenerate it: build/bin/spt-python -m spt report"


@needs_committed
def test_the_committed_results_page_is_generated_from_the_committed_run():
    committed = (DOCUMENTATION / "results.md").read_text()
    date = re.search(r"Measured in runs up to (\d{4}-\d\d-\d\d)", committed).group(1)
    command = report.REPORT_COMMAND.format(input="Documentation/bench/bench.json",
                                           output="Documentation/results.md")
    generated = report.compose(report.load(BENCH), date, command, "bench/", "bench/bench.md")
    assert committed == generated, "regenerate it: " + command


def race_rows(scene, cells, pt_seconds, spt):
    rows = [{"scene": scene, "cells": cells, "method": "pt", "rmse": 0.01,
             "seconds": pt_seconds, "read_back_floor": 0.0011},
            {"scene": scene, "cells": cells, "method": "havs6", "rmse": 0.02, "seconds": 1.0}]
    summary = [{"scene": scene, "method": "spt", "label": "SPT",
                "reached": {"VTK PT's error": spt}}]
    return rows, summary


def test_the_race_findings_follow_its_rows():
    small, small_summary = race_rows("small", 1000, 0.1, {"ratio": 2.5, "repetitions": 4})
    large, large_summary = race_rows("large", 10 ** 6, 3.0, {"ratio": 0.6, "repetitions": 64})
    missed, missed_summary = race_rows("missed", 10 ** 5, 1.0, None)
    race = {"size": 64, "azimuth": 35.0, "elevation": 25.0, "frames": 2,
            "max_repetitions": 256, "rows": small + large + missed,
            "summary": small_summary + large_summary + missed_summary}
    text = "\n".join(race_section.summary({"race": race}, "bench/"))
    assert "at most one VTK PT frame on: large (0.6 at L=64)." in text
    assert "longer than VTK PT's frame on small (2.5 at L=4)" in text
    assert "does not reach VTK PT's error by L = 256 on missed" in text
    assert "smaller error than VTK PT on no scene and a larger one on small, large, missed" \
        in text
    table = [line for line in text.splitlines() if line.startswith("| small")]
    assert table and "2.5 (L=4)" in table[0] and "not raced" in table[0]


def test_a_run_that_measured_nothing_says_how_to_measure_each_section(tmp_path):
    source = tmp_path / "bench.json"
    source.write_text(json.dumps({"machine": "a test machine", "entries": [],
                                  "settings": {}, "shape": "drill", "frames": 1,
                                  "date": "2000-01-02"}))
    text = report.write_results(source, tmp_path / "results.md")
    assert headings(text) == list(report.HEADINGS)
    assert "Measured in runs up to 2000-01-02 on a test machine. Times vary" in text
    for section in ("race", "camera", "cells", "quality", "host", "large", "parallel"):
        command = f"build/bin/spt-python -m spt bench --sections {section} --output out/bench"
        assert f"`{command}`" in text
    assert "![" not in text


def test_bad_input_is_refused_with_the_reason(tmp_path):
    missing = run("report", "--input", str(tmp_path / "nosuch.json"),
                  "--output", str(tmp_path / "results.md"))
    assert missing.returncode == 1 and "cannot read the benchmark results" in missing.stderr
    other = tmp_path / "other.json"
    other.write_text(json.dumps({"entries": []}))
    wrong = run("report", "--input", str(other), "--output", str(tmp_path / "results.md"))
    assert wrong.returncode == 1 and "not a benchmark's bench.json: no machine" in wrong.stderr
    assert not (tmp_path / "results.md").exists()
    usage = run("report", "--input")
    assert usage.returncode == 2 and "expected one argument" in usage.stderr
