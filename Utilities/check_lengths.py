#!/usr/bin/env python3
"""The project's length limits: no source file over 600 lines, no function over 60.

A developer tool (``make lint`` runs it; nothing installs it). It reads the C++ (``.cxx``,
``.h``, ``.c``), GLSL (``.glsl``) and Python (``.py``) files that git tracks, or the files
given on the command line, and prints one line per breach, naming the file, the line and the
function; the exit status is 1 if there is one.

The rules, as counted here:

- A file's lines are its newline-terminated lines, as ``wc -l`` counts them.
- A function's lines run from the first line of its definition to the line of its end, both
  included: blank lines, comments and the docstring count.
- Python: every ``def`` (methods and nested functions too; a nested one also counts in the
  function around it), from the ``def`` line (decorators left out) to ``end_lineno``, by
  :mod:`ast`.
- C++ and GLSL: every function body at file, namespace or class scope (``extern "C"``
  blocks are namespaces here), from the first line of its signature (its return type, or
  ``template <...>``) to its closing brace. Braces inside comments, string and character
  literals (raw strings too) and preprocessor lines are ignored. A lambda, a local class or
  a block inside a function counts as part of that function; a lambda assigned at namespace
  scope, an initializer list, an enum or a GLSL interface block is not a function. Brace
  initializers in a constructor's member initializer list are part of its signature. Braces
  that do not match (e.g. a function opened differently in two ``#if`` branches) are an
  error that names the file, never a silent miss.
"""

from __future__ import annotations

import argparse
import ast
import bisect
import pathlib
import re
import subprocess
import sys
from typing import Iterable, List, NamedTuple, Optional, Sequence

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 60
CXX_SUFFIXES = (".cxx", ".h", ".c", ".glsl")
PYTHON_SUFFIXES = (".py",)


class Function(NamedTuple):
    """A function found in a source file: its name and its first and last lines (1-based)."""

    name: str
    first: int
    last: int

    @property
    def lines(self) -> int:
        return self.last - self.first + 1


class SourceError(ValueError):
    """A file the counter cannot read as the language its name says."""


# --------------------------------------------------------------------------------------------
# Python
# --------------------------------------------------------------------------------------------

def python_functions(text: str) -> List[Function]:
    """Every function and method of a Python source, nested ones included."""
    try:
        tree = ast.parse(text)
    except SyntaxError as error:
        raise SourceError(f"not valid Python: {error}") from error
    return [Function(node.name, node.lineno, node.end_lineno) for node in ast.walk(tree)
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))]


# --------------------------------------------------------------------------------------------
# C++ and GLSL: blank what braces in it must not count, then match the braces
# --------------------------------------------------------------------------------------------

_RAW_STRING = re.compile(r'R"([^()\\\s]{0,16})\(')


def _skip_quoted(text: str, start: int, quote: str) -> int:
    """The index after the literal that opens with ``quote`` at ``start``."""
    i = start + 1
    while i < len(text) and text[i] != quote:
        i += 2 if text[i] == "\\" else 1
    return i + 1


def _literal_end(text: str, i: int) -> Optional[int]:
    """The end of the comment, literal or preprocessor line at ``i``, or None if none is."""
    if text.startswith("//", i):
        end = text.find("\n", i)
        return len(text) if end < 0 else end
    if text.startswith("/*", i):
        end = text.find("*/", i + 2)
        return len(text) if end < 0 else end + 2
    char = text[i]
    if char == '"':
        raw = _RAW_STRING.match(text, i - 1) if i > 0 else None
        if raw:
            end = text.find(")" + raw.group(1) + '"', raw.end())
            return len(text) if end < 0 else end + len(raw.group(1)) + 2
        return _skip_quoted(text, i, '"')
    if char == "'":
        # A digit separator (1'000) is not a character literal.
        token = re.search(r"[\w.]*$", text[max(0, i - 64):i]).group(0)
        return None if token[:1].isdigit() else _skip_quoted(text, i, "'")
    if char == "#" and text[text.rfind("\n", 0, i) + 1:i].strip() == "":
        end = i
        while True:
            end = text.find("\n", end)
            if end < 0 or text[end - 1] != "\\":
                return len(text) if end < 0 else end
            end += 1
    return None


def blank_non_code(text: str) -> str:
    """``text`` with its comments, string and character literals and preprocessor lines
    replaced by spaces (newlines kept, so that offsets and line numbers stay)."""
    out = []
    i = 0
    while i < len(text):
        end = _literal_end(text, i)
        if end is None:
            out.append(text[i])
            i += 1
        else:
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
    return "".join(out)


def _depth_zero(head: str) -> str:
    """``head`` with whatever is inside parentheses blanked."""
    out, depth = [], 0
    for char in head:
        depth -= char == ")"
        out.append(char if depth == 0 else " ")
        depth += char == "("
    return "".join(out)


def _strip_template(head: str) -> str:
    """``head`` without its leading access specifiers and ``template <...>`` clauses."""
    while True:
        head = re.sub(r"^\s*(public|protected|private)\s*:(?!:)", "", head)
        match = re.match(r"\s*template\s*<", head)
        if not match:
            return head
        depth, i = 1, match.end()
        while i < len(head) and depth:
            depth += {"<": 1, ">": -1}.get(head[i], 0)
            i += 1
        head = head[i:]


_ASSIGNMENT = re.compile(r"(?<![=<>!+\-*/%&|^])=(?!=)")
_QUALIFIER_END = re.compile(r"(\)|\bconst|\boverride|\bfinal|\bnoexcept|\bmutable|\bvolatile|"
                            r"&|\btry)\s*$")


def _initializer_list(head: str) -> bool:
    """Whether ``head`` is a constructor's signature with a member initializer list."""
    flat = _depth_zero(head)
    close = flat.find(")")
    return close >= 0 and re.search(r"(?<!:):(?!:)", flat[close:]) is not None


def classify(head: str) -> str:
    """What a brace at file, namespace or class scope opens, from the text before it:
    ``namespace``, ``class``, ``function`` or ``other``."""
    head = _strip_template(head)
    flat = _depth_zero(re.sub(r"\boperator\s*[^\s(]+", "operator", head))
    before_call = flat.split("(", 1)[0]
    if re.search(r"\bnamespace\b", before_call) or re.fullmatch(r"\s*extern\s*", flat):
        return "namespace"
    if re.search(r"\b(class|struct|union)\b", before_call):
        return "class"
    if re.search(r"\benum\b", before_call) or "(" not in flat or _ASSIGNMENT.search(flat):
        return "other"
    if _QUALIFIER_END.search(flat) or "->" in flat or _initializer_list(head):
        return "function"
    return "other"


def _function_name(head: str) -> str:
    head = _strip_template(head)
    operator = re.search(r"[\w:~]*operator\s*(\(\)|[^\s(]+)", head)
    if operator:
        return re.sub(r"\s+", "", operator.group(0))
    match = re.search(r"([~\w:]+)\s*$", head.split("(", 1)[0])
    return match.group(1) if match else "(unnamed)"


class _Scanner:
    """Matches the braces of blanked C++ or GLSL and collects the functions."""

    def __init__(self, code: str):
        self.code = code
        self.newlines = [i for i, char in enumerate(code) if char == "\n"]
        self.stack: List[tuple] = [("file", 0, "")]
        self.head_start = 0
        self.functions: List[Function] = []

    def line(self, offset: int) -> int:
        return bisect.bisect_left(self.newlines, offset) + 1

    def open(self, i: int) -> None:
        kind = self.stack[-1][0]
        if kind in ("function", "inner", "other", "initializer"):
            self.stack.append(("inner", i, ""))
            return
        head = self.code[self.head_start:i]
        previous = head.rstrip()[-1:]
        if _initializer_list(head) and (previous.isalnum() or previous in "_>"):
            self.stack.append(("initializer", i, ""))
            return
        start = self.head_start + len(head) - len(_strip_access(head).lstrip())
        self.stack.append((classify(head), start, _function_name(head)))
        self.head_start = i + 1

    def close(self, i: int) -> None:
        if len(self.stack) == 1:
            raise SourceError(f"a closing brace without an opening one at line {self.line(i)}")
        kind, start, name = self.stack.pop()
        if kind == "function":
            self.functions.append(Function(name, self.line(start), self.line(i)))
        if kind != "initializer" and self.stack[-1][0] in ("file", "namespace", "class"):
            self.head_start = i + 1

    def scan(self) -> List[Function]:
        for i, char in enumerate(self.code):
            if char == "{":
                self.open(i)
            elif char == "}":
                self.close(i)
            elif char == ";" and self.stack[-1][0] in ("file", "namespace", "class"):
                self.head_start = i + 1
        if len(self.stack) > 1:
            kind, start, _ = self.stack[-1]
            raise SourceError(f"the block from line {self.line(start)} is never closed")
        return self.functions


def _strip_access(head: str) -> str:
    return re.sub(r"^\s*((public|protected|private)\s*:(?!:)\s*)+", "", head)


def cxx_functions(text: str) -> List[Function]:
    """Every function body at file, namespace or class scope of a C++ or GLSL source."""
    return _Scanner(blank_non_code(text)).scan()


# --------------------------------------------------------------------------------------------
# The check
# --------------------------------------------------------------------------------------------

def check_text(path: str, text: str, max_file: int = MAX_FILE_LINES,
               max_function: int = MAX_FUNCTION_LINES) -> List[str]:
    """The breaches of one source, one message each (empty when there is none)."""
    problems = []
    lines = text.count("\n")
    if lines > max_file:
        problems.append(f"{path}: {lines} lines (at most {max_file})")
    try:
        functions = (python_functions(text) if path.endswith(PYTHON_SUFFIXES)
                     else cxx_functions(text))
    except SourceError as error:
        return problems + [f"{path}: cannot count its functions: {error}"]
    for function in sorted(functions, key=lambda f: f.first):
        if function.lines > max_function:
            problems.append(f"{path}:{function.first}: function '{function.name}' has "
                            f"{function.lines} lines (at most {max_function})")
    return problems


def tracked_sources(root: pathlib.Path) -> List[pathlib.Path]:
    """The C++, GLSL and Python files that git tracks under ``root``."""
    patterns = [f"*{suffix}" for suffix in CXX_SUFFIXES + PYTHON_SUFFIXES]
    result = subprocess.run(["git", "ls-files", "--", *patterns], cwd=root, check=True,
                            capture_output=True, text=True)
    return [root / name for name in result.stdout.splitlines()]


def check_files(paths: Iterable[pathlib.Path], root: pathlib.Path, max_file: int,
                max_function: int) -> List[str]:
    problems = []
    for path in paths:
        if not path.name.endswith(CXX_SUFFIXES + PYTHON_SUFFIXES):
            continue
        name = str(path.relative_to(root)) if path.is_relative_to(root) else str(path)
        problems += check_text(name, path.read_text(encoding="utf-8", errors="replace"),
                               max_file, max_function)
    return problems


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("paths", nargs="*", type=pathlib.Path,
                        help="the files to check (default: every tracked source)")
    parser.add_argument("--max-file-lines", type=int, default=MAX_FILE_LINES)
    parser.add_argument("--max-function-lines", type=int, default=MAX_FUNCTION_LINES)
    arguments = parser.parse_args(argv)
    root = pathlib.Path.cwd().resolve()
    paths = ([path.resolve() for path in arguments.paths] if arguments.paths
             else tracked_sources(root))
    problems = check_files(paths, root, arguments.max_file_lines, arguments.max_function_lines)
    for problem in problems:
        print(problem)
    if problems:
        print(f"{len(problems)} over the limits: files of at most {arguments.max_file_lines} "
              f"lines, functions of at most {arguments.max_function_lines}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    raise SystemExit(main())
