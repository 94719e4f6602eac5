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
