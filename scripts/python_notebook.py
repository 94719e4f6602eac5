#!/usr/bin/env python3
"""Writes examples/python/two_frames.ipynb from examples/python/two_frames.py: the same code as a
notebook (Jupyter's format 4, plain JSON: no tool beyond Python is needed to make it), a cell
per top-level block, the docstring as its first text, and a last cell that runs the study.

    /usr/bin/python3 scripts/python_notebook.py [--check]

--check: exit 1 if the notebook differs from what the script would write (a test runs it, so
the two cannot drift apart).
"""
import ast
import json
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "examples" / "python" / "two_frames.py"
NOTEBOOK = SCRIPT.with_suffix(".ipynb")


def cell(kind, text):
    lines = text.rstrip("\n").split("\n")
    source = [line + "\n" for line in lines[:-1]] + [lines[-1]]
    c = {"cell_type": kind, "metadata": {}, "source": source}
    if kind == "code":
        c.update(execution_count=None, outputs=[])
    return c


def notebook():
    text = SCRIPT.read_text()
    tree = ast.parse(text)
    lines = text.split("\n")
    cells = [cell("markdown", "# " + ast.get_docstring(tree).strip())]
    body = [n for n in tree.body if not (isinstance(n, ast.Expr) and isinstance(n.value, ast.Constant))]
    body = [n for n in body if not (isinstance(n, ast.If))]  # the script's `if __name__ == "__main__"`
    for node in body:
        start = node.lineno - 1 - len(getattr(node, "decorator_list", []))
        cells.append(cell("code", "\n".join(lines[start:node.end_lineno])))
    cells.append(cell("code", 'main(["out/python-two-frames", "--jobs", "2"])'))
    return {"cells": cells, "metadata": {"kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
                                         "language_info": {"name": "python"}}, "nbformat": 4, "nbformat_minor": 5}


def main():
    made = json.dumps(notebook(), indent=1) + "\n"
    if "--check" in sys.argv:
        if not NOTEBOOK.exists() or NOTEBOOK.read_text() != made:
            print(f"{NOTEBOOK} is not what {SCRIPT.name} makes: run scripts/python_notebook.py", file=sys.stderr)
            return 1
        return 0
    NOTEBOOK.write_text(made)
    return 0


if __name__ == "__main__":
    sys.exit(main())
