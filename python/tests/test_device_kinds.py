"""Storey devices of any kind built by their scene keys (BuildingBuilder.device, SPEC §8): the
keywords are the kind's scene keys from the one table of device kinds
(structure/device_kinds.hpp), a structure built so runs to the very numbers of the equivalent
scene, and a bad or missing keyword is named."""
import pytest

import adjoin
from conftest import RECORDS

NORTHRIDGE = RECORDS / "peer" / "RSN1044_DirRot2.AT2"
RUN = {"h": 0.004, "t_end": 6.0}


def test_a_kelvin_frame_built_by_keys_runs_as_its_scene():
    scene = adjoin.Scene.from_dict({
        "name": "frame",
        "model": {"units": "SI"},
        "building": {"A": {
            "storeys": 3, "mass": 40.0e3, "stiffness": 5.0e6,
            "damping": {"model": "modal", "ratio": 0.03},
            "device": [
                {"storeys": [1, 2], "type": "kelvin", "stiffness": 2.0e6, "c": 1.5e5},
                {"storeys": [3], "type": "dashpot", "c": 5.0e4, "alpha": 0.5},
            ],
        }},
        "ground": {"source": "record", "file": str(NORTHRIDGE), "scale_pga": 0.3},
        "solver": RUN,
    })
    s = adjoin.StructureBuilder()
    (s.building("A", 3).mass(40.0e3).stiffness(5.0e6).modal_damping(0.03)
     .device("kelvin", [1, 2], stiffness=2.0e6, c=1.5e5)
     .device("dashpot", [3], c=5.0e4, alpha=0.5))
    code = adjoin.run_structure(s.build(), NORTHRIDGE, scale_pga=0.3, timeseries=False, **RUN)
    from_scene = adjoin.run(scene, timeseries=False)
    assert code.summary["peaks"], "no peaks compared"
    assert code.summary["peaks"] == from_scene.summary["peaks"]
    assert code.summary["peaks"]["A.x3"]["max_abs"] > 1e-3  # (the frame moved)


@pytest.mark.parametrize(
    "make, field",
    [
        (lambda b: b.device("kelvin", [1], stiffness=1e6), "building.B.device.1.c"),
        (lambda b: b.device("kelvin", [1], stiffness=1e6, c=-2.0), "building.B.device.1.c"),
        (lambda b: b.device("kelvin", [1], stiffness=1e6, c=1e4, alpha=0.5), "building.B.device.1.alpha"),
        (lambda b: b.device("zener", [1], stiffness=1e6, order=0.5, tau_x=0.1, tau_f=0.2), "building.B.device.1.tau_x"),
        (lambda b: b.device("kelvn", [1], stiffness=1e6, c=1e4), "building.B.device.type"),
    ],
)
def test_a_bad_device_keyword_is_named(make, field):
    with pytest.raises(adjoin.InputError) as e:
        make(adjoin.StructureBuilder().building("B", 2).mass(1e4))
    assert e.value.field == field


def test_a_link_built_by_keys_is_the_typed_one():
    def pair():
        s = adjoin.StructureBuilder()
        s.building("A", 3).mass(4e4).stiffness(5e6).modal_damping(0.05)
        s.building("B", 2).mass(5e4).stiffness(8e6).modal_damping(0.05)
        return s
    by_keys, typed = pair(), pair()
    by_keys.link("dashpot", 3, 2, c=2.0e5, alpha=0.5).link("spring", 2, 1, stiffness=1.0e6)
    typed.dashpot_link(3, 2, 2.0e5, 0.5).spring_link(2, 1, 1.0e6)
    run = dict(timeseries=False, **RUN)
    a = adjoin.run_structure(by_keys.build(), NORTHRIDGE, scale_pga=0.3, **run)
    b = adjoin.run_structure(typed.build(), NORTHRIDGE, scale_pga=0.3, **run)
    assert a.summary["links"] == b.summary["links"]
    assert a.summary["links"][0]["force_max"] > 0.0


@pytest.mark.parametrize(
    "make, field",
    [
        (lambda s: s.link("dashpot", 1, 1), "link.1.c"),
        (lambda s: s.link("spring", 1, 1, stiffness=1e6, c=1.0), "link.1.c"),
        (lambda s: s.link("friction", 1, 1, slip_force=1e4), "link.1.type"),
    ],
)
def test_a_bad_link_keyword_is_named(make, field):
    s = adjoin.StructureBuilder()
    s.building("A", 1).mass(1e4).stiffness(1e6)
    s.building("B", 1).mass(1e4).stiffness(1e6)
    with pytest.raises(adjoin.InputError) as e:
        make(s)
    assert e.value.field == field
