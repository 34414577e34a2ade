"""The covariance of a linear model from rest, under a stationary or a
modulated excitation (the paper's sigma(t), Eq. 26-28, computed exactly):
the covariance history behind Michaelov's equivalent process (Eq. 29) and
the gap-aware estimator's sigma_X(t), sigma_V(t).

Units: SI; times in [s].
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp
from scipy.linalg import expm

from pounding.closed_form.linearization import StateSpace, lyapunov_covariance
from pounding.errors import ArgumentError

__all__ = ["time_varying_covariance"]


def _envelope_values(envelope, times):
    return np.ones_like(times) if envelope is None else np.asarray(envelope(times), dtype=float)


def time_varying_covariance(model: StateSpace, envelope, times, modulation: str = "bedrock", rtol: float = 1e-8, outputs=None):
    """Covariance P(t) of a linear model under modulated excitation, from rest
    (or C P(t) C^T of outputs C).

    ``modulation = "bedrock"`` (default): the white noise driving the ground
    filter is modulated, dP/dt = A P + P A^T + 2 pi G0 A(t)^2 b b^T. Stepped
    exactly for an A(t)^2 linear between the given times: with P_s the
    stationary solution (A P_s + P_s A^T + Q = 0) and R with
    A R + R A^T = P_s, a forcing (a + b tau) Q has the particular solution
    a P_s + b (tau P_s + R), and the rest decays as exp(A tau) (.) exp(A^T tau).
    Fast (a few tens of ms for a record).

    ``modulation = "ground"``: the filtered ground acceleration itself is
    modulated, as Eq. 8 and the simulated records do: the filter runs
    stationary from before the onset and only its drive of the buildings is
    scaled, dP/dt = A(t) P + P A(t)^T + Q with A(t) = A_0 + A(t) A_coupling.
    Integrated by ``scipy.integrate.solve_ivp`` (DOP853; about ten times
    slower). The two differ only while the envelope changes over the filter's
    time scale (1 / (xi_g omega_g), about 0.1 s for the paper's soil): about
    0.3 % on the relative-velocity variance of the paper's cases.

    The buildings keep their stationary linearization: the paper's approach.

    Parameters
    ----------
    model : StateSpace
        E.g. :func:`~pounding.closed_form.linearization.pair_state_space`.
    envelope : callable or None
        A(t) [-]; None is 1 (a stationary motion switched on at ``times[0]``).
    times : array_like
        Increasing times [s]; the motion starts at ``times[0]`` with the
        buildings at rest.
    modulation : str
        ``"bedrock"`` or ``"ground"``.
    rtol : float
        Relative tolerance of the ``"ground"`` integration.
    outputs : ndarray, (k, n), optional
        Rows C over the state: return the outputs' covariance C P(t) C^T (for a
        stationary motion switched on, computed for the outputs alone).

    Returns
    -------
    ndarray, (n_times, n, n), or (n_times, k, k) with ``outputs``
    """
    times = np.asarray(times, dtype=float)
    if times.ndim != 1 or times.size < 1 or np.any(np.diff(times) <= 0.0):
        raise ArgumentError("times", "must be a one-dimensional increasing array")
    A = model.matrix
    values = _envelope_values(envelope, times)
    rows = None if outputs is None else np.atleast_2d(np.asarray(outputs, dtype=float))
    if envelope is None and modulation == "ground":
        return _switched_on(model, times, rows)
    if modulation == "bedrock":
        history = _bedrock(A, model.covariance(), times, values**2)
    elif modulation == "ground":
        history = _ground(model, envelope, times, rtol)
    else:
        raise ValueError(f"modulation must be 'bedrock' or 'ground', got {modulation!r}")
    return history if rows is None else rows @ history @ rows.T


def _bedrock(A, stationary, times, forcing):
    # A R + R A^T = P_s: lyapunov_covariance solves A X + X A^T + Q' = 0.
    ramp = lyapunov_covariance(A, -stationary)
    out = np.zeros((times.size,) + A.shape)
    propagators = {}
    covariance = np.zeros_like(A)
    for k, h in enumerate(np.diff(times)):
        key = round(h, 12)
        if key not in propagators:
            propagators[key] = expm(A * h)
        propagator = propagators[key]
        level, slope = forcing[k], (forcing[k + 1] - forcing[k]) / h
        start = level * stationary + slope * ramp
        end = start + slope * h * stationary
        covariance = end + propagator @ (covariance - start) @ propagator.T
        out[k + 1] = covariance
    return out


def _switched_on(model: StateSpace, times, rows):
    """C P(t) C^T for a stationary ground motion acting from ``times[0]`` on
    buildings at rest (the filter already stationary): a time-invariant
    system, so P(t) = P_s + exp(A t) (P_0 - P_s) exp(A^T t).

    With A = V diag(l) V^-1 this is V (D * exp((l_i + l_j) t)) V^T with
    D = V^-1 (P_0 - P_s) V^-T: every instant at once, and only the rows C
    carried through (C V). An ill-conditioned eigenvector basis (a nearly
    defective A) falls back to stepping with one propagator per distinct step."""
    A, stationary = model.matrix, model.covariance()
    f = model.filter_states
    deviation = -stationary.copy()
    deviation[f, f] = 0.0  # the filter starts in its stationary state
    elapsed = times - times[0]
    values, vectors, inverse, condition = model.modes()
    if condition >= 1e6:
        history = _stepped(A, stationary, deviation, times)
        return history if rows is None else rows @ history @ rows.T
    modal = inverse @ deviation @ inverse.T
    decay = np.exp(np.outer(values, elapsed))  # exp(l_i t); exp((l_i + l_j) t) is a product of two
    if rows is None:  # the whole state: n^2 numbers per instant
        growth = decay.T[:, :, None] * decay.T[:, None, :]
        out = stationary + (vectors @ (modal * growth) @ vectors.T).real
        out[elapsed == 0.0] = stationary + deviation  # exactly at rest, not P_s less itself
        return out
    projected = rows @ vectors
    k, n = projected.shape
    # (C V)_ai D_ij (C V)_bj exp((l_i + l_j) t), summed over i, j as one product for every instant (k^2 n^2 numbers).
    coefficients = np.einsum("ai,ij,bj->abij", projected, modal, projected).reshape(k * k, n * n)
    growth = (decay[:, None, :] * decay[None, :, :]).reshape(n * n, elapsed.size)
    out = rows @ stationary @ rows.T + (coefficients @ growth).real.T.reshape(elapsed.size, k, k)
    out[elapsed == 0.0] = rows @ (stationary + deviation) @ rows.T
    return out


def _stepped(A, stationary, deviation, times):
    """P_s + exp(A t) deviation exp(A^T t), stepped from ``times[0]``."""
    out = np.empty((times.size,) + A.shape)
    out[0] = stationary + deviation
    steps = np.diff(times)
    uniform = steps.size > 0 and np.allclose(steps, steps[0], rtol=1e-12, atol=0.0)
    propagator = expm(A * steps[0]) if uniform else None
    for k, h in enumerate(steps):
        step_propagator = propagator if uniform else expm(A * h)
        deviation = step_propagator @ deviation @ step_propagator.T
        out[k + 1] = stationary + deviation
    return out


def _ground(model: StateSpace, envelope, times, rtol):
    n = model.size
    coupling = model.coupling
    base = model.matrix - coupling
    Q = model.noise_covariance
    initial = np.zeros((n, n))
    f = model.filter_states
    # The filter is stationary from before the onset; the buildings are at rest.
    initial[f, f] = lyapunov_covariance(model.matrix[f, f], Q[f, f])
    scale = np.sqrt(np.abs(np.diag(model.covariance())))
    atol = rtol * 1e-3 * np.outer(scale, scale).ravel()

    def rhs(t, p):
        P = p.reshape(n, n)
        a = base + float(_envelope_values(envelope, np.array([t]))[0]) * coupling
        ap = a @ P
        return (ap + ap.T + Q).ravel()

    solution = solve_ivp(rhs, (times[0], times[-1]), initial.ravel(), method="DOP853", t_eval=times, rtol=rtol, atol=atol)
    if not solution.success:
        raise RuntimeError(f"time-varying covariance: {solution.message}")
    out = solution.y.T.reshape(times.size, n, n)
    return 0.5 * (out + out.transpose(0, 2, 1))
