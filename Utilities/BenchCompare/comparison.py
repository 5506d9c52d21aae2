"""The arithmetic of a side-by-side comparison: each run's race figures, their medians, the
head's ratio over the base's, the run-to-run spread, and the table.

A run's *ratio* on a scene is what the race reports as SPT's time to VTK PT's error: the best
frame of SPT at the smallest repetition level L (1, 2, 4, ...) whose RMSE against the exact
reference is at most VTK PT's RMSE, divided by VTK PT's best frame, both measured in that run's
process. ``head_over_base`` is the median of the head's ratios over the median of the base's:
below 1 the head reaches VTK PT's error in less of VTK PT's time than the base does. Each
side's *spread* is its largest ratio over its smallest, less one; a scene is *within noise*
when the ranges of the two sides' ratios overlap.
"""

from __future__ import annotations

import statistics
from typing import Dict, List, Optional, Sequence

Record = Dict[str, object]

#: The error that the headline ratio is measured at, as the race's summary names it.
TARGET = "VTK PT's error"
#: The method of the headline ratio.
HEADLINE = "spt"
#: What each race row keeps in the comparison's record.
ROW_FIELDS = ("method", "label", "repetitions", "rmse", "seconds", "cpu_seconds")


def race_of(bench: Record, scenes: Sequence[str], size: int) -> Record:
    """The race of ``bench`` (a ``bench.json`` of ``python3 -m spt bench --sections race``)
    at ``size``, checked to hold every scene of ``scenes``."""
    races = [bench.get("race")] + list(bench.get("race_sizes") or [])
    found = next((r for r in races if r and int(r.get("size", -1)) == size), None)
    if found is None:
        raise ValueError(f"the benchmark's results hold no race at {size} x {size}")
    raced = {row["scene"] for row in found.get("rows", [])}
    missing = [name for name in scenes if name not in raced]
    if missing:
        raise ValueError(f"the race did not run the scene(s) {', '.join(missing)}")
    return found


def scene_figures(race: Record, scene: str) -> Record:
    """One scene of one run: every row's figures, VTK PT's frame, and each stochastic
    method's ratio at VTK PT's error with the L it took (None where it was not reached)."""
    rows = [{key: row.get(key) for key in ROW_FIELDS}
            for row in race["rows"] if row["scene"] == scene]
    pt = next((row for row in rows if row["method"] == "pt"), None)
    if pt is None:
        raise ValueError(f"the race of {scene} has no VTK PT row")
    ratios: Dict[str, Optional[Record]] = {}
    for entry in race.get("summary", []):
        if entry["scene"] == scene:
            reached = entry["reached"].get(TARGET)
            ratios[entry["method"]] = (None if reached is None else
                                       {"ratio": reached["ratio"],
                                        "repetitions": reached["repetitions"]})
    if HEADLINE not in ratios:
        raise ValueError(f"the race's summary of {scene} has no {HEADLINE} entry")
    return {"pt_rmse": pt["rmse"], "pt_seconds": pt["seconds"], "ratios": ratios, "rows": rows}


def ratios_of(runs: Sequence[Record], scene: str, method: str = HEADLINE
              ) -> List[Optional[float]]:
    """The ratio of ``method`` on ``scene`` in each of ``runs`` (run records of one side),
    None where that run did not reach VTK PT's error."""
    reached = [run["scenes"][scene]["ratios"].get(method) for run in runs]
    return [None if r is None else float(r["ratio"]) for r in reached]


def median(values: Sequence[Optional[float]]) -> Optional[float]:
    """The median of ``values``; None if any is None (a run that did not reach the error)
    or there are none."""
    if not values or any(value is None for value in values):
        return None
    return float(statistics.median(values))


def spread(values: Sequence[Optional[float]]) -> Optional[float]:
    """The largest of ``values`` over the smallest, less one; None as for median()."""
    if median(values) is None:
        return None
    return max(values) / min(values) - 1.0


def overlap(head: Sequence[Optional[float]], base: Sequence[Optional[float]]) -> Optional[bool]:
    """Whether the ranges of the two sides' values overlap; None as for median()."""
    if median(head) is None or median(base) is None:
        return None
    return max(head) >= min(base) and max(base) >= min(head)


def compare_method(head_runs: Sequence[Record], base_runs: Sequence[Record], scene: str,
                   method: str) -> Record:
    """The two sides' ratios of ``method`` on ``scene``, their medians, spreads and
    ``head_over_base``."""
    head, base = ratios_of(head_runs, scene, method), ratios_of(base_runs, scene, method)
    head_median, base_median = median(head), median(base)
    ratio = None if head_median is None or base_median is None else head_median / base_median
    return {"head_ratios": head, "base_ratios": base, "head_median": head_median,
            "base_median": base_median, "head_over_base": ratio, "head_spread": spread(head),
            "base_spread": spread(base), "within_noise": overlap(head, base)}


def compare_scene(head_runs: Sequence[Record], base_runs: Sequence[Record], scene: str
                  ) -> Record:
    """One scene: SPT's comparison at the top level, every stochastic method's that both
    sides raced under ``methods``, and VTK PT's frame per run."""
    methods = [m for m in head_runs[0]["scenes"][scene]["ratios"]
               if m in base_runs[0]["scenes"][scene]["ratios"]]
    result = compare_method(head_runs, base_runs, scene, HEADLINE)
    result["head_pt_seconds"] = [run["scenes"][scene]["pt_seconds"] for run in head_runs]
    result["base_pt_seconds"] = [run["scenes"][scene]["pt_seconds"] for run in base_runs]
    result["methods"] = {m: compare_method(head_runs, base_runs, scene, m) for m in methods}
    return result


def comparison(runs: Sequence[Record], scenes: Sequence[str], commits: Record,
               settings: Record) -> Record:
    """What ``compare.json`` holds: the commits, the settings, per scene the comparison,
    and every run's record in the order the runs were made."""
    head_runs = [run for run in runs if run["side"] == "head"]
    base_runs = [run for run in runs if run["side"] == "base"]
    if not head_runs or not base_runs:
        raise ValueError("a comparison needs at least one run of each side")
    return {"commits": dict(commits), "settings": dict(settings),
            "definition": __doc__.split("\n\n", 1)[1].strip(),
            "scenes": {name: compare_scene(head_runs, base_runs, name) for name in scenes},
            "runs": list(runs)}


# --------------------------------------------------------------------------------------------
# The table
# --------------------------------------------------------------------------------------------

def _ratio_text(value: Optional[float], run: Optional[Record] = None, scene: str = "") -> str:
    if value is None:
        return "not reached"
    if run is None:
        return f"{value:.2f}"
    level = run["scenes"][scene]["ratios"][HEADLINE]["repetitions"]
    return f"{value:.2f}x (L={level})"


def _percent(value: Optional[float]) -> str:
    return "-" if value is None else f"{100.0 * value:.0f} %"


def table(result: Record) -> str:
    """The comparison as a Markdown table: per scene each run's ratio (with its L), the
    head's median over the base's, each side's spread and whether the two overlap."""
    runs = result["runs"]
    head_runs = [run for run in runs if run["side"] == "head"]
    base_runs = [run for run in runs if run["side"] == "base"]
    lines = ["| scene | head, SPT to VTK PT's error | base | head / base (medians) "
             "| spread: head, base | within noise |", "|---|---|---|---|---|---|"]
    for scene, figures in result["scenes"].items():
        head = ", ".join(_ratio_text(v, r, scene)
                         for v, r in zip(figures["head_ratios"], head_runs))
        base = ", ".join(_ratio_text(v, r, scene)
                         for v, r in zip(figures["base_ratios"], base_runs))
        noise = {None: "-", True: "yes", False: "no"}[figures["within_noise"]]
        lines.append(f"| {scene} | {head} | {base} | {_ratio_text(figures['head_over_base'])} "
                     f"| {_percent(figures['head_spread'])}, {_percent(figures['base_spread'])} "
                     f"| {noise} |")
    commits = result["commits"]
    loads = [run["load_average"][0] for run in runs]
    lines.append("")
    changes = " (with local changes)" if commits.get("modified") else ""
    lines.append(f"head {commits['head']}{changes}, base {commits['base']}; runs alternate "
                 f"head, base, ...; load average (1 min) {min(loads):.1f} to {max(loads):.1f}")
    return "\n".join(lines)
