"""Statistical linearization of Bouc-Wen shear buildings (Eq. 19-21) and the
linear state-space model of the linearized buildings under filtered white noise.

Each hysteretic storey law (Eq. 2) is replaced by the linear law
zdot = c_e udot + k_e z (Eq. 19) on the storey drift u, with c_e and k_e the
Gaussian expectations of the partial derivatives of Eq. 2 (Wen 1980,
Atalik & Utku 1976), which for Gaussian (udot, z) also minimise the mean-square
error of the linear law. The statistics they need come from the stationary
covariance of the linear system, so the two are iterated to self-consistency.

The linear system's state stacks, building by building, the floor
displacements d and velocities v relative to the ground and the hysteretic
displacements z of the yielding storeys, then the states of the ground
filter: the Kanai-Tajimi filter (Eq. 7), followed by the Clough-Penzien
high-pass filter for that spectrum. The filter is driven by white noise w of
two-sided intensity G0, whose covariance is 2 pi G0 delta(tau), so the
stationary state covariance P solves A P + P A^T + 2 pi G0 b b^T = 0.

Units: SI throughout (N, m, kg, s); frequencies in [rad/s].

Modules: :mod:`.wen` (the equivalent linear coefficients, Eq. 20-21),
:mod:`.ground` (the ground filter), :mod:`.lyapunov` (the stationary
covariance), :mod:`.linear_system` (linearized buildings and their state
space), :mod:`.iteration` (the fixed-point iteration), :mod:`.equivalent`
(the equivalent storey forces along drift histories), :mod:`.residual` (the
part of the Bouc-Wen law the linearization drops, as an input: its Wiener
chaos, correlation and the pair's response to it).
"""

from pounding.closed_form.linearization.equivalent import equivalent_storey_force
from pounding.closed_form.linearization.ground import GroundFilter, ground_filter
from pounding.closed_form.linearization.iteration import (
    DEFAULT_MAX_ITERATIONS,
    DEFAULT_MEMORY,
    DEFAULT_RELAXATION,
    DEFAULT_TOLERANCE,
    linearize,
    linearize_pair,
    linearize_row,
)
from pounding.closed_form.linearization.linear_system import (
    LinearizedBuilding,
    StateSpace,
    building_state_space,
    pair_state_space,
    state_space,
)
from pounding.closed_form.linearization.lyapunov import lyapunov_covariance
from pounding.closed_form.linearization.wen import equivalent_coefficients, wen_expectations

__all__ = [
    "DEFAULT_MAX_ITERATIONS",
    "DEFAULT_MEMORY",
    "DEFAULT_RELAXATION",
    "DEFAULT_TOLERANCE",
    "GroundFilter",
    "LinearizedBuilding",
    "StateSpace",
    "building_state_space",
    "equivalent_coefficients",
    "equivalent_storey_force",
    "ground_filter",
    "linearize",
    "linearize_pair",
    "linearize_row",
    "lyapunov_covariance",
    "pair_state_space",
    "state_space",
    "wen_expectations",
]
