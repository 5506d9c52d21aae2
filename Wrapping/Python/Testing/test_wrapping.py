"""The wrapped mapper: importable next to vtk, VTK conventions for its settings, PrintSelf."""

import os
import subprocess
import sys

import pytest
import vtk

import spt

from robustness_support import check_clamped_setting


def test_mapper_is_a_vtk_unstructured_grid_volume_mapper():
    mapper = spt.vtkSPTVolumeMapper()
    assert isinstance(mapper, vtk.vtkUnstructuredGridVolumeMapper)
    # The package loads the parallel module, which overrides the mapper in VTK's factory.
    assert isinstance(mapper, spt.vtkSPTVolumeMapper)
    assert mapper.GetClassName() == "vtkPSPTVolumeMapper"


@pytest.mark.parametrize("name, default, low, high", [
    ("RepetitionLevel", 32, 1, 65536),
    ("SubpixelLevel", 1, 1, 8),
    ("PreIntegrationScalarResolution", 128, 8, 1024),
    ("PreIntegrationThicknessResolution", 64, 4, 1024),
])
def test_settings_have_defaults_and_clamps(name, default, low, high):
    check_clamped_setting(spt.vtkSPTVolumeMapper(), name, default, low, high)


def test_vector_mode_seed_estimator_and_exact_coverage():
    mapper = spt.vtkSPTVolumeMapper()
    assert mapper.GetVectorMode() == spt.vtkSPTVolumeMapper.MAGNITUDE
    mapper.SetVectorModeToComponent()
    mapper.SetVectorComponent(2)
    assert (mapper.GetVectorMode(), mapper.GetVectorComponent()) == (1, 2)
    mapper.SetSeed(4000000000)
    assert mapper.GetSeed() == 4000000000
    assert mapper.GetEstimator() == spt.vtkSPTVolumeMapper.VISIBILITY_ESTIMATOR
    assert mapper.GetExactCoverage() == 1
    mapper.SetEstimatorToSurvivor()
    assert mapper.GetEstimator() == spt.vtkSPTVolumeMapper.SURVIVOR_ESTIMATOR
    mapper.SetEstimator(7)
    assert mapper.GetEstimator() == spt.vtkSPTVolumeMapper.VISIBILITY_ESTIMATOR
    mapper.ExactCoverageOff()
    assert "ExactCoverage: Off" in str(mapper)


_SAMPLING_SETTINGS = ["RepetitionsPerPass", "Estimator", "StratifiedSampling", "ExactCoverage",
                      "DepthSlabs"]


def _sampling(mapper):
    return {name: getattr(mapper, "Get" + name)() for name in _SAMPLING_SETTINGS}


def test_paper_sampling_is_one_call_and_the_defaults_another():
    mapper = spt.vtkSPTVolumeMapper()
    defaults = _sampling(mapper)
    mapper.SetSamplingToPaper()
    assert _sampling(mapper) == {
        "RepetitionsPerPass": 1, "Estimator": spt.vtkSPTVolumeMapper.SURVIVOR_ESTIMATOR,
        "StratifiedSampling": 0, "ExactCoverage": 0, "DepthSlabs": 1}
    mapper.SetDepthSlabs(4)
    mapper.SetSamplingToDefault()
    assert _sampling(mapper) == defaults


def test_frame_statistics_of_a_mapper_that_has_not_rendered():
    mapper = spt.vtkSPTVolumeMapper()
    statistics = mapper.GetFrameStatistics()
    assert isinstance(statistics, spt.vtkSPTFrameStatistics)
    assert statistics is mapper.GetFrameStatistics()
    assert (statistics.GetRepetitionCount(), statistics.GetEstimatedError(),
            statistics.GetPointCellCount(), statistics.GetComputedCellCount(),
            statistics.GetParallelBytes()) == (0, -1.0, 0, 0, 0)
    assert "FrameStatistics:" in str(mapper) and "ParallelBytes: 0" in str(mapper)


def test_print_self_lists_every_setting():
    text = str(spt.vtkSPTVolumeMapper())
    for setting in ["RepetitionLevel", "SubpixelLevel", "Seed", "PreIntegrationScalarResolution",
                    "PreIntegrationThicknessResolution", "VectorMode", "VectorComponent",
                    "RepetitionsPerPass", "StratifiedSampling", "Estimator", "ExactCoverage",
                    "TargetError", "ReuseNoiseEstimate",
                    "ProgressiveRefinement", "MaximumProgressiveRepetitions",
                    "AutoAdjustRepetitions", "NumberOfTetrahedra", "GPUMemorySize",
                    "ScalarMode"]:
        assert setting + ":" in text


def installed_python(wheel: bool = True):
    """The interpreter and environment of the installed package, without the build tree on
    PYTHONPATH: the wheel's virtual environment (SPT_WHEEL_VTK_VERSION, where ``wheel``), or
    Debian's python3 after `make install` (SPT_TEST_INSTALLED=1); else the test is skipped."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    if wheel and os.environ.get("SPT_WHEEL_VTK_VERSION"):
        return sys.executable, env
    if os.environ.get("SPT_TEST_INSTALLED") == "1":
        return "/usr/bin/python3", env
    pytest.skip("set SPT_TEST_INSTALLED=1 after installing to check the installed package")


def test_installed_package_imports_from_any_directory(tmp_path):
    """After `make install`, Debian's python3 finds spt without PYTHONPATH (checked when the
    Makefile ran the install: SPT_TEST_INSTALLED=1)."""
    python, env = installed_python(wheel=False)
    result = subprocess.run(
        [python, "-c", "import vtk, spt; print(spt.vtkSPTVolumeMapper().GetClassName())"],
        cwd=tmp_path, env=env, capture_output=True, text=True, check=False)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "vtkPSPTVolumeMapper"  # the parallel module's override
    location = subprocess.run([python, "-c", "import spt; print(spt.__file__)"], cwd=tmp_path,
                              env=env, capture_output=True, text=True, check=True).stdout
    assert "dist-packages" in location and "/build/" not in location, location


def test_installed_package_is_the_library_without_the_experiments(tmp_path):
    """An install and the wheel ship the library: no spt.experiments, and the experiments'
    commands say where they run instead of failing on an import; the library's command runs."""
    python, env = installed_python()
    found = subprocess.run(
        [python, "-c", "import importlib.util as u; print(u.find_spec('spt.experiments'))"],
        cwd=tmp_path, env=env, capture_output=True, text=True, check=True).stdout
    assert found.strip() == "None", found
    for command in ("demo", "bench", "figures"):
        result = subprocess.run([python, "-m", "spt", command, "--output", str(tmp_path)],
                                cwd=tmp_path, env=env, capture_output=True, text=True)
        assert result.returncode == 2, result.stderr
        assert f"spt-python -m spt {command}" in result.stderr, result.stderr
        assert "Traceback" not in result.stderr, result.stderr
    mesh = subprocess.run([python, "-m", "spt", "mesh", "--help"], cwd=tmp_path, env=env,
                          capture_output=True, text=True)
    assert mesh.returncode == 0 and "--cells" in mesh.stdout, mesh.stderr


CONSUMER_CMAKE = """
cmake_minimum_required(VERSION 3.16)
project(consumer CXX)
find_package(SPT REQUIRED COMPONENTS {component})
add_executable(consumer main.cxx)
target_link_libraries(consumer PRIVATE SPT::{component})
"""

CONSUMER_MAIN = """
#include "vtkNew.h"
#include "vtkSPTVolumeMapper.h"
int main()
{
  vtkNew<vtkSPTVolumeMapper> mapper;
  mapper->SetRepetitionLevel(7);
  return mapper->GetRepetitionLevel() == 7 ? 0 : 1;
}
"""


@pytest.mark.parametrize("component", ["RenderingSPT", "RenderingParallel"])
def test_installed_cmake_package_builds_a_cxx_program(tmp_path, component):
    """After `make install`, find_package(SPT) gives SPT::RenderingSPT to a C++ project, which
    then links neither MPI nor libEGL, and SPT::RenderingParallel, which brings SPT::RenderingSPT
    with it."""
    installed_python(wheel=False)
    (tmp_path / "CMakeLists.txt").write_text(CONSUMER_CMAKE.format(component=component))
    (tmp_path / "main.cxx").write_text(CONSUMER_MAIN)
    build = tmp_path / "build"
    for command in (["cmake", "-S", str(tmp_path), "-B", str(build)],
                    ["cmake", "--build", str(build)],
                    [str(build / "consumer")]):
        result = subprocess.run(command, capture_output=True, text=True, check=False)
        assert result.returncode == 0, result.stdout + result.stderr
    if component == "RenderingSPT":
        libraries = subprocess.run(["ldd", str(build / "consumer")], capture_output=True,
                                   text=True, check=True).stdout
        assert "libSPTRenderingSPT" in libraries, libraries
        for other in ("libEGL", "libmpi", "libvtkParallelCore", "libSPTRenderingParallel"):
            assert other not in libraries, libraries
