"""The length counter of `make lint` on small sources whose lengths are known by construction."""

import pathlib
import sys

import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent))

import check_lengths  # noqa: E402


def body(lines):
    """``lines`` statement lines of C++ (each one line)."""
    return "".join(f"  x += {i};\n" for i in range(lines))


def cxx_function(name, lines, signature=None):
    """A C++ function of exactly ``lines`` lines, signature and braces included."""
    signature = signature or f"void {name}(int x)"
    return f"{signature}\n{{\n{body(lines - 3)}}}\n"


def lengths(text):
    return {(f.name, f.lines) for f in check_lengths.cxx_functions(text)}


@pytest.mark.parametrize("lines, flagged", [(60, False), (61, True), (200, True)])
def test_a_cxx_function_over_the_limit_is_named(lines, flagged):
    text = "#include <vector>\n\n" + cxx_function("Long", lines) + cxx_function("Short", 5)
    problems = check_lengths.check_text("a.cxx", text)
    assert bool(problems) == flagged, problems
    if flagged:
        assert problems == [f"a.cxx:3: function 'Long' has {lines} lines (at most 60)"]


def test_braces_in_comments_strings_and_preprocessor_lines_are_ignored():
    text = ('// a comment { with a brace\n'
            '/* and { another\n } */\n'
            '#define OPEN {\n'
            'const char* text = "{ \\" {";\n'
            "const char brace = '{';\n"
            'const char* raw = R"glsl(void main() { })glsl";\n'
            'int million = 1\'000\'000;\n'
            + cxx_function("Counted", 8))
    assert lengths(text) == {("Counted", 8)}


def test_methods_in_classes_and_namespaces_and_their_lambdas():
    method = ("  int Get() const\n  {\n    auto f = [](int y) {\n      return y;\n    };\n"
              "    return f(1);\n  }\n")
    text = ("namespace spt\n{\nnamespace\n{\nstruct Helper\n{\n" + method + "};\n}\n"
            "class vtkThing : public vtkObject\n{\npublic:\n" + method + "};\n}\n"
            'extern "C"\n{\n' + cxx_function("Plain", 4) + "}\n")
    functions = check_lengths.cxx_functions(text)
    assert sorted((f.name, f.first, f.lines) for f in functions) == [
        ("Get", 7, 7), ("Get", 19, 7), ("Plain", 30, 4)]


def test_signatures_of_templates_constructors_and_operators():
    text = ("template <typename T, int N = 3>\nT Sum(const T* values)\n{\n  return T();\n}\n"
            "vtkThing::vtkThing()\n  : Values{ 1, 2 }\n  , Other(3)\n{\n  this->A = { 4 };\n}\n"
            "bool operator==(const A& a, const B& b)\n{\n  return true;\n}\n"
            "auto Next(int i) -> int\n{\n  return i + 1;\n}\n"
            "void vtkThing::Release() noexcept\n{\n}\n")
    assert lengths(text) == {("Sum", 5), ("vtkThing::vtkThing", 6), ("operator==", 4),
                             ("Next", 4), ("vtkThing::Release", 3)}


def test_what_is_not_a_function():
    text = ("static const int Table[] = {\n  1, 2,\n};\n"
            "enum Kind\n{\n  A,\n  B\n};\n"
            "static auto lambda = [](int x) {\n  return x;\n};\n"
            "layout(std430, binding = 0) buffer Keys\n{\n  uint keys[];\n};\n"
            "uniform Block\n{\n  vec4 color;\n};\n")
    assert lengths(text) == set()


def test_a_glsl_function():
    text = ("//VTK::System::Dec\n#version 150\nuniform sampler2D table;\n"
            "vec4 shade(vec2 p)\n{\n  if (p.x > 0.0)\n  {\n    return vec4(1.0);\n  }\n"
            "  return vec4(0.0);\n}\n" + cxx_function("main", 61, "void main()"))
    problems = check_lengths.check_text("s.glsl", text)
    assert problems == ["s.glsl:12: function 'main' has 61 lines (at most 60)"]


def test_unmatched_braces_are_an_error_not_a_miss():
    """A function opened differently in two #if branches: two opening braces, one closing."""
    text = "#if A\nvoid f()\n{\n#else\nvoid g()\n{\n#endif\n}\n"
    problems = check_lengths.check_text("u.cxx", text)
    assert problems == ["u.cxx: cannot count its functions: the block from line 2 is never "
                        "closed"]
    problems = check_lengths.check_text("v.cxx", "int x;\n}\n")
    assert problems == ["v.cxx: cannot count its functions: a closing brace without an "
                        "opening one at line 2"]


def python_function(name, lines, indent=""):
    """A Python function of exactly ``lines`` lines, its ``def`` line included."""
    statements = "".join(f"{indent}    x = {i}\n" for i in range(lines - 1))
    return f"{indent}def {name}():\n{statements}"


@pytest.mark.parametrize("lines, flagged", [(60, False), (61, True)])
def test_a_python_function_over_the_limit_is_named(lines, flagged):
    text = ("import os\n\n\n@decorator\n" + python_function("long", lines) + "\n\n"
            "class Thing:\n" + python_function("method", 3, "    "))
    problems = check_lengths.check_text("m.py", text)
    assert problems == ([f"m.py:5: function 'long' has {lines} lines (at most 60)"] if flagged
                        else [])


def test_a_long_nested_python_function_and_its_parent_are_both_named():
    text = "def outer():\n" + python_function("inner", 61, "    ") + "    return inner\n"
    problems = check_lengths.check_text("n.py", text)
    assert problems == ["n.py:1: function 'outer' has 63 lines (at most 60)",
                        "n.py:2: function 'inner' has 61 lines (at most 60)"]


@pytest.mark.parametrize("suffix, line", [("py", "x = 1\n"), ("h", "int x;\n"),
                                          ("glsl", "float x;\n")])
def test_a_file_over_600_lines_is_named(suffix, line):
    assert check_lengths.check_text(f"f.{suffix}", line * 600) == []
    assert check_lengths.check_text(f"f.{suffix}", line * 601) == [
        f"f.{suffix}: 601 lines (at most 600)"]


def test_the_command_line_names_the_files_and_fails(tmp_path, capsys, monkeypatch):
    (tmp_path / "ok.py").write_text(python_function("short", 10))
    (tmp_path / "long.cxx").write_text(cxx_function("Long", 70))
    monkeypatch.chdir(tmp_path)
    assert check_lengths.main(["ok.py"]) == 0
    assert check_lengths.main(["ok.py", "long.cxx"]) == 1
    output = capsys.readouterr()
    assert output.out == "long.cxx:1: function 'Long' has 70 lines (at most 60)\n"
    assert "1 over the limits" in output.err
