"""Linearized buildings (Eq. 19) and the joint linear state space of
buildings on a common ground under the ground filter's white noise."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from pounding.closed_form.linearization.ground import ground_filter
from pounding.closed_form.linearization.lyapunov import lyapunov_covariance
from pounding.errors import ConvergenceError
from pounding.hazard.excitation import KanaiTajimi
from pounding.mechanics.structures import Building

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
    noise_input : ndarray, (n, m)
        B: one column per independent white noise (one for a Kanai-Tajimi or
        Clough-Penzien filter, one per component of a filter bank).
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
        """2 pi G0 B B^T: the intensity matrix of the white noises, each of
        covariance 2 pi G0 delta(tau) for a two-sided PSD G0."""
        return 2.0 * math.pi * self.G0 * (self.noise_input @ self.noise_input.T)

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
        """Stationary state covariance P: A P + P A^T + 2 pi G0 B B^T = 0
        (solved once per model; read-only)."""
        return self._stationary_covariance

    def modes(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """Eigenvalues l, eigenvectors V and V^-1 of the state matrix, and the
        condition number of V (1-norm; large for a nearly defective matrix)
        (computed once per model; read-only)."""
        return self._modes

    @cached_property
    def _modes(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        values, vectors = np.linalg.eig(self.matrix)
        inverse = np.linalg.inv(vectors)
        condition = float(np.linalg.norm(vectors, 1) * np.linalg.norm(inverse, 1))
        for array in (values, vectors, inverse):
            array.setflags(write=False)
        return values, vectors, inverse, condition

    @cached_property
    def _stationary_covariance(self) -> np.ndarray:
        try:
            covariance = lyapunov_covariance(self.matrix, self.noise_covariance)
        except np.linalg.LinAlgError:
            covariance = np.full(self.matrix.shape, np.nan)
        if not (np.all(np.isfinite(covariance)) and np.all(np.diagonal(covariance) >= 0.0)):
            raise ConvergenceError("the linearized buildings have no stationary response (the Lyapunov equation is "
                                   "singular: a mode without damping, or magnitudes beyond double precision)")
        covariance.setflags(write=False)
        return covariance


def _drift_operator(floor_rows: np.ndarray) -> np.ndarray:
    drift = floor_rows.copy()
    drift[1:] -= floor_rows[:-1]
    return drift


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
    spectrum : KanaiTajimi, CloughPenzien or FilterBank
        Stationary ground-acceleration spectrum (two-sided, [m^2/s^3]).
    """
    buildings = tuple(buildings)
    ground = ground_filter(spectrum)
    size = sum(b.n_states for b in buildings) + ground.size
    matrix = np.zeros((size, size))
    coupling = np.zeros((size, size))
    filter_slice = slice(size - ground.size, size)
    matrix[filter_slice, filter_slice] = ground.matrix
    noise_input = np.zeros((size, ground.noise_input.shape[1]))
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
    if not np.all(np.isfinite(matrix)):
        raise ConvergenceError("the linearized buildings' equations overflow double precision: check the masses, "
                               "stiffnesses and damping")
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


def pair_state_space(case, linearized) -> StateSpace:
    """Joint state space of a case's two linearized buildings and the ground
    filter of its stationary spectrum: the model behind the cross covariances
    of Eq. 16-18 and 25 (:attr:`pounding.closed_form.pair.LinearizedPair.state_space`).

    Parameters
    ----------
    case : Case
    linearized : tuple of two LinearizedBuilding
        From :func:`~pounding.closed_form.linearization.linearize_pair`.
    """
    return state_space(linearized, case.excitation.spectrum)
