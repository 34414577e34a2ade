"""What the impacts take out of the relative motion: its damping by the pounding.

An impact at approach speed v leaves e^2 of the relative motion's kinetic energy
(e the restitution, momentum kept). Between impacts the pair moves freely and
the ground restores the energy. Where impacts come often against the time the
pair takes to forget one (a lightly damped, narrow-band relative motion near
the mean position), the motion before each approach is the weaker for the
impacts before it; where the pair forgets an impact before the next (yielded
or dephasing buildings, a gap far from the mean), it is not.

The model (docs/theory.md, G10-G15; the energy map with exponential
intervals was chosen among five readings of the memory by looking at Monte
Carlo results, docs/theory.md, "Constants chosen by looking at Monte Carlo
results"):

- *impacts* come at Rice's rate with the time cut, nu = (sigma_V / sigma_X)
  exp(-u^2 / 2) / (2 pi Phi(u)), u = d / sigma_X, at intervals taken as
  exponential with mean 1 / nu;
- *memory*: after an impact, the share of its disturbance still in the relative
  motion at the next approach is rho = E[(omega x_J(D))^2 + v_J(D)^2] over the
  interval D, where x_J, v_J are X and V of the free pair after a unit jump of V
  at the contact floors (the jump an impact makes: floor velocities change by
  -m2 / (m1 + m2) and +m1 / (m1 + m2)), omega = sigma_V / sigma_X;
- *energy before an approach*: H = rho e^2 H + (1 - rho) H_free, so the impacts
  leave the motion R = (1 - rho) / (1 - rho e^2) of its free energy;
- *the damped motion* is the pair with a dashpot c between the contact floors
  such that sigma_V^2 falls to R times the free one. The dashpot feeds back on X
  alone, so whatever drives the pair, X_c(w) = X(w) / (1 + c G(w)),
  G(w) = i w (R_1(w) + R_2(w)), R_b the receptance of building b's contact
  floor: the spectrum of X is divided by ``|1 + c G|^2``, which gives the damped
  sigma_X and bandwidth too. nu and rho depend on the damped sigmas; the fixed
  point is solved for each gap.

For a single oscillator whose energy relaxes at rate r, under impacts at
exponential intervals, rho = nu / (nu + r) and the dashpot is the classical
energy balance c = m (1 - e^2) nu (m the reduced mass): it dissipates, on
average, what the impacts do. With no memory (rho = 0) nothing changes.

Units: SI.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pounding.closed_form.response import spectral_grid, spectral_weights
from pounding.errors import ConvergenceError
from pounding.random_vibration.crossing_kernels import (
    jump_memory,
    solve_dashpots,
    with_dashpot,
)

__all__ = ["DampedMotion", "ImpactDamping", "impact_damping", "jump_modes"]


@dataclass(frozen=True)
class DampedMotion:
    """The relative motion with the impacts' dashpot, per gap.

    Attributes
    ----------
    dashpot : ndarray
        Dashpot coefficient c between the contact floors [N s/m] (0: the free motion).
    ratio_displacement, ratio_velocity : ndarray
        sigma_X and sigma_V of the damped motion over the free motion's [-].
    bandwidth : ndarray
        Vanmarcke's q of the damped X [-].
    memory : ndarray
        rho: share of an impact's disturbance left at the next approach [-].
    """

    dashpot: np.ndarray
    ratio_displacement: np.ndarray
    ratio_velocity: np.ndarray
    bandwidth: np.ndarray
    memory: np.ndarray

    @classmethod
    def undamped(cls, gaps: int, bandwidth: float) -> DampedMotion:
        """The free motion itself at ``gaps`` gaps (no dashpot), of bandwidth q [-]."""
        ones, zeros = np.ones(gaps), np.zeros(gaps)
        return cls(zeros, ones, ones, np.full(gaps, float(bandwidth)), zeros)


@dataclass(frozen=True, eq=False)
class ImpactDamping:
    """The free relative motion's spectrum and memory, from which
    :meth:`damped` finds the impacts' dashpot at any gap (module docstring).

    Attributes
    ----------
    sigma_relative_displacement, sigma_relative_velocity : float
        Stationary sigma_X [m] and sigma_V [m/s] of the free motion, the
        residual's response included.
    reduced_mass : float
        m1 m2 / (m1 + m2) of the contact floors [kg].
    restitution : float
        e [-].
    bandwidth : float
        Vanmarcke's q of the free X [-]
        (:attr:`~pounding.closed_form.pair.LinearizedPair.bandwidth`).
    """

    sigma_relative_displacement: float
    sigma_relative_velocity: float
    reduced_mass: float
    restitution: float
    bandwidth: float
    _spectra: tuple
    _modes: tuple
    _feedback_max: float

    def memory(self, rate: float) -> float:
        """rho: the share of an impact's disturbance still in the relative motion
        at the next approach, impacts at exponential intervals of mean 1 / ``rate`` [1/s]."""
        sigma_x, sigma_v = self.sigma_relative_displacement, self.sigma_relative_velocity
        return float(jump_memory(float(rate), sigma_v / sigma_x, *self._modes))

    def with_dashpot(self, dashpot: float) -> tuple[float, float, float]:
        """sigma_X and sigma_V of the motion with a dashpot [N s/m] between the
        contact floors over the free motion's, and its bandwidth q [-]."""
        return tuple(float(value) for value in with_dashpot(float(dashpot), self._spectra))

    def damped(self, gaps) -> DampedMotion:
        """The damped motion at each gap [m]."""
        gaps = np.ascontiguousarray(gaps, dtype=float).ravel()
        dissipation = self.reduced_mass * (1.0 - self.restitution**2)
        sigma_x, sigma_v = self.sigma_relative_displacement, self.sigma_relative_velocity
        out = solve_dashpots(
            gaps, sigma_x, sigma_v, sigma_v / sigma_x, self.restitution, dissipation, self._spectra, self._modes,
            self._feedback_max,
        )
        failed = out[:, 0] < 0.0
        if np.any(failed):
            raise ConvergenceError(
                f"the impacts' equivalent dashpot found no fixed point at gap {gaps[failed][0]:.6g} m"
            )
        return DampedMotion(*(np.ascontiguousarray(column) for column in out.T))


def jump_modes(model, buildings, floors, contact_masses) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Eigenvalues of each building's free dynamics and the modal parts of X and V
    after a unit jump of V at the contact floors (floor velocities change by
    -m2 / (m1 + m2) and +m1 / (m1 + m2): momentum kept).

    ``model`` is the linearized pair's state space (``StateSpace``), ``buildings`` its two linearized buildings,
    ``floors`` their contact floors counted from 0, ``contact_masses`` (m1, m2) those floors' masses [kg]."""
    m1, m2 = contact_masses
    jumps = (-m2 / (m1 + m2), m1 / (m1 + m2))
    signs = (1.0, -1.0)  # X = x1 - x2, V = v1 - v2
    rates, x_modes, v_modes = [], [], []
    start = 0
    for b, (lb, floor) in enumerate(zip(buildings, floors)):
        states = slice(start, start + lb.n_states)
        start += lb.n_states
        matrix = model.matrix[states, states]
        x_row = model.displacement[b][floor, states]
        v_row = model.velocity[b][floor, states]
        jump = jumps[b] * v_row  # the floor's velocity is a state
        values, vectors = np.linalg.eig(matrix)
        # The modal sums are exact for a diagonalizable matrix; a (nearly)
        # defective one would make them cancel in large terms.
        if not np.linalg.cond(vectors) < 1e8:
            raise ConvergenceError(f"building {b + 1}'s free dynamics has no usable eigenbasis for the impacts' memory")
        amplitudes = np.linalg.solve(vectors, jump.astype(complex))
        rates.append(values)
        x_modes.append(signs[b] * (x_row @ vectors) * amplitudes)
        v_modes.append(signs[b] * (v_row @ vectors) * amplitudes)
    return np.concatenate(rates), np.concatenate(x_modes), np.concatenate(v_modes)


def impact_damping(sigma_relative_displacement: float, sigma_relative_velocity: float, relative_displacement_psd,
                   relative_displacement_moments, receptances, bandwidth: float, reduced_mass: float, restitution: float,
                   modes: tuple[np.ndarray, np.ndarray, np.ndarray]) -> ImpactDamping:
    """The free motion's data for the impacts' dashpot (G10-G15). A
    :class:`~pounding.closed_form.pair.LinearizedPair` gives it, computed once, as its
    :attr:`~pounding.closed_form.pair.LinearizedPair.impact_damping`.

    Parameters
    ----------
    sigma_relative_displacement, sigma_relative_velocity : float
        sigma_X [m] and sigma_V [m/s] of the free motion, the residual's response included.
    relative_displacement_psd : ndarray
        One-sided PSD of X on the spectral grid [m^2 s/rad].
    relative_displacement_moments : array_like
        Its moments lambda_0, lambda_1, lambda_2.
    receptances : (ndarray, ndarray)
        Each contact floor's receptance R_b on the spectral grid [m/N].
    bandwidth : float
        Vanmarcke's q of the free X [-].
    reduced_mass : float
        m1 m2 / (m1 + m2) of the contact floors [kg].
    restitution : float
        e [-].
    modes : tuple
        :func:`jump_modes` of the pair.
    """
    omega = spectral_grid()
    r1, r2 = receptances
    psd = relative_displacement_psd
    feedback = 1j * omega * (r1 + r2)
    # Trapezoid weights, explicit: the kernels sum the damped spectrum many times.
    weights = spectral_weights()
    moments = [float(moment) for moment in relative_displacement_moments]
    spectra = (
        weights,
        psd,
        psd * omega,
        psd * omega**2,
        np.ascontiguousarray(feedback.real),
        np.ascontiguousarray(feedback.imag),
        moments[0],
        moments[2],
    )
    return ImpactDamping(
        sigma_relative_displacement,
        sigma_relative_velocity,
        reduced_mass,
        restitution,
        bandwidth,
        spectra,
        modes,
        float(np.max(np.abs(feedback))),
    )
