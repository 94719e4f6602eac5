"""adjoin.optimize (SPEC §9) against `adjoin optimize` on the same study: the same optimum and
designs, a rerun from the cache, and bad input named by InputError.field."""
import json
import subprocess

import numpy as np
import pytest

import adjoin
from conftest import RECORDS, SOURCE

SCENE = SOURCE / "examples" / "buildings" / "two-frames-one-damper.toml"


def study(tmp_path, method="bobyqa", extra=""):
    path = tmp_path / "study.toml"
    path.write_text(f"""[optimize]
scene = "{SCENE}"
suite = ["{RECORDS / 'smc'}"]
im = "pga"
level = 0.2
variables = [{{key = "link.1.slip_force", min = 1.0e4, max = 3.0e5}}]
objective = {{edp = "A.drift_max", statistic = "mean"}}
method = "{method}"
max_evaluations = 10
{extra}""")
    return path


def test_optimize_equals_the_command(tmp_path, adjoin_cli):
    path = study(tmp_path)
    subprocess.run([adjoin_cli, "optimize", str(path), "--out", str(tmp_path / "cli"), "-q"], check=True, capture_output=True)
    cli = json.loads((tmp_path / "cli" / "optimum.json").read_text())
    py = adjoin.optimize(path, jobs=2)
    assert py["variables"] == cli["variables"]
    assert py["objective"] == cli["objective"]
    assert py["evaluations"] == cli["evaluations"] <= 10
    assert py["history"] == cli["history"]
    table = py["table"]
    assert len(table["evaluation"]) == py["evaluations"]
    assert table["feasible"].dtype == bool and table["feasible"].all()
    best = int(np.argmin(table["mean(A.drift_max)"]))
    assert table["link.1.slip_force"][best] == py["variables"]["link.1.slip_force"]


def test_optimize_rerun_takes_the_cache(tmp_path):
    path = study(tmp_path, "cobyla")
    first = adjoin.optimize(path, out=tmp_path / "out")
    again = adjoin.optimize(path, out=tmp_path / "out")
    assert first["runs_now"] == 2 * first["evaluations"]
    assert again["runs_now"] == 0 and again["from_cache"] == first["evaluations"]
    assert again["variables"] == first["variables"]
    assert (tmp_path / "out" / "evaluations.csv").exists()


def test_optimize_bad_study_names_the_line(tmp_path):
    path = study(tmp_path, "newton")
    with pytest.raises(adjoin.InputError) as e:
        adjoin.optimize(path)
    assert e.value.field == "study"
    assert "study.toml:8:" in str(e.value) and "newton" in str(e.value)
    with pytest.raises(adjoin.InputError) as e:
        adjoin.optimize(42)
    assert e.value.field == "study"
