"""A slow, independent reference (validation code, not the product) for :func:`~pounding.closed_form.linearization.residual.residual_response`:
the linearized pair's response to the residual of the Bouc-Wen law, by sampling trajectories."""

from __future__ import annotations

import numpy as np
from scipy.linalg import expm

from pounding.closed_form.linearization import LinearizedBuilding, StateSpace
from pounding.closed_form.linearization.residual import residual_storeys
from pounding.mechanics.integrator import bouc_wen_rates

__all__ = ["residual_response_sampled", "sampled_residual_paths"]


def residual_response_sampled(
    model: StateSpace,
    linearized: tuple[LinearizedBuilding, ...],
    outputs: np.ndarray,
    trajectories: int = 600,
    duration: float = 14.0,
    step: float = 0.004,
    seed: int = 2,
) -> np.ndarray:
    """Variances of ``outputs`` driven by the residual, by sampling: a slow,
    independent reference for :func:`residual_response`.

    The linearized pair is stepped exactly under the ground filter's white
    noise (the noise's covariance over a step by Van Loan's method), started
    in its stationary state; the residual g(u', z) - c_e u' - k_e z of every
    yielding storey is evaluated along each trajectory, held over a step and
    fed into a second copy of the linear system from rest. The variances are
    averaged over the last 4 s and the trajectories.

    Parameters
    ----------
    model, linearized, outputs
        As for :func:`residual_response`.
    trajectories : int
    duration : float
        [s]; long enough for the response to the residual to settle.
    step : float
        [s].
    seed : int

    Returns
    -------
    ndarray, (k,)
    """
    outputs = np.atleast_2d(np.asarray(outputs, dtype=float))
    squares, samples = np.zeros(outputs.shape[0]), 0
    for _, driven in sampled_residual_paths(model, linearized, trajectories, duration, step, seed, kept=4.0, every=10):
        squares += np.mean((driven @ outputs.T) ** 2, axis=0)
        samples += 1
    return squares / samples


def sampled_residual_paths(
    model: StateSpace,
    linearized: tuple[LinearizedBuilding, ...],
    trajectories: int,
    duration: float,
    step: float,
    seed: int,
    kept: float,
    every: int,
):
    """The sampling behind :func:`residual_response_sampled`.

    Yields
    ------
    state, driven : ndarray, (trajectories, n)
        The linearized pair's states and those of its copy driven by the
        residual, every ``every`` steps over the last ``kept`` [s] of ``duration``.
    """
    n = model.size
    blocks = np.zeros((2 * n, 2 * n))
    blocks[:n, :n], blocks[:n, n:], blocks[n:, n:] = -model.matrix, model.noise_covariance, model.matrix.T
    exponential = expm(blocks * step)
    transition = exponential[n:, n:].T
    noise = transition @ exponential[:n, n:]
    values, vectors = np.linalg.eigh(0.5 * (noise + noise.T))
    noise_root = vectors * np.sqrt(np.clip(values, 0.0, None))
    hold = np.linalg.solve(model.matrix, transition - np.eye(n))  # int_0^step exp(A s) ds
    rng = np.random.default_rng(seed)
    values, vectors = np.linalg.eigh(model.covariance())
    state = rng.standard_normal((trajectories, n)) @ (vectors * np.sqrt(np.clip(values, 0.0, None))).T
    driven = np.zeros((trajectories, n))
    storeys = residual_storeys(model, linearized)
    steps = round(duration / step)
    for index in range(steps):
        forcing = np.zeros((trajectories, n))
        for storey in storeys:
            building = linearized[storey.building]
            law = building.building.storeys[storey.storey].bouc_wen
            velocity, z = state @ storey.rows[0], state @ storey.rows[1]
            rate = bouc_wen_rates(velocity, z, law.A, law.beta, law.gamma, law.n)
            residual = rate - building.c_e[storey.storey] * velocity - building.k_e[storey.storey] * z
            forcing += np.outer(residual, hold[:, storey.input_state])
        driven = driven @ transition.T + forcing
        state = state @ transition.T + rng.standard_normal((trajectories, n)) @ noise_root.T
        if (steps - index) * step <= kept and index % every == 0:
            yield state, driven
