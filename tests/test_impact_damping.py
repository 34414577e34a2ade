"""The impacts' damping of the relative motion (pounding.closed_form.impact_damping):
each piece against an independent route, and the fixed point against its
definition."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.linalg import expm

from pounding import load_case
from pounding.closed_form.estimator import estimate
from pounding.closed_form.gap_aware import gap_for_probability
from pounding.closed_form.impact_damping import impact_damping, jump_modes
from pounding.closed_form.pair import LinearizedPair
from pounding.closed_form.response import contact_output_matrix
from pounding.mechanics.structures import BoucWen
from pounding.studies.paper_tables import mdof_case, varied_case
from tests.free_count import free_force

CASES = {
    "yielding one-storey pair": lambda: load_case("section5-T2-0.8"),
    "elastic pair": lambda: varied_case(load_case("section5-T2-0.4"), elastic=True, periods=(0.61, 0.48), g0=5.86, restitution=0.42),
    "three-storey against two-storey": mdof_case,
}


def _pair(case):
    pair = LinearizedPair.of(case)
    return pair.buildings, pair.state_space, pair.impact_damping


def _floors(case):
    """The contact floors counted from 0."""
    return tuple(level - 1 for level in case.contact.levels)


def _with_dashpot(case, model, dashpot):
    """The pair's state space with a dashpot between the contact floors, written
    into the equations of motion: m1 v1' += -c (v1 - v2), m2 v2' += +c (v1 - v2)."""
    outputs = contact_output_matrix(_floors(case), model)
    floor_1, floor_2 = int(np.flatnonzero(outputs[2])[0]), int(np.flatnonzero(outputs[3])[0])
    m1, m2 = case.contact_masses
    matrix = model.matrix.copy()
    relative = outputs[2] - outputs[3]
    matrix[floor_1] -= dashpot / m1 * relative
    matrix[floor_2] += dashpot / m2 * relative
    return dataclasses.replace(model, matrix=matrix)


def _sigmas(case, model):
    outputs = contact_output_matrix(_floors(case), model)
    rows = np.array([outputs[0] - outputs[1], outputs[2] - outputs[3]])
    return np.sqrt(np.diag(rows @ model.covariance() @ rows.T))


@pytest.mark.parametrize("kind", CASES)
def test_the_dashpot_divides_the_spectrum_as_the_state_space_with_a_dashpot_says(kind):
    """The feedback route (X / (1 + c G) on the frequency grid) against the
    Lyapunov equation of the pair with the dashpot in its equations of motion."""
    case = CASES[kind]()
    _, model, damping = _pair(case)
    free = _sigmas(case, model)
    for dashpot in (1e3, 1e4, 1e5):
        ratio_x, ratio_v, bandwidth = damping.with_dashpot(dashpot)
        sigmas = _sigmas(case, _with_dashpot(case, model, dashpot))
        assert ratio_x == pytest.approx(sigmas[0] / free[0], rel=5e-4)
        assert ratio_v == pytest.approx(sigmas[1] / free[1], rel=5e-4)
        assert 0.0 < bandwidth < 1.0
    assert damping.with_dashpot(0.0)[2] == pytest.approx(damping.bandwidth, rel=1e-12)


@pytest.mark.slow
@pytest.mark.parametrize("kind", CASES)
def test_memory_is_the_jump_response_averaged_over_exponential_intervals(kind):
    """rho against (omega x_J)^2 + v_J^2 of the pair's state space after the
    impact's velocity jump (scipy's expm), integrated over the intervals' law."""
    case = CASES[kind]()
    _, model, damping = _pair(case)
    outputs = contact_output_matrix(_floors(case), model)
    m1, m2 = case.contact_masses
    jump = (-m2 * outputs[2] + m1 * outputs[3]) / (m1 + m2)  # V falls by 1, momentum kept
    rows = np.array([outputs[0] - outputs[1], outputs[2] - outputs[3]])
    omega = damping.sigma_relative_velocity / damping.sigma_relative_displacement
    assert rows[1] @ jump == pytest.approx(-1.0)

    def share(lag):
        x, v = rows @ expm(model.matrix * lag) @ jump
        return min(1.0, (omega * x) ** 2 + v**2)

    for rate in (0.3 * omega, omega / math.pi, 2.0 * omega):
        expected, _ = quad(lambda lag: share(lag) * rate * math.exp(-rate * lag), 0.0, 40.0 / rate, limit=400)
        assert damping.memory(rate) == pytest.approx(expected, rel=2e-3, abs=1e-5)


def test_a_single_oscillator_forgets_at_its_own_damping():
    """For one elastic oscillator the share of a disturbance's energy left after
    an exponential interval of rate nu is nu / (nu + 2 zeta omega_n)."""
    base = load_case("section5-T2-0.4")
    building, wall = base.buildings
    storey = dataclasses.replace(building.storeys[0], bouc_wen=BoucWen(alpha=1.0))
    mass = storey.mass * 1e4  # the second building as a wall: heavy and stiff
    rigid = dataclasses.replace(wall.storeys[0], mass=mass, stiffness=mass * (2 * math.pi / 0.02) ** 2, bouc_wen=BoucWen(alpha=1.0))
    case = dataclasses.replace(
        base,
        buildings=(dataclasses.replace(building, storeys=(storey,)), dataclasses.replace(wall, storeys=(rigid,))),
        name="oscillator against a wall",
    )
    _, _, damping = _pair(case)
    natural = math.sqrt(storey.stiffness / storey.mass)
    zeta = case.buildings[0].storey_damping()[0] / (2.0 * storey.mass * natural)
    for rate in (natural / math.pi, 2.0 * natural / math.pi):
        assert damping.memory(rate) == pytest.approx(rate / (rate + 2.0 * zeta * natural), rel=0.01)


@pytest.mark.parametrize("kind", CASES)
def test_the_dashpot_leaves_the_motion_the_energy_its_impacts_leave_it(kind):
    """At the solved dashpot, sigma_V^2 has fallen to (1 - rho) / (1 - rho e^2)
    of the free one, rho the memory at the damped motion's impact rate
    (Rice's rate with the time cut): the defining equation, from the public pieces."""
    case = CASES[kind]()
    _, _, damping = _pair(case)
    e = case.contact.restitution
    for gap in (0.0, 0.5 * damping.sigma_relative_displacement, case.contact.gap):
        motion = damping.damped([gap])
        ratio_x, ratio_v, bandwidth = damping.with_dashpot(motion.dashpot[0])
        sigma_x = damping.sigma_relative_displacement * ratio_x
        sigma_v = damping.sigma_relative_velocity * ratio_v
        u = gap / sigma_x
        rate = sigma_v / sigma_x * math.exp(-0.5 * u * u) / (math.pi * math.erfc(-u / math.sqrt(2.0)))
        rho = damping.memory(rate)
        assert motion.memory[0] == pytest.approx(rho, rel=1e-5, abs=1e-9)
        assert ratio_v**2 == pytest.approx((1.0 - rho) / (1.0 - rho * e * e), abs=1e-6)
        assert (motion.ratio_displacement[0], motion.ratio_velocity[0], motion.bandwidth[0]) == pytest.approx(
            (ratio_x, ratio_v, bandwidth), rel=1e-9
        )


def test_the_damping_vanishes_with_the_dissipation_and_with_the_impacts():
    """Continuously: as e -> 1 the impacts take no energy, and as the gap
    leaves the motion's reach there are no impacts."""
    case = CASES["elastic pair"]()
    near = LinearizedPair.of(case).impact_damping.damped([0.0]).ratio_velocity[0]
    assert near < 0.8  # this pair remembers its impacts
    losses = [1.0 - LinearizedPair.of(varied_case(case, restitution=e)).impact_damping.damped([0.0]).ratio_velocity[0] for e in (0.9, 0.99, 0.999, 1.0)]
    assert losses[0] > losses[1] > losses[2] > 0.0 and losses[2] < 2e-3 and losses[3] == pytest.approx(0.0, abs=1e-12)
    _, _, damping = _pair(case)
    sigma = damping.sigma_relative_displacement
    losses = [1.0 - damping.damped([u * sigma]).ratio_velocity[0] for u in (1.0, 2.0, 3.0, 4.0, 12.0)]
    assert all(a > b for a, b in zip(losses[:-2], losses[1:-1])) and losses[3] < 1e-3 and losses[4] == pytest.approx(0.0, abs=1e-12)


def test_the_count_uses_the_damped_sigmas_and_bandwidth():
    """The impacting count at a gap equals the free count of a pair whose sigma
    history is scaled by the damped ratios and whose bandwidth is the damped one."""
    case = CASES["elastic pair"]()
    crossings = estimate(case).crossings
    gap = np.array([0.01])
    motion = crossings.damped(gap)
    speeds = np.linspace(0.0, 3.0 * crossings.sigma_v.max(), 7)
    scaled = dataclasses.replace(
        crossings,
        sigma_x=crossings.sigma_x * motion.ratio_displacement[0],
        sigma_v=crossings.sigma_v * motion.ratio_velocity[0],
        bandwidth=motion.bandwidth[0],
    )
    assert motion.ratio_velocity[0] < 0.9
    np.testing.assert_allclose(crossings.impacting_intensity(gap, speeds, motion), scaled.intensity(gap, speeds), rtol=1e-12)


def test_the_free_count_keeps_the_probability_and_the_gap_for_the_target():
    """The first impact meets the free motion: the damping changes the force,
    not the pounding probability or the gap for the target probability."""
    case = CASES["elastic pair"]()
    damped = estimate(case)
    free = damped.crossings  # its counts of the free motion
    gap = np.array([case.contact.gap])
    assert damped.pounding_probability == float(-math.expm1(-free.intensity(gap, np.zeros(1))[0, 0]))
    assert damped.required_gap == gap_for_probability(free, damped.target_probability)
    assert damped.impacting_velocity_ratio < 1.0
    assert damped.force_expected < free_force(case, damped.crossings, gap)[0]


def test_gap_curve_agrees_with_single_estimates():
    case = CASES["elastic pair"]()
    result = estimate(case)
    gaps = np.array([0.0, 0.01, 0.03])
    curve = result.gap_curve(gaps)
    for gap, force in zip(gaps, curve.force_expected):
        single = estimate(varied_case(case, gap=gap))
        # the curve integrates on 81 speeds, the estimate on 121 (1e-4)
        assert force == pytest.approx(single.force_expected, rel=1e-3)



def test_the_dashpot_takes_only_what_it_is_given():
    """impact_damping reads nothing back from the pair: given the pair's pieces with e = 1 (elastic impacts, no
    loss) it finds no dashpot and the free motion; with the pair's own e it finds the pair's dashpot."""
    pair = LinearizedPair.of(load_case("section5-T2-0.8"))
    response, case = pair.response_with_residual, pair.case
    (_, r1), (_, r2) = pair.contact_floor_frfs
    modes = jump_modes(pair.state_space, pair.buildings, pair.floors, case.contact_masses)
    pieces = (response.sigma_relative_displacement, response.sigma_relative_velocity, pair.relative_displacement_psd,
              pair.relative_displacement_moments, (r1, r2), pair.bandwidth, case.reduced_mass)
    elastic = impact_damping(*pieces, 1.0, modes).damped([0.0, 0.01])
    np.testing.assert_array_equal(elastic.dashpot, 0.0)
    np.testing.assert_allclose(elastic.ratio_velocity, 1.0, rtol=1e-12)
    lossy = impact_damping(*pieces, case.contact.restitution, modes).damped([0.0, 0.01])
    np.testing.assert_array_equal(lossy.dashpot, pair.impact_damping.damped([0.0, 0.01]).dashpot)
    assert np.all(lossy.dashpot > 0) and np.all(lossy.ratio_velocity < 1)
