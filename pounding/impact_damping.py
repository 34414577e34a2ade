"""What the impacts take out of the relative motion: its damping by the pounding.

An impact at approach speed v leaves e^2 of the relative motion's kinetic energy
(e the restitution, momentum kept). Between impacts the pair moves freely and
the ground restores the energy. Where impacts come often against the time the
pair takes to forget one (a lightly damped, narrow-band relative motion near
the mean position), the motion before each approach is the weaker for the
impacts before it; where the pair forgets an impact before the next (yielded
or dephasing buildings, a gap far from the mean), it is not.

The model (docs/estimator.md, "The impacts' damping"):

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
  floor: the spectrum of X is divided by |1 + c G|^2, which gives the damped
  sigma_X and bandwidth too. nu and rho depend on the damped sigmas; the fixed
  point is solved for each gap.

For a single oscillator whose energy relaxes at rate r, under impacts at
exponential intervals, rho = nu / (nu + r) and the dashpot is the classical
energy balance c = m (1 - e^2) nu (m the reduced mass): it dissipates, on
average, what the impacts do. With no memory (rho = 0) nothing changes.

Units: SI.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from .errors import ConvergenceError
from .linearization import pair_state_space
from .response import (
    ContactResponse,
    _contact_floors,
    _linearized,
    contact_floor_frfs,
    relative_displacement_psd,
    response_with_residual,
    spectral_grid,
    spectral_moments,
    spectral_weights,
    vanmarcke_bandwidth,
)

__all__ = ["U_MAX", "DampedMotion", "ImpactDamping", "impact_damping", "time_cut_rate"]

U_MAX = 10.0
"""gap / sigma_X (and v / sigma_V) beyond which there is no impact (exp(-50))."""
_TOLERANCE = 1e-7  # on the mismatch of sigma_V^2 / sigma_V,free^2 [-]


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


@njit(cache=True)
def _jump_memory(rate, frequency, rates, x_modes, v_modes):
    """rho-bar: E[(omega x_J)^2 + v_J^2] at the next impact, the intervals between
    impacts exponential with ``rate`` (E[exp(s Delta)] = rate / (rate - s)), capped at 1."""
    total = 0.0
    for j in range(rates.size):
        for k in range(rates.size):
            weight = (frequency * frequency * x_modes[j] * x_modes[k] + v_modes[j] * v_modes[k]) * rate / (rate - rates[j] - rates[k])
            total += weight.real
    return min(1.0, max(0.0, total))


@njit(cache=True)
def time_cut_rate(gap, sigma_x, sigma_v):
    """Rice's rate of upcrossings of the gap per unit of time spent below it,
    (sigma_V / (2 pi sigma_X)) exp(-u^2 / 2) / Phi(u), u = gap / sigma_X [1/s];
    0 beyond :data:`U_MAX`.

    The estimator's kernel calls it too; numba's on-disk cache of a caller in
    another file does not see an edit here (nor of :data:`U_MAX`): after one,
    delete the ``*.nbi``/``*.nbc`` files in ``pounding/__pycache__``."""
    u = gap / sigma_x
    if u >= U_MAX:
        return 0.0
    below = 0.5 * math.erfc(-u / math.sqrt(2.0))  # P(X < gap)
    return sigma_v / (2.0 * math.pi * sigma_x) * math.exp(-0.5 * u * u) / below


@njit(cache=True)
def _spectral_sums(c, weights, psd, psd_omega, psd_omega2, feedback_re, feedback_im):
    """int G_X w^k / |1 + c G|^2 for k = 0, 1, 2 (trapezoid weights)."""
    s0 = 0.0
    s1 = 0.0
    s2 = 0.0
    for i in range(weights.size):
        re = 1.0 + c * feedback_re[i]
        im = c * feedback_im[i]
        gain = weights[i] / (re * re + im * im)
        s0 += gain * psd[i]
        s1 += gain * psd_omega[i]
        s2 += gain * psd_omega2[i]
    return s0, s1, s2


@njit(cache=True)
def _with_dashpot(c, spectra):
    """sigma_X and sigma_V ratios to the free motion's and the bandwidth of X under a dashpot c."""
    weights, psd, psd_omega, psd_omega2, feedback_re, feedback_im, free0, free2 = spectra
    s0, s1, s2 = _spectral_sums(c, weights, psd, psd_omega, psd_omega2, feedback_re, feedback_im)
    return math.sqrt(s0 / free0), math.sqrt(s2 / free2), vanmarcke_bandwidth(s0, s1, s2)


@njit(cache=True)
def _mismatch(c, gap, sigma_x, sigma_v, frequency, restitution, spectra, modes):
    """g(c) = sigma_V(c)^2 / sigma_V(0)^2 - R(c): the damped motion's velocity
    variance against the energy its impacts leave it, R = (1 - rho) / (1 - rho e^2);
    also the sigma ratios, the bandwidth, rho and the impact rate."""
    rates, x_modes, v_modes = modes
    ratio_x, ratio_v, bandwidth = _with_dashpot(c, spectra)
    rate = time_cut_rate(gap, sigma_x * ratio_x, sigma_v * ratio_v)
    rho = _jump_memory(rate, frequency, rates, x_modes, v_modes) if rate > 0.0 else 0.0
    left = (1.0 - rho) / (1.0 - rho * restitution * restitution)
    return ratio_v * ratio_v - left, ratio_x, ratio_v, bandwidth, rho, rate


@njit(cache=True)
def _solve_dashpots(gaps, sigma_x, sigma_v, frequency, restitution, dissipation, spectra, modes, feedback_max):
    """c with g(c) = 0 for each gap (:func:`_mismatch`), by a safeguarded secant
    (Illinois) in units of the energy balance's m (1 - e^2) nu, bracketed from
    g(0) = 1 - R >= 0. Where g(0) is below 1e-12 or that unit's largest feedback
    c |G| below 1e-10, the impacts change nothing: c = 0.

    One row per gap: c, sigma_X ratio, sigma_V ratio, bandwidth, rho; c = -1
    marks a gap where no fixed point was found (raised by the caller). Each gap
    is solved on its own, so a curve's values do not depend on its other gaps."""
    out = np.zeros((gaps.size, 5))
    for k in range(gaps.size):
        gap = gaps[k]
        g_low, rx, rv, q, rho, rate = _mismatch(0.0, gap, sigma_x, sigma_v, frequency, restitution, spectra, modes)
        scale = dissipation * rate
        c = 0.0
        if g_low > 1e-12 and scale * feedback_max > 1e-10:
            low, high = 0.0, 1.0
            g_high = _mismatch(high * scale, gap, sigma_x, sigma_v, frequency, restitution, spectra, modes)[0]
            doublings = 0
            while g_high >= 0.0 and doublings < 60:
                low, g_low = high, g_high
                high *= 2.0
                g_high = _mismatch(high * scale, gap, sigma_x, sigma_v, frequency, restitution, spectra, modes)[0]
                doublings += 1
            if g_high >= 0.0:
                out[k, 0] = -1.0  # flagged: no bracket
                continue
            side = 0
            converged = False
            x = low
            for _ in range(200):
                x = (low * g_high - high * g_low) / (g_high - g_low)  # g_low >= 0 > g_high
                g_x, rx, rv, q, rho, rate = _mismatch(x * scale, gap, sigma_x, sigma_v, frequency, restitution, spectra, modes)
                if abs(g_x) <= _TOLERANCE or high - low <= _TOLERANCE * high:
                    converged = True
                    break
                if g_x > 0.0:
                    low, g_low = x, g_x
                    if side == 1:
                        g_high *= 0.5
                    side = 1
                else:
                    high, g_high = x, g_x
                    if side == -1:
                        g_low *= 0.5
                    side = -1
            if not converged:
                out[k, 0] = -1.0
                continue
            c = x * scale
        out[k, 0] = c
        out[k, 1] = rx
        out[k, 2] = rv
        out[k, 3] = q
        out[k, 4] = rho
    return out


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
        (:func:`~pounding.response.bandwidth_relative_displacement`).
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
        return float(_jump_memory(float(rate), sigma_v / sigma_x, *self._modes))

    def with_dashpot(self, dashpot: float) -> tuple[float, float, float]:
        """sigma_X and sigma_V of the motion with a dashpot [N s/m] between the
        contact floors over the free motion's, and its bandwidth q [-]."""
        return tuple(float(value) for value in _with_dashpot(float(dashpot), self._spectra))

    def damped(self, gaps) -> DampedMotion:
        """The damped motion at each gap [m]."""
        gaps = np.ascontiguousarray(gaps, dtype=float).ravel()
        dissipation = self.reduced_mass * (1.0 - self.restitution**2)
        sigma_x, sigma_v = self.sigma_relative_displacement, self.sigma_relative_velocity
        out = _solve_dashpots(
            gaps, sigma_x, sigma_v, sigma_v / sigma_x, self.restitution, dissipation, self._spectra, self._modes,
            self._feedback_max,
        )
        failed = out[:, 0] < 0.0
        if np.any(failed):
            raise ConvergenceError(
                f"the impacts' equivalent dashpot found no fixed point at gap {gaps[failed][0]:.6g} m"
            )
        return DampedMotion(*(np.ascontiguousarray(column) for column in out.T))


def _jump_modes(case, linearized, model) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Eigenvalues of each building's free dynamics and the modal parts of X and V
    after a unit jump of V at the contact floors (floor velocities change by
    -m2 / (m1 + m2) and +m1 / (m1 + m2): momentum kept)."""
    m1, m2 = case.contact_masses
    floors = _contact_floors(case)
    jumps = (-m2 / (m1 + m2), m1 / (m1 + m2))
    signs = (1.0, -1.0)  # X = x1 - x2, V = v1 - v2
    rates, x_modes, v_modes = [], [], []
    start = 0
    for b, lb in enumerate(linearized):
        states = slice(start, start + lb.n_states)
        start += lb.n_states
        matrix = model.matrix[states, states]
        x_row = model.displacement[b][floors[b], states]
        v_row = model.velocity[b][floors[b], states]
        jump = jumps[b] * v_row  # the floor's velocity is a state
        values, vectors = np.linalg.eig(matrix)
        # The modal sums are exact for a diagonalizable matrix; a (nearly)
        # defective one would make them cancel in large terms.
        if not np.linalg.cond(vectors) < 1e8:
            raise ConvergenceError(f"building {b + 1}'s free dynamics has no usable eigenbasis for the impacts' memory")
        amplitudes = np.linalg.solve(vectors, jump.astype(complex))
        x_part = signs[b] * (x_row @ vectors) * amplitudes
        v_part = signs[b] * (v_row @ vectors) * amplitudes
        rates.append(values)
        x_modes.append(x_part)
        v_modes.append(v_part)
    return np.concatenate(rates), np.concatenate(x_modes), np.concatenate(v_modes)


def impact_damping(
    case, linearized=None, model=None, response: ContactResponse | None = None, floor_frfs=None
) -> ImpactDamping:
    """The free motion's data for the impacts' dashpot of ``case``.

    Parameters
    ----------
    case : Case
    linearized : tuple of two LinearizedBuilding, optional
    model : StateSpace, optional
        The pair's :func:`~pounding.linearization.pair_state_space`, if built already.
    response : ContactResponse, optional
        The free motion's stationary response (default: with the residual's
        response, :func:`~pounding.response.response_with_residual`).
    floor_frfs : tuple, optional
        :func:`~pounding.response.contact_floor_frfs`, if computed already.
    """
    linearized = _linearized(case, linearized)
    if model is None:
        model = pair_state_space(case, linearized)
    if response is None:
        response = response_with_residual(case, linearized, model)
    omega = spectral_grid()
    (h1, r1), (h2, r2) = floor_frfs if floor_frfs is not None else contact_floor_frfs(case, linearized)
    psd = relative_displacement_psd(case, linearized, omega, (h1, h2))
    feedback = 1j * omega * (r1 + r2)
    # Trapezoid weights, explicit: the kernels sum the damped spectrum many times.
    weights = spectral_weights()
    moments = [float(moment) for moment in spectral_moments(psd)]
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
        response.sigma_relative_displacement,
        response.sigma_relative_velocity,
        case.reduced_mass,
        case.contact.restitution,
        vanmarcke_bandwidth(*moments),
        spectra,
        _jump_modes(case, linearized, model),
        float(np.max(np.abs(feedback))),
    )
