"""The part of the Bouc-Wen law that the linearization drops, kept as an input.

Statistical linearization writes each yielding storey's law as
z' = g(u', z) = c_e u' + k_e z + r and drops the residual r. Along the
linearized (Gaussian) motion, c_e u' + k_e z is exactly the first Wiener chaos
of g (Eq. 20: c_e and k_e are the Gaussian expectations of its derivatives),
so r lives in the higher chaoses and is uncorrelated, at every lag, with every
linear function of the ground motion and of the response. To second order it
is therefore an extra input, independent of the ground motion, acting on the
z equation of its storey. This module computes, in one pass, the stationary
covariance of the linearized pair's response to that input:

1. the chaos expansion of r for each yielding storey, in whitened coordinates
   xi = L^-1 (u', z) (L L^T = Cov(u', z)): r = sum over odd orders p >= 3 of
   sum_a t_(p,a) p! / (a! (p-a)!) He_a(xi_1) He_(p-a)(xi_2), the coefficients
   t_(p,a) = E[r He_a(xi_1) He_(p-a)(xi_2)] / p! by quadrature in polar
   coordinates (g is odd in (u', z), so the even chaoses vanish);
2. the correlation of the residuals of storeys j, k at lag tau by the diagram
   formula for Hermite polynomials of jointly Gaussian vectors: with
   M_il(tau) = E[xi_i^j(t) xi_l^k(t + tau)],
   E[r_j(t) r_k(t + tau)] = sum_p sum_m (p!)^2 / prod m! t^j_(p, m00 + m01) t^k_(p, m00 + m10) prod M^m,
   the inner sum over the 2 x 2 tables m of non-negative integers adding up to p;
3. its cross-spectral density by FFT, and the response
   int G S_r G^* d omega of the linearized pair to it (G the modal frequency
   response from the z equations to the outputs).

The correction is one pass (r evaluated on the linearized motion, not on the
corrected one) and changes nothing for elastic storeys (r = 0). The Gaussian
z is not bounded by z_u = (A / (beta + gamma))^(1/n) as the Bouc-Wen z is, and
for nearly elastic-perfectly plastic storeys most of E[r^2] comes from beyond
that bound: there the correction overshoots (docs/accuracy.md). The full
residual in one pass was chosen by looking at Monte Carlo results: cutting it
at z_u put sigma_X 10-37 % low under Clough-Penzien, and further passes
oscillate for the Section 6 frames (docs/theory.md).
Units: SI; the input r is a rate of z [m/s].
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numba import njit
from numpy.polynomial.hermite_e import herme2poly
from numpy.polynomial.legendre import leggauss
from scipy.special import gamma as gamma_function

from pounding.closed_form.linearization.linear_system import LinearizedBuilding, StateSpace

__all__ = [
    "CHAOS_ORDERS",
    "ResidualStorey",
    "residual_chaos",
    "residual_correlation",
    "residual_response",
    "residual_storeys",
]

CHAOS_ORDERS = (3, 5)
"""Odd Wiener chaoses of the residual kept: they carry 90-100 % of its variance
for the grid's storeys; adding order 7 moves the sigmas by under 0.1 %."""
_ANGULAR_NODES = 8  # Gauss-Legendre nodes per sector between the kinks of r
_CORRELATION_FLOOR = 1e-2  # bound on |M| below which M^3 (the correlation of r) is negligible, 1e-6
_HARMONIC_SAMPLES = 2.5  # lag samples per period of the highest harmonic (top order x fastest mode): above Nyquist
_MAX_LAGS = 16384  # beyond, the step is coarsened (a nearly elastic storey's slow mode)
_FREQUENCIES = np.geomspace(1e-3, 2.0e3, 1001)  # [rad/s]: 1.5 % steps resolve a mode damped 1.5 % or more


@dataclass(frozen=True, eq=False)
class ResidualStorey:
    """A yielding storey's residual, ready to correlate.

    Parameters
    ----------
    building, storey : int
        Indices (from 0) of the building in the pair and of the storey.
    rows : ndarray, (2, n)
        u' and z of the storey as rows over the pair's state.
    input_state : int
        The state (z) whose equation the residual enters.
    whitening : ndarray, (2, 2)
        L, lower triangular, with L L^T = Cov(u', z).
    chaos : tuple of ndarray
        t_(p, a), a = 0..p, for each order p of :data:`CHAOS_ORDERS`.
    variance : float
        E[r^2] by the same quadrature [m^2/s^2]; the chaoses kept carry
        sum_p sum_a (p!)^2 / (a! (p-a)!) t_(p,a)^2 of it.
    """

    building: int
    storey: int
    rows: np.ndarray
    input_state: int
    whitening: np.ndarray
    chaos: tuple[np.ndarray, ...]
    variance: float

    @property
    def captured(self) -> float:
        """Fraction of E[r^2] carried by the chaoses kept [-]."""
        kept = sum(
            math.factorial(p) ** 2 * sum(t[a] ** 2 / (math.factorial(a) * math.factorial(p - a)) for a in range(p + 1))
            for p, t in zip(CHAOS_ORDERS, self.chaos)
        )
        return kept / self.variance if self.variance > 0.0 else 1.0


@lru_cache(maxsize=1)
def _hermite_monomials() -> np.ndarray:
    """Coefficients of x^k in He_a(x) at [a, k], a, k = 0..top order."""
    top = max(CHAOS_ORDERS)
    out = np.zeros((top + 1, top + 1))
    for a in range(top + 1):
        out[a, : a + 1] = herme2poly([0.0] * a + [1.0])
    return out


@lru_cache(maxsize=4)
def _legendre(count: int) -> tuple[np.ndarray, np.ndarray]:
    return leggauss(count)


def _radial_moment(power):
    """int_0^inf R^power exp(-R^2 / 2) R dR = 2^(power / 2) Gamma(power / 2 + 1)."""
    return 2.0 ** (0.5 * power) * gamma_function(0.5 * power + 1.0)


def residual_chaos(law, c_e: float, k_e: float, covariance: np.ndarray, nodes: int = _ANGULAR_NODES):
    """Whitening L, chaos coefficients t_(p,a) and E[r^2] of one storey's
    residual r = g(u', z) - c_e u' - k_e z (Bouc-Wen g, Eq. 2) for Gaussian
    (u', z) of covariance ``covariance``.

    In polar coordinates of xi = L^-1 (u', z), r is R a(theta) + R^(n+1) b(theta)
    (its terms are homogeneous of degree 1 and n + 1), and He_a(xi_1) He_b(xi_2)
    a polynomial in R: the radial integrals are Gamma functions, and the
    angular ones are smooth between the angles where u' = 0 or z = 0 (the kinks
    of ``|u'|`` and ``|z|^n``), so Gauss-Legendre on each of the four sectors is
    accurate to 1e-9 with 8 nodes.

    Parameters
    ----------
    law : BoucWen
    c_e, k_e : float
        The storey's equivalent coefficients (Eq. 20).
    covariance : ndarray, (2, 2)
        Cov(u', z) [m^2/s^2, m^2/s; m^2/s, m^2].
    nodes : int
        Gauss-Legendre nodes per sector.

    Returns
    -------
    whitening : ndarray, (2, 2)
    chaos : tuple of ndarray
        t_(p, a) for p in :data:`CHAOS_ORDERS`.
    variance : float
    """
    # A tiny ridge keeps L invertible should u' and z be (numerically) collinear.
    whitening = np.linalg.cholesky(covariance + 1e-12 * np.trace(covariance) * np.eye(2))
    z_zero = math.atan2(-whitening[1, 0], whitening[1, 1])
    edges = np.sort(np.mod([0.5 * math.pi, 1.5 * math.pi, z_zero, z_zero + math.pi], 2.0 * math.pi))
    edges = np.concatenate([edges, [edges[0] + 2.0 * math.pi]])
    x, w = _legendre(nodes)
    half = 0.5 * np.diff(edges)[:, None]
    theta = (half * x + 0.5 * (edges[1:] + edges[:-1])[:, None]).ravel()
    weight = (half * w).ravel() / (2.0 * math.pi)
    cosine, sine = np.cos(theta), np.sin(theta)
    velocity = whitening[0, 0] * cosine
    z = whitening[1, 0] * cosine + whitening[1, 1] * sine
    n = law.n
    linear = (law.A - c_e) * velocity - k_e * z  # degree 1 in R
    hysteretic = -law.beta * np.abs(velocity) * np.abs(z) ** (n - 1.0) * z - law.gamma * velocity * np.abs(z) ** n  # degree n + 1
    top = max(CHAOS_ORDERS)
    degree = np.arange(top + 1)
    # E[R^(k+l) cos^k sin^l r] for k, l = 0..top.
    angular = (cosine[:, None, None] ** degree[:, None]) * (sine[:, None, None] ** degree[None, :]) * weight[:, None, None]
    total = degree[:, None] + degree[None, :]
    moments = np.einsum("qkl,q->kl", angular, linear) * _radial_moment(1.0 + total) + np.einsum(
        "qkl,q->kl", angular, hysteretic
    ) * _radial_moment(n + 1.0 + total)
    hermite = _hermite_monomials()
    projections = hermite @ moments @ hermite.T  # E[r He_a(xi_1) He_b(xi_2)] at [a, b]
    chaos = tuple(np.array([projections[a, p - a] for a in range(p + 1)]) / math.factorial(p) for p in CHAOS_ORDERS)
    variance = float(
        np.sum(
            weight
            * (linear**2 * _radial_moment(2.0) + 2.0 * linear * hysteretic * _radial_moment(n + 2.0) + hysteretic**2 * _radial_moment(2.0 * n + 2.0))
        )
    )
    return whitening, chaos, variance


def residual_storeys(model: StateSpace, linearized: tuple[LinearizedBuilding, ...]) -> list[ResidualStorey]:
    """The yielding storeys (k_e != 0) of ``model``, building by building, with their residual's chaos."""
    covariance = model.covariance()
    out = []
    for b, building in enumerate(linearized):
        velocity_rows, z_rows = model.drift_velocity(b), model.hysteretic[b]
        for j in np.flatnonzero(building.hysteretic):
            rows = np.array([velocity_rows[j], z_rows[j]])
            whitening, chaos, variance = residual_chaos(
                building.building.storeys[j].bouc_wen, building.c_e[j], building.k_e[j], rows @ covariance @ rows.T
            )
            state = int(np.flatnonzero(z_rows[j])[0])
            out.append(ResidualStorey(b, int(j), rows, state, whitening, chaos, variance))
    return out


@lru_cache(maxsize=8)
def _monomials(order: int) -> tuple[np.ndarray, np.ndarray]:
    """The 2 x 2 tables (m00, m01, m10, m11) of non-negative integers adding up
    to ``order``, and (order!)^2 / prod m! for each."""
    tables = np.array(
        [(a, b, c, order - a - b - c) for a in range(order + 1) for b in range(order + 1 - a) for c in range(order + 1 - a - b)]
    )
    multinomial = np.array([math.factorial(order) ** 2 / math.prod(math.factorial(int(m)) for m in row) for row in tables])
    return tables, multinomial


def _diagram_coefficients(storeys: list[ResidualStorey]):
    """Exponent tables (q, 4) and coefficients (m, m, q) of E[r_j(t) r_k(t + tau)]
    as a polynomial in the entries (M00, M01, M10, M11) of M(tau), at [j, k]."""
    exponents = np.concatenate([_monomials(p)[0] for p in CHAOS_ORDERS])
    coefficients = np.empty((len(storeys), len(storeys), exponents.shape[0]))
    for j, left in enumerate(storeys):
        for k, right in enumerate(storeys):
            parts = []
            for p, t_left, t_right in zip(CHAOS_ORDERS, left.chaos, right.chaos):
                tables, multinomial = _monomials(p)
                parts.append(multinomial * t_left[tables[:, 0] + tables[:, 1]] * t_right[tables[:, 0] + tables[:, 2]])
            coefficients[j, k] = np.concatenate(parts)
    return exponents, coefficients


@njit(cache=True)
def _correlation_kernel(values, lefts, rights, step, count, exponents, coefficients):
    """E[r_k(t + tau) r_j(t)] at [tau, k, j] for tau = 0, step, ..., with
    M_jk(tau) = Re(lefts[j] diag(exp(values tau)) rights[k]) and the diagram
    polynomial of :func:`_diagram_coefficients`."""
    storeys, modes = lefts.shape[0], values.size
    top = 0
    for q in range(exponents.shape[0]):
        for e in range(4):
            top = max(top, exponents[q, e])
    out = np.empty((count, storeys, storeys))
    growth = np.ones(modes, dtype=np.complex128)
    factor = np.exp(values * step)
    grown = np.empty((storeys, 2, modes), dtype=np.complex128)
    powers = np.empty((4, top + 1))
    for t in range(count):
        if t > 0:
            growth *= factor  # exp(values t step), without an exponential per lag
        for j in range(storeys):
            for a in range(2):
                for n in range(modes):
                    grown[j, a, n] = lefts[j, a, n] * growth[n]
        for j in range(storeys):
            for k in range(storeys):
                for a in range(2):
                    for b in range(2):
                        entry = 0.0j
                        for n in range(modes):
                            entry += grown[j, a, n] * rights[k, n, b]
                        e = 2 * a + b
                        powers[e, 0] = 1.0
                        for power in range(1, top + 1):
                            powers[e, power] = powers[e, power - 1] * entry.real
                total = 0.0
                for q in range(exponents.shape[0]):
                    total += (
                        coefficients[j, k, q]
                        * powers[0, exponents[q, 0]]
                        * powers[1, exponents[q, 1]]
                        * powers[2, exponents[q, 2]]
                        * powers[3, exponents[q, 3]]
                    )
                out[t, k, j] = total
    return out


def _lag_grid(values: np.ndarray, modal_weights: np.ndarray) -> tuple[float, int]:
    """Lag step [s] and count.

    The step samples the highest harmonic (the top chaos order times the
    fastest mode) above Nyquist. The grid runs until the bound
    sum_n weight_n exp(Re(l_n) tau) on the whitened correlation M has fallen
    below the floor, so that M^3, the correlation of r, is below its cube: a
    slow mode of small weight (a yielded storey's drift) does not stretch it."""
    top = max(CHAOS_ORDERS) * float(np.max(np.abs(values)))
    step = 2.0 * math.pi / (_HARMONIC_SAMPLES * top)
    candidates = np.geomspace(step, 600.0, 120)
    bound = np.exp(np.outer(candidates, values.real)) @ modal_weights
    below = np.flatnonzero(bound <= _CORRELATION_FLOOR)
    span = float(candidates[below[0]] if below.size else candidates[-1])
    count = int(min(_MAX_LAGS, math.ceil(span / step) + 1))
    if count == _MAX_LAGS:
        step = span / (count - 1)  # a very slow mode: keep the span, coarsen the step
    return step, max(count, 16)


def _modal_correlation(model: StateSpace, linearized):
    """:func:`residual_correlation`, with the eigenvalues and eigenvectors of the state matrix."""
    storeys = residual_storeys(model, linearized)
    values, vectors, inverse, _ = model.modes()
    covariance = model.covariance()
    # E[y_j(t) y_k(t + tau)^T] = R_j P exp(A^T tau) R_k^T = (R_j P V^-T) diag(exp(l tau)) (V^T R_k^T),
    # whitened: M = L_j^-1 (...) L_k^-T.
    lefts = np.array([np.linalg.solve(s.whitening, s.rows @ covariance @ inverse.T) for s in storeys])
    rights = np.array([np.linalg.solve(s.whitening, s.rows @ vectors).T for s in storeys])
    weights = np.max(np.abs(lefts), axis=(0, 1)) * np.max(np.abs(rights), axis=(0, 2))
    step, count = _lag_grid(values, weights)
    exponents, coefficients = _diagram_coefficients(storeys)
    correlation = _correlation_kernel(values, lefts, rights, step, count, exponents, coefficients)
    return storeys, step * np.arange(count), correlation, values, vectors


def residual_correlation(model: StateSpace, linearized: tuple[LinearizedBuilding, ...]):
    """Correlation of the yielding storeys' residuals over lags from 0.

    Returns
    -------
    storeys : list of ResidualStorey
    lags : ndarray, (L,)
        [s], uniform from 0.
    correlation : ndarray, (L, m, m)
        E[r_k(t + tau) r_j(t)] at [tau, k, j] [m^2/s^2].
    """
    storeys, lags, correlation, _, _ = _modal_correlation(model, linearized)
    return storeys, lags, correlation


def residual_response(model: StateSpace, linearized: tuple[LinearizedBuilding, ...], outputs: np.ndarray) -> np.ndarray:
    """Stationary covariance of ``outputs`` (rows over the state) driven by the
    yielding storeys' residuals, int_(-inf)^inf G S_r G^* d omega, with
    G = outputs (i omega - A)^-1 B, B the residuals' entry into the z equations.

    Parameters
    ----------
    model : StateSpace
        The linearized pair's (or building's) state space.
    linearized : tuple of LinearizedBuilding
        The buildings of ``model``, in order.
    outputs : ndarray, (k, n)

    Returns
    -------
    ndarray, (k, k)
        Zero for elastic buildings.
    """
    outputs = np.atleast_2d(np.asarray(outputs, dtype=float))
    if not any(building.hysteretic.any() for building in linearized):
        return np.zeros((outputs.shape[0], outputs.shape[0]))
    storeys, lags, correlation, values, vectors = _modal_correlation(model, linearized)
    step = lags[1] - lags[0]
    size = 1 << math.ceil(math.log2(2 * lags.size))
    # F(w) = int_0^inf Q(tau) e^(-i w tau) d tau (trapezoid), S = (F + F^H) / (2 pi).
    trapezoid = correlation.copy()
    trapezoid[0] *= 0.5
    transform = np.fft.rfft(trapezoid, n=size, axis=0) * step
    grid = 2.0 * math.pi * np.fft.rfftfreq(size, step)
    spectrum = (transform + np.conj(np.swapaxes(transform, 1, 2))) / (2.0 * math.pi)
    omega = _FREQUENCIES[_FREQUENCIES < grid[-1]]
    weights = np.zeros(omega.size)  # trapezoid rule on the logarithmic grid
    weights[1:] += 0.5 * np.diff(omega)
    weights[:-1] += 0.5 * np.diff(omega)
    inputs = np.zeros((model.size, len(storeys)))
    for i, storey in enumerate(storeys):
        inputs[storey.input_state, i] = 1.0
    return _response_kernel(
        omega, weights, values, outputs @ vectors, np.linalg.solve(vectors, inputs), grid[1], np.ascontiguousarray(spectrum)
    )


@njit(cache=True)
def _response_kernel(omega, weights, values, left, right, spacing, spectrum):
    """2 sum_w weights_w Re(G S G^H) at the frequencies ``omega``, with
    G = left diag(1 / (i w - values)) right (the modal frequency response from
    the z equations to the outputs) and S interpolated linearly between the
    FFT bins (``spacing`` apart from 0); S is smooth, a transform of a
    product of decaying correlations."""
    outputs, modes, storeys = left.shape[0], values.size, right.shape[1]
    out = np.zeros((outputs, outputs))
    resolvent = np.empty(modes, dtype=np.complex128)
    gain = np.empty((outputs, storeys), dtype=np.complex128)
    density = np.empty((storeys, storeys), dtype=np.complex128)
    driven = np.empty((outputs, storeys), dtype=np.complex128)
    for w in range(omega.size):
        for n in range(modes):
            resolvent[n] = 1.0 / (1j * omega[w] - values[n])
        for o in range(outputs):
            for m in range(storeys):
                total = 0.0j
                for n in range(modes):
                    total += left[o, n] * resolvent[n] * right[n, m]
                gain[o, m] = total
        position = omega[w] / spacing
        below = int(position)
        fraction = position - below
        for m in range(storeys):
            for k in range(storeys):
                density[m, k] = spectrum[below, m, k] * (1.0 - fraction) + spectrum[below + 1, m, k] * fraction
        for o in range(outputs):
            for k in range(storeys):
                total = 0.0j
                for m in range(storeys):
                    total += gain[o, m] * density[m, k]
                driven[o, k] = total
        for o in range(outputs):
            for q in range(outputs):
                total = 0.0j
                for k in range(storeys):
                    total += driven[o, k] * np.conj(gain[q, k])
                out[o, q] += 2.0 * weights[w] * total.real
    return out
