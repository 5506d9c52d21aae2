"""The check that ``import spt`` makes before loading its extensions: the vtk installed beside
the wheel is one the wheel was built for. VTK keeps no C++ ABI between releases and the vtk
wheel's libraries carry no version in their names, so another vtk would load and then fail on a
missing symbol, or worse; this says which vtk is needed instead."""

from typing import List, Tuple


def _version(text: str) -> Tuple[int, ...]:
    parts = []
    for part in text.split("."):
        digits = "".join(c for c in part if c.isdigit()) if part[:1].isdigit() else ""
        if not digits:
            break
        parts.append(int(digits))
    return tuple(parts)


def _clauses(requirement: str) -> List[Tuple[str, Tuple[int, ...]]]:
    """The comparisons of a requirement such as ``vtk==9.5.0`` or ``vtk>=9.7.0,<9.8``."""
    specifiers = requirement.strip()
    if specifiers.startswith("vtk"):
        specifiers = specifiers[3:]
    clauses = []
    for clause in specifiers.replace(" ", "").split(","):
        operator = next(o for o in ("==", ">=", "<=", "<", ">") if clause.startswith(o))
        clauses.append((operator, _version(clause[len(operator):])))
    return clauses


def satisfies(version: str, requirement: str) -> bool:
    """Whether a vtk version (``9.7.2``) meets the requirement (``vtk>=9.7.0,<9.8``)."""
    have = _version(version)
    tests = {"==": lambda v: have == v, ">=": lambda v: have >= v, "<=": lambda v: have <= v,
             "<": lambda v: have < v, ">": lambda v: have > v}
    return all(tests[operator](bound) for operator, bound in _clauses(requirement))


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
