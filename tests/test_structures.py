"""Bouc-Wen storeys and shear buildings."""

import numpy as np
import pytest
from scipy.linalg import eig

from pounding import BoucWen, Building, Storey
from pounding.mechanics.structures import hysteresis


@pytest.mark.parametrize("n", [1.0, 2.0, 3.0])
@pytest.mark.parametrize("alpha", [0.05, 0.2])
def test_slow_cycles_yield_at_the_bouc_wen_yield_displacement(n, alpha):
    beta_plus_gamma = 4.0e4  # yield at 5 mm for n = 2
    bouc_wen = BoucWen(alpha=alpha, A=1.0, beta=0.75 * beta_plus_gamma, gamma=0.25 * beta_plus_gamma, n=n)
    x_yield = bouc_wen.yield_displacement
    assert x_yield == pytest.approx((1.0 / beta_plus_gamma) ** (1 / n))
    k = 2.0e6
    storey = Storey(mass=1e4, stiffness=k, bouc_wen=bouc_wen)
    amplitude = 10 * x_yield
    drift = amplitude * np.sin(np.linspace(0, 4 * np.pi, 400_001))  # two slow cycles
    z, force = hysteresis(storey, drift)
    # z saturates at the yield displacement (Eq. 33) and never exceeds it.
    assert np.max(np.abs(z)) == pytest.approx(x_yield, rel=2e-3)
    assert np.max(np.abs(z)) <= x_yield * (1 + 1e-6)
    # Initial tangent k.
    first = slice(1, 20)
    assert np.polyfit(drift[first], force[first], 1)[0] == pytest.approx(k, rel=3e-3)
    # Post-yield tangent alpha k, and the asymptote meets the elastic line at x_yield.
    loading = (drift > 0.8 * amplitude) & (np.gradient(drift) > 0)
    slope, intercept = np.polyfit(drift[loading], force[loading], 1)
    assert slope == pytest.approx(alpha * k, rel=0.01)
    assert intercept / (k - slope) == pytest.approx(x_yield, rel=0.01)
    # A closed loop dissipates energy: the enclosed area is positive.
    second_cycle = slice(200_000, None)
    assert np.trapezoid(force[second_cycle], drift[second_cycle]) > 0


def test_linear_storey_is_elastic():
    storey = Storey(mass=1e4, stiffness=3.0e6, bouc_wen=BoucWen(alpha=1.0))
    drift = 0.05 * np.sin(np.linspace(0, 2 * np.pi, 1001))
    _, force = hysteresis(storey, drift)
    np.testing.assert_allclose(force, 3.0e6 * drift)


@pytest.mark.parametrize("storeys", [1, 2, 5])
def test_first_mode_gets_the_damping_ratio(storeys):
    masses = np.linspace(3e4, 2e4, storeys)
    stiffnesses = np.linspace(4e7, 2e7, storeys)
    building = Building(tuple(Storey(m, k) for m, k in zip(masses, stiffnesses)), damping_ratio=0.05)
    k_matrix = building.stiffness_matrix()
    c = building.storey_damping()
    c_matrix = Building(tuple(Storey(1.0, ci) for ci in c)).stiffness_matrix()  # same assembly as K
    m_matrix = np.diag(masses)
    n = storeys
    state = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(m_matrix, k_matrix), -np.linalg.solve(m_matrix, c_matrix)]])
    poles = eig(state)[0]
    poles = poles[poles.imag > 0]
    first = poles[np.argmin(np.abs(poles))]
    assert -first.real / abs(first) == pytest.approx(0.05, rel=1e-6)
    assert abs(first) == pytest.approx(2 * np.pi / building.periods[0], rel=1e-9)


def test_two_storey_period_matches_closed_form():
    m, k = 4.85e4, 3.48e6
    building = Building((Storey(m, k), Storey(m, k)))
    expected = np.sqrt((3 - np.sqrt(5)) / 2 * k / m)
    assert building.periods[0] == pytest.approx(2 * np.pi / expected)
