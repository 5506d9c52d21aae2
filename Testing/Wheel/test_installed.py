"""The wheel as pip installed it: beside PyPI's vtk, with no Debian VTK on the path, its
extensions loading the vtk wheel's libraries (none of their own), VTK's Python conventions on
the classes, and a clear message where the left-out meshing module would be needed."""

import importlib.metadata
import os
import pathlib
import subprocess
import sys

import pytest
import vtk
from vtkmodules.vtkRenderingVolume import vtkUnstructuredGridVolumeMapper

import spt
import spt.vtkcheck
from spt import meshes


def test_spt_and_vtk_come_from_the_environment_not_debian():
    prefix = pathlib.Path(sys.prefix).resolve()
    for module in (spt, vtk):
        assert prefix in pathlib.Path(module.__file__).resolve().parents, module.__file__
    assert not any("dist-packages" in entry for entry in sys.path), sys.path
    expected = os.environ.get("SPT_WHEEL_VTK_VERSION")
    if expected:
        assert vtk.vtkVersion.GetVTKVersion() == expected


def test_metadata_requires_a_vtk_that_the_installed_one_meets():
    """The wheel names one vtk requirement (an exact release, or the series it was proven
    with), the installed vtk meets it, and the next minor series does not."""
    requirements = importlib.metadata.requires("spt-volume")
    pins = [r.replace(" ", "") for r in requirements if r.replace(" ", "").startswith("vtk")
            and r.replace(" ", "")[3:4] in "=<>"]
    assert len(pins) == 1, requirements
    installed = vtk.vtkVersion.GetVTKVersion()
    assert spt.vtkcheck.satisfies(installed, pins[0]), (installed, pins[0])
    major, minor = (int(part) for part in installed.split(".")[:2])
    assert not spt.vtkcheck.satisfies(f"{major}.{minor + 1}.0", pins[0]), pins[0]


def test_no_vtk_library_in_the_package():
    package = pathlib.Path(spt.__file__).parent
    libraries = sorted(p.name for p in package.glob("*.so"))
    assert "libSPTRenderingSPT.so" in libraries and "SPTRenderingSPT.so" in libraries
    assert not [name for name in libraries if name.startswith("libvtk")], libraries
    assert not list(package.parent.glob("spt_volume.libs")), "auditwheel grafted libraries"


@pytest.mark.parametrize("name", ["vtkSPTVolumeMapper", "vtkHAVSVolumeMapper",
                                  "vtkPBVRVolumeMapper"])
def test_mappers_are_vtk_unstructured_grid_volume_mappers(name):
    mapper = getattr(spt, name)()
    assert isinstance(mapper, vtkUnstructuredGridVolumeMapper)
    assert isinstance(mapper, vtk.vtkAbstractVolumeMapper)
    # VTK's own pipeline accepts it: a volume takes it as its mapper.
    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    assert volume.GetMapper() is mapper


def test_keyword_constructors_and_snake_case_properties():
    mapper = spt.vtkSPTVolumeMapper(target_error=0.02, repetition_level=64, seed=7)
    assert (mapper.GetTargetError(), mapper.GetRepetitionLevel(), mapper.GetSeed()) == \
        (0.02, 64, 7)
    mapper.depth_slabs = 4
    assert mapper.GetDepthSlabs() == 4
    havs = spt.vtkHAVSVolumeMapper(k_buffer_size=4)
    assert havs.k_buffer_size == 4
    with pytest.raises(TypeError, match="no_such_setting"):
        spt.vtkSPTVolumeMapper(no_such_setting=1)


@pytest.mark.parametrize("cls, name, low, high", [
    (spt.vtkSPTVolumeMapper, "TargetError", 0.0, 1.0),
    (spt.vtkSPTVolumeMapper, "DepthSlabs", 1, 8),
    (spt.vtkHAVSVolumeMapper, "KBufferSize", 2, 6),
    (spt.vtkPBVRVolumeMapper, "MaximumParticleMemory", 1, 65536),
])
def test_setters_clamp_as_vtk_does(cls, name, low, high):
    mapper = cls()
    getattr(mapper, "Set" + name)(low - 1)
    assert getattr(mapper, "Get" + name)() == low
    getattr(mapper, "Set" + name)(high + 1)
    assert getattr(mapper, "Get" + name)() == high


def test_meshing_module_is_left_out_with_a_clear_message():
    assert not spt.HAVE_MESHING
    assert not hasattr(spt, "vtkTetGenMesher")
    with pytest.raises(spt.MeshingUnavailable, match="TetGen"):
        meshes.generate("drill", 20_000, cache=False)


def test_command_line_without_meshing_names_the_module(tmp_path):
    # An empty mesh cache: a drill meshed earlier (by a build with TetGen) would be read back.
    environment = dict(os.environ, SPT_CACHE_DIR=str(tmp_path / "cache"))
    result = subprocess.run(
        [sys.executable, "-m", "spt", "mesh", "--shape", "drill", "--cells", "20000",
         "--output", str(tmp_path / "drill.vtk")], capture_output=True, text=True, timeout=600,
        env=environment)
    assert result.returncode != 0
    assert "TetGen" in result.stderr and "Traceback" not in result.stderr, result.stderr
