"""Yielding storeys, yielding devices and isolated bases built in Python (SPEC §7, §8): the
builder's keywords are the scene's keys, a structure built in code runs (adjoin.run_structure)
to the very numbers of the equivalent scene run through adjoin.run, and a bad value names its
keyword."""
import math

import pytest

import adjoin
from conftest import RECORDS

NORTHRIDGE = RECORDS / "peer" / "RSN1044_DirRot2.AT2"
RUN = {"h": 0.004, "t_end": 6.0}  # short: the strong part of the record


def ground(scale_pga):
    return {"source": "record", "file": str(NORTHRIDGE), "scale_pga": scale_pga}


def same_results(code, scene):
    """The built structure's run and the scene's: the same peaks, residuals, yield and base
    reports, bit for bit (one library, the same calls)."""
    for key in ("peaks", "residual", "yield", "base", "links"):
        assert code.summary.get(key) == scene.summary.get(key), key
    assert code.summary["peaks"], "no peaks compared"


def test_bouc_wen_frame_built_in_python_runs_as_its_scene():
    scene = adjoin.Scene.from_dict({
        "name": "frame",
        "model": {"units": "SI"},
        "building": {"A": {
            "storeys": 4, "mass": 40.0e3, "period": 0.6, "height": 3.2,
            "damping": {"model": "modal", "ratio": 0.03},
            "hysteresis": {"model": "bouc-wen", "yield_drift_ratio": 0.004, "hardening": 0.05,
                           "n": 1.5, "beta": 0.6, "gamma": 0.4},
            "device": [
                {"storeys": [1, 2], "type": "bilinear", "stiffness": 2.0e7, "yield_force": 4.0e4, "hardening": 0.02},
                {"storeys": [3], "type": "bouc-wen", "stiffness": 1.0e7, "yield_force": 2.0e4, "n": 3.0},
            ],
        }},
        "ground": ground(0.35),
        "solver": RUN,
    })
    s = adjoin.StructureBuilder()
    (s.building("A", 4).mass(40.0e3).period(0.6).height(3.2).modal_damping(0.03)
     .bouc_wen(yield_drift_ratio=0.004, hardening=0.05, n=1.5, beta=0.6, gamma=0.4)
     .bilinear_device([1, 2], stiffness=2.0e7, yield_force=4.0e4, hardening=0.02)
     .bouc_wen_device([3], stiffness=1.0e7, yield_force=2.0e4, n=3.0))
    code = adjoin.run_structure(s.build(), NORTHRIDGE, scale_pga=0.35, timeseries=False, **RUN)
    from_scene = adjoin.run(scene, timeseries=False)
    same_results(code, from_scene)
    assert code.summary["yield"]["A"][0]["yielded"]  # the run is the one the test is about


def test_isolated_building_built_in_python_runs_as_its_scene():
    scene = adjoin.Scene.from_dict({
        "name": "pair",
        "model": {"units": "SI"},
        "building": {
            "A": {"storeys": 3, "mass": 45.0e3, "stiffness": 6.0e7, "damping": {"model": "modal", "ratio": 0.05}},
            "B": {"storeys": 3, "masses": [60.0e3, 60.0e3, 50.0e3], "period": 0.4,
                  "damping": {"model": "modal", "ratio": 0.05},
                  "base": {"mass": 60.0e3, "model": "friction-pendulum", "friction": 0.06, "radius": 2.5}},
        },
        "link": [{"floors": [3, 3], "type": "dashpot", "c": 2.0e5, "alpha": 0.5}],
        "ground": ground(0.35),
        "solver": RUN,
    })
    s = adjoin.StructureBuilder()
    s.building("A", 3).mass(45.0e3).stiffness(6.0e7).modal_damping(0.05)
    (s.building("B", 3).masses([60.0e3, 60.0e3, 50.0e3]).period(0.4).modal_damping(0.05)
     .friction_pendulum(mass=60.0e3, friction=0.06, radius=2.5))
    s.dashpot_link(3, 3, 2.0e5, alpha=0.5)
    code = adjoin.run_structure(s.build(), NORTHRIDGE, scale_pga=0.35, timeseries=False, **RUN)
    from_scene = adjoin.run(scene, timeseries=False)
    same_results(code, from_scene)
    base = code.summary["base"]["B"]
    assert base["switches"] > 0 and base["max_abs"] > 1e-3  # the base slid
    assert "B.x0" in code.summary["peaks"]


@pytest.mark.parametrize(
    "make, field",
    [
        (lambda b: b.bouc_wen(yield_force=1e5, n=0.5), "building.B.hysteresis.n"),
        (lambda b: b.bouc_wen(yield_force=1e5, gamma=-0.6), "building.B.hysteresis.gamma"),
        (lambda b: b.bouc_wen(yield_force=1e5, hardening=1.0), "building.B.hysteresis.hardening"),
        (lambda b: b.bouc_wen(hardening=0.1), "building.B.hysteresis"),
        (lambda b: b.bilinear_device([1], stiffness=1e7, yield_force=-1.0), "building.B.device.1.yield_force"),
        (lambda b: b.bouc_wen_device([1], stiffness=0.0, yield_force=1e4), "building.B.device.1.stiffness"),
        (lambda b: b.bouc_wen_device([1], stiffness=1e7, yield_force=1e4, beta=-1.0), "building.B.device.1.beta"),
        (lambda b: b.flat_slider(mass=-5e4, friction=0.05), "building.B.base.mass"),
        (lambda b: b.flat_slider(mass=5e4, friction=1.2), "building.B.base.friction"),
        (lambda b: b.friction_pendulum(mass=5e4, friction=0.05, radius=0.0), "building.B.base.radius"),
    ],
)
def test_a_bad_keyword_names_its_field(make, field):
    with pytest.raises(adjoin.InputError) as e:
        make(adjoin.StructureBuilder().building("B", 2))
    assert e.value.field == field
    assert field.rsplit(".", 1)[-1] in str(e.value)


def test_a_bad_run_keyword_is_named():
    s = adjoin.StructureBuilder()
    s.building("A", 1).mass(1e4).stiffness(1e6)
    for kwargs, keyword in (({"h": -0.01}, "h"), ({"scale_pga": -0.3}, "scale_pga"), ({"scale": 0.0}, "scale")):
        with pytest.raises(adjoin.InputError) as e:
            adjoin.run_structure(s.build(), NORTHRIDGE, **kwargs)
        assert e.value.field == keyword
        assert str(e.value).startswith(keyword + ": ")


def test_scale_keyword_is_the_scene_key_ground_scale():
    """run_structure(..., scale=f) runs as the scene with ground.scale = f: the same peaks."""
    scene = adjoin.Scene.from_dict({
        "name": "frame", "model": {"units": "SI"},
        "building": {"A": {"storeys": 2, "mass": 40.0e3, "period": 0.5, "damping": {"model": "modal", "ratio": 0.05}}},
        "ground": {**ground(0.3), "scale": 1.7},
        "solver": RUN,
    })
    s = adjoin.StructureBuilder()
    s.building("A", 2).mass(40.0e3).period(0.5).modal_damping(0.05)
    code = adjoin.run_structure(s.build(), NORTHRIDGE, scale_pga=0.3, scale=1.7, timeseries=False, **RUN)
    same_results(code, adjoin.run(scene, timeseries=False))
    plain = adjoin.run_structure(s.build(), NORTHRIDGE, scale_pga=0.3, timeseries=False, **RUN)
    assert code.summary["peaks"]["A.x2"]["max_abs"] == pytest.approx(1.7 * plain.summary["peaks"]["A.x2"]["max_abs"], rel=1e-12)


def test_modes_state_the_isolated_period():
    """adjoin.modes, as adjoin modes: a friction pendulum's 2 pi sqrt(R/g), NaN for a flat slider."""
    s = adjoin.StructureBuilder()
    s.building("A", 2).mass(5e4).stiffness(5e7).friction_pendulum(mass=5e4, friction=0.05, radius=2.0)
    b = s.build().modes()["A"]
    assert b["isolated_period"] == pytest.approx(2 * math.pi * math.sqrt(2.0 / 9.80665), rel=1e-14)
    assert b["isolated_period_flexible"] > b["isolated_period"]
    s = adjoin.StructureBuilder()
    s.building("A", 2).mass(5e4).stiffness(5e7).flat_slider(mass=5e4, friction=0.05)
    assert math.isnan(s.build().modes()["A"]["isolated_period"])
    s = adjoin.StructureBuilder()
    s.building("A", 2).mass(5e4).stiffness(5e7)
    assert "isolated_period" not in s.build().modes()["A"]
