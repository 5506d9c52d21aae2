"""The check `import spt` makes of the vtk beside a wheel: a vtk the wheel was not built for is
refused with both versions and the commands that install a matching pair."""

import pytest

from spt import vtkcheck


@pytest.mark.parametrize("version, requirement, expected", [
    ("9.5.0", "vtk==9.5.0", True),
    ("9.5.2", "vtk==9.5.0", False),
    ("9.7.0", "vtk>=9.7.0,<9.8", True),
    ("9.7.2", "vtk>=9.7.0,<9.8", True),
    ("9.8.0", "vtk>=9.7.0,<9.8", False),
    ("9.6.2", "vtk>=9.7.0,<9.8", False),
    ("9.7.2rc1", "vtk>=9.7.0, <9.8", True),
])
def test_requirement(version, requirement, expected):
    assert vtkcheck.satisfies(version, requirement) is expected


def test_a_mismatched_vtk_names_both_versions_and_the_commands():
    with pytest.raises(ImportError) as raised:
        vtkcheck.check("9.5.0", "9.7.0", "vtk>=9.7.0,<9.8")
    message = str(raised.value)
    assert "VTK 9.7.0" in message and "vtk 9.5.0 is installed" in message
    assert 'pip install "vtk>=9.7.0,<9.8"' in message
    assert "make wheel VTK_WHEEL_VERSION=9.5.0" in message


def test_a_matching_vtk_or_a_build_with_its_own_vtk_passes():
    vtkcheck.check("9.7.2", "9.7.0", "vtk>=9.7.0,<9.8")
    vtkcheck.check("9.2.6", "9.2.6", "")
