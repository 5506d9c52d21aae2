"""What a benchmark run measures."""

from __future__ import annotations

import dataclasses
from typing import Optional, Tuple

#: The sections of a full run, in the order they run. The race is the headline.
SECTIONS = ("race", "camera", "cells", "repetitions", "subpixels", "image", "quality", "host",
            "large", "parallel", "paraview")

#: The race's scenes: the real data sets and the generated drill at three sizes.
RACE_SCENES = ("spx", "torus", "bluntfin", "post", "drill-0.2M", "drill-1M", "drill-3M")


@dataclasses.dataclass
class Settings:
    """What a run measures. The defaults are the full benchmark; ``quick()`` is a smoke run
    of every section at small sizes."""

    shape: str = "drill"
    cells: Tuple[int, ...] = (10_000, 30_000, 100_000, 300_000, 1_000_000, 3_000_000,
                              10_000_000)
    sweep_cells: int = 300_000            # the mesh of the repetition, subpixel, image sweeps
    size: int = 512                       # image size of the cell and repetition sweeps
    sweep_repetitions: int = 16           # L_r of SPT and PBVR in the other sweeps
    paper_sweep_repetitions: int = 2      # the paper's mode costs a mesh traversal each
    repetitions: Tuple[int, ...] = (1, 2, 4, 8, 16, 32, 64, 128, 256)
    paper_repetitions: int = 32           # the largest L_r of the paper's mode
    subpixels: Tuple[int, ...] = (1, 2, 3, 4)
    sizes: Tuple[int, ...] = (256, 512, 768, 1024)
    frames: int = 3
    methods: Tuple[str, ...] = ("spt", "spt-visibility", "spt-paper", "havs2", "havs6", "pbvr",
                                "pt", "floor")
    # the slow methods stop growing the cell sweep here (seconds of one frame)
    frame_limit: float = 120.0
    quality_datasets: Tuple[str, ...] = ("spx", "bluntfin", "post")
    quality_size: int = 256
    quality_levels: Tuple[int, ...] = (4, 16, 64, 256)
    host_cells: Tuple[int, ...] = (100_000, 1_000_000, 3_000_000)
    large_cells: int = 13_000_000
    large_size: int = 1024
    large_repetitions: int = 144
    race_scenes: Tuple[str, ...] = RACE_SCENES
    race_size: int = 256
    # the race at several image sizes, each measured alone (None: race_size only)
    race_sizes: Optional[Tuple[int, ...]] = None
    race_max_repetitions: int = 256       # the cap of L in the race: 1, 2, 4, ... up to it
    camera_scenes: Tuple[str, ...] = ("default", "bluntfin")
    camera_size: int = 256
    camera_repetitions: int = 16
    # SPT on several MPI ranks, each with an interleaved piece (see spt.experiments.bench.parallel)
    parallel_scenes: Tuple[str, ...] = ("drill-1M", "post")
    parallel_ranks: Tuple[int, ...] = (1, 2, 4)
    parallel_size: int = 256
    # SPT with the plugin's defaults: an error target, and a cap on the repetitions
    parallel_target_error: float = 0.005
    parallel_repetitions: int = 256
    # pvbatch with the plugin: SPT (no redistribution) against methods ParaView redistributes
    parallel_paraview_ranks: Tuple[int, ...] = (1, 2, 4)
    parallel_paraview_representations: Tuple[str, ...] = ("Volume (SPT)", "Volume (HAVS-like)",
                                                          "Volume")
    # pvpython with the plugin: a ParaView view, its still and interactive renders
    paraview_scenes: Tuple[str, ...] = ("disk", "drill-0.2M", "drill-1M")
    paraview_size: Tuple[int, int] = (1280, 800)
    paraview_representations: Tuple[str, ...] = ("Volume", "Volume (HAVS-like)",
                                                 "Volume (SPT)")
    # run the sections for these methods only, keeping the other methods' earlier results
    only_methods: Optional[Tuple[str, ...]] = None

    def race_image_sizes(self) -> Tuple[int, ...]:
        """The race's image sizes, smallest first."""
        return tuple(sorted(set(self.race_sizes or (self.race_size,))))

    def wants(self, name: str) -> bool:
        return self.only_methods is None or name in self.only_methods

    @staticmethod
    def quick() -> "Settings":
        return Settings(cells=(10_000, 30_000, 100_000), sweep_cells=30_000, size=256,
                        sweep_repetitions=4, paper_sweep_repetitions=1,
                        repetitions=(1, 4, 16), paper_repetitions=4, subpixels=(1, 2),
                        sizes=(128, 256), frames=2, quality_datasets=("spx",),
                        quality_size=128, quality_levels=(4, 16), host_cells=(10_000, 30_000),
                        large_cells=100_000, large_size=256, large_repetitions=16,
                        race_scenes=("default",), race_size=128, race_max_repetitions=16,
                        camera_scenes=("default",), camera_size=64, camera_repetitions=4,
                        parallel_scenes=("default",), parallel_ranks=(1, 2),
                        parallel_size=128, parallel_paraview_ranks=(2,),
                        paraview_scenes=("default",), paraview_size=(160, 100))
