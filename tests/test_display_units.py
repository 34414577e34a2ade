"""The one display-units class (pounding.display_units.Display): inputs typed in the units shown go to SI and
to the case file's units and back, its labels name the units its numbers are shown in, and it agrees with the
library's unit systems."""

from __future__ import annotations

import pytest

from pounding.display_units import DISPLAY_UNITS, display
from pounding.errors import ArgumentError
from pounding.units import KGF_CM_S, SI, STANDARD_GRAVITY

DIMENSIONS = [{"length": 1}, {"force": 1}, {"mass": 1}, {"force": 1, "length": -1.5}, {"length": 2, "time": -3},
              {"length": -2.5}, {}]


@pytest.mark.parametrize("units", list(DISPLAY_UNITS))
@pytest.mark.parametrize("dimension", DIMENSIONS)
@pytest.mark.parametrize("value", [1.0, 0.0137, 2.5e9, -100.0])
def test_a_value_goes_to_si_and_to_the_file_and_back(units, dimension, value):
    shown = display(units)
    assert shown.to_si(shown.from_si(value, **dimension), **dimension) == pytest.approx(value, rel=1e-13)
    assert shown.from_si(shown.to_si(value, **dimension), **dimension) == pytest.approx(value, rel=1e-13)
    assert shown.from_file(shown.to_file(value, **dimension), **dimension) == pytest.approx(value, rel=1e-13)
    # the file's units are the system's: a value typed here means the same in SI through either path
    assert shown.system.to_si(shown.to_file(value, **dimension), **dimension) == pytest.approx(shown.to_si(value, **dimension), rel=1e-13)


def test_si_is_typed_in_mm_kn_and_t_and_written_to_the_file_in_si():
    si = display("SI")
    assert si.system is SI
    assert si.to_si(10.0, length=1) == pytest.approx(0.01)  # 10 mm
    assert si.to_si(2.0, force=1) == pytest.approx(2000.0)  # 2 kN
    assert si.to_si(40.0, mass=1) == pytest.approx(4.0e4)  # 40 t
    assert si.to_file(2.0, force=1, length=-1) == pytest.approx(2.0e6)  # 2 kN/mm = 2e6 N/m
    assert si.to_si(65.03, length=2, time=-3) == pytest.approx(65.03e-6)  # mm^2/s^3: seconds are seconds


def test_the_papers_units_are_the_case_files_own():
    kgf = display("kgf-cm-s")
    assert kgf.system is KGF_CM_S
    for dimension in DIMENSIONS:
        assert kgf.to_file(3.7, **dimension) == 3.7  # no conversion, not even a rounding error
        assert kgf.to_si(3.7, **dimension) == pytest.approx(KGF_CM_S.to_si(3.7, **dimension), rel=1e-15)
    assert kgf.to_si(1.0, force=1) == pytest.approx(STANDARD_GRAVITY)


def test_labels_name_the_units_shown():
    si, kgf = display("SI"), display("kgf-cm-s")
    assert si.label(length=1) == "mm" and si.label(mass=1) == "t" and si.label(force=1, length=-1) == "kN/mm"
    assert si.label(force=1, length=-1.5) == "kN/mm^1.5" and si.label(length=2, time=-3) == "mm^2/s^3"
    assert kgf.label(force=1, length=-1.5) == "kgf/cm^1.5" and kgf.label(mass=1) == "kgf*s^2/cm" and kgf.label(length=-2) == "1/cm^2"
    # a result shown as text carries the unit an input of its dimension is labelled with
    assert si.force(2.0e3) == "2 kN" and si.label(force=1) == "kN"
    assert kgf.length(0.01) == "1 cm" and kgf.label(length=1) == "cm"


def test_an_unknown_unit_system_is_named():
    with pytest.raises(ArgumentError, match="units"):
        display("imperial")
