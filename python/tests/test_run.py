"""adjoin.run and adjoin.run_many against `adjoin run`: the same scene gives the same numbers,
bit for bit (summary.json and every time-series column); results are in input order; arrays
outlive their result; scenes round-trip through dicts and TOML."""
import csv
import gc
import io
import json
import pathlib
import re
import subprocess

import numpy as np
import pytest

import adjoin
from conftest import SCENES

# Short runs of the three kinds of scene: a two-block scene (the paper's), a building scene
# with Zener dampers, a friction link and a contact pair with a law (impacts), and a
# two-block scene shaken by a record (SI).
CASES = {
    "two-block": (SCENES / "paper-strong.toml", {"solver.t_end": 8.0, "output.timeseries": True}),
    "building": (SCENES / "buildings" / "two-frames.toml",
                 {"solver.t_end": 6.0, "contact.1.gap": 0.0, "contact.1.model": "linear",
                  "contact.1.stiffness": 1e8, "contact.1.restitution": 0.65, "output.every": 2}),
    "record": (SCENES / "si-record.toml", {"solver.t_end": 5.0, "output.timeseries": True}),
}


def cli_run(adjoin_cli, scene, overrides, out):
    args = [adjoin_cli, "run", str(scene), "--out", str(out), "--quiet"]
    for key, value in overrides.items():
        text = str(value).lower() if isinstance(value, bool) else str(value)
        args += ["--set", f"{key}={text}"]
    subprocess.run(args, check=True)
    return out


def without_wall_time(summary):
    """summary.json without the values that are the clock's, not the computation's."""
    if isinstance(summary, dict):
        return {k: without_wall_time(v) for k, v in summary.items() if "wall_seconds" not in k}
    if isinstance(summary, list):
        return [without_wall_time(v) for v in summary]
    return summary


def csv_columns(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return {name: [r[k] for r in rows[1:]] for k, name in enumerate(rows[0])}


def assert_same_columns(result_columns, csv_path):
    expected = csv_columns(csv_path)
    assert list(result_columns) == list(expected)
    for name, cells in expected.items():
        got = result_columns[name]
        assert len(got) == len(cells), name
        if got.dtype.kind == "U":
            assert list(got) == cells, name
        else:
            assert got.dtype == np.float64
            # float(cell) is the exact double the CSV's shortest text stands for.
            assert np.array_equal(got, np.array([float(c) for c in cells]), equal_nan=False), name


@pytest.mark.parametrize("kind", list(CASES))
def test_run_gives_the_cli_numbers_bit_for_bit(kind, adjoin_cli, tmp_path):
    scene_file, overrides = CASES[kind]
    out = cli_run(adjoin_cli, scene_file, overrides, tmp_path / "out")
    result = adjoin.run(adjoin.load_scene(scene_file, set=overrides))

    cli_summary = json.loads((out / "summary.json").read_text())
    assert without_wall_time(result.summary) == without_wall_time(cli_summary)
    assert_same_columns(result.timeseries, out / "timeseries.csv")
    assert result.channels == [c for c in result.timeseries if c != "t"]
    if kind == "building":
        # The contact law made impacts: the same rows as impacts.csv.
        assert len(result.impacts) > 0
        rows = list(csv.DictReader(io.StringIO((out / "impacts.csv").read_text())))
        assert len(rows) == len(result.impacts)
        for mine, theirs in zip(result.impacts, rows):
            assert mine["contact"] == int(theirs["contact"])
            assert mine["force_max"] == float(theirs["force_max"])
            assert mine["complete"] == (theirs["complete"] == "true")
    else:
        assert result.impacts == []
        assert result.timeseries["phase"][0] in ("stick", "slip_right", "slip_left")


@pytest.mark.parametrize("kind", ["two-block", "building"])
def test_brief_is_the_terminal_report(kind, adjoin_cli, tmp_path):
    scene_file, overrides = CASES[kind]
    args = [adjoin_cli, "run", str(scene_file), "--out", str(tmp_path / "out")]
    for key, value in overrides.items():
        args += ["--set", f"{key}={str(value).lower() if isinstance(value, bool) else value}"]
    printed = subprocess.run(args, check=True, capture_output=True, text=True).stdout.splitlines()
    assert printed[-1].startswith("wrote ")
    brief = adjoin.run(adjoin.load_scene(scene_file, set=overrides)).brief().splitlines()
    # Every line but the one with the wall-clock time of the run.
    clock = re.compile(r"[0-9.e+-]+ s wall|steps in [0-9.e+-]+ s")
    assert [clock.sub("", l) for l in brief] == [clock.sub("", l) for l in printed[:-1]]
    assert len(brief) > 4


def test_timeseries_false_and_every():
    scene = adjoin.load_scene(SCENES / "paper-strong.toml", set={"solver.t_end": 4.0, "output.timeseries": True})
    full = adjoin.run(scene)
    assert adjoin.run(scene, timeseries=False).timeseries == {}
    thinned = adjoin.run(scene, every=10)
    assert np.array_equal(thinned.timeseries["x1"][:-1], full.timeseries["x1"][::10][: len(thinned.timeseries["x1"]) - 1])
    assert thinned.summary["peaks"] == full.summary["peaks"]  # peaks come from every step


def test_run_many_equals_serial_runs_in_input_order():
    scenes = [adjoin.load_scene(SCENES / "paper-strong.toml",
                                set={"solver.t_end": 4.0, "model.mu": mu, "output.timeseries": True})
              for mu in (0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8)]
    serial = [adjoin.run(s) for s in scenes]
    threaded = adjoin.run_many(scenes, jobs=2)
    assert len(threaded) == len(scenes)
    for a, b in zip(serial, threaded):
        assert without_wall_time(a.summary) == without_wall_time(b.summary)
        assert np.array_equal(a.timeseries["q"], b.timeseries["q"])
    # Different scenes, different answers: the order is the input's, not the finishing order.
    peaks = [r.summary["peaks"]["x1"]["max_abs"] for r in threaded]
    assert len(set(peaks)) == len(peaks)


def test_run_many_names_the_failing_scene():
    good = {"solver.t_end": 2.0}
    scenes = [adjoin.load_scene(SCENES / "paper-strong.toml", set=good) for _ in range(3)]
    # A building scene refused when run (its memory rule) as the third of four.
    huge = adjoin.load_scene(SCENES / "buildings" / "two-frames.toml",
                             set={"solver.h": 1e-5, "solver.t_end": 1e4, "output.timeseries": False,
                                  "solver.history": "fft"})
    with pytest.raises(adjoin.InputError) as caught:
        adjoin.run_many(scenes[:2] + [huge] + scenes[2:], jobs=2)
    assert str(caught.value).startswith("scenes[2]: ")


def test_arrays_outlive_their_result():
    result = adjoin.run(adjoin.load_scene(SCENES / "paper-strong.toml",
                                          set={"solver.t_end": 16.0, "solver.h": 0.001, "output.timeseries": True}))
    x1 = result.timeseries["x1"]
    expected = x1.copy()
    assert x1.base is not None  # a view of the buffer the run filled, not a copy
    del result
    gc.collect()
    _ = [np.ones(len(expected)) for _ in range(20)]  # reuse freed memory if the buffer were freed
    assert len(x1) == 16001
    assert np.array_equal(x1, expected)
    assert np.isclose(np.max(np.abs(x1)), 1.1665, atol=1e-3)


def test_scene_round_trips_through_dict_and_toml(adjoin_cli, tmp_path):
    scene_file, overrides = CASES["record"]
    scene = adjoin.load_scene(scene_file, set=overrides)
    original = adjoin.run(scene)
    again = adjoin.run(adjoin.Scene.from_dict(scene.to_dict()))
    ground_free = lambda s: {k: v for k, v in without_wall_time(s).items() if k != "ground"}
    assert ground_free(again.summary) == ground_free(original.summary)
    assert np.array_equal(again.timeseries["x2"], original.timeseries["x2"])
    # to_toml() is a scene file `adjoin run` reads to the same numbers.
    text = tmp_path / "scene.toml"
    text.write_text(scene.to_toml())
    out = cli_run(adjoin_cli, text, {}, tmp_path / "out")
    assert ground_free(json.loads((out / "summary.json").read_text())) == ground_free(original.summary)


def test_building_scene_from_a_dict_runs():
    d = adjoin.load_scene(SCENES / "buildings" / "two-frames.toml").to_dict()
    assert d["building"]["A"]["storeys"] == 5
    assert d["link"][0]["type"] == "friction"
    d["solver"]["t_end"] = 2.0
    d["link"][0]["slip_ratio"] = 0.1
    result = adjoin.run(d)
    assert result.summary["scene"] == "two-frames"
    assert result.summary["solver"]["t_end"] == 2.0
    assert "A.x5" in result.timeseries and "link1.force" in result.timeseries
    assert pathlib.Path(d["ground"]["file"]).is_absolute()


def test_to_dict_applies_the_edits_as_load_scene_does():
    """A building key that replaces its alternative (period for stiffness), a removed link and
    a contact law: the dict is the scene load_scene read, so it runs to the same numbers."""
    edits = {"building.A.period": 0.9, "contact.1.model": "linear", "contact.1.stiffness": 1e8,
             "contact.1.restitution": 0.65, "solver.t_end": 3.0}
    scene = adjoin.load_scene(SCENES / "buildings" / "two-frames.toml", set=edits, unset=["link.1"])
    d = scene.to_dict()
    assert d["building"]["A"]["period"] == 0.9 and "stiffness" not in d["building"]["A"]
    assert "link" not in d or d["link"] == []
    assert d["contact"][0]["model"] == "linear"
    a, b = adjoin.run(scene), adjoin.run(adjoin.Scene.from_dict(d))
    drop = lambda s: {k: v for k, v in without_wall_time(s).items() if k != "ground"}
    assert drop(a.summary) == drop(b.summary)
    assert np.array_equal(a.timeseries["A.x5"], b.timeseries["A.x5"])
