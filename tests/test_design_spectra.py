"""Design spectra against the codes' corner values, worked by hand."""

import numpy as np
import pytest

from pounding.errors import ArgumentError, CaseError
from pounding.hazard.design_spectra import ASCE7Spectrum, Eurocode8Spectrum, TabulatedSpectrum

G = 9.80665


def test_eurocode8_type1_ground_c_corners():
    # EN 1998-1 Table 3.2, ground C: S = 1.15, TB = 0.2, TC = 0.6, TD = 2.0; ag = 0.3 g.
    spectrum = Eurocode8Spectrum(0.3 * G, "C", 1)
    ag_s = 0.3 * G * 1.15
    values = spectrum.pseudo_acceleration([0.0, 0.1, 0.2, 0.4, 0.6, 1.2, 2.0, 4.0])
    expected = [ag_s, ag_s * 1.75, 2.5 * ag_s, 2.5 * ag_s, 2.5 * ag_s, 2.5 * ag_s * 0.5,
                2.5 * ag_s * 0.3, 2.5 * ag_s * 0.6 * 2.0 / 16.0]
    np.testing.assert_allclose(values, expected, rtol=1e-12)
    assert spectrum.peak_ground_acceleration == pytest.approx(ag_s)
    assert "type 1" in spectrum.describe() and "\n" not in spectrum.describe()


def test_eurocode8_type2_ground_d_corners():
    # Table 3.3, ground D: S = 1.8, TB = 0.1, TC = 0.3, TD = 1.2.
    spectrum = Eurocode8Spectrum(2.0, "d", 2)
    values = spectrum.pseudo_acceleration([0.05, 0.3, 0.6, 2.4])
    np.testing.assert_allclose(values, [3.6 * 1.75, 9.0, 4.5, 9.0 * 0.3 * 1.2 / 2.4**2], rtol=1e-12)


def test_eurocode8_is_continuous_at_every_corner():
    for kind in (1, 2):
        for ground in "ABCDE":
            spectrum = Eurocode8Spectrum(1.0, ground, kind)
            for corner in spectrum.parameters[1:]:
                below, above = spectrum.pseudo_acceleration([corner * (1 - 1e-9), corner * (1 + 1e-9)])
                assert below == pytest.approx(above, rel=1e-6)


def test_asce7_corners():
    spectrum = ASCE7Spectrum(SDS=1.0 * G, SD1=0.6 * G, TL=8.0)
    # T0 = 0.12 s, TS = 0.6 s.
    values = spectrum.pseudo_acceleration([0.0, 0.06, 0.12, 0.6, 1.2, 8.0, 16.0])
    np.testing.assert_allclose(values / G, [0.4, 0.7, 1.0, 1.0, 0.5, 0.075, 0.6 * 8 / 256], rtol=1e-12)
    assert spectrum.peak_ground_acceleration == pytest.approx(0.4 * G)


def test_tabulated_is_log_log_flat_below_and_one_over_t_squared_beyond():
    spectrum = TabulatedSpectrum((0.1, 1.0, 2.0), (5.0, 2.0, 1.0))
    # log-log midpoint of (0.1, 5) and (1, 2): at sqrt(0.1) the geometric mean.
    assert spectrum.pseudo_acceleration(np.sqrt(0.1)) == pytest.approx(np.sqrt(10.0))
    np.testing.assert_allclose(spectrum.pseudo_acceleration([0.0, 0.05, 1.0, 4.0]), [5.0, 5.0, 2.0, 0.25])
    assert spectrum.peak_ground_acceleration == 5.0


@pytest.mark.parametrize("make, field", [
    (lambda: Eurocode8Spectrum(0.0, "C", 1), "ag"),
    (lambda: Eurocode8Spectrum(float("nan"), "C", 1), "ag"),
    (lambda: Eurocode8Spectrum(3.0, "F", 1), "ground_type"),
    (lambda: Eurocode8Spectrum(3.0, "C", 3), "spectrum_type"),
    (lambda: ASCE7Spectrum(-1.0, 1.0, 8.0), "SDS"),
    (lambda: ASCE7Spectrum(1.0, float("inf"), 8.0), "SD1"),
    (lambda: ASCE7Spectrum(1.0, 2.0, 1.0), "TL"),
    (lambda: TabulatedSpectrum((0.1,), (1.0,)), "periods"),
    (lambda: TabulatedSpectrum((0.2, 0.1), (1.0, 1.0)), "periods"),
    (lambda: TabulatedSpectrum((0.1, 0.2), (1.0, 0.0)), "accelerations"),
    (lambda: TabulatedSpectrum((0.1, 0.2), (1.0,)), "accelerations"),
])
def test_bad_input_names_its_field(make, field):
    with pytest.raises(CaseError) as error:
        make()
    assert error.value.field.split(".")[0] == field
    assert len(str(error.value)) < 200 and "\n" not in str(error.value)


def test_negative_period_is_refused():
    with pytest.raises(ArgumentError, match="periods"):
        ASCE7Spectrum(1.0, 0.5).pseudo_acceleration([-1.0])
