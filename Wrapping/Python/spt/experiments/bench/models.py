"""The fitted time and memory models.

Time in milliseconds in the paper's form ``T = L_r (a n_c + b w h L_s^2)`` for SPT (and the
same with particles for PBVR), with the passes and the fragments made explicit, and linear
models for HAVS-like, VTK's projected tetrahedra and the floor; memory in bytes in the form
``M = c n_c + d w h L_s^2``.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Dict, List, Optional, Sequence

import numpy as np

from .methods import PER_PASS

Entry = Dict[str, object]


@dataclasses.dataclass
class Fit:
    """A linear least-squares model ``y = sum(coefficient_i * term_i)``."""

    name: str
    terms: List[str]
    coefficients: List[float]
    r2: float
    n: int
    observed: List[float]
    predicted: List[float]

    def predict(self, columns: Sequence[float]) -> float:
        columns = list(columns) + [1.0] * (len(self.coefficients) - len(columns))
        return float(np.dot(self.coefficients, columns))


def fit(name: str, terms: Sequence[str], rows: Sequence[Sequence[float]],
        observed: Sequence[float], constant: bool = True) -> Optional[Fit]:
    """Least squares weighted by 1 / observed, so that every point counts by its relative
    error (the sweeps span four decades). ``constant`` adds a fixed term (``fixed``): what a
    frame or a mapper costs whatever the mesh and the image (window, pre-integration table),
    which the paper's forms leave out."""
    terms = list(terms) + (["fixed"] if constant else [])
    rows = [list(row) + ([1.0] if constant else []) for row in rows]
    if len(observed) < len(terms) + 1:
        return None
    design = np.asarray(rows, dtype=float)
    y = np.asarray(observed, dtype=float)
    weights = 1.0 / np.maximum(y, 1e-12)
    coefficients, *_ = np.linalg.lstsq(design * weights[:, None], y * weights, rcond=None)
    predicted = design @ coefficients
    residual = np.sum((y - predicted) ** 2)
    total = np.sum((y - y.mean()) ** 2)
    r2 = 1.0 - residual / total if total > 0 else float("nan")
    return Fit(name + (" + fixed" if constant else ""), terms,
               [float(c) for c in coefficients], float(r2), len(y), y.tolist(),
               predicted.tolist())


def time_key(entries: Sequence[Dict[str, object]]) -> str:
    """``cpu_seconds`` when every entry has it: on a machine that runs other jobs it measures
    the work of the frame, where wall time also counts the waiting; else ``seconds``."""
    have = [e for e in entries if np.isfinite(e.get("cpu_seconds", float("nan")))]
    return "cpu_seconds" if entries and len(have) == len(entries) else "seconds"


def pixels(entry: Dict[str, object]) -> float:
    return float(entry["width"]) * float(entry["height"]) * float(entry["subpixels"]) ** 2


def _select(entries: Sequence[Entry], name: str, key: str) -> List[Entry]:
    return [e for e in entries if e["method"] == name and e.get("sweep") != "quality"
            and np.isfinite(e.get(key, float("nan")))]


def _fitted(models: Dict[str, Optional[Fit]]) -> Dict[str, Fit]:
    """The models that had enough points to be fitted."""
    return {name: model for name, model in models.items() if model}


def _paper_models(entries: Sequence[Entry], key: str) -> Dict[str, Optional[Fit]]:
    """The paper's form, and SPT with N repetitions per pass: the mesh is traversed twice
    per pass (keys, colors) and every fragment works for each of the pass's repetitions."""
    models: Dict[str, Optional[Fit]] = {}
    for name in ("spt-paper", "spt"):
        chosen = _select(entries, name, key)
        rows = [(e["repetitions"] * e["cells"], e["repetitions"] * pixels(e)) for e in chosen]
        models[name] = fit(f"{name}: T = L_r (a n_c + b w h L_s^2)", ["a", "b"], rows,
                           [1000.0 * e[key] for e in chosen])
    spt = _select(entries, "spt", key)
    rows = [(math.ceil(e["repetitions"] / PER_PASS) * e["cells"],
             math.ceil(e["repetitions"] / PER_PASS) * pixels(e),
             e["repetitions"] * pixels(e)) for e in spt]
    models["spt-passes"] = fit("spt: T = P a n_c + (P b + L_r c) w h L_s^2, P = ceil(L_r / 16)",
                               ["a", "b", "c"], rows, [1000.0 * e[key] for e in spt])
    return models


def _fragment_models(entries: Sequence[Entry], key: str) -> Dict[str, Optional[Fit]]:
    """On a software rasterizer the cost is the fragments': a traversal covers the footprint
    about as many times as a ray crosses cells, which grows as n_c^(1/3), not as n_c. The
    default (visibility estimator, exact coverage) adds one traversal per image: half a pass
    of two traversals."""
    models: Dict[str, Optional[Fit]] = {}
    for name, per_pass, extra in (("spt-paper", 1, 0.0), ("spt", PER_PASS, 0.0),
                                  ("spt-visibility", PER_PASS, 0.5)):
        chosen = _select(entries, name, key)
        passes = [math.ceil(e["repetitions"] / per_pass) + extra for e in chosen]
        rows = [(p * e["cells"], p * pixels(e) * e["cells"] ** (1 / 3),
                 e["repetitions"] * pixels(e)) for p, e in zip(passes, chosen)]
        label = f"ceil(L_r / {per_pass})" + (f" + {extra:g}" if extra else "")
        models[f"{name}-fragments"] = fit(
            f"{name}: T = P (a n_c + b w h L_s^2 n_c^(1/3)) + L_r c w h L_s^2, P = {label}",
            ["a", "b", "c"], rows, [1000.0 * e[key] for e in chosen])
    return models


def _linear_models(entries: Sequence[Entry], key: str) -> Dict[str, Optional[Fit]]:
    """PBVR in particles; HAVS-like, VTK's projected tetrahedra and the floor linear."""
    pbvr = [e for e in _select(entries, "pbvr", key) if e.get("particles")]
    rows = [(e["particles"], e["repetitions"] * pixels(e)) for e in pbvr]  # particles: n_p L_r
    models = {"pbvr": fit("pbvr: T = L_r (a n_p + b w h L_s^2), n_p particles per repetition",
                          ["a", "b"], rows, [1000.0 * e[key] for e in pbvr])}
    for name in ("havs2", "havs6", "pt", "floor"):
        chosen = _select(entries, name, key)
        models[name] = fit(f"{name}: T = a n_c + b w h", ["a", "b"],
                           [(e["cells"], pixels(e)) for e in chosen],
                           [1000.0 * e[key] for e in chosen])
    return models


def time_models(entries: Sequence[Entry], key: str = "seconds") -> Dict[str, Fit]:
    """Time in milliseconds, per method, in the paper's form where it has one. ``key`` is
    ``seconds`` (wall time of the frame) or ``cpu_seconds`` (CPU time of all the process's
    threads, llvmpipe's included: the work done, whatever else the machine runs)."""
    return _fitted({**_paper_models(entries, key), **_fragment_models(entries, key),
                    **_linear_models(entries, key)})


def memory_models(entries: Sequence[Dict[str, object]]) -> Dict[str, Fit]:
    """GPU bytes each mapper reports, in the paper's form ``M = c n + d w h L_s^2``."""
    models: Dict[str, Optional[Fit]] = {}
    with_memory = [e for e in entries if e.get("gpu_memory")]
    for name in ("spt", "spt-visibility", "spt-paper", "havs2", "havs6"):
        chosen = [e for e in with_memory if e["method"] == name]
        models[name] = fit(f"{name}: M = c n_c + d w h L_s^2", ["c", "d"],
                           [(e["cells"], pixels(e)) for e in chosen],
                           [e["gpu_memory"] for e in chosen])
    chosen = [e for e in with_memory if e["method"] == "pbvr" and e.get("particles")]
    # PBVR reports the particles of all its sets: n_p L_r.
    models["pbvr"] = fit("pbvr: M = c n_p L_r + d w h L_s^2", ["c", "d"],
                         [(e["particles"], pixels(e)) for e in chosen],
                         [e["gpu_memory"] for e in chosen])
    return _fitted(models)


def predict_large(entry: Entry, time_fits: Dict[str, Fit], cpu_fits: Dict[str, Fit],
                  memory_fits: Dict[str, Fit]) -> None:
    """The fitted models' prediction for the large case, next to its measurement."""
    area = pixels(entry)
    passes = math.ceil(entry["repetitions"] / PER_PASS)
    columns = [passes * entry["cells"], passes * area, entry["repetitions"] * area]
    fragments = [passes * entry["cells"], passes * area * entry["cells"] ** (1 / 3),
                 entry["repetitions"] * area]
    for models, suffix in ((time_fits, "seconds"), (cpu_fits, "cpu_seconds")):
        if "spt-passes" in models:
            entry[f"predicted_{suffix}"] = models["spt-passes"].predict(columns) / 1000.0
        if "spt-fragments" in models:
            entry[f"predicted_{suffix}_fragments"] = (
                models["spt-fragments"].predict(fragments) / 1000.0)
    if "spt" in memory_fits:
        entry["predicted_memory"] = memory_fits["spt"].predict([entry["cells"], area])
