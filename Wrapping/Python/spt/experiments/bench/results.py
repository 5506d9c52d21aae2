"""The benchmark's two documents, from a ``bench.json``: ``results.md``, the summary for
readers, dated and naming the machine, each figure with the command that measures it again; and
``bench.md``, its appendix, every table of the run. The sections' own text is in
:mod:`.sections`.

``build/bin/spt-python -m spt report --input out/bench/bench.json --output out/results.md``
writes them without measuring anything (``bench.md`` next to the input); ``--figures`` draws
the figures there again too. A benchmark run writes all of them.
"""

from __future__ import annotations

import datetime
import json
import os
import pathlib
import subprocess
from typing import List

from .plots import plot_results
from .sections import host, models, parallel, race, sweeps, views
from .sections.markdown import BENCH_COMMAND, SPT, Results
from .sections.views import attach

#: The sections in the order of both documents.
SECTIONS = (race.RACE, views.VIEWS, views.CAMERA, sweeps.CELLS, sweeps.LEVELS, models.MODELS,
            models.CROSSOVERS, sweeps.QUALITY, host.HOST, models.LARGE, parallel.PARALLEL)

#: The headings of ``results.md``, in order: each is written whether or not the run measured
#: it (a section that was not measured says how to measure it).
OTHER, APPENDIX = "Figures made outside the benchmark", "Appendix"
HEADINGS = tuple(s.heading for s in SECTIONS) + (OTHER, APPENDIX)
#: The benchmark's figures: file, caption, and the sections whose run draws it again.
FIGURES = {name: spec for s in SECTIONS for name, spec in s.figures.items()}
REPORT_COMMAND = SPT + " report --input {input} --output {output}"
OTHER_FIGURES = (
    ("convergence against the exact reference per repetition level",
     "figures convergence --output out/convergence"),
    ("the influence of visibility sorting, with difference images",
     "figures sorting --output out/sorting"),
    ("PBVR against SPT", "figures pbvr --output out/pbvr"),
    ("the sampling modes' error against time", "figures sampling --output out/sampling"),
    ("the accuracy of the Monte Carlo estimate", "figures accuracy --output out/accuracy"),
    ("the demo: sorted rendering where it fails, and a large mesh", "demo"),
)


def measured_date(path: pathlib.Path, results: Results) -> str:
    """The day the results were measured: recorded in the run, else the day the file was
    last committed, else the day it was written."""
    if results.get("date"):
        return str(results["date"])[:10]
    try:
        done = subprocess.run(["git", "log", "-1", "--format=%cs", "--", path.name],
                              cwd=path.parent, capture_output=True, text=True, check=False,
                              timeout=30)
        if done.returncode == 0 and done.stdout.strip():
            return done.stdout.strip()
    except (OSError, subprocess.SubprocessError):
        pass
    stamp = path.stat().st_mtime
    return datetime.datetime.fromtimestamp(stamp, datetime.timezone.utc).date().isoformat()


def software(machine: str) -> bool:
    """Whether the machine's OpenGL renderer is a software rasterizer."""
    return any(name in machine.lower() for name in ("llvmpipe", "softpipe", "swiftshader"))


def header(results: Results, date: str, command: str) -> List[str]:
    return ["# Results", "",
            f"Measured in runs up to {date} on {results['machine']}"
            + (": a software rasterizer, no GPU. " if software(results["machine"]) else ". ")
            + "Times vary with the machine's load, so every comparison is a ratio taken within "
            "one process. Errors are RMSE of premultiplied RGBA against the exact reference "
            "(`spt.raycast`) over the volume's footprint.", "",
            f"This page is generated from the benchmark's `bench.json` by `{command}`. A full "
            f"benchmark run (`{SPT} bench --output out/bench`) measures everything "
            "again and writes `bench.json`, the figures, the full tables and this page; "
            "`--sections` measures part of it (each figure names its sections), keeping the "
            "rest of an earlier `bench.json` in the same folder.", ""]


def compose(results: Results, date: str, command: str, folder: str, appendix: str) -> str:
    """The Markdown text of ``results.md``."""
    lines = header(results, date, command)
    for section in SECTIONS:
        lines += [f"## {section.heading}", ""] + (
            section.lines(results, folder)
            or ["This run did not measure it. Measure it with "
                f"`{BENCH_COMMAND.format(sections=section.measure)}`.", ""])
    lines += [f"## {OTHER}", "",
              "Not part of `bench.json`; each command writes its images, a table and a plot:",
              ""] + [f"- {what}: `{SPT} {command}`" for what, command in OTHER_FIGURES] + [""]
    lines += [f"## {APPENDIX}", "",
              f"Every measurement of the run, table by table: [{appendix}]({appendix}).", ""]
    text = "\n".join(line.rstrip(" ") for line in lines)
    while "\n\n\n" in text:
        text = text.replace("\n\n\n", "\n\n")
    return text


def compose_full(results: Results) -> str:
    """The Markdown text of ``bench.md``."""
    lines = ["# SPT benchmark", "",
             f"Machine: {results['machine']}. Sweep times are medians of {results['frames']} "
             "frames after a warm-up frame, with the GPU finished; every ratio is taken within "
             "one run of its section (of its scene in the race). Generated meshes: "
             + results["shape"] + ".", ""]
    for section in SECTIONS:
        lines += section.lines(results)
    return "\n".join(lines)


def load(path: pathlib.Path) -> Results:
    """A ``bench.json``, with the files of views measured apart next to it, if there are
    any (:func:`.sections.views.attach`)."""
    try:
        results = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as error:
        raise ValueError(f"cannot read the benchmark results {path}: {error}") from None
    missing = [k for k in ("machine", "entries", "settings") if k not in results]
    if missing:
        raise ValueError(f"{path} is not a benchmark's bench.json: no {', '.join(missing)}")
    return attach(results, path)


def _relative(path: pathlib.Path, start: pathlib.Path) -> str:
    return pathlib.Path(os.path.relpath(path.resolve(), start.resolve())).as_posix()


def write_results(source: pathlib.Path, output: pathlib.Path, figures: bool = False) -> str:
    """Write ``output`` (results.md) and the appendix ``bench.md`` next to ``source``, from
    the run in ``source`` (bench.json), and with ``figures`` the figures there too; returns
    the text of ``output``."""
    results = load(source)
    (source.parent / "bench.md").write_text(compose_full(results), encoding="utf-8")
    if figures:
        plot_results(results, source.parent)
    folder = _relative(source.parent, output.parent)
    folder = "" if folder == "." else folder + "/"
    command = REPORT_COMMAND.format(input=_relative(source, pathlib.Path.cwd()),
                                    output=_relative(output, pathlib.Path.cwd()))
    text = compose(results, measured_date(source, results), command, folder,
                   folder + "bench.md")
    output.write_text(text, encoding="utf-8")
    return text


__all__ = ["FIGURES", "HEADINGS", "compose", "compose_full", "load", "measured_date",
           "write_results"]
