"""The package's surface: docstrings on every public function, the stub of the compiled
module covering its functions, the exception hierarchy."""

import ast
import inspect
import pathlib

import mortar
from mortar import _mortar, laws

STUB = pathlib.Path(mortar.__file__).with_name("_mortar.pyi")


def test_public_functions_have_docstrings():
    public = [getattr(mortar, n) for n in mortar.__all__] + [getattr(laws, n) for n in laws.__all__]
    public += [mortar.Coupling.weighted_gap, mortar.Coupling.normal_gaps]
    for obj in public:
        if callable(obj):
            doc = inspect.getdoc(obj)
            assert doc and len(doc) > 40, obj
    doc = inspect.getdoc(mortar.couple)
    for word in ("Args:", "Returns:", "Raises:", "Copies:", "length", "0-based"):
        assert word in doc


def test_stub_covers_the_compiled_module():
    tree = ast.parse(STUB.read_text())
    stubbed = {n.name for n in tree.body if isinstance(n, ast.FunctionDef)}
    compiled = {n for n in dir(_mortar) if not n.startswith("_") and callable(getattr(_mortar, n))}
    assert stubbed == compiled
    assert (STUB.parent / "py.typed").exists()


def test_exception_hierarchy():
    assert issubclass(mortar.InvalidInputError, ValueError)
    assert issubclass(mortar.MeshFileError, OSError)
    for name in ("InvalidInputError", "GeometryError", "NoOverlapError", "CoverageError",
                 "MeshFileError", "SceneError", "LawError"):
        assert issubclass(getattr(mortar, name), mortar.MortarError)
    assert issubclass(mortar.MortarError, Exception)


def test_readme_example_runs():
    # The README's Python example, as written, with what its comments say.
    readme = (pathlib.Path(__file__).resolve().parents[2] / "README.md").read_text()
    section = readme.split("## Python", 1)[1]
    code = section.split("```python\n", 1)[1].split("```", 1)[0]
    scope = {}
    exec(compile(code, "README.md", "exec"), scope)
    c = scope["c"]
    assert abs(c.D.sum() - 1.0) < 1e-14 and c.stats["pairs"] == 324
    assert abs(scope["gap"]).max() < 1e-17
