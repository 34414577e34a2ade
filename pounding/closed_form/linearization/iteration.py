"""The fixed-point iteration of the statistical linearization: stationary
covariance of the linear building, storey statistics, equivalent
coefficients (Eq. 20-21), an under-relaxed step with Anderson mixing, until
self-consistent."""

from __future__ import annotations

import math

import numpy as np

from pounding.closed_form.linearization.kernels import iteration_moments, mixing_step
from pounding.closed_form.linearization.linear_system import LinearizedBuilding, state_space
from pounding.closed_form.linearization.lyapunov import DENSE_LYAPUNOV_LIMIT, lyapunov_covariance, lyapunov_maps
from pounding.closed_form.linearization.wen import coefficients_from_statistics, wen_constants
from pounding.errors import ConvergenceError
from pounding.hazard.excitation import KanaiTajimi
from pounding.mechanics.structures import Building

DEFAULT_TOLERANCE = 1e-8
"""Relative change of c_e and k_e between iterates that ends the iteration [-]."""
DEFAULT_MAX_ITERATIONS = 200
DEFAULT_RELAXATION = 0.7
"""Under-relaxation factor of the fixed-point iteration (1: none) [-]."""
DEFAULT_MEMORY = 2
"""Iterates remembered by the Anderson mixing of the iteration (0: none)."""


# --- the fixed-point iteration -----------------------------------------------


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
        self.rows, self.cols = lyapunov_maps(model.size)
        noise = model.noise_covariance
        self.rhs = np.ascontiguousarray(-noise[self.rows, self.cols])
        velocity, z = model.drift_velocity(0)[index], model.hysteretic[0][index]
        self.left = np.concatenate([velocity, z, velocity])
        self.right = np.concatenate([velocity, z, z])
        self.noise = noise
        self.dense = model.size <= DENSE_LYAPUNOV_LIMIT

        # The elastic start: substitute z = A u = A (drift rows) d, drop the z states.
        keep = np.concatenate([np.arange(2 * N), np.arange(2 * N + count, model.size)])
        substitution = np.zeros((count, model.size))
        substitution[:, :N] = A[index, None] * self.drift_rows
        matrix = model.matrix + model.matrix[:, self.z_states] @ substitution
        self.start_k_e = np.zeros(count)
        try:
            covariance = lyapunov_covariance(matrix[np.ix_(keep, keep)], noise[np.ix_(keep, keep)])
            velocity, z = velocity[:, keep], substitution[:, keep]
            self.start = _quadratic_forms(np.concatenate([velocity, z, velocity]), covariance, np.concatenate([velocity, z, z]))
        except np.linalg.LinAlgError:
            self.start = np.full(3 * count, np.nan)
        if not np.all(np.isfinite(self.start)):
            # Undamped storeys (damping_ratio = 0): the elastic start has no stationary response, but the
            # yielding storeys' hysteresis damps the linearized building. Start from k_e = -sqrt(k / m) instead.
            self.start_k_e = -np.sqrt(building.stiffnesses / building.masses)[index]
            self.start = self(A[index], self.start_k_e)

    def __call__(self, c_e: np.ndarray, k_e: np.ndarray) -> np.ndarray:
        """(Var udot, Var z, Cov(udot, z)) of the yielding storeys, concatenated;
        NaN if the Lyapunov equation is singular."""
        if self.dense:
            return iteration_moments(
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
        iterate. Also for an undamped building without a yielding storey,
        which has no stationary response, and for an elastic-perfectly plastic storey (alpha = 0), which
        drifts without bound.
    """
    if not 0.0 < relaxation <= 1.0:
        raise ValueError(f"relaxation must lie in (0, 1], got {relaxation!r}")
    storeys = building.storeys
    yielding = np.array([s.bouc_wen.alpha < 1.0 for s in storeys])
    elastic = LinearizedBuilding.elastic(building)
    if spectrum.G0 > 0.0 and not yielding.any() and not np.any(building.storey_damping() > 0.0):
        raise ConvergenceError(f"{label} has no damping and no yielding storey: an undamped elastic building has no "
                               "stationary response to random ground motion (give it a damping_ratio > 0)")
    if spectrum.G0 == 0.0 or not yielding.any():
        # No motion, or no hysteresis: the elastic system is exact.
        return elastic
    plastic = [i for i, storey in enumerate(storeys) if storey.bouc_wen.alpha == 0.0]
    if plastic:
        # alpha = 0: the storey force k z no longer holds the drift u itself, which the linearized storey
        # then integrates without bound (a zero eigenvalue): there is no stationary response to linearize.
        error = ConvergenceError(f"{label}, storey {plastic[0] + 1} is elastic-perfectly plastic (post-yield ratio 0): "
                                 "it drifts without bound, so the closed form has no answer. Give a post-yield "
                                 "ratio > 0, or use `pounding simulate`.")
        error.building, error.storey = label, plastic[0] + 1
        raise error
    index = np.flatnonzero(yielding)
    laws = [storeys[i].bouc_wen for i in index]
    constants = [tuple(float(c) for c in wen_constants(law.n)) for law in laws]
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
            c_e, k_e = coefficients_from_statistics(law.A, law.beta, law.gamma, (sigma_velocity, sigma_z, rho), constants[s])
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

    coefficients = np.concatenate([[law.A for law in laws], moments.start_k_e])
    target, sigma, worst, worst_storey = targets(moments.start, 1, coefficients)
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
        step, filled = mixing_step(x, target / scale - x, history_x, history_f, filled, relaxation, count)
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


FREQUENCY_RANGE = (1e-8, 1e8)
"""[rad/s] Storey frequencies sqrt(k / m) and ground-filter frequencies the closed form takes (periods of 0.06 us
to 20 years). Within it the closed form answers or says why not (a runaway, an unstable linearization); far beyond
it double precision cannot hold the buildings and the ground in one system (a mass of 1e300: 1e-149 rad/s)."""


def check_frequencies(case) -> None:
    """Raise :class:`ConvergenceError` naming the key where a storey frequency sqrt(k / m) or the ground
    filter's omega_g (omega_f) lies outside :data:`FREQUENCY_RANGE`: the closed form cannot answer there."""
    low, high = FREQUENCY_RANGE
    found = [(f"buildings.{b}.storeys.{s}: sqrt(stiffness / mass)", math.sqrt(storey.stiffness / storey.mass))
             for b, building in enumerate(case.buildings, start=1) for s, storey in enumerate(building.storeys, start=1)]
    spectrum = case.excitation.spectrum
    found += [(f"excitation.{key}", getattr(spectrum, key)) for key in ("omega_g", "omega_f") if hasattr(spectrum, key)]
    found += [(f"excitation.frequencies.{k}", w) for k, w in enumerate(getattr(spectrum, "frequencies", ()), start=1)]
    for where, frequency in found:
        if not low <= frequency <= high:
            raise ConvergenceError(f"{where} = {frequency:.3g} rad/s lies outside {low:g} to {high:g} rad/s, "
                                   "where the closed form's solutions hold")


def linearize_pair(case, **options) -> tuple[LinearizedBuilding, LinearizedBuilding]:
    """Linearize both buildings of a two-building case under its stationary spectrum (:func:`linearize_row`)."""
    first, second = linearize_row(case, **options)
    return first, second


def linearize_row(case, **options) -> tuple[LinearizedBuilding, ...]:
    """Linearize every building of a case under its stationary spectrum.

    The buildings do not interact in the linearization (no contact), so each
    is linearized alone, once, whatever contacts it has. For a non-stationary
    case the envelope is ignored: the paper linearizes under the stationary
    (unmodulated) excitation.

    Parameters
    ----------
    case : Case
    **options
        ``tolerance``, ``max_iterations``, ``relaxation`` of :func:`linearize`.
    """
    check_frequencies(case)
    spectrum = case.excitation.spectrum
    return tuple(linearize(building, spectrum, label=f"building {number}", **options)
                 for number, building in enumerate(case.buildings, start=1))
