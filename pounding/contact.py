"""Impact laws between the colliding floors (Eq. 3-6).

delta = x1 - x2 - gap is the penetration (positive in contact) and delta_dot
its rate; the force pushes building 1 back and building 2 forward (Eq. 10).

Models, selected by name:

``jankowski``
    Nonlinear viscoelastic (Jankowski 2005), Eq. 3-5: F = beta delta^1.5 +
    c(delta) delta_dot while approaching, beta delta^1.5 while restoring, with
    c = 2 xi sqrt(beta sqrt(delta) m1 m2 / (m1 + m2)). Eq. 4 as printed has
    sqrt(beta delta ...), which is not dimensionally consistent (NOTES.md 1b);
    Jankowski's own law, and OpenSees' ``JankowskiImpact``, use sqrt(delta).
``hertz``
    Elastic Hertz law F = beta delta^1.5 (no energy loss; ``restitution`` unused).
``hertzdamp``
    Muthukumar & DesRoches (2006): F = beta delta^1.5 (1 + 3 (1 - e^2) / (4 v0) delta_dot)
    with v0 the approach velocity at the onset of the impact.
``linear``
    Linear viscoelastic (Anagnostopoulos 1988): F = k delta + c delta_dot with
    c = 2 xi sqrt(k m1 m2 / (m1 + m2)), xi = -ln e / sqrt(pi^2 + ln^2 e); the
    force is not allowed to pull (F >= 0). ``stiffness`` is then in [N/m].
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numba import njit

from .errors import CaseError

__all__ = [
    "CONTACT_MODELS",
    "Contact",
    "contact_force",
    "hertz_peak_penetration",
    "impact_peak_force",
    "jankowski_damping_ratio",
    "linear_damping_ratio",
    "opposed_peak_force_ratio",
    "peak_force_ratio",
    "undamped_peak_force",
]

CONTACT_MODELS = ("jankowski", "hertz", "hertzdamp", "linear")
"""Names of the contact laws; their index is the code the integrator uses."""

JANKOWSKI, HERTZ, HERTZDAMP, LINEAR = range(4)


def jankowski_damping_ratio(restitution: float) -> float:
    """Impact damping ratio xi of the nonlinear viscoelastic law, Eq. 5 [-]."""
    e = restitution
    return 9.0 * math.sqrt(5.0) / 2.0 * (1.0 - e * e) / (e * (e * (9.0 * math.pi - 16.0) + 16.0))


def linear_damping_ratio(restitution: float) -> float:
    """Damping ratio of the linear viscoelastic law for restitution e [-]."""
    log_e = math.log(restitution)
    return -log_e / math.sqrt(math.pi**2 + log_e**2)


def hertz_peak_penetration(approach_velocity: float, stiffness: float, reduced_mass: float) -> float:
    """Peak penetration of an undamped Hertz impact [m], Eq. 13 with the
    approach velocity: kinetic energy m v^2 / 2 = work 2/5 beta delta^(5/2)."""
    return (5.0 * reduced_mass * approach_velocity**2 / (4.0 * stiffness)) ** 0.4


@dataclass(frozen=True)
class Contact:
    """The impact element between one floor of each building.

    Parameters
    ----------
    gap : float
        Separation at rest [m], >= 0.
    stiffness : float
        Impact stiffness beta [N/m^1.5] (``linear``: [N/m]).
    restitution : float
        Coefficient of restitution e, Eq. 6 [-], 0 < e <= 1.
    levels : tuple of int
        Floor of building 1 and floor of building 2 that meet, counted from 1.
    model : str
        One of ``CONTACT_MODELS``.
    """

    gap: float
    stiffness: float
    restitution: float = 0.65
    levels: tuple[int, int] = (1, 1)
    model: str = "jankowski"

    def __post_init__(self):
        if self.model not in CONTACT_MODELS:
            raise CaseError("model", f"unknown contact model {self.model!r}; allowed: {', '.join(CONTACT_MODELS)}")
        for name in ("gap", "stiffness", "restitution"):
            value = getattr(self, name)
            if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value):
                raise CaseError(name, f"must be a finite number, got {value!r}")
        if self.gap < 0:
            raise CaseError("gap", f"must be >= 0 m, got {self.gap:g}")
        if self.stiffness <= 0:
            raise CaseError("stiffness", f"must be > 0, got {self.stiffness:g}")
        if not 0.0 < self.restitution <= 1.0:
            raise CaseError("restitution", f"must lie in (0, 1], got {self.restitution:g}")
        levels = tuple(self.levels)
        if len(levels) != 2 or not all(isinstance(v, int) and not isinstance(v, bool) and v >= 1 for v in levels):
            raise CaseError("levels", f"must be two floor numbers >= 1 (building 1, building 2), got {self.levels!r}")
        object.__setattr__(self, "levels", levels)

    @property
    def model_code(self) -> int:
        return CONTACT_MODELS.index(self.model)

    @property
    def stiffness_exponent(self) -> float:
        """Exponent of the penetration in the elastic term: 1.5, or 1 for ``linear``."""
        return 1.0 if self.model == "linear" else 1.5

    def damping_ratio(self) -> float:
        """The law's impact damping ratio for ``restitution`` [-]
        (Eq. 5 for ``jankowski``; 0 for ``hertz``)."""
        if self.model == "jankowski":
            return jankowski_damping_ratio(self.restitution)
        if self.model == "linear":
            return linear_damping_ratio(self.restitution)
        if self.model == "hertzdamp":
            return 0.75 * (1.0 - self.restitution**2)
        return 0.0


@njit(cache=True, nogil=True)
def contact_force(model, delta, delta_dot, stiffness, damping_ratio, reduced_mass, approach_velocity):
    """Pounding force [N] for penetration ``delta`` [m] and its rate [m/s], Eq. 3.

    Parameters
    ----------
    model : int
        Index of the law in ``CONTACT_MODELS``.
    delta, delta_dot : float
        Penetration and penetration rate.
    stiffness : float
        beta [N/m^1.5] (``linear``: k [N/m]).
    damping_ratio : float
        ``Contact.damping_ratio()``.
    reduced_mass : float
        m1 m2 / (m1 + m2) of the colliding floors [kg].
    approach_velocity : float
        Penetration rate at the onset of this impact [m/s] (``hertzdamp`` only).
    """
    if delta <= 0.0:
        return 0.0
    if model == LINEAR:
        damping = 2.0 * damping_ratio * math.sqrt(stiffness * reduced_mass)
        return max(stiffness * delta + damping * delta_dot, 0.0)
    elastic = stiffness * delta * math.sqrt(delta)
    if model == JANKOWSKI:
        if delta_dot > 0.0:
            damping = 2.0 * damping_ratio * math.sqrt(stiffness * math.sqrt(delta) * reduced_mass)
            return elastic + damping * delta_dot
        return elastic
    if model == HERTZDAMP:
        # damping_ratio holds 3 (1 - e^2) / 4; the law divides by the approach velocity.
        return max(elastic * (1.0 + damping_ratio * delta_dot / max(approach_velocity, 1e-12)), 0.0)
    return elastic


def undamped_peak_force(contact: Contact, approach_velocity, reduced_mass: float):
    """Peak force of an impact without energy loss [N]: Hertz, beta delta_H^1.5
    with delta_H of Eq. 13 (approach velocity in place of Eq. 13's separation
    velocity, NOTES.md 10); ``linear``: v sqrt(k m)."""
    if contact.model == "linear":
        return approach_velocity * math.sqrt(contact.stiffness * reduced_mass)
    return contact.stiffness * hertz_peak_penetration(approach_velocity, contact.stiffness, reduced_mass) ** 1.5


@lru_cache(maxsize=1024)
def peak_force_ratio(model: str, restitution: float) -> float:
    """Peak force of one impact over ``undamped_peak_force`` [-].

    Every law here is self-similar: scaling the penetration by the undamped
    peak and time by it over the approach velocity removes beta, the masses
    and the velocity, so the ratio depends on the law and the restitution
    alone. It is found by running the time-history kernel on two free unit
    masses meeting at unit speed (about 0.1 ms).
    """
    from . import integrator as kernel  # imports this module: import late

    contact = Contact(gap=0.0, stiffness=1.0, restitution=restitution, model=model)
    # Two free floors of mass 2 (reduced mass 1), closing at unit speed.
    free_floor = [2.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0]
    floors = np.array([free_floor, free_floor])
    contact_vector = np.array([contact.model_code, 0.0, 1.0, contact.damping_ratio(), 1.0])
    summary = np.zeros(kernel.SUMMARY_COLUMNS)
    no_history = np.empty(0)
    kernel.integrate_record(
        np.zeros(2), 10.0, np.array([0.0, 0.0, 0.5, -0.5, 0.0, 0.0]), floors, np.array([-1, -1]),
        contact_vector, 0, 1, 1e-10, np.full(6, 1e-14), 1e3, summary, no_history, np.empty((0, 6)), no_history,
    )
    return float(summary[kernel.S_FORCE_MAX]) / undamped_peak_force(contact, 1.0, 1.0)


def impact_peak_force(contact: Contact, approach_velocity, reduced_mass: float, opposing_force=0.0):
    """Peak force of one impact of two masses meeting at ``approach_velocity`` [N]:
    ``peak_force_ratio`` times ``undamped_peak_force``, which grows as v^1.2
    (v for ``linear``). With an ``opposing_force`` [N] (the buildings' own
    forces braking the approach, constant over the impact; broadcast against
    the velocities) the ratio is :func:`opposed_peak_force_ratio`."""
    undamped = undamped_peak_force(contact, approach_velocity, reduced_mass)
    opposing = np.asarray(opposing_force, dtype=float)
    if np.any(opposing < 0.0) or not np.all(np.isfinite(opposing)):
        raise CaseError("opposing_force", f"must be finite and >= 0 N (it opposes the approach), got {opposing_force!r}")
    if not np.any(opposing):
        return peak_force_ratio(contact.model, contact.restitution) * undamped
    undamped, opposing = np.broadcast_arrays(np.asarray(undamped, dtype=float), opposing)
    moving = undamped > 0.0
    phi = np.divide(opposing, undamped, out=np.zeros(undamped.shape), where=moving)
    return np.where(moving, opposed_peak_force_ratio(contact.model, contact.restitution, phi), 0.0) * undamped


# --- an impact against the buildings' own forces ----------------------------

_OPPOSED_SCALE = 1e-3
_OPPOSED_GRID = np.linspace(0.0, math.asinh(1e6 / _OPPOSED_SCALE), 193)
"""asinh(phi / 1e-3) on which the opposed peak-force ratio is tabulated: linear
in phi near 0, logarithmic beyond (the ratio falls slowly, as a power of phi,
for a large phi), phi up to 1e6."""


@njit(cache=True)
def _opposed_peak(model, damping_ratio, opposing_force, steps_per_unit):
    """Peak of F_c for x'' = -(F_c(x, x') + f0), x(0) = 0, x'(0) = 1: two
    masses of reduced mass 1 meeting at unit speed under beta = 1 (k = 1 for
    ``linear``) against a constant force f0. Classical RK4, stopped at the
    largest penetration (F_c only falls after it). Plain loops: tiny sizes."""
    time_scale = 1.0 / (1.0 + opposing_force)  # the impact lasts about this long
    h = time_scale / steps_per_unit
    x, rate, peak = 0.0, 1.0, 0.0
    for _ in range(100 * steps_per_unit):
        k1x, k1v = rate, -(contact_force(model, x, rate, 1.0, damping_ratio, 1.0, 1.0) + opposing_force)
        x2, v2 = x + 0.5 * h * k1x, rate + 0.5 * h * k1v
        k2x, k2v = v2, -(contact_force(model, x2, v2, 1.0, damping_ratio, 1.0, 1.0) + opposing_force)
        x3, v3 = x + 0.5 * h * k2x, rate + 0.5 * h * k2v
        k3x, k3v = v3, -(contact_force(model, x3, v3, 1.0, damping_ratio, 1.0, 1.0) + opposing_force)
        x4, v4 = x + h * k3x, rate + h * k3v
        k4x, k4v = v4, -(contact_force(model, x4, v4, 1.0, damping_ratio, 1.0, 1.0) + opposing_force)
        x += h * (k1x + 2.0 * k2x + 2.0 * k3x + k4x) / 6.0
        rate += h * (k1v + 2.0 * k2v + 2.0 * k3v + k4v) / 6.0
        peak = max(peak, contact_force(model, x, rate, 1.0, damping_ratio, 1.0, 1.0))
        if rate <= 0.0:
            break
    return peak


@lru_cache(maxsize=256)
def _opposed_table(model: str, restitution: float) -> np.ndarray:
    contact = Contact(gap=0.0, stiffness=1.0, restitution=restitution, model=model)
    unit = undamped_peak_force(contact, 1.0, 1.0)
    ratios = np.empty(_OPPOSED_GRID.size)
    for i, phi in enumerate(_OPPOSED_SCALE * np.sinh(_OPPOSED_GRID)):
        ratios[i] = _opposed_peak(contact.model_code, contact.damping_ratio(), phi * unit, 1000) / unit
    ratios.setflags(write=False)
    return ratios


def opposed_peak_force_ratio(model: str, restitution: float, phi):
    """Peak force of one impact against a constant opposing force, over
    ``undamped_peak_force`` [-].

    During an impact (milliseconds) the storeys' restoring and damping forces
    hardly change, so they act on the colliding floors as a constant force
    f0 opposing the approach. With phi = f0 / F_H(v), F_H the undamped
    (Hertz) peak, the law stays self-similar: the ratio depends on the law,
    the restitution and phi alone. phi = 0 is :func:`peak_force_ratio`; the
    ratio falls as phi grows (the approach is braked before it compresses the
    contact): as phi^-1.5 for Hertz, more slowly for the damped laws, whose
    damping force acts from the first touch. Tabulated once per law and
    restitution (about 10 ms) for phi up to 1e6, interpolated linearly in
    asinh(phi / 1e-3).

    Parameters
    ----------
    model : str
        One of ``CONTACT_MODELS``.
    restitution : float
    phi : array_like
        Opposing force over the undamped peak force, >= 0 [-].
    """
    phi = np.asarray(phi, dtype=float)
    if np.any(phi < 0.0) or not np.all(np.isfinite(phi)):
        raise CaseError("phi", "must be finite numbers >= 0 (a force opposing the approach)")
    return np.interp(np.arcsinh(phi / _OPPOSED_SCALE), _OPPOSED_GRID, _opposed_table(model, float(restitution)))
