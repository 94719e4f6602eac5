#!/usr/bin/env python3
"""Writes docs/reference/python.md, the reference of every public name of the `adjoin`
package, from the package's own docstrings (python/tests/test_package.py checks that the page
is current).

Usage: PYTHONPATH=build/python /usr/bin/python3 scripts/python_reference.py [OUT]
       (default OUT: docs/reference/python.md next to this script's project)
"""
import inspect
import re
import pathlib
import sys

HEADER = """# The Python package: reference

Every public name of `import adjoin` (SPEC §8), generated from the package's docstrings by
`scripts/python_reference.py`; a test checks that this page is current. How to build and
install the package: [use from Python](../how-to/use-from-python.md).
"""


def annotation(a):
    # Written as a string in the source (and so quoted again by postponed evaluation).
    return a.strip("'\"") if isinstance(a, str) else getattr(a, "__name__", str(a))


def formatted(sig):
    """A signature as its source spells it (annotations unquoted)."""
    parts, star = [], False
    for p in sig.parameters.values():
        if p.kind == p.KEYWORD_ONLY and not star:
            parts.append("*")
            star = True
        text = p.name
        if p.annotation is not p.empty:
            text += f": {annotation(p.annotation)}"
        if p.default is not p.empty:
            text += f" = {p.default!r}"
        parts.append(text)
    out = f"({', '.join(parts)})"
    if sig.return_annotation is not sig.empty:
        out += f" -> {annotation(sig.return_annotation)}"
    return out


def signature(obj, name):
    try:
        return name + formatted(inspect.signature(obj))
    except (TypeError, ValueError):
        # A compiled function: pybind11 puts its signature on the docstring's first line.
        first = (inspect.getdoc(obj) or name).splitlines()[0]
        first = re.sub(r"self: [\w.]+(, )?", "", first)
        return first.replace("adjoin._adjoin.", "")


def doc_block(obj):
    doc = inspect.getdoc(obj) or ""
    # pybind11 puts the signature first: it is shown in the heading's code line already.
    lines = doc.splitlines()
    if lines and "(" in lines[0] and "->" in lines[0]:
        lines = lines[1:]
    text = "\n".join(lines).strip()
    return f"```\n{text}\n```\n" if text else ""


def members(cls):
    """The class's own public methods and properties (not those it inherits)."""
    for name, member in sorted(vars(cls).items()):
        if name.startswith("_") and name != "__init__":
            continue
        if name == "__init__" and inspect.isfunction(member):
            continue  # a Python class made by the package's functions, not by users
        if isinstance(member, (classmethod, staticmethod)):
            member = member.__func__
        if isinstance(member, property) or inspect.isroutine(member) or inspect.ismethoddescriptor(member):
            yield name, member


def page():
    import adjoin

    out = [HEADER]
    for name in adjoin.__all__:
        obj = getattr(adjoin, name)
        out.append(f"## adjoin.{name}\n")
        if inspect.isclass(obj):
            bases = [b.__name__ for b in obj.__bases__ if b is not object and not b.__name__.startswith("pybind11")]
            out.append(f"`class {name}{'(' + ', '.join(bases) + ')' if bases else ''}`\n")
            out.append(doc_block(obj))
            for mname, member in members(obj):
                target = member.fget if isinstance(member, property) else member
                if mname in ("__init__",) and not inspect.getdoc(target):
                    continue
                if isinstance(member, property):
                    out.append(f"- `{mname}` (property)\n")
                    target = member
                else:
                    out.append(f"- `{signature(target, mname)}`\n")
                block = doc_block(target)
                if block:
                    out.append("\n".join("  " + l if l else l for l in block.splitlines()) + "\n")
        else:
            out.append(f"`{signature(obj, name)}`\n")
            out.append(doc_block(obj))
    return "\n".join(out)


def main():
    root = pathlib.Path(__file__).resolve().parents[1]
    target = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else root / "docs" / "reference" / "python.md"
    target.write_text(page())
    print(f"wrote {target}")


if __name__ == "__main__":
    main()
