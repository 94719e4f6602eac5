"""The package as a user meets it: `import adjoin` from build/python, a docstring with units on
every public name, help(adjoin.run) reading like a reference, type stubs shipped and agreeing
with the functions' signatures."""
import ast
import inspect
import pathlib
import pydoc
import subprocess
import sys

import adjoin
from conftest import SOURCE

PUBLIC_FUNCTIONS = ["load_scene", "run", "run_many", "read_record", "spectrum", "rotd", "ductility_spectrum",
                    "default_periods", "modes", "joint"]


def test_import_from_the_build_tree_in_a_fresh_interpreter():
    out = subprocess.run([sys.executable, "-c", "import adjoin; print(adjoin.__file__)"], check=True,
                         capture_output=True, text=True).stdout
    assert pathlib.Path(out.strip()).parent.name == "adjoin"


def test_every_public_name_is_documented():
    for name in adjoin.__all__:
        obj = getattr(adjoin, name)
        assert inspect.getdoc(obj), f"adjoin.{name} has no docstring"
    for name in ["mass", "period", "zener"]:
        assert "[" in inspect.getdoc(getattr(adjoin.BuildingBuilder, name)), name  # a unit in brackets


def test_help_of_run_reads_like_a_reference():
    text = pydoc.render_doc(adjoin.run, renderer=pydoc.plaintext)
    for words in ["run(scene", "timeseries", "every", "Returns:", "Raises:", "InputError", "NumericalError",
                  "summary.json", "numpy"]:
        assert words in text, words
    assert "[s]" in inspect.getdoc(adjoin.spectrum) and "[g]" in inspect.getdoc(adjoin.spectrum)
    assert "field" in inspect.getdoc(adjoin.InputError) and "time" in inspect.getdoc(adjoin.NumericalError)


def test_stubs_are_shipped_and_agree_with_the_signatures():
    stub = pathlib.Path(adjoin.__file__).with_name("__init__.pyi")
    assert stub.is_file() and pathlib.Path(adjoin.__file__).with_name("py.typed").is_file()
    tree = ast.parse(stub.read_text())
    stubbed = {n.name: n for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    for name in adjoin.__all__:
        assert name in stubbed, f"{name} is not in __init__.pyi"
    for name in PUBLIC_FUNCTIONS:
        a = stubbed[name].args
        stub_names = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs]
        assert stub_names == list(inspect.signature(getattr(adjoin, name)).parameters), name


def test_the_package_source_is_what_the_build_tree_holds():
    built = pathlib.Path(adjoin.__file__).parent
    for source in (SOURCE / "python" / "adjoin").iterdir():
        if source.suffix in (".py", ".pyi"):
            assert (built / source.name).read_text() == source.read_text(), f"rebuild: {source.name} changed"


def test_reference_page_is_current(tmp_path):
    """docs/reference/python.md is what scripts/python_reference.py writes from the docstrings
    (ADJOIN_UPDATE_DOCS=1 rewrites it)."""
    import importlib.util
    import os

    spec = importlib.util.spec_from_file_location("python_reference", SOURCE / "scripts" / "python_reference.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    page = module.page()
    target = SOURCE / "docs" / "reference" / "python.md"
    if os.environ.get("ADJOIN_UPDATE_DOCS") == "1":
        target.write_text(page)
    assert target.read_text() == page, "docs/reference/python.md is stale: run scripts/python_reference.py"
    for name in adjoin.__all__:
        assert f"## adjoin.{name}" in page
