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
