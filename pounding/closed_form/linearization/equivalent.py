"""The restoring forces of the equivalent linear storeys along given drift
histories: the linear counterpart of the Bouc-Wen loop."""

from __future__ import annotations

import numpy as np
from numba import njit

from pounding.closed_form.linearization.linear_system import LinearizedBuilding


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
