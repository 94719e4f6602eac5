"""No bad input kills the interpreter: the bad-input catalogue's scenes (tests/bad_inputs/*.toml,
format in tests/test_bad_inputs.cpp) go through adjoin.load_scene and Scene.from_dict, and each
raises the exception class its exit status stands for (2: InputError, a ValueError; 3:
NumericalError, an ArithmeticError), naming the key the catalogue names."""
import os
import pathlib
import re
import tomllib

import pytest

import adjoin
from conftest import RECORDS, SCENES, SOURCE

CATALOGUE = SOURCE / "tests" / "bad_inputs"
# A dotted scene key as a case's expected message quotes it ("contact.1.restitution").
KEY = re.compile(r"\b(?:model|solver|ground|output|building|link|contact)(?:\.[A-Za-z0-9_]+|\[[0-9]+\])+")


def run_cases():
    """Every catalogue case that is `adjoin run SCENE [--set K=V] [--unset K]` (other options
    are about the command line: --out, --quiet), with its exit status."""
    for path in sorted(CATALOGUE.glob("*.toml")):
        with open(path, "rb") as f:
            for case in tomllib.load(f).get("case", []):
                args = case["args"]
                if len(args) < 2 or args[0] != "run" or case.get("exit") not in (0, 2, 3):
                    continue
                if any(f.get("kind") for f in case.get("file", [])) or "env" in case:
                    continue  # folders, FIFOs, environments: about the program, not the scene
                if any("--out" in s or "output folder" in s for s in case.get("stderr", [])) or scene_call(case, "/tmp") is None:
                    continue  # about the output folder or other options of the command line
                yield pytest.param(case, id=f"{path.stem}: {case['name']}")


def placeholders(text, tmp):
    for key, value in {"{tmp}": str(tmp), "{records}": str(RECORDS), "{scenes}": str(SCENES),
                       "{source}": str(SOURCE), "{long}": "x" * 100000}.items():
        text = text.replace(key, value)
    return text


def make_files(case, tmp):
    for f in case.get("file", []):
        path = pathlib.Path(placeholders(f["path"], tmp))
        path.parent.mkdir(parents=True, exist_ok=True)
        data = b""
        if "hex" in f:
            data = bytes.fromhex(f["hex"])
        if "copy" in f:
            data = pathlib.Path(placeholders(f["copy"], tmp)).read_bytes()
        if "text" in f:
            data = placeholders(f["text"], tmp).encode()
        path.write_bytes(data)
        if "append" in f:
            with open(path, "ab") as out:
                out.write(placeholders(f["append"], tmp).encode())
        if "size" in f:
            os.truncate(path, f["size"])


def scene_call(case, tmp):
    """load_scene's arguments from the case's command line (None if it has options load_scene
    does not take)."""
    args = [placeholders(a, tmp) for a in case["args"][1:]]
    scene, sets, unsets, i = args[0], {}, [], 1
    while i < len(args):
        if args[i] in ("--set", "--unset") and i + 1 < len(args):
            if args[i] == "--set":
                key, eq, value = args[i + 1].partition("=")
                if not eq:
                    return None
                sets[key.strip()] = _value(value.strip())
            else:
                unsets.append(args[i + 1])
            i += 2
        elif args[i] == "--out" and i + 1 < len(args):
            i += 2
        elif args[i] in ("--quiet", "-q", "--allow-long"):
            i += 1
        else:
            return None
    return scene, sets, unsets


def _value(text):
    """A --set value as the Python value it stands for (a TOML value, or a bare word)."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def named_keys(case):
    """The scene keys the case's expected message names (dotted, "link[1].x" as "link.1.x")."""
    return [adjoin._adjoin._field_of(k) for text in case.get("stderr", []) for k in KEY.findall(text)]


# Cases whose message names a key but whose InputError carries no field yet (the scene
# readers' gap, not the binding's): listed so that the test says when that changes.
KNOWN_WITHOUT_FIELD = set()  # (every catalogue case that names a key now gives it as .field)


def related(field, key):
    return field == key or field.startswith(key + ".") or key.startswith(field + ".")


def assert_field_named(case, error, sets, unsets):
    """The error's .field is a key the catalogue's message names, or the key of one of the
    case's own edits (an unknown key is the field; the message suggests the known one)."""
    keys = named_keys(case)
    if case["name"] in KNOWN_WITHOUT_FIELD:
        assert error.field is None, f"the library names the field now ({error.field}): take the case off the list"
        return
    if not keys:
        return
    assert error.field is not None, f"no .field; the catalogue names {keys}"
    edited = list(sets) + list(unsets)
    assert any(related(error.field, k) for k in keys + edited), \
        f"field {error.field!r}; the catalogue names {keys}, the case edits {edited}"


@pytest.mark.parametrize("case", list(run_cases()))
def test_catalogue_scene_raises_the_right_exception(case, tmp_path, monkeypatch):
    cwd = pathlib.Path(placeholders(case.get("cwd", "{tmp}"), tmp_path))
    cwd.mkdir(parents=True, exist_ok=True)
    monkeypatch.chdir(cwd)  # relative paths of the case start where the program would run
    make_files(case, tmp_path)
    scene_file, sets, unsets = scene_call(case, tmp_path)
    expected = {0: None, 2: adjoin.InputError, 3: adjoin.NumericalError}[case["exit"]]
    try:
        scene = adjoin.load_scene(scene_file, set=sets, unset=unsets)
    except adjoin.InputError as e:
        assert expected is adjoin.InputError, f"refused a scene `adjoin run` accepts: {e}"
        assert isinstance(e, ValueError)
        assert_field_named(case, e, sets, unsets)
        # The same scene as a dict is refused the same way (when its text is TOML at all).
        try:
            with open(scene_file, "rb") as f:
                d = tomllib.load(f)
        except (tomllib.TOMLDecodeError, OSError, UnicodeDecodeError):
            return
        if sets or unsets or "file" in d.get("ground", {}):
            return  # the edits and relative paths are load_scene's; the dict alone may be valid
        with pytest.raises(adjoin.InputError) as again:
            adjoin.Scene.from_dict(d)
        assert again.value.field == e.field
        return
    # Accepted when read: what `adjoin run` refuses is refused by the run.
    if expected is None:
        return
    with pytest.raises(expected) as caught:
        adjoin.run(scene, timeseries=False)
    # (A refusal of the run as a whole, memory or time, names the keys to change as advice:
    # it is about no one field.)
    if expected is adjoin.NumericalError:
        assert isinstance(caught.value, ArithmeticError)
        assert caught.value.time is not None


def test_input_error_field_is_the_dotted_key():
    with pytest.raises(adjoin.InputError) as caught:
        adjoin.load_scene(SCENES / "buildings" / "two-frames.toml", set={"link.1.slip_ratio": -0.5})
    assert caught.value.field == "link.1.slip_ratio"
    assert "link" in str(caught.value)
    with pytest.raises(ValueError):  # InputError is a ValueError
        adjoin.Scene.from_dict({"name": "x"})


def test_dict_values_that_are_not_toml_name_their_key():
    d = adjoin.load_scene(SCENES / "paper-strong.toml").to_dict()
    d["solver"]["h"] = None
    with pytest.raises(adjoin.InputError) as caught:
        adjoin.Scene.from_dict(d)
    assert caught.value.field == "solver.h"
    d["solver"]["h"] = object()
    with pytest.raises(adjoin.InputError) as caught:
        adjoin.Scene.from_dict(d)
    assert caught.value.field == "solver.h"


def test_unknown_key_names_the_nearest_known_one():
    d = adjoin.load_scene(SCENES / "paper-strong.toml").to_dict()
    d["solver"]["t_edn"] = 3.0
    with pytest.raises(adjoin.InputError) as caught:
        adjoin.Scene.from_dict(d)
    assert caught.value.field == "solver.t_edn"
    assert "t_end" in str(caught.value)


def test_bad_arguments_of_the_spectra_are_input_errors():
    with pytest.raises(adjoin.InputError):
        adjoin.spectrum([0.0, 0.1, float("nan")], 0.01)
    with pytest.raises(adjoin.InputError) as caught:
        adjoin.spectrum([0.0, 0.1], 0.01, damping=1.5)
    assert "damping" in str(caught.value)
    with pytest.raises(adjoin.InputError):
        adjoin.read_record(SOURCE / "README.md")
    with pytest.raises(adjoin.InputError):
        adjoin.read_record(SOURCE / "no-such-file.at2")
