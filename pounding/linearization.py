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
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np
from numba import njit
from scipy.linalg import solve_continuous_lyapunov
from scipy.special import beta as beta_function
from scipy.special import betainc, gamma

from .errors import ConvergenceError
from .excitation import CloughPenzien, KanaiTajimi
from .structures import Building

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
    "lyapunov_covariance",
    "pair_state_space",
    "state_space",
    "wen_expectations",
]

DEFAULT_TOLERANCE = 1e-8
"""Relative change of c_e and k_e between iterates that ends the iteration [-]."""
DEFAULT_MAX_ITERATIONS = 200
DEFAULT_RELAXATION = 0.7
"""Under-relaxation factor of the fixed-point iteration (1: none) [-]."""
DEFAULT_MEMORY = 2
"""Iterates remembered by the Anderson mixing of the iteration (0: none)."""

_DENSE_LYAPUNOV_LIMIT = 10
"""Largest state dimension solved as a dense linear system in the entries of
the symmetric covariance; beyond, scipy's Bartels-Stewart solver is faster."""


# --- Eq. 20-21: the equivalent linear coefficients ---------------------------


def _wen_constants(n):
    """Constants of Eq. 21 that depend on n only: E[r^n] of the Rayleigh
    radius split as in Wen (1980), and B(1/2, (n+1)/2) of I_s."""
    n = np.asarray(n, dtype=float)
    root = 2.0 ** (0.5 * n)
    a = root * gamma(0.5 * n + 1.0) / math.pi
    b = root * gamma(0.5 * (n + 1.0)) / math.sqrt(math.pi)
    return n, a, b, beta_function(0.5, 0.5 * (n + 1.0))


def _wen_integral(rho, n, beta_half):
    """I_s = 2 int_l^(pi/2) sin^n(theta) d theta with l = arccos(rho) [-] (Eq. 21).

    With s = cos(theta) it is 2 int_0^rho (1 - s^2)^((n-1)/2) ds, an odd function
    of rho: sign(rho) B(1/2, (n+1)/2) I_(rho^2)(1/2, (n+1)/2), with I the
    regularized incomplete beta function and ``beta_half`` = B(1/2, (n+1)/2).
    """
    return np.sign(rho) * beta_half * betainc(0.5, 0.5 * (n + 1.0), rho * rho)


def _wen_terms(sigma_velocity, sigma_z, rho, constants):
    """(F1, F2, F3, F4) of Eq. 21 with the constants of :func:`_wen_constants`."""
    n, a, b, beta_half = constants
    i_s = _wen_integral(rho, n, beta_half)
    sigma_z_n1 = sigma_z ** (n - 1.0)
    sigma_z_n = sigma_z_n1 * sigma_z
    f1 = a * sigma_z_n * i_s
    f2 = b * sigma_z_n
    f3 = n * a * sigma_velocity * sigma_z_n1 * (2.0 * (1.0 - rho * rho) ** (0.5 * (n + 1.0)) / n + rho * i_s)
    f4 = n * b * rho * sigma_velocity * sigma_z_n1
    return f1, f2, f3, f4


def wen_expectations(sigma_velocity, sigma_z, rho, n):
    """Gaussian expectations F1..F4 of the Bouc-Wen law, Eq. 21 (corrected).

    For a zero-mean Gaussian pair (udot, z) with standard deviations
    ``sigma_velocity``, ``sigma_z`` and correlation ``rho``:

    - F1 = E[sgn(udot) |z|^(n-1) z]
    - F2 = E[|z|^n]
    - F3 = n E[|udot| |z|^(n-1)]
    - F4 = n E[udot |z|^(n-1) sgn(z)]

    so that E[d zdot/d udot] = A - beta F1 - gamma F2 and
    E[d zdot/d z] = -beta F3 - gamma F4 (Eq. 20). With polar coordinates of
    the standardized pair, E[r^n] = 2^(n/2) Gamma(n/2 + 1) and the angular
    averages give I_s / pi and the other factors of Eq. 21.

    Two printing errors of Eq. 21 are corrected here. F3 and F4 scale with the
    standard deviation of the drift *velocity*, not of the drift: as printed
    k_e would have the wrong dimensions (NOTES.md point 4). The angle of I_s is
    l = arccos(rho); the printed atan(sqrt(1 - rho^2) / rho) takes the wrong
    branch for rho < 0 and flips the sign of I_s there (NOTES.md point 5).

    Parameters
    ----------
    sigma_velocity : array_like
        Standard deviation of the storey drift velocity udot [m/s].
    sigma_z : array_like
        Standard deviation of the hysteretic displacement z [m].
    rho : array_like
        Correlation coefficient of udot and z [-], in [-1, 1].
    n : array_like
        Bouc-Wen exponent [-], >= 1.

    Returns
    -------
    F1, F2 : ndarray
        [m^n].
    F3, F4 : ndarray
        [m^n / s].
    """
    sigma_velocity, sigma_z, rho, n = np.broadcast_arrays(
        *(np.asarray(value, dtype=float) for value in (sigma_velocity, sigma_z, rho, n))
    )
    return _wen_terms(sigma_velocity, sigma_z, np.clip(rho, -1.0, 1.0), _wen_constants(n))


def _coefficients(A, beta, gamma_, statistics, constants):
    f1, f2, f3, f4 = _wen_terms(*statistics, constants)
    return A - beta * f1 - gamma_ * f2, -beta * f3 - gamma_ * f4


def equivalent_coefficients(A, beta, gamma_, n, sigma_velocity, sigma_z, rho):
    """Equivalent linear coefficients c_e [-] and k_e [1/s] of Eq. 19-20:
    c_e = A - beta F1 - gamma F2, k_e = -beta F3 - gamma F4.

    Parameters
    ----------
    A, beta, gamma_, n : array_like
        Bouc-Wen parameters (``beta``, ``gamma_`` in [1/m^n]).
    sigma_velocity, sigma_z, rho : array_like
        Statistics of the storey drift velocity and hysteretic displacement,
        see :func:`wen_expectations`.

    Returns
    -------
    c_e, k_e : ndarray
    """
    sigma_velocity, sigma_z, rho, n = np.broadcast_arrays(
        *(np.asarray(value, dtype=float) for value in (sigma_velocity, sigma_z, rho, n))
    )
    return _coefficients(A, beta, gamma_, (sigma_velocity, sigma_z, np.clip(rho, -1.0, 1.0)), _wen_constants(n))


# --- the ground filter --------------------------------------------------------


@dataclass(frozen=True, eq=False)
class GroundFilter:
    """Linear filter turning white noise into ground acceleration.

    x_f' = matrix x_f + noise_input w,  a_g = output . x_f, with w white noise
    of two-sided intensity ``G0`` [m^2/s^3]; |output . (i omega - matrix)^-1
    noise_input|^2 G0 is the spectrum's PSD.
    """

    matrix: np.ndarray
    noise_input: np.ndarray
    output: np.ndarray
    G0: float

    @property
    def size(self) -> int:
        return self.matrix.shape[0]


def ground_filter(spectrum: KanaiTajimi) -> GroundFilter:
    """State-space filter of a Kanai-Tajimi (Eq. 7) or Clough-Penzien spectrum.

    Kanai-Tajimi: x'' + 2 xi_g omega_g x' + omega_g^2 x = w and
    a_g = omega_g^2 x + 2 xi_g omega_g x'. Clough-Penzien adds
    y'' + 2 xi_f omega_f y' + omega_f^2 y = a_KT and a_g = a_KT - omega_f^2 y - 2 xi_f omega_f y'.
    """
    wg, xg = spectrum.omega_g, spectrum.xi_g
    kt_output = np.array([wg * wg, 2.0 * xg * wg])
    kt_matrix = np.array([[0.0, 1.0], [-wg * wg, -2.0 * xg * wg]])
    if not isinstance(spectrum, CloughPenzien):
        return GroundFilter(kt_matrix, np.array([0.0, 1.0]), kt_output, float(spectrum.G0))
    wf, xf = spectrum.omega_f, spectrum.xi_f
    matrix = np.zeros((4, 4))
    matrix[:2, :2] = kt_matrix
    matrix[2, 3] = 1.0
    matrix[3, :2] = kt_output
    matrix[3, 2:] = [-wf * wf, -2.0 * xf * wf]
    output = np.concatenate([kt_output, [-wf * wf, -2.0 * xf * wf]])
    return GroundFilter(matrix, np.array([0.0, 1.0, 0.0, 0.0]), output, float(spectrum.G0))


# --- linearized buildings and their state space ------------------------------


@dataclass(frozen=True, eq=False)
class LinearizedBuilding:
    """A shear building whose Bouc-Wen storeys are replaced by Eq. 19.

    Parameters
    ----------
    building : Building
    c_e : ndarray
        Equivalent coefficient of the drift velocity per storey [-] (Eq. 20).
    k_e : ndarray
        Equivalent coefficient of z per storey [1/s] (Eq. 20), <= 0. A storey
        with k_e = 0 is elastic: its z is c_e u (alpha = 1, or no excitation).
    iterations : int
        Fixed-point iterations used (0: elastic, nothing to iterate).
    sigma_drift_velocity, sigma_z, rho : ndarray
        Stationary statistics of the linearized storeys behind c_e and k_e:
        standard deviations of udot [m/s] and z [m], correlation of udot and z [-].
    """

    building: Building
    c_e: np.ndarray
    k_e: np.ndarray
    iterations: int = 0
    sigma_drift_velocity: np.ndarray | None = None
    sigma_z: np.ndarray | None = None
    rho: np.ndarray | None = None

    @property
    def hysteretic(self) -> np.ndarray:
        """Mask of the storeys that keep a state z (k_e != 0)."""
        return self.k_e != 0.0

    @property
    def n_states(self) -> int:
        """States of this building in the state space: d, v and the z of hysteretic storeys."""
        return 2 * self.building.n_storeys + int(np.count_nonzero(self.hysteretic))

    @classmethod
    def elastic(cls, building: Building) -> LinearizedBuilding:
        """The small-amplitude limit: c_e = A, k_e = 0, i.e. z = A u in every storey."""
        A = np.array([s.bouc_wen.A for s in building.storeys])
        return cls(building, A, np.zeros_like(A))


@dataclass(frozen=True, eq=False)
class StateSpace:
    """Linear model x' = matrix x + noise_input w under white noise w of
    two-sided intensity ``G0`` [m^2/s^3].

    The output matrices map the state to physical quantities, one tuple entry
    per building and one row per floor or storey (floors and storeys counted
    from the ground up, index 0 = first floor / first storey).

    Parameters
    ----------
    matrix : ndarray, (n, n)
        State matrix A_s.
    noise_input : ndarray, (n,)
        b.
    G0 : float
        Two-sided white-noise intensity [m^2/s^3].
    displacement, velocity, hysteretic : tuple of ndarray
        Floor displacements relative to the ground [m], floor velocities [m/s],
        and storey hysteretic displacements z [m] as rows over the state.
    ground_acceleration : ndarray, (n,)
        The ground acceleration a_g [m/s^2] as a row over the state.
    coupling : ndarray, (n, n)
        The part of ``matrix`` through which a_g drives the buildings
        (-1 a_g in every floor's acceleration); used to modulate the ground
        motion (Eq. 8).
    filter_states : slice
        The states of the ground filter (the last ones).
    """

    matrix: np.ndarray
    noise_input: np.ndarray
    G0: float
    displacement: tuple[np.ndarray, ...]
    velocity: tuple[np.ndarray, ...]
    hysteretic: tuple[np.ndarray, ...]
    ground_acceleration: np.ndarray
    coupling: np.ndarray
    filter_states: slice

    @property
    def size(self) -> int:
        return self.matrix.shape[0]

    @property
    def noise_covariance(self) -> np.ndarray:
        """2 pi G0 b b^T: the intensity matrix of the white noise, whose
        covariance is 2 pi G0 delta(tau) for a two-sided PSD G0."""
        return 2.0 * math.pi * self.G0 * np.outer(self.noise_input, self.noise_input)

    def acceleration(self, building: int) -> np.ndarray:
        """Rows of the floor accelerations relative to the ground [m/s^2]
        (no direct noise feed-through: a_g is a filter output)."""
        return self.velocity[building] @ self.matrix

    def drift(self, building: int) -> np.ndarray:
        """Rows of the storey drifts u_i = d_i - d_(i-1) [m] (Eq. 37)."""
        return _drift_operator(self.displacement[building])

    def drift_velocity(self, building: int) -> np.ndarray:
        """Rows of the storey drift velocities [m/s]."""
        return _drift_operator(self.velocity[building])

    def covariance(self) -> np.ndarray:
        """Stationary state covariance P: A P + P A^T + 2 pi G0 b b^T = 0
        (solved once per model; read-only)."""
        return self._stationary_covariance

    @cached_property
    def _stationary_covariance(self) -> np.ndarray:
        covariance = lyapunov_covariance(self.matrix, self.noise_covariance)
        covariance.setflags(write=False)
        return covariance


def _drift_operator(floor_rows: np.ndarray) -> np.ndarray:
    drift = floor_rows.copy()
    drift[1:] -= floor_rows[:-1]
    return drift


@lru_cache(maxsize=32)
def _lyapunov_maps(n: int):
    """Rows and columns of the upper triangle of an n x n matrix: the
    coordinates (m = n (n + 1) / 2 unknowns) of a symmetric covariance."""
    return np.triu_indices(n)


@njit(cache=True)
def _solve(matrix, rhs):
    """Solve matrix x = rhs by Gaussian elimination with partial pivoting
    (small dense systems; numba's LAPACK binding costs seconds to compile).
    Returns NaNs if the matrix is singular. Overwrites ``matrix``."""
    n = rhs.size
    x = rhs.copy()
    for k in range(n):
        pivot = k
        for i in range(k + 1, n):
            if abs(matrix[i, k]) > abs(matrix[pivot, k]):
                pivot = i
        if matrix[pivot, k] == 0.0:
            return np.full(n, np.nan)
        if pivot != k:
            for j in range(n):
                matrix[k, j], matrix[pivot, j] = matrix[pivot, j], matrix[k, j]
            x[k], x[pivot] = x[pivot], x[k]
        for i in range(k + 1, n):
            factor = matrix[i, k] / matrix[k, k]
            if factor != 0.0:
                for j in range(k, n):
                    matrix[i, j] -= factor * matrix[k, j]
                x[i] -= factor * x[k]
    for k in range(n - 1, -1, -1):
        total = x[k]
        for j in range(k + 1, n):
            total -= matrix[k, j] * x[j]
        x[k] = total / matrix[k, k]
    return x


@njit(cache=True)
def _lyapunov_upper(matrix, rhs, rows, cols):
    """Upper triangle p of the symmetric P with A P + P A^T = -Q, from the
    dense m x m system (m = n (n + 1) / 2) on ``rhs`` = upper triangle of Q
    negated; NaNs if singular."""
    n = matrix.shape[0]
    m = rows.size
    unknown = np.empty((n, n), dtype=np.int64)
    for e in range(m):
        unknown[rows[e], cols[e]] = e
        unknown[cols[e], rows[e]] = e
    operator = np.zeros((m, m))
    for e in range(m):
        i, j = rows[e], cols[e]
        for k in range(n):
            operator[e, unknown[k, j]] += matrix[i, k]
            operator[e, unknown[i, k]] += matrix[j, k]
    return _solve(operator, rhs)


def lyapunov_covariance(matrix: np.ndarray, noise_covariance: np.ndarray) -> np.ndarray:
    """Solve A P + P A^T + Q = 0 for the stationary covariance P.

    Small systems (the usual case here: a few storeys and a filter) are solved
    as a dense linear system in the n (n + 1) / 2 unknowns of the symmetric P,
    several times faster than scipy's Schur-based ``solve_continuous_lyapunov``
    at this size; larger ones by scipy.

    Parameters
    ----------
    matrix : ndarray, (n, n)
        A, asymptotically stable.
    noise_covariance : ndarray, (n, n)
        Q, symmetric.

    Returns
    -------
    ndarray, (n, n)
        P, symmetric.
    """
    n = matrix.shape[0]
    if n > _DENSE_LYAPUNOV_LIMIT:
        solution = solve_continuous_lyapunov(matrix, -noise_covariance)
        return 0.5 * (solution + solution.T)
    rows, cols = _lyapunov_maps(n)
    # Equation (i, j) of A P + P A^T = -Q is sum_k A_ik P_kj + A_jk P_ik = -Q_ij.
    upper = _lyapunov_upper(np.ascontiguousarray(matrix, dtype=float), -noise_covariance[rows, cols], rows, cols)
    if not np.all(np.isfinite(upper)):
        raise np.linalg.LinAlgError("the Lyapunov equation is singular (the system has a mode at or symmetric about zero)")
    solution = np.empty((n, n))
    solution[rows, cols] = upper
    solution[cols, rows] = upper
    return solution


def state_space(buildings, spectrum: KanaiTajimi) -> StateSpace:
    """Joint state space of linearized buildings on a common ground.

    Equations of motion of each building, floor displacements d relative to
    the ground (Eq. 36-39 with a storey damper): M d'' + T^T q = -M 1 a_g, with
    T the drift operator (u = T d) and storey forces
    q_i = alpha k u_i + (1 - alpha) k z_i + c_i udot_i acting between floors
    i-1 and i; z_i' = c_e udot_i + k_e z_i (Eq. 19). The buildings do not
    interact (no contact); they share the ground motion of ``spectrum``.

    Parameters
    ----------
    buildings : sequence of LinearizedBuilding
    spectrum : KanaiTajimi or CloughPenzien
        Stationary ground-acceleration spectrum (two-sided, [m^2/s^3]).
    """
    buildings = tuple(buildings)
    ground = ground_filter(spectrum)
    size = sum(b.n_states for b in buildings) + ground.size
    matrix = np.zeros((size, size))
    coupling = np.zeros((size, size))
    filter_slice = slice(size - ground.size, size)
    matrix[filter_slice, filter_slice] = ground.matrix
    noise_input = np.zeros(size)
    noise_input[filter_slice] = ground.noise_input
    ground_row = np.zeros(size)
    ground_row[filter_slice] = ground.output

    displacements, velocities, hysteretics = [], [], []
    offset = 0
    for linearized in buildings:
        building = linearized.building
        N = building.n_storeys
        d, v = slice(offset, offset + N), slice(offset + N, offset + 2 * N)
        hysteretic = linearized.hysteretic
        h_index = np.flatnonzero(hysteretic)
        z = slice(offset + 2 * N, offset + 2 * N + h_index.size)
        k = building.stiffnesses
        alpha = np.array([s.bouc_wen.alpha for s in building.storeys])
        # An elastic storey's z is c_e u: its (1 - alpha) k c_e adds to alpha k.
        k_elastic = alpha * k + np.where(hysteretic, 0.0, (1.0 - alpha) * k * linearized.c_e)
        drift = np.eye(N) - np.eye(N, k=-1)
        inverse_mass = (1.0 / building.masses)[:, None]
        matrix[d, v] = np.eye(N)
        matrix[v, d] = -inverse_mass * (drift.T @ (k_elastic[:, None] * drift))
        matrix[v, v] = -inverse_mass * (drift.T @ (building.storey_damping()[:, None] * drift))
        matrix[v, z] = -inverse_mass * (drift.T[:, h_index] * ((1.0 - alpha) * k)[h_index])
        matrix[z, v] = linearized.c_e[h_index, None] * drift[h_index]
        matrix[z, z] = np.diag(linearized.k_e[h_index])
        # M^-1 (-M 1 a_g) = -1 a_g.
        coupling[v, filter_slice] = -ground.output
        displacement = np.zeros((N, size))
        displacement[:, d] = np.eye(N)
        velocity = np.zeros((N, size))
        velocity[:, v] = np.eye(N)
        z_rows = linearized.c_e[:, None] * _drift_operator(displacement)
        z_rows[h_index] = 0.0
        z_rows[h_index, z] = np.eye(h_index.size)
        displacements.append(displacement)
        velocities.append(velocity)
        hysteretics.append(z_rows)
        offset += linearized.n_states
    matrix += coupling
    return StateSpace(
        matrix,
        noise_input,
        ground.G0,
        tuple(displacements),
        tuple(velocities),
        tuple(hysteretics),
        ground_row,
        coupling,
        filter_slice,
    )


def building_state_space(linearized: LinearizedBuilding, spectrum: KanaiTajimi) -> StateSpace:
    """State space of one linearized building and the ground filter."""
    return state_space((linearized,), spectrum)


def pair_state_space(case, linearized=None) -> StateSpace:
    """Joint state space of a case's two linearized buildings and the ground
    filter of its stationary spectrum: the model behind the cross covariances
    of Eq. 16-18 and 25.

    Parameters
    ----------
    case : Case
    linearized : tuple of two LinearizedBuilding, optional
        From :func:`linearize_pair`; computed when omitted.
    """
    if linearized is None:
        linearized = linearize_pair(case)
    return state_space(linearized, case.excitation.spectrum)


# --- the fixed-point iteration -----------------------------------------------


@njit(cache=True)
def _second_moments(matrix, rhs, rows, cols, left, right):
    """left_i^T P right_i for the stationary covariance P of ``matrix`` under
    the noise whose negated upper triangle is ``rhs``."""
    upper = _lyapunov_upper(matrix, rhs, rows, cols)
    n = matrix.shape[0]
    covariance = np.empty((n, n))
    for e in range(rows.size):
        covariance[rows[e], cols[e]] = upper[e]
        covariance[cols[e], rows[e]] = upper[e]
    out = np.zeros(left.shape[0])
    for i in range(left.shape[0]):
        for j in range(n):
            if left[i, j] != 0.0:
                for k in range(n):
                    out[i] += left[i, j] * covariance[j, k] * right[i, k]
    return out


@njit(cache=True)
def _iteration_moments(matrix, z_states, velocity_start, drift_rows, c_e, k_e, rhs, rows, cols, left, right):
    """Put (c_e, k_e) of the yielding storeys into the state matrix (in place)
    and return their second moments, see :class:`_StoreyMoments`."""
    for s in range(z_states.size):
        row = z_states[s]
        for j in range(drift_rows.shape[1]):
            matrix[row, velocity_start + j] = c_e[s] * drift_rows[s, j]
        matrix[row, row] = k_e[s]
    return _second_moments(matrix, rhs, rows, cols, left, right)


class _StoreyMoments:
    """Var(udot), Var(z) and Cov(udot, z) of the yielding storeys of one
    building (concatenated), for the elastic start and as a function of
    (c_e, k_e), with all that does not depend on the coefficients prepared once."""

    def __init__(self, building: Building, spectrum: KanaiTajimi, yielding: np.ndarray):
        A = np.array([s.bouc_wen.A for s in building.storeys])
        # Any k_e != 0 gives every yielding storey a state z.
        model = state_space((LinearizedBuilding(building, A, np.where(yielding, -1.0, 0.0)),), spectrum)
        index = np.flatnonzero(yielding)
        N, count = building.n_storeys, index.size
        self.z_states = 2 * N + np.arange(count)
        self.velocity_start = N
        self.drift_rows = np.ascontiguousarray((np.eye(N) - np.eye(N, k=-1))[index])
        self.matrix = model.matrix.copy()
        self.rows, self.cols = _lyapunov_maps(model.size)
        noise = model.noise_covariance
        self.rhs = np.ascontiguousarray(-noise[self.rows, self.cols])
        velocity, z = model.drift_velocity(0)[index], model.hysteretic[0][index]
        self.left = np.concatenate([velocity, z, velocity])
        self.right = np.concatenate([velocity, z, z])
        self.noise = noise
        self.dense = model.size <= _DENSE_LYAPUNOV_LIMIT

        # The elastic start: substitute z = A u = A (drift rows) d, drop the z states.
        keep = np.concatenate([np.arange(2 * N), np.arange(2 * N + count, model.size)])
        substitution = np.zeros((count, model.size))
        substitution[:, :N] = A[index, None] * self.drift_rows
        matrix = model.matrix + model.matrix[:, self.z_states] @ substitution
        covariance = lyapunov_covariance(matrix[np.ix_(keep, keep)], noise[np.ix_(keep, keep)])
        velocity, z = velocity[:, keep], substitution[:, keep]
        self.elastic = _quadratic_forms(np.concatenate([velocity, z, velocity]), covariance, np.concatenate([velocity, z, z]))

    def __call__(self, c_e: np.ndarray, k_e: np.ndarray) -> np.ndarray:
        """(Var udot, Var z, Cov(udot, z)) of the yielding storeys, concatenated;
        NaN if the Lyapunov equation is singular."""
        if self.dense:
            return _iteration_moments(
                self.matrix, self.z_states, self.velocity_start, self.drift_rows, c_e, k_e, self.rhs, self.rows, self.cols, self.left, self.right
            )
        N = self.velocity_start
        self.matrix[self.z_states, N : 2 * N] = c_e[:, None] * self.drift_rows
        self.matrix[self.z_states, self.z_states] = k_e
        try:
            covariance = lyapunov_covariance(self.matrix, self.noise)
        except (np.linalg.LinAlgError, ValueError):
            return np.full(self.left.shape[0], np.nan)
        return _quadratic_forms(self.left, covariance, self.right)


def _quadratic_forms(left: np.ndarray, covariance: np.ndarray, right: np.ndarray) -> np.ndarray:
    """left_i^T P right_i for every row i."""
    return np.einsum("ij,jk,ik->i", left, covariance, right)


@njit(cache=True)
def _mixing_step(x, residual, history_x, history_f, filled, relaxation, count):
    """Under-relaxed fixed-point step with Anderson mixing (Walker & Ni 2011).

    ``history_x`` and ``history_f`` hold the last ``filled`` iterates and
    residuals (updated in place). The step is shortened until c_e > 0 and
    k_e < 0 (the first ``count`` entries of x are c_e, the next k_e).
    Returns the step (all zeros if no admissible step exists) and the new
    ``filled``. Plain loops: numba compiles array expressions and BLAS calls
    slowly (seconds), and the sizes here are tiny.
    """
    depth, size = history_x.shape
    if filled == depth:
        for i in range(depth - 1):
            for j in range(size):
                history_x[i, j] = history_x[i + 1, j]
                history_f[i, j] = history_f[i + 1, j]
        filled -= 1
    for j in range(size):
        history_x[filled, j] = x[j]
        history_f[filled, j] = residual[j]
    filled += 1
    step = np.empty(size)
    for j in range(size):
        step[j] = relaxation * residual[j]
    columns = filled - 1
    if columns > 0:
        # The combination of the last differences that best cancels the
        # residual (least squares by the normal equations, lightly
        # regularized against repeated residuals), applied to the iterates
        # and residuals.
        gram = np.zeros((columns, columns))
        projection = np.zeros(columns)
        for a in range(columns):
            for j in range(size):
                d_fa = history_f[a + 1, j] - history_f[a, j]
                projection[a] += d_fa * residual[j]
                for b in range(columns):
                    gram[a, b] += d_fa * (history_f[b + 1, j] - history_f[b, j])
        trace = 0.0
        for a in range(columns):
            trace += gram[a, a]
        for a in range(columns):
            gram[a, a] += 1e-12 * trace + 1e-300
        weights = _solve(gram, projection)
        finite = True
        for a in range(columns):
            finite = finite and math.isfinite(weights[a])
        if finite:
            for a in range(columns):
                for j in range(size):
                    d_x = history_x[a + 1, j] - history_x[a, j]
                    d_f = history_f[a + 1, j] - history_f[a, j]
                    step[j] -= (d_x + relaxation * d_f) * weights[a]
    for _ in range(60):
        admissible = True
        for i in range(count):
            if not (x[i] + step[i] > 0.0 and x[count + i] + step[count + i] < 0.0):
                admissible = False
        if admissible:
            return step, filled
        for j in range(size):
            step[j] *= 0.5
    return np.zeros(size), filled


def linearize(
    building: Building,
    spectrum: KanaiTajimi,
    tolerance: float = DEFAULT_TOLERANCE,
    max_iterations: int = DEFAULT_MAX_ITERATIONS,
    relaxation: float = DEFAULT_RELAXATION,
    memory: int = DEFAULT_MEMORY,
    label: str = "building",
) -> LinearizedBuilding:
    """Statistical linearization of a Bouc-Wen shear building (Eq. 19-21).

    Starts from the elastic system (c_e = A, k_e = 0: z = A u, so
    sigma_z = A sigma_u and rho = 0), then repeats: stationary covariance of
    the linear building under the ground filter's white noise (Lyapunov
    equation), storey statistics, target c_e and k_e from Eq. 20-21
    (corrected, see :func:`wen_expectations`), under-relaxed update; until the
    relative change of every coefficient is below ``tolerance``. Storeys with
    alpha = 1 are exactly elastic and are not iterated.

    The under-relaxed fixed-point step is accelerated by Anderson mixing over
    the last ``memory`` iterates (Walker & Ni 2011): plain under-relaxation
    needs 20-60 iterations and, for strongly yielding multi-storey buildings,
    a relaxation small enough to stop it oscillating; mixing converges in
    about 10 over the range tried (G0 from 1e-6 to 1e5 times the paper's). A
    step that would leave c_e > 0, k_e < 0 (where the linear storey is a
    passive Maxwell element, so the system stays stable) is shortened.

    Parameters
    ----------
    building : Building
    spectrum : KanaiTajimi or CloughPenzien
        Stationary ground-acceleration spectrum (two-sided, [m^2/s^3]). For a
        non-stationary case pass the unmodulated spectrum: the paper linearizes
        under the stationary response (sigma_inf).
    tolerance : float
        Relative change of c_e and k_e below which the iteration stops [-];
        a k_e smaller than 1e-6 of the storey's frequency sqrt(k / m) is
        measured against that (near the elastic limit).
    max_iterations : int
    relaxation : float
        Under-relaxation factor in (0, 1]: the plain step moves this fraction
        of the way to the target coefficients.
    memory : int
        Iterates remembered by the Anderson mixing; 0 gives plain
        under-relaxation.
    label : str
        Name of the building in error messages.

    Returns
    -------
    LinearizedBuilding

    Raises
    ------
    ConvergenceError
        If the iteration does not converge or the linear system loses
        stability; the message names the building, the storey, and the last
        iterate.
    """
    if not 0.0 < relaxation <= 1.0:
        raise ValueError(f"relaxation must lie in (0, 1], got {relaxation!r}")
    storeys = building.storeys
    yielding = np.array([s.bouc_wen.alpha < 1.0 for s in storeys])
    elastic = LinearizedBuilding.elastic(building)
    if spectrum.G0 == 0.0 or not yielding.any():
        # No motion, or no hysteresis: the elastic system is exact.
        return elastic
    index = np.flatnonzero(yielding)
    laws = [storeys[i].bouc_wen for i in index]
    constants = [tuple(float(c) for c in _wen_constants(law.n)) for law in laws]
    # k_e is converged relative to itself, or to 1e-6 of the storey's
    # frequency when smaller: near the elastic limit k_e -> 0 and the
    # Lyapunov equation becomes ill-conditioned (a mode decaying as k_e).
    floors = [1e-6 * math.sqrt(storeys[i].stiffness / storeys[i].mass) for i in index]
    count = index.size
    moments = _StoreyMoments(building, spectrum, yielding)

    def targets(values, iteration, current):
        """Target coefficients (c_e then k_e) of the second moments ``values``,
        the storey statistics, and the largest relative change from ``current``
        with its storey."""
        values, current = values.tolist(), current.tolist()
        out = np.empty(2 * count)
        sigma = np.empty((3, count))
        worst, worst_storey = 0.0, 0
        # Scalar arithmetic: a handful of storeys, where numpy's per-call cost dominates.
        for s, law in enumerate(laws):
            var_velocity, var_z, cross = values[s], values[count + s], values[2 * count + s]
            if not (0.0 < var_velocity < math.inf and 0.0 < var_z < math.inf):
                # NaN from a singular Lyapunov equation, or a 'covariance' that is not one.
                _fail(label, f"the linear system is singular or unstable at iteration {iteration}", index[s], current, count)
            sigma_velocity, sigma_z = math.sqrt(var_velocity), math.sqrt(var_z)
            rho = min(1.0, max(-1.0, cross / (sigma_velocity * sigma_z)))
            sigma[:, s] = sigma_velocity, sigma_z, rho
            c_e, k_e = _coefficients(law.A, law.beta, law.gamma, (sigma_velocity, sigma_z, rho), constants[s])
            if not (math.isfinite(c_e) and math.isfinite(k_e)):
                _fail(label, f"non-finite coefficients at iteration {iteration}", index[s], current, count)
            change = max(
                abs(c_e - current[s]) / max(abs(c_e), 1e-300),
                abs(k_e - current[count + s]) / max(abs(k_e), floors[s]),
            )
            if change >= worst:
                worst, worst_storey = change, s
            out[s], out[count + s] = c_e, k_e
        return out, sigma, worst, worst_storey

    coefficients = np.concatenate([[law.A for law in laws], np.zeros(count)])
    target, sigma, worst, worst_storey = targets(moments.elastic, 1, coefficients)
    # Iterate on scaled coefficients (c_e / A, k_e / |first k_e|), so that the
    # mixing's least squares weighs them alike.
    scale = np.concatenate([coefficients[:count], np.maximum(np.abs(target[count:]), 1e-300)])
    history_x = np.empty((memory + 1, 2 * count))
    history_f = np.empty_like(history_x)
    filled = 0
    for iteration in range(1, max_iterations + 1):
        if iteration > 1:
            values = moments(coefficients[:count], coefficients[count:])
            target, sigma, worst, worst_storey = targets(values, iteration, coefficients)
        if worst < tolerance:
            full_c, full_k = elastic.c_e.copy(), elastic.k_e.copy()
            full_c[index], full_k[index] = target[:count], target[count:]
            statistics = np.full((3, len(storeys)), np.nan)
            statistics[:, index] = sigma
            return LinearizedBuilding(building, full_c, full_k, iteration, *statistics)
        x = coefficients / scale
        step, filled = _mixing_step(x, target / scale - x, history_x, history_f, filled, relaxation, count)
        if not step.any():
            _fail(label, f"no step keeps c_e > 0 and k_e < 0 at iteration {iteration}", index[worst_storey], coefficients, count)
        coefficients = (x + step) * scale
    _fail(
        label,
        f"no convergence in {max_iterations} iterations (relative change {worst:.3g} > {tolerance:g})",
        index[worst_storey],
        coefficients,
        count,
    )


def _fail(label: str, reason: str, storey: int, coefficients, count: int):
    """Raise ConvergenceError naming the building, the storey (counted from 0
    here, from 1 in the message) and the last iterate (c_e then k_e of the
    yielding storeys)."""
    coefficients = np.asarray(coefficients, dtype=float)
    c_e, k_e = coefficients[:count], coefficients[count:]
    error = ConvergenceError(
        f"statistical linearization of {label}, storey {storey + 1}: {reason}; last iterate (yielding storeys) "
        f"c_e = {np.array2string(c_e, precision=6)}, k_e = {np.array2string(k_e, precision=6)} 1/s"
    )
    error.building, error.storey, error.c_e, error.k_e = label, int(storey) + 1, c_e.copy(), k_e.copy()
    raise error


def linearize_pair(case, **options) -> tuple[LinearizedBuilding, LinearizedBuilding]:
    """Linearize both buildings of a case under its stationary spectrum.

    The buildings do not interact in the linearization (no contact), so each
    is linearized alone. For a non-stationary case the envelope is ignored:
    the paper linearizes under the stationary (unmodulated) excitation.

    Parameters
    ----------
    case : Case
    **options
        ``tolerance``, ``max_iterations``, ``relaxation`` of :func:`linearize`.
    """
    spectrum = case.excitation.spectrum
    first, second = (
        linearize(building, spectrum, label=f"building {number}", **options)
        for number, building in enumerate(case.buildings, start=1)
    )
    return first, second


def equivalent_storey_force(linearized: LinearizedBuilding, time, drift) -> np.ndarray:
    """Restoring forces of the equivalent linear storeys along given drift histories.

    The storey law of the linearized building, q = alpha k u + (1 - alpha) k z
    with zdot = c_e udot + k_e z (Eq. 19), driven by the drifts ``drift``
    (linear between samples, starting from rest); it is the linear
    counterpart of the Bouc-Wen loop (Eq. 36) that the same drifts trace.

    Parameters
    ----------
    linearized : LinearizedBuilding
    time : array_like, shape (steps,)
        Increasing instants [s].
    drift : array_like, shape (steps, storeys)
        Storey drifts u of ``linearized.building`` at ``time`` [m].

    Returns
    -------
    ndarray, shape (steps, storeys)
        Restoring forces [N] (damper forces excluded).
    """
    time = np.asarray(time, dtype=float)
    drift = np.asarray(drift, dtype=float).reshape(time.size, -1)
    building = linearized.building
    if drift.shape[1] != building.n_storeys:
        raise ValueError(f"drift must have one column per storey ({building.n_storeys}), got {drift.shape[1]}")
    k = building.stiffnesses
    alpha = np.array([s.bouc_wen.alpha for s in building.storeys])
    z = linearized.c_e * drift  # the elastic storeys (k_e = 0): z = c_e u
    step = np.diff(time)[:, None]
    increment = np.diff(drift, axis=0)
    for j in np.flatnonzero(linearized.hysteretic):
        # Exact for a drift rate s constant over each step:
        # z(t + h) = z e^(k_e h) + c_e s (e^(k_e h) - 1) / k_e.
        k_e = linearized.k_e[j]
        decay = np.exp(k_e * step[:, 0])
        with np.errstate(invalid="ignore", divide="ignore"):
            rate = np.where(step[:, 0] > 0, increment[:, j] / step[:, 0], 0.0)
        forcing = linearized.c_e[j] * rate * np.expm1(k_e * step[:, 0]) / k_e
        z[:, j] = _first_order_recurrence(decay, forcing)
    return alpha * k * drift + (1.0 - alpha) * k * z


@njit(cache=True)
def _first_order_recurrence(decay, forcing):
    """y[0] = 0, y[i + 1] = y[i] decay[i] + forcing[i] (compiled: a record has thousands of steps)."""
    out = np.zeros(decay.size + 1)
    value = 0.0
    for i in range(decay.size):
        value = value * decay[i] + forcing[i]
        out[i + 1] = value
    return out
