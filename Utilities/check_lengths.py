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

# Whatever starts first wins, so that a comment's quote or a string's slashes do not count.
# A number is matched only to keep its digit separators (1'000) from opening a character
# literal.
_NON_CODE = re.compile(r"""
    (?P<number>\b\d[\w.']*)
  | //[^\n]* | /\*.*?(?:\*/|\Z)
  | R"(?P<delimiter>[^()\\\s]{0,16})\(.*?(?:\)(?P=delimiter)"|\Z)
  | "(?:\\.|[^"\\])*"? | '(?:\\.|[^'\\])*'?
  | ^[ \t]*\#(?:[^\n]*\\\n)*[^\n]*
""", re.VERBOSE | re.DOTALL | re.MULTILINE)


def blank_non_code(text: str) -> str:
    """``text`` with its comments, string and character literals and preprocessor lines
    replaced by spaces (newlines kept, so that offsets and line numbers stay)."""
    return _NON_CODE.sub(lambda match: match.group() if match.group("number")
                         else re.sub(r"[^\n]", " ", match.group()), text)


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
    ``scope`` (a namespace, class or ``extern`` block), ``function`` or ``other``."""
    head = _strip_template(head)
    flat = _depth_zero(re.sub(r"\boperator\s*[^\s(]+", "operator", head))
    before_call = flat.split("(", 1)[0]
    if (re.search(r"\b(namespace|class|struct|union)\b", before_call)
            or re.fullmatch(r"\s*extern\s*", flat)):
        return "scope"
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


def cxx_functions(text: str) -> List[Function]:
    """Every function body at file, namespace or class scope of a C++ or GLSL source.

    A stack of the open blocks, each (kind, first offset, name): ``scope`` for the file, a
    namespace or a class, where a block's head (the text since the last ``;``, ``{`` or
    ``}``) says what it opens; ``function``, ``other``, and ``inner`` for every block inside
    those two; ``initializer`` for a brace initializer in a constructor's signature, which
    does not end that signature."""
    code = blank_non_code(text)
    newlines = [i for i, char in enumerate(code) if char == "\n"]

    def line(offset: int) -> int:
        return bisect.bisect_left(newlines, offset) + 1

    stack = [("scope", 0, "")]
    functions: List[Function] = []
    head_start = 0
    for match in re.finditer(r"[{};]", code):
        i, char, at_scope = match.start(), match.group(), stack[-1][0] == "scope"
        head = code[head_start:i]
        if char == ";" and at_scope:
            head_start = i + 1
        elif char == "{" and not at_scope:
            stack.append(("inner", i, ""))
        elif char == "{" and _initializer_list(head) and re.search(r"[\w>]\s*$", head):
            stack.append(("initializer", i, ""))
        elif char == "{":
            signature = re.sub(r"^\s*((public|protected|private)\s*:(?!:)\s*)+", "", head)
            start = head_start + len(head) - len(signature.lstrip())
            stack.append((classify(head), start, _function_name(head)))
            head_start = i + 1
        elif char == "}":
            if len(stack) == 1:
                raise SourceError(f"a closing brace without an opening one at line {line(i)}")
            kind, start, name = stack.pop()
            if kind == "function":
                functions.append(Function(name, line(start), line(i)))
            if kind != "initializer" and stack[-1][0] == "scope":
                head_start = i + 1
    if len(stack) > 1:
        raise SourceError(f"the block from line {line(stack[-1][1])} is never closed")
    return functions


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
