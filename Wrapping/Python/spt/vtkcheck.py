"""The check that ``import spt`` makes before loading its extensions: the vtk installed beside
the wheel is one the wheel was built for. VTK keeps no C++ ABI between releases and the vtk
wheel's libraries carry no version in their names, so another vtk would load and then fail on a
missing symbol, or worse; this says which vtk is needed instead."""

import operator
from typing import Tuple

# The comparisons of a requirement, the two-character ones first (they start with the others).
_OPERATORS = {"==": operator.eq, ">=": operator.ge, "<=": operator.le, "<": operator.lt,
              ">": operator.gt}


def _version(text: str) -> Tuple[int, ...]:
    parts = []
    for part in text.split("."):
        digits = "".join(c for c in part if c.isdigit()) if part[:1].isdigit() else ""
        if not digits:
            break
        parts.append(int(digits))
    return tuple(parts)


def satisfies(version: str, requirement: str) -> bool:
    """Whether a vtk version (``9.7.2``) meets the requirement (``vtk>=9.7.0,<9.8``)."""
    specifiers = requirement.strip()
    if specifiers.startswith("vtk"):
        specifiers = specifiers[3:]
    for clause in specifiers.replace(" ", "").split(","):
        symbol = next(o for o in _OPERATORS if clause.startswith(o))
        if not _OPERATORS[symbol](_version(version), _version(clause[len(symbol):])):
            return False
    return True


def check(installed: str, built: str, requirement: str) -> None:
    """Raise ImportError naming both versions and what to install where ``installed`` does not
    meet ``requirement`` (empty: a build with its own VTK, nothing to check)."""
    if not requirement or satisfies(installed, requirement):
        return
    raise ImportError(
        f"spt-volume was built against VTK {built} and requires {requirement}, but vtk "
        f"{installed} is installed: its libraries are not compatible with this wheel's "
        f"extensions. Install the vtk it was built for (pip install \"{requirement}\"), or a "
        f"spt-volume wheel built for vtk {installed} (from a clone of SPT: make wheel "
        f"VTK_WHEEL_VERSION={installed}, then pip install dist/spt_volume-*.whl).")
