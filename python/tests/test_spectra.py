"""Records, spectra, RotD and inelastic spectra from Python equal the CSV files of
`adjoin spectrum` (every value as the CLI prints it, %.10g), and their arrays own their memory."""
import csv
import gc
import io
import subprocess

import numpy as np
import pytest

import adjoin
from conftest import RECORDS

NORTHRIDGE = RECORDS / "peer" / "RSN1044_DirRot2.AT2"
PAIR = (RECORDS / "peer" / "RSN8883_14383980_13849090.AT2", RECORDS / "peer" / "RSN8883_14383980_13849360.AT2")


def cli_csv(adjoin_cli, *args):
    out = subprocess.run([adjoin_cli, "spectrum", *map(str, args)], check=True, capture_output=True, text=True).stdout
    return list(csv.DictReader(io.StringIO(out)))


def assert_as_printed(result, rows, columns):
    """Each value of the dict of arrays, printed as the CLI prints it, is the CSV's cell."""
    assert len(result["period"]) == len(rows)
    for i, row in enumerate(rows):
        for name in columns:
            assert "%.10g" % result[name][i] == row[name], (name, i)


def test_read_record_gives_the_file_in_g():
    r = adjoin.read_record(NORTHRIDGE)
    assert r.dt == 0.02
    assert len(r) == 2000 and r.accel.shape == (2000,)
    assert r.units == "g"
    assert np.isclose(np.max(np.abs(r.accel)), 0.6972, atol=1e-4)  # the PGA `adjoin run` reports
    assert np.allclose(r.accel * 9.80665, r.accel_m_s2, rtol=1e-15, atol=0)
    assert not r.accel_m_s2.flags.writeable
    assert "RSN1044" in r.header


def test_spectrum_equals_the_cli_csv(adjoin_cli):
    periods, dampings = [0, 0.1, 0.5, 1, 2], [0.02, 0.05]
    rows = cli_csv(adjoin_cli, NORTHRIDGE, "--periods", "0,0.1,0.5,1,2", "--damping", "0.02,0.05")
    result = adjoin.spectrum(adjoin.read_record(NORTHRIDGE), periods=periods, damping=dampings)
    assert_as_printed(result, rows, ["period", "damping", "sd", "sv", "sa", "psv", "psa"])
    assert list(result["damping"][:5]) == [0.02] * 5  # damping-major, as the CSV


def test_spectrum_of_an_array_in_g_matches_the_record():
    r = adjoin.read_record(NORTHRIDGE)
    from_record = adjoin.spectrum(r, periods=[0.3, 1.0])
    from_array = adjoin.spectrum(r.accel, r.dt, periods=[0.3, 1.0], units="g")
    assert np.allclose(from_array["psa"], from_record["psa"], rtol=1e-12)
    with pytest.raises(adjoin.InputError) as caught:
        adjoin.spectrum(r.accel, periods=[1.0])  # an array needs its step
    assert caught.value.field == "dt"


def test_rotd_equals_the_cli_csv(adjoin_cli):
    rows = cli_csv(adjoin_cli, *PAIR, "--rotd", "50,100,84", "--periods", "0.2,1")
    result = adjoin.rotd(adjoin.read_record(PAIR[0]), adjoin.read_record(PAIR[1]), periods=[0.2, 1],
                         percentiles=(50, 100, 84))
    assert_as_printed(result, rows, ["period", "damping", "rotd00", "rotd50", "rotd100", "angle00", "angle100",
                                     "gmroti50", "rotd84"])
    assert np.all(result["rotd00"] <= result["rotd50"]) and np.all(result["rotd50"] <= result["rotd100"])


def test_ductility_spectrum_equals_the_cli_csv(adjoin_cli):
    rows = cli_csv(adjoin_cli, NORTHRIDGE, "--ductility", "2,4", "--periods", "0.5,1")
    result = adjoin.ductility_spectrum(adjoin.read_record(NORTHRIDGE), periods=[0.5, 1], ductility=[2, 4])
    assert_as_printed(result, rows, ["period", "damping", "ductility", "cy", "uy", "R", "ductility_reached"])


def test_spectrum_arrays_outlive_everything_else():
    psa = adjoin.spectrum(adjoin.read_record(NORTHRIDGE), periods=np.linspace(0.05, 4, 400))["psa"]
    expected = psa.copy()
    gc.collect()
    _ = [np.zeros(400) for _ in range(50)]
    assert psa.flags.owndata is False and psa.base is not None  # the capsule owns the buffer
    assert np.array_equal(psa, expected)


def test_modes_of_a_scene_and_of_a_built_structure():
    from conftest import SCENES

    m = adjoin.modes(SCENES / "buildings" / "two-frames.toml")
    assert m["A"]["shapes"].shape == (5, 5)
    assert np.isclose(m["B"]["periods"][0], 0.5, rtol=1e-12)  # B's period is the scene's
    s = adjoin.StructureBuilder()
    s.building("A", 5).mass(45.0e3).stiffness(5.482e6).modal_damping(0.05).zener(
        [1, 2], stiffness=1.0e6, order=0.5, tau_x=0.2, tau_f=0.01)
    s.building("B", 3).masses([60.0e3, 60.0e3, 50.0e3]).period(0.5).rayleigh_damping(0.05, 1, 2)
    s.friction_link_ratio(3, 3, 0.05, "B")
    s.contact(3, 3, 0.05)
    built = adjoin.modes(s.build())
    assert np.array_equal(built["A"]["periods"], m["A"]["periods"])
    assert np.array_equal(built["coupled"]["periods_locked"], m["coupled"]["periods_locked"])
    with pytest.raises(adjoin.InputError) as caught:
        adjoin.StructureBuilder().building("A", 3).mass(-1.0)
    assert caught.value.field.startswith("building.A")


def test_joint_equals_adjoin_joint(adjoin_cli, tmp_path):
    import json
    from conftest import SCENES

    scene = SCENES / "buildings" / "two-frames.toml"
    subprocess.run([adjoin_cli, "joint", str(scene), "--set", "solver.t_end=6", "--out", str(tmp_path), "--quiet"],
                   check=True)
    expected = json.loads((tmp_path / "joint.json").read_text())
    j = adjoin.joint(adjoin.load_scene(scene, set={"solver.t_end": 6.0}))
    assert j["joint"] == expected["joint"] and j["runs"] == expected["bisection"]["runs"]
    assert j["s_max"] == expected["direct"]["s_max"] and j["agree"] == expected["direct"]["agree"]
    assert j["srss"] == expected["code_rules"]["srss"]
    assert 0.0 <= j["joint"] - j["s_max"] <= j["tolerance"]
    with pytest.raises(adjoin.InputError) as caught:
        adjoin.joint(scene, contact=2)
    assert caught.value.field == "contact"
