"""examples/python/two_frames.py runs: three damper designs over the shipped records with
run_many, a table of peaks and impacts, and a PNG of the drift profiles (matplotlib: the test
is skipped, and CTest shows it skipped, when matplotlib is missing)."""
import os
import subprocess
import sys

import pytest

from conftest import SOURCE


def test_two_frames_example(tmp_path):
    pytest.importorskip("matplotlib")
    env = dict(os.environ, MPLBACKEND="Agg")
    out = subprocess.run([sys.executable, str(SOURCE / "examples" / "python" / "two_frames.py"), str(tmp_path / "fig"),
                          "--jobs", "2"], check=True, capture_output=True, text=True, env=env).stdout
    lines = out.splitlines()
    records = len(list((SOURCE / "records" / "real" / "peer").glob("*.AT2")))
    rows = [l for l in lines[1:] if l.startswith(("friction", "viscous"))]
    assert len(rows) == 3 * records
    assert sum(int(r.split()[-2]) for r in rows) > 0  # some runs pound, and their impacts are counted
    png = tmp_path / "fig" / "two_frames_drifts.png"
    assert lines[-1] == f"wrote {png}"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10000


def test_the_notebook_is_the_script():
    """examples/python/two_frames.ipynb holds the script's code cell by cell (made by
    scripts/python_notebook.py, which says the notebook is stale when the two differ)."""
    check = subprocess.run([sys.executable, str(SOURCE / "scripts" / "python_notebook.py"), "--check"],
                           capture_output=True, text=True)
    assert check.returncode == 0, check.stderr


def test_the_notebook_runs(tmp_path, monkeypatch):
    """The notebook's code cells, run in order as a kernel would, make the study's table and
    figure (the last cell's output folder is put in a temporary folder)."""
    pytest.importorskip("matplotlib")
    import json
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.chdir(tmp_path)
    cells = json.loads((SOURCE / "examples" / "python" / "two_frames.ipynb").read_text())["cells"]
    code = ["".join(c["source"]) for c in cells if c["cell_type"] == "code"]
    code[-1] = code[-1].replace('"--jobs", "2"]', '"--jobs", "2", "--t-end", "20"]')
    namespace = {"__file__": str(SOURCE / "examples" / "python" / "two_frames.py"), "__name__": "notebook"}
    for source in code:
        exec(compile(source, "two_frames.ipynb", "exec"), namespace)
    assert (tmp_path / "out" / "python-two-frames" / "two_frames_drifts.png").stat().st_size > 10000
