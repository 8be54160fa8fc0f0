"""No name of a result cube spelt outside its schema: the Python package and post-processing
(src/post) read the names of the cube's coordinates, variables, attributes and metrics from
the schema (pcrf._names in Python, cube_vocabulary and the metric handles in C++). The names
are the schema's own (pcrf.vocabulary()), so a literal added later fails here."""
import ast
import pathlib

import pcrf
from pcrf import _names

SOURCE = pathlib.Path(__file__).resolve().parents[2] / "src"

# Literals equal to a cube name that name something else, each with what it names.
NOT_CUBE_NAMES = {
    ("__init__.py", "record"): "the keyword record= of pcrf.record_measures (a record file)",
    ("__init__.py", "uplift_threshold_g"): "a property of pcrf frame --json (Frame.threshold)",
    ("cli.py", "status"): "the figure kind `pcrf plot status` (the module pcrf.plot.status)",
    ("table3.py", "record"): "a column of bench/paper_comparison.py's CSV, not of a cube",
}


def schema_names():
    vocabulary = pcrf.vocabulary()
    return set(vocabulary["cube_names"].values()) | {m["name"] for m in vocabulary["metrics"]}


def docstrings(tree):
    """The docstring nodes of a module, its classes and functions (prose, not names)."""
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant):
                found.add(id(first.value))
    return found


def python_literals(path):
    """(line, text) of each string literal of a Python file, docstrings and f-string text left out."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    skipped = docstrings(tree)
    for node in ast.walk(tree):
        if isinstance(node, ast.JoinedStr):
            skipped.update(id(v) for v in node.values)
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in skipped:
            yield node.lineno, node.value


def cpp_literals(path):
    """(line, text) of each string literal of a C++ file, comments left out."""
    text, at, line = path.read_text(encoding="utf-8"), 0, 1
    while at < len(text):
        c = text[at]
        if text.startswith("//", at):
            at = text.find("\n", at)
            at = len(text) if at < 0 else at
            continue
        if text.startswith("/*", at):
            end = text.find("*/", at) + 2
            line += text.count("\n", at, end)
            at = end
            continue
        if c == "'":  # a character literal ('"' is one)
            at = text.index("'", at + 1 + (text[at + 1] == "\\")) + 1
            continue
        if c == '"':
            end = at + 1
            while text[end] != '"':
                end += 2 if text[end] == "\\" else 1
            yield line, text[at + 1:end]
            at = end + 1
            continue
        line += c == "\n"
        at += 1


def spelt(files, literals, names):
    hits = []
    for path in files:
        for line, value in literals(path):
            if value in names and (path.name, value) not in NOT_CUBE_NAMES:
                hits.append(f"{path.relative_to(SOURCE)}:{line}: \"{value}\"")
    return hits


def test_the_schema_gives_the_names_the_module_reads():
    names = schema_names()
    assert {_names.RECORD, _names.STATUS, _names.IDA_INTENSITY, _names.THETA_MAX} <= names
    assert set(_names.METRICS) <= names and _names.THETA_MAX in _names.METRICS
    assert len(names) > 40, sorted(names)


def test_an_unknown_role_fails_when_read():
    try:
        _names.NO_SUCH_ROLE
    except AttributeError as e:
        assert "NO_SUCH_ROLE" in str(e)
    else:
        raise AssertionError("an unknown role gave a name")


def test_the_python_package_spells_no_cube_name():
    package = SOURCE / "python" / "pcrf"
    files = sorted(p for p in package.rglob("*.py") if p.name != "_names.py")
    assert len(files) > 10
    hits = spelt(files, python_literals, schema_names())
    assert not hits, "cube names spelt as literals (read them from pcrf._names):\n" + "\n".join(hits)


def test_post_processing_spells_no_cube_name():
    files = sorted((SOURCE / "post").rglob("*.[ch]pp"))
    assert len(files) > 10
    hits = spelt(files, cpp_literals, schema_names())
    assert not hits, "cube names spelt as literals (use study::vocabulary or the metric handles):\n" + "\n".join(hits)


def test_a_literal_added_is_found(tmp_path):
    python = tmp_path / "added.py"
    python.write_text('"""A docstring may say record."""\nx = row["status"]\ny = f"{row} status"\n')
    cpp = tmp_path / "added.cpp"
    cpp.write_text('// "status" in a comment\nauto c = \'"\';\nauto s = layout.find("ida_intensity");\n')
    names = schema_names()
    assert [v for _, v in python_literals(python) if v in names] == ["status"]
    assert [(n, v) for n, v in cpp_literals(cpp) if v in names] == [(3, "ida_intensity")]
