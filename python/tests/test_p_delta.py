"""Storey heights, P-Delta and collapse from Python (SPEC §7): the builder's setters mirror the
C++ ones, the modes of a P-Delta building are those of K0 + K_G, and a bad value names its field."""
import math

import pytest

import adjoin

G = 9.80665


def test_p_delta_period_is_the_closed_form():
    m, k, h = 1.0e4, 1.0e5, 3.0
    s = adjoin.StructureBuilder()
    s.building("A", 1).mass(m).stiffness(k).height(h).p_delta(True)
    modes = s.build().modes()["A"]
    assert modes["p_delta"] is True
    assert modes["periods"][0] == pytest.approx(2 * math.pi / math.sqrt((k - m * G / h) / m), rel=1e-12)


@pytest.mark.parametrize(
    "make, field",
    [
        (lambda b: b.height(-1.0), "building.A.height"),
        (lambda b: b.heights([3.0]), "building.A.heights"),
        (lambda b: b.collapse_drift_ratio(0.0), "building.A.collapse_drift_ratio"),
    ],
)
def test_bad_heights_name_their_field(make, field):
    s = adjoin.StructureBuilder()
    with pytest.raises(adjoin.InputError) as e:
        make(s.building("A", 2))
    assert e.value.field == field


def test_p_delta_without_heights_is_refused_by_build():
    s = adjoin.StructureBuilder()
    s.building("A", 2).mass(1e4).stiffness(1e6).p_delta(True)
    with pytest.raises(adjoin.InputError) as e:
        s.build()
    assert e.value.field == "building.A.p_delta"


def test_bilinear_storeys_name_their_fields():
    """bilinear() takes one of yield_force, yield_forces, yield_drift_ratio (F_y = k x ratio x h,
    needs heights), as the scene's hysteresis table does; each problem names its field."""
    m, k, h = 1.0e4, 1.0e6, 3.5
    s = adjoin.StructureBuilder()
    s.building("A", 2).mass(m).stiffness(k).height(h).bilinear(yield_drift_ratio=0.01, hardening=0.03)
    assert s.build().dofs == 2
    s = adjoin.StructureBuilder()
    s.building("A", 2).mass(m).stiffness(k).bilinear(yield_drift_ratio=0.01)
    with pytest.raises(adjoin.InputError) as e:
        s.build()
    assert e.value.field == "building.A.hysteresis.yield_drift_ratio"  # no heights
    cases = [
        (lambda b: b.bilinear(yield_force=1e5, yield_drift_ratio=0.01), "building.A.hysteresis"),
        (lambda b: b.bilinear(hardening=0.1), "building.A.hysteresis"),
        (lambda b: b.bilinear(yield_forces=[1e5]), "building.A.hysteresis.yield_forces"),
        (lambda b: b.bilinear(yield_force=1e5, hardening=1.0), "building.A.hysteresis.hardening"),
        (lambda b: b.bilinear(yield_drift_ratio=0.0), "building.A.hysteresis.yield_drift_ratio"),
    ]
    for make, field in cases:
        with pytest.raises(adjoin.InputError) as e:
            make(adjoin.StructureBuilder().building("A", 2))
        assert e.value.field == field
