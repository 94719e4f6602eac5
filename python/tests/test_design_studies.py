"""adjoin.ida and adjoin.fragility (SPEC §9) against `adjoin ida` and `adjoin fragility` on the
same inputs: the same numbers, and bad keywords named by InputError.field."""
import json
import math
import shutil
import subprocess

import numpy as np
import pytest

import adjoin
from conftest import SOURCE

SCENE = SOURCE / "examples" / "buildings" / "yielding-frames-no-damper.toml"
PEER = SOURCE / "records" / "real" / "peer"
SUITE = [PEER / "RSN1044_DirRot2.AT2", PEER / "RSN175_IMPVALL.H_H-E12140.AT2"]

# Stripes: 6 records x 4 levels with event counts that rise with IM but do not separate the
# runs (a fit exists). Traces: records with their own levels (the IM-at-first-event fit too).
STRIPES = {
    "r1": [0, 0, 1, 1], "r2": [0, 1, 0, 1], "r3": [0, 0, 0, 1],
    "r4": [1, 0, 1, 1], "r5": [0, 0, 1, 0], "r6": [0, 1, 1, 1],
}
LEVELS = [0.1, 0.2, 0.4, 0.8]
TRACES = {
    "r1": [(0.1, 0), (0.15, 0), (0.225, 1)], "r2": [(0.1, 0), (0.15, 1)],
    "r3": [(0.1, 0), (0.15, 0), (0.225, 0), (0.3375, 1)], "r4": [(0.1, 1)],
    "r5": [(0.1, 0), (0.15, 0), (0.225, 0)],
}


def write_table(path, rows):
    with open(path, "w") as f:
        f.write("record,im,scale,A.drift_ratio_max,contact1.impacts\n")
        for record, im, event in rows:
            f.write(f"{record},{im!r},1,{0.03 if event else 0.01!r},{3 if event else 0}\n")


def stripe_rows():
    return [(r, im, e) for r, events in STRIPES.items() for im, e in zip(LEVELS, events)]


def trace_rows():
    return [(r, im, e) for r, runs in TRACES.items() for im, e in runs]


def cli_fragility(adjoin_cli, table, out, event, *extra):
    subprocess.run([adjoin_cli, "fragility", str(table), "--event", event, "--out", str(out), *extra], check=True,
                   capture_output=True)
    return json.loads(out.read_text())


def assert_same(py, cli):
    """Every number of the CLI's JSON equal (to 1e-12) to the Python dict's, key by key."""
    if isinstance(cli, dict):
        for key, value in cli.items():
            if key in ("file", "label", "method"):
                continue
            assert key in py, key
            assert_same(py[key], value)
    elif isinstance(cli, list):
        assert len(py) == len(cli)
        for a, b in zip(py, cli):
            assert_same(a, b)
    elif isinstance(cli, float):
        assert py is not None and math.isclose(py, cli, rel_tol=1e-12, abs_tol=0.0), (py, cli)
    else:
        assert py == cli, (py, cli)


@pytest.mark.parametrize("rows", [stripe_rows, trace_rows])
def test_fragility_equals_the_cli(tmp_path, adjoin_cli, rows):
    table = tmp_path / "ida.csv"
    write_table(table, rows())
    cli = cli_fragility(adjoin_cli, table, tmp_path / "f.json", "A.drift_ratio_max > 0.02", "--bootstrap", "200",
                        "--seed", "7", "--at", "0.3")
    py = adjoin.fragility(table, "A.drift_ratio_max > 0.02", bootstrap=200, seed=7, at=0.3)
    assert cli["fitted"] and py["fitted"]
    assert_same(py, cli)
    assert (py["first_event"] is not None) == (rows is trace_rows)


def test_fragility_of_columns_equals_that_of_the_file(tmp_path):
    table = tmp_path / "ida.csv"
    write_table(table, stripe_rows())
    columns = {
        "record": [r for r, _, _ in stripe_rows()],
        "im": np.array([im for _, im, _ in stripe_rows()]),
        "contact1.impacts": np.array([3.0 if e else 0.0 for _, _, e in stripe_rows()]),
    }
    a = adjoin.fragility(columns, "contact1.impacts > 0", bootstrap=100)
    b = adjoin.fragility(table, "contact1.impacts > 0", bootstrap=100)
    assert a["theta"] == b["theta"] and a["beta"] == b["beta"] and a["bootstrap"] == b["bootstrap"]
    assert list(a["n"]) == [6, 6, 6, 6] and list(a["events"]) == [1, 2, 4, 5]


def read_ida_csv(path):
    lines = path.read_text().splitlines()
    return lines[0].split(","), [line.split(",") for line in lines[1:]]


def assert_rows_equal(py, header, rows):
    """The Python columns hold the CLI's ida.csv, bit for bit (the CLI writes the shortest text
    that reads back to the same double)."""
    assert list(py)[:len(header)] == header
    assert len(py["im"]) == len(rows)
    for k, name in enumerate(header):
        cells = [r[k] for r in rows]
        if name == "record":
            assert list(py[name]) == cells
        else:
            np.testing.assert_array_equal(py[name], np.array([float(c) if c else math.nan for c in cells]), err_msg=name)


def test_ida_stripes_equal_the_cli(tmp_path, adjoin_cli):
    out = tmp_path / "ida"
    subprocess.run([adjoin_cli, "ida", str(SCENE), "--suite", *map(str, SUITE), "--im", "pga", "--levels", "0.2,0.5",
                    "--jobs", "2", "--out", str(out), "-q"], check=True, capture_output=True)
    header, rows = read_ida_csv(out / "ida.csv")
    py = adjoin.ida(SCENE, SUITE, im="pga", levels=[0.2, 0.5], jobs=2)
    assert len(rows) == 4
    assert_rows_equal(py, header, rows)
    assert list(py["error"]) == [""] * 4 and not py["capacity_event"].any()
    fit = adjoin.fragility(py, "contact1.impacts > 10", bootstrap=0)
    assert list(fit["n"]) == [2, 2] and list(fit["events"]) == [1, 1]


def test_ida_traces_equal_the_cli(tmp_path, adjoin_cli):
    out = tmp_path / "ida"
    capacity = "A.drift_ratio_max > 0.03"
    subprocess.run([adjoin_cli, "ida", str(SCENE), "--suite", *map(str, SUITE), "--im", "pga", "--trace", "--capacity",
                    capacity, "--trace-runs", "5", "--out", str(out), "-q"], check=True, capture_output=True)
    header, rows = read_ida_csv(out / "ida.csv")
    py = adjoin.ida(SCENE, SUITE, im="pga", trace=True, capacity=capacity, trace_runs=5)
    assert len(rows) == 10
    assert_rows_equal(py, header, rows)
    np.testing.assert_array_equal(py["capacity_event"], py["A.drift_ratio_max"] > 0.03)
    assert py["capacity_event"].any() and not py["capacity_event"].all()


@pytest.mark.parametrize("keywords, field", [
    ({"event": ""}, "event"),
    ({"event": "nope > 1"}, "event"),
    ({"bootstrap": -1}, "bootstrap"),
    ({"bootstrap": 2.5}, "bootstrap"),
    ({"bootstrap": 10**6}, "bootstrap"),
    ({"seed": -3}, "seed"),
    ({"at": 0.0}, "at"),
    ({"table": 42}, "table"),
    ({"table": {"record": ["a"], "im": [-1.0], "x": [1.0]}}, "table"),
])
def test_fragility_names_a_bad_keyword(tmp_path, keywords, field):
    table = tmp_path / "ida.csv"
    write_table(table, stripe_rows())
    args = {"table": table, "event": "contact1.impacts > 0", **keywords}
    with pytest.raises(adjoin.InputError) as e:
        adjoin.fragility(args.pop("table"), args.pop("event"), **args)
    assert e.value.field == field
    assert str(e.value).startswith(field)


@pytest.mark.parametrize("keywords, field", [
    ({"levels": None}, "levels"),
    ({"levels": [0.2, -1]}, "levels"),
    ({"levels": [0.2, 0.2]}, "levels"),
    ({"im": "sa"}, "im"),
    ({"edp": ["no.such_column"]}, "edp"),
    ({"capacity": "A.drift_ratio_max >> 1"}, "capacity"),
    ({"jobs": -1}, "jobs"),
    ({"trace": True}, "levels"),
    ({"trace": True, "levels": None, "trace_runs": 1}, "trace_runs"),
    ({"trace": True, "levels": None, "trace_factor": 0.5}, "trace_factor"),
    ({"units": "furlongs"}, "units"),
    ({"out": 3}, "out"),
    ({"out": ""}, "out"),
])
def test_ida_names_a_bad_keyword(keywords, field):
    args = {"im": "pga", "levels": [0.2], **keywords}
    with pytest.raises(adjoin.InputError) as e:
        adjoin.ida(SCENE, SUITE[:1], **args)
    assert e.value.field == field, str(e.value)


@pytest.mark.parametrize("how", [["--levels", "0.2,0.5"], ["--trace", "--trace-runs", "4", "--capacity",
                                                          "A.drift_ratio_max > 0.03 or contact1.impacts > 50"]])
def test_ida_out_writes_the_files_of_the_cli(tmp_path, adjoin_cli, how):
    """ida(out=DIR) writes the command's ida.csv byte for byte, and its figure."""
    cli_dir, py_dir = tmp_path / "cli", tmp_path / "made" / "py"
    subprocess.run([adjoin_cli, "ida", str(SCENE), "--suite", *map(str, SUITE), "--im", "pga", *how, "--out", str(cli_dir),
                    "-q"], check=True, capture_output=True)
    if how[0] == "--levels":
        adjoin.ida(SCENE, SUITE, im="pga", levels=[0.2, 0.5], out=py_dir)
    else:
        adjoin.ida(SCENE, SUITE, im="pga", trace=True, trace_runs=4, capacity=how[-1], out=py_dir)
    assert (py_dir / "ida.csv").read_bytes() == (cli_dir / "ida.csv").read_bytes()
    if shutil.which("gnuplot"):
        assert (py_dir / "ida.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert not (py_dir / "sweep.csv").exists()  # the figure and the table only


def test_fragility_of_several_designs_equals_the_cli(tmp_path, adjoin_cli):
    """A list of tables is several designs: the numbers and labels of `adjoin fragility A B --label`."""
    (tmp_path / "none").mkdir()
    (tmp_path / "friction").mkdir()
    first, second = tmp_path / "none" / "ida.csv", tmp_path / "friction" / "ida.csv"
    write_table(first, stripe_rows())
    write_table(second, trace_rows())
    event = "contact1.impacts > 0 or A.drift_ratio_max > 0.05"
    cli = cli_fragility(adjoin_cli, first, tmp_path / "f.json", event, str(second), "--label", "bare,damped",
                        "--bootstrap", "100", "--seed", "5", "--at", "0.3")
    py = adjoin.fragility([first, second], event, labels=["bare", "damped"], bootstrap=100, seed=5, at=0.3)
    assert py["event"] == cli["event"] == event
    assert [d["label"] for d in py["designs"]] == ["bare", "damped"] == [d["label"] for d in cli["designs"]]
    assert [d["file"] for d in py["designs"]] == [str(first), str(second)]
    assert_same(py, cli)
    # Each design alone is the one-table fit; labels default to the tables' folders, as --label does.
    alone = adjoin.fragility(second, event, bootstrap=100, seed=5, at=0.3)
    assert py["designs"][1]["theta"] == alone["theta"] and py["designs"][1]["first_event"] == alone["first_event"]
    default = adjoin.fragility([first, second], event, bootstrap=0)
    assert [d["label"] for d in default["designs"]] == ["none", "friction"]
    columns = adjoin.fragility([{"record": ["a", "b"], "im": [0.1, 0.2], "x": [0.0, 1.0]}] * 2, "x > 0.5", bootstrap=0)
    assert [d["label"] for d in columns["designs"]] == ["design 1", "design 2"]


@pytest.mark.parametrize("tables, labels", [(2, ["one"]), (1, ["one"])])
def test_fragility_labels_are_one_per_table_of_a_list(tmp_path, tables, labels):
    table = tmp_path / "ida.csv"
    write_table(table, stripe_rows())
    with pytest.raises(adjoin.InputError) as e:
        adjoin.fragility([table] * tables if tables > 1 else table, "contact1.impacts > 0", labels=labels)
    assert e.value.field == "labels"
