"""``python3 -m spt``: the demo, the paper's figures and the benchmark from the command line.

The commands' work is in the library (``mesh``) and in :mod:`spt.experiments` (``demo``,
``bench``, ``report``, ``figures``), imported only when its command runs. The experiments live
in the source and build trees only (``build/bin/spt-python -m spt demo``): an install and the
wheel ship the library.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import pathlib
import sys
from typing import Dict, List, Optional, Sequence

from . import HAVE_MESHING
from .meshes import MAX_CELLS, MIN_CELLS

MAX_IMAGE_SIZE = 4096


def _number(kind, accept, refusal: str):
    """A parser of an int or a float (``kind``, ``_`` allowed between digits) that refuses
    what is not one, and says "VALUE ``refusal``" where ``accept(value)`` is false."""
    def parse(text: str):
        try:
            value = kind(text)
        except ValueError:
            noun = "a whole number" if kind is int else "a number"
            raise argparse.ArgumentTypeError(f"'{text}' is not {noun}") from None
        if not accept(value):
            raise argparse.ArgumentTypeError(f"{value} {refusal}")
        return value
    return parse


def _positive_int(limit: int):
    return _number(int, lambda value: 1 <= value <= limit, f"is outside 1..{limit}")


def _positive_ints(limit: int, what: str):
    """A comma-separated list of at least one whole number in 1..limit."""
    def parse(text: str) -> List[int]:
        values = [_positive_int(limit)(part) for part in text.split(",") if part.strip()]
        if not values:
            raise argparse.ArgumentTypeError(f"give at least one {what}")
        return values
    return parse


_levels = _positive_ints(65536, "repetition level")


def _names_in(module: str, attribute: str, what: str, one: bool = False):
    """A parser of comma-separated names, each one of ``module.attribute`` (a collection of
    names or a function that returns one, imported when the option is parsed); with ``one``,
    of exactly one name, returned alone."""
    def parse(text: str):
        choices = getattr(importlib.import_module(module, __package__), attribute)
        choices = list(choices() if callable(choices) else choices)
        names = [part.strip() for part in text.split(",") if part.strip()]
        unknown = [name for name in names if name not in choices]
        if unknown or not names:
            raise argparse.ArgumentTypeError(
                f"unknown {what}(s) {', '.join(unknown) or '(none)'}; choose from "
                f"{', '.join(choices)}")
        if one and len(names) != 1:
            raise argparse.ArgumentTypeError(f"give one {what}, not {len(names)}")
        return names[0] if one else names
    return parse


# The options' lists of names, each checked against what the library or the experiments name.
_datasets = _names_in(".scenes", "SCENES", "data set")
_dataset = _names_in(".scenes", "SCENES", "data set", one=True)
_steep_datasets = _names_in(".experiments.figures", "STEEP_SCENES", "data set")
_demo_scene = _names_in(".experiments.bench.race", "scene_names", "data set", one=True)
_sections = _names_in(".experiments.bench", "SECTIONS", "section")
_methods = _names_in(".experiments.bench", "METHODS", "method")
_race_scenes = _names_in(".experiments.bench.race", "scene_names", "scene")
_paraview_scenes = _names_in(".experiments.bench.paraview_view", "scene_names", "scene")


def _data_directory(text: str) -> pathlib.Path:
    path = pathlib.Path(text).expanduser()
    if not path.is_dir():
        raise argparse.ArgumentTypeError(f"'{text}' is not a directory")
    return path.resolve()


def _output_directory(text: str) -> pathlib.Path:
    path = pathlib.Path(text)
    if path.exists() and not path.is_dir():
        raise argparse.ArgumentTypeError(f"'{text}' exists and is not a directory")
    return path


def _cells(pieces: int):
    """A cell count of the generated meshes, of ``pieces`` meshes in all."""
    low = pieces * MIN_CELLS
    return _number(int, lambda value: low <= value <= MAX_CELLS, f"is outside {low}..{MAX_CELLS}")


_target_error = _number(float, lambda value: 0.0 < value <= 1.0, "is outside 0 (exclusive) .. 1")
_seed = _number(int, lambda value: value >= 0, "is negative")


# The options of the commands, (flag, add_argument's keyword arguments), in the order of --help.
# The folder of the real data sets: the default is $SPT_DATA_DIR, and nowhere else.
_DATA_DIR = ("--data-dir", dict(type=_data_directory, default=None,
                                help="the folder holding the real data sets (default: "
                                     "$SPT_DATA_DIR; without either, the generated meshes only)"))
_SIZE = ("--size", dict(type=_positive_int(MAX_IMAGE_SIZE), default=256))
_REPETITIONS = dict(type=_positive_int(65536), default=144)

_DEMO = [
    ("--output", dict(type=_output_directory, default=pathlib.Path("out/demo"))),
    ("--size", dict(_SIZE[1], help="image width and height in pixels (default 256)")),
    ("--repetitions", dict(type=_positive_int(65536), default=256,
                           help="SPT's largest repetition level (default 256)")),
    ("--target-error", dict(type=_target_error, default=None,
                            help="the error SPT races to besides VTK PT's, RMSE of premultiplied "
                                 "RGBA (default 0.005)")),
    ("--dataset", dict(type=_demo_scene, default=None,
                       help="the large scene (default: ironprot_full, 1.5M tetrahedra, where the "
                            "data sets are, else drill-1M, the generated drill of 10^6; "
                            "'default' is the embedded helix mesh)")),
    ("--pair-cells", dict(type=_cells(2), default=200_000,
                          help="tetrahedra of the interpenetrating drill and ring, in all "
                               "(default 200000)")),
    _DATA_DIR]

# The options that replace a setting of the benchmark when given (their dest is its name).
_BENCH_SETTINGS = ("large_cells", "frames", "only_methods", "race_scenes", "race_max_repetitions",
                   "race_size", "race_sizes", "paraview_scenes")
_BENCH = [
    ("--output", dict(type=pathlib.Path, default=pathlib.Path("out/bench"))),
    _DATA_DIR,
    ("--sections", dict(type=_sections, default=None,
                        help="comma-separated sections to run (default: all): race,cells,"
                             "repetitions,subpixels,image,quality,host,large,parallel,paraview")),
    ("--shape", dict(choices=("drill", "torus", "helix"),
                     default="drill" if HAVE_MESHING else "helix",
                     help="generated mesh of the sweeps (default drill; helix, which needs no "
                          "TetGen, in builds without the meshing module)")),
    ("--max-cells", dict(type=_positive_int(10 ** 9), default=None,
                         help="largest mesh of the cell sweep (default 10,000,000)")),
    ("--large-cells", dict(type=_positive_int(10 ** 9), default=None,
                           help="cells of the paper's large case (default 13,000,000)")),
    ("--methods", dict(type=_methods, default=None, dest="only_methods", metavar="METHODS",
                       help="comma-separated methods to run (default: all); the other methods' "
                            "results in OUTPUT/bench.json are kept")),
    ("--frames", dict(type=_positive_int(100), default=None,
                      help="timed frames per point, their median is reported (default 3)")),
    ("--scenes", dict(type=_race_scenes, default=None, dest="race_scenes", metavar="SCENES",
                      help="comma-separated scenes of the race (default: spx,torus,bluntfin,"
                           "post,drill-0.2M,drill-1M,drill-3M); the other scenes of a race "
                           "measured alike in OUTPUT/bench.json are kept")),
    ("--max-repetitions", dict(type=_positive_int(65536), default=None,
                               dest="race_max_repetitions", metavar="MAX_REPETITIONS",
                               help="the race's largest repetition level (default 256)")),
    ("--race-size", dict(type=_positive_int(MAX_IMAGE_SIZE), default=None,
                         help="the race's image width and height (default 256)")),
    ("--size", dict(type=_positive_ints(MAX_IMAGE_SIZE, "image size"), default=None,
                    dest="race_sizes",
                    help="comma-separated image sizes of the race, each width and height, e.g. "
                         "256,1024 (default 256); the races at other sizes in OUTPUT/bench.json "
                         "are kept")),
    ("--paraview-scenes", dict(type=_paraview_scenes, default=None,
                               help="comma-separated scenes of the paraview section (default: "
                                    "disk,drill-0.2M,drill-1M)")),
    ("--quick", dict(action="store_true",
                     help="every section at small sizes, a smoke run of a few minutes"))]

_REPORT = [
    ("--input", dict(type=pathlib.Path, default=pathlib.Path("Documentation/bench/bench.json"),
                     help="a bench.json written by `spt-python -m spt bench`")),
    ("--output", dict(type=pathlib.Path, default=pathlib.Path("Documentation/results.md"),
                      help="the Markdown file to write")),
    ("--figures", dict(action="store_true",
                       help="also draw the figures again next to the input, from its results"))]

_MESH = [
    ("--shape", dict(choices=("drill", "torus"), default="drill")),
    ("--cells", dict(type=_cells(1), default=1_000_000,
                     help="number of tetrahedra, within 25 %% (default 1000000)")),
    ("--seed", dict(type=_seed, default=0, help="places the field's maxima")),
    ("--output", dict(type=pathlib.Path, required=True,
                      help="the .vtk file to write (VTK legacy binary)")),
    ("--no-cache", dict(action="store_true",
                        help="mesh again instead of reading SPT_CACHE_DIR (which is not written)"))]


def _print_table(header: Sequence[str], rows: Sequence[Sequence[object]]) -> None:
    from .experiments.tables import print_table

    print_table(header, rows)


def _bench(arguments: argparse.Namespace) -> None:
    import dataclasses

    from .experiments import bench

    settings = bench.Settings.quick() if arguments.quick else bench.Settings()
    changes: Dict[str, object] = {"shape": arguments.shape}
    if arguments.max_cells is not None:
        changes["cells"] = tuple(c for c in settings.cells if c < arguments.max_cells) + (
            arguments.max_cells,)
    for setting in _BENCH_SETTINGS:  # each option given replaces its setting
        value = getattr(arguments, setting)
        if value is not None:
            changes[setting] = tuple(value) if isinstance(value, list) else value
    settings = dataclasses.replace(settings, **changes)
    sections = arguments.sections or list(bench.SECTIONS)
    bench.run(arguments.output, sections, settings)
    print((arguments.output / "bench.md").read_text(encoding="utf-8"))
    print(f"Results, plots and bench.md written to {arguments.output}")


def _report(arguments: argparse.Namespace) -> None:
    from .experiments.bench.results import write_results

    write_results(arguments.input, arguments.output, figures=arguments.figures)
    drawn = " and the figures" if arguments.figures else ""
    print(f"{arguments.output}, {arguments.input.parent / 'bench.md'}{drawn} written from "
          f"{arguments.input}")


def _demo(arguments: argparse.Namespace) -> None:
    import json

    from . import render
    from .experiments import demo

    target = (render.DEFAULT_TARGET_ERROR if arguments.target_error is None
              else arguments.target_error)
    results = demo.demo(arguments.output, arguments.size, arguments.repetitions,
                        arguments.dataset, arguments.pair_cells, target_error=target)
    _print_table([column.format(target=target) for column in demo.RACE_HEADER],
                 demo.race_rows(results))
    document = json.loads((arguments.output / "results.json").read_text(encoding="utf-8"))
    load = document["load_average"]
    print(f"Times are multiples of VTK PT's frame (best of {demo.FRAMES}), "
          f"{arguments.size} x {arguments.size}, on {document['machine']} (load average "
          f"{load['start']:.1f} at the start, {load['end']:.1f} at the end).")
    print(demo.WHERE_SPT_LOSES)
    print(f"Images, comparison.png, race.md and results.json written to {arguments.output}")


def _mesh(arguments: argparse.Namespace) -> None:
    from .meshes import generate, write_legacy

    grid = generate(arguments.shape, arguments.cells, arguments.seed,
                    cache=not arguments.no_cache)
    write_legacy(grid, arguments.output)
    print(f"{grid.GetNumberOfCells()} tetrahedra, {grid.GetNumberOfPoints()} points "
          f"written to {arguments.output}")


def _convergence(arguments: argparse.Namespace) -> None:
    from .experiments import figures

    results = figures.convergence(arguments.datasets, arguments.levels, arguments.size,
                                  arguments.output)
    print((arguments.output / "convergence.md").read_text(encoding="utf-8"))
    print(f"{len(results)} data sets; figures written to {arguments.output}")


def _pbvr(arguments: argparse.Namespace) -> None:
    from .experiments import figures

    rows = figures.pbvr_figure(arguments.datasets, arguments.repetitions,
                               arguments.levels, arguments.size, arguments.output)
    _print_table(figures.PBVR_TABLE_HEADER, rows)
    print()
    print((arguments.output / "pbvr_convergence.md").read_text(encoding="utf-8"))
    print(f"Images, comparisons and pbvr_convergence.png written to {arguments.output}")


def _sampling(arguments: argparse.Namespace) -> None:
    from .experiments.sampling import sampling_figure

    result = sampling_figure(arguments.dataset, arguments.levels, arguments.size,
                             arguments.output)
    print((arguments.output / "sampling.md").read_text(encoding="utf-8"))
    check = result["per_pass_check"]
    print(f"16 per pass against 1 per pass at {check['repetitions']} repetitions: "
          f"{check['speedup']:.2f}x faster, largest pixel difference "
          f"{check['max_abs_difference']:.4f}")
    print(f"stratified thresholds reach the error of {result['levels'][-1]} independent "
          f"repetitions with {result['stratified_repetitions_to_match']}")
    print(f"the default estimator reaches it with {result['default_repetitions_to_match']}")


def _sorting(arguments: argparse.Namespace) -> None:
    from .experiments import figures

    rows = figures.sorting(arguments.datasets, arguments.size, arguments.output,
                           arguments.repetitions)
    _print_table(figures.SORTING_HEADER, rows)
    print(f"Images, comparisons and sorting.md written to {arguments.output}")


def _accuracy(arguments: argparse.Namespace) -> None:
    from .experiments import figures

    result = figures.accuracy_figure(arguments.output, arguments.rays)
    print(f"log-log slope of the error: {result['slope']:.3f} (Monte Carlo: -0.5); "
          f"plot written to {arguments.output / 'accuracy.png'}")


def _readme(arguments: argparse.Namespace) -> None:
    from .experiments.readme import readme_figures

    for path in readme_figures(arguments.output, arguments.bench, arguments.size):
        print(f"{path} ({path.stat().st_size // 1024} KiB)")


# command -> (its function, its help, its options), figures apart: in the order of --help.
_COMMANDS = {
    "demo": (_demo, "two scenes where sorting fails or costs: SPT against VTK's projected "
                    "tetrahedra, HAVS-like and the exact reference", _DEMO),
    "bench": (_bench, "time and GPU memory of every method, fitted models and a report (long: "
                      "about an hour; --quick takes minutes)", _BENCH),
    "report": (_report, "write results.md (and the full tables, bench.md, next to the input) "
                        "from a benchmark's bench.json, without measuring", _REPORT),
    "mesh": (_mesh, "write a generated tetrahedral mesh (drill or torus) as a legacy .vtk file",
             _MESH),
}
# Each figure's options come after --output (default out/figures/NAME) and --data-dir.
_FIGURES = {
    "convergence": (_convergence, "RMSE against repetitions on SPX, Blunt Fin and Oxygen Post", [
        ("--datasets", dict(type=_datasets, default=["spx", "bluntfin", "post"])),
        ("--levels", dict(type=_levels, default=[4, 16, 64, 256, 1024])), _SIZE]),
    "pbvr": (_pbvr, "PBVR against SPT and the reference with a steep transfer function", [
        ("--datasets", dict(type=_steep_datasets, default=["bluntfin", "post"])),
        ("--repetitions", dict(_REPETITIONS,
                               help="RepetitionLevel of the images and the table (default 144)")),
        ("--levels", dict(type=_levels, default=[4, 16, 64, 144], help="repetition levels of "
                          "the convergence curves (default 4,16,64,144)")),
        _SIZE]),
    "sampling": (_sampling, "several repetitions per pass and stratified thresholds, measured", [
        ("--dataset", dict(type=_dataset, default="default")),
        ("--levels", dict(type=_levels, default=[16, 32, 64, 128, 256])), _SIZE]),
    "sorting": (_sorting, "SPT against sorted renderers (HAVS-like k=2 and 6, VTK PT)", [
        ("--datasets", dict(type=_datasets,
                            default=["spx", "bluntfin", "post", "torus", "default"])),
        ("--repetitions", dict(_REPETITIONS,
                               help="SPT RepetitionLevel (default 144, as in the paper)")),
        _SIZE]),
    "accuracy": (_accuracy, "stochastic against exact brightness along random rays", [
        ("--rays", dict(type=_positive_int(10 ** 6), default=1000))]),
    "readme": (_readme, "the README's picture (interpenetrating volumes) and race plot", [
        ("--bench", dict(type=pathlib.Path, default=pathlib.Path("Documentation/bench/bench.json"),
                         help="the benchmark's results whose race is plotted")), _SIZE]),
}


def _add(commands, name: str, help_text: str, options) -> None:
    parser = commands.add_parser(name, help=help_text)
    for flag, keywords in options:
        parser.add_argument(flag, **keywords)


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="python3 -m spt",
        description="Sorting-free pre-integrated projected tetrahedra (SPT) for VTK.")
    commands = parser.add_subparsers(dest="command", required=True)
    _add(commands, "demo", *_COMMANDS["demo"][1:])
    figures = commands.add_parser("figures", help="reproduce the paper's figures")
    figure = figures.add_subparsers(dest="figure", required=True)
    for name, (_, help_text, options) in _FIGURES.items():
        output = ("--output", dict(type=_output_directory,
                                   default=pathlib.Path("out/figures") / name))
        _add(figure, name, help_text, [output, _DATA_DIR, *options])
    for name in ("bench", "report", "mesh"):
        _add(commands, name, *_COMMANDS[name][1:])
    return parser


def _without_experiments(argv: Sequence[str]) -> Optional[str]:
    """Why the command of ``argv`` cannot run here: it is one of the experiments' and this
    package (an install, a wheel) has none; None where it can run."""
    command = next((word for word in argv if not word.startswith("-")), None)
    if command not in ("demo", "bench", "report", "figures"):
        return None
    if importlib.util.find_spec(f"{__package__}.experiments") is not None:
        return None
    return (f"'{command}' is one of the experiments (the demo, the benchmark, the paper's "
            f"figures), which an installed package does not hold: run it from a build of the "
            f"source tree, as build/bin/spt-python -m spt {command}")


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Run the command line; returns the exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    missing = _without_experiments(argv)
    if missing:
        print(f"python3 -m spt: error: {missing}", file=sys.stderr)
        return 2
    arguments = _parser().parse_args(argv)
    if getattr(arguments, "data_dir", None) is not None:
        # Through the environment, so that the processes a command starts (the benchmark's
        # ParaView and MPI ranks) read the same data sets.
        os.environ["SPT_DATA_DIR"] = str(arguments.data_dir)
    command = (_COMMANDS[arguments.command] if arguments.command in _COMMANDS
               else _FIGURES[arguments.figure])[0]
    try:
        command(arguments)
    except (OSError, ValueError, RuntimeError) as error:
        # Missing or unreadable data sets, unwritable output folders, data the figures cannot
        # use, no OpenGL, a mesher that fails: each error says which and why.
        print(f"python3 -m spt: error: {error}", file=sys.stderr)
        return 1
    return 0
