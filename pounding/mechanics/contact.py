"""Impact laws between the colliding floors (Eq. 3-6).

delta = x1 - x2 - gap is the penetration (positive in contact) and delta_dot
its rate; the force pushes building 1 back and building 2 forward (Eq. 10).

Laws, selected by name from :data:`CONTACT_LAWS` (each written once there:
its name, force exponent, damping from the restitution and kernel code; the
force itself is compiled in :func:`pounding.mechanics.integrator.contact_force`):

``jankowski``
    Nonlinear viscoelastic (Jankowski 2005), Eq. 3-5: F = beta delta^1.5 +
    c(delta) delta_dot while approaching, beta delta^1.5 while restoring, with
    c = 2 xi sqrt(beta sqrt(delta) m1 m2 / (m1 + m2)). Eq. 4 as printed has
    sqrt(beta delta ...), which is not dimensionally consistent (docs/errata.md, E2);
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
import numbers
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from pounding.errors import ArgumentError, CaseError, finite_number, quote
from pounding.mechanics import integrator
from pounding.mechanics.integrator import contact_force, single_impact_peak

__all__ = [
    "CONTACT_LAWS",
    "CONTACT_MODELS",
    "MIN_RESTITUTION",
    "Contact",
    "ContactLaw",
    "contact_force",
    "contact_law",
    "hertz_peak_penetration",
    "impact_peak_force",
    "jankowski_damping_ratio",
    "linear_damping_ratio",
    "opposed_peak_force_ratio",
    "peak_force_ratio",
    "undamped_peak_force",
]


def jankowski_damping_ratio(restitution: float) -> float:
    """Impact damping ratio xi of the nonlinear viscoelastic law, Eq. 5 [-]."""
    e = restitution
    return 9.0 * math.sqrt(5.0) / 2.0 * (1.0 - e * e) / (e * (e * (9.0 * math.pi - 16.0) + 16.0))


def linear_damping_ratio(restitution: float) -> float:
    """Damping ratio of the linear viscoelastic law for restitution e [-]."""
    log_e = math.log(restitution)
    return -log_e / math.sqrt(math.pi**2 + log_e**2)


def _hertzdamp_factor(restitution: float) -> float:
    """3 (1 - e^2) / 4 of Muthukumar & DesRoches' law [-]."""
    return 0.75 * (1.0 - restitution**2)


def _no_damping(restitution: float) -> float:
    return 0.0


@dataclass(frozen=True)
class ContactLaw:
    """One impact law of :data:`CONTACT_LAWS`.

    Attributes
    ----------
    name : str
        As written in a case file (``contact.model``).
    code : int
        The law's code in the compiled kernels (:data:`pounding.mechanics.integrator.JANKOWSKI`, ...).
    stiffness_exponent : float
        Exponent of the penetration in the elastic term: 1.5 (Hertz), 1 (linear).
    damping : callable
        restitution e -> the law's damping parameter [-] (Eq. 5 for Jankowski).
    reference : str
        Where the law comes from.
    """

    name: str
    code: int
    stiffness_exponent: float
    damping: Callable[[float], float]
    reference: str

    @property
    def hertzian(self) -> bool:
        """Whether the elastic term is Hertz's beta delta^1.5 (Eq. 13-14 then apply)."""
        return self.stiffness_exponent == 1.5

    @property
    def peak_force_exponent(self) -> float:
        """p of the undamped peak force's growth with the approach speed, F ~ v^p [-]:
        1.2 for Hertz (Eq. 13 with v: delta_H ~ v^0.8), 1 for the linear law."""
        return 1.2 if self.hertzian else 1.0


CONTACT_LAWS = {
    law.name: law
    for law in (
        ContactLaw("jankowski", integrator.JANKOWSKI, 1.5, jankowski_damping_ratio, "Jankowski (2005), Eq. 3-5"),
        ContactLaw("hertz", integrator.HERTZ, 1.5, _no_damping, "Hertz, elastic"),
        ContactLaw("hertzdamp", integrator.HERTZDAMP, 1.5, _hertzdamp_factor, "Muthukumar & DesRoches (2006)"),
        ContactLaw("linear", integrator.LINEAR, 1.0, linear_damping_ratio, "Anagnostopoulos (1988)"),
    )
}
"""The impact laws by name."""
CONTACT_MODELS = tuple(CONTACT_LAWS)
"""Names of the impact laws."""
MIN_RESTITUTION = 1e-3
"""The smallest coefficient of restitution a contact takes [-]. Down to it the closed form and the time histories
agree (Section 5 under Jankowski's law: 69.6 against 73.4 MN at 1e-3, 10.97 against 10.82 MN at 0.01, for 0.32 MN at
0.65); below it the impact damping is critical to within 1e-3, the peak forces grow without bound (17 GN at 1e-6), the
time histories stop resolving the impacts (1e-9: the step falls below 1e-12 s) and the closed form underflows to 0
(1e-300). Measured concrete and steel impacts lie at 0.4 to 0.9."""


def contact_law(name: str, field: str = "model") -> ContactLaw:
    """The law called ``name``; :class:`CaseError` naming ``field`` otherwise."""
    if isinstance(name, str) and name in CONTACT_LAWS:
        return CONTACT_LAWS[name]
    raise CaseError(field, f"unknown contact model {quote(name)}; allowed: {', '.join(CONTACT_MODELS)}")


def hertz_peak_penetration(approach_velocity: float, stiffness: float, reduced_mass: float) -> float:
    """Peak penetration of an undamped Hertz impact [m], Eq. 13 with the
    approach velocity: kinetic energy m v^2 / 2 = work 2/5 beta delta^(5/2)."""
    return (5.0 * reduced_mass * approach_velocity**2 / (4.0 * stiffness)) ** 0.4


@dataclass(frozen=True)
class Contact:
    """The impact element between one floor of each of two neighbouring buildings.

    Parameters
    ----------
    gap : float
        Separation at rest [m], >= 0.
    stiffness : float
        Impact stiffness beta [N/m^1.5] (``linear``: [N/m]).
    restitution : float
        Coefficient of restitution e, Eq. 6 [-], 0 < e <= 1.
    levels : tuple of int
        The floor of each building that meets, counted from 1 (the left
        building's first). A floor meeting the other building between two of
        its floors is modelled as the paper does (Section 6): give that
        building a floor at the contact's height.
    model : str
        One of :data:`CONTACT_MODELS`.
    between : tuple of int
        The two neighbouring buildings, counted from 1 left to right: (i, i + 1).
        A positive displacement of the left building closes the gap.
    """

    gap: float
    stiffness: float
    restitution: float = 0.65
    levels: tuple[int, int] = (1, 1)
    model: str = "jankowski"
    between: tuple[int, int] = (1, 2)

    def __post_init__(self):
        contact_law(self.model)
        for name in ("gap", "stiffness", "restitution"):
            object.__setattr__(self, name, finite_number(name, getattr(self, name)))
        if self.gap < 0:
            raise CaseError("gap", f"must be >= 0 m, got {self.gap:g}")
        if self.stiffness <= 0:
            raise CaseError("stiffness", f"must be > 0, got {self.stiffness:g}")
        if not MIN_RESTITUTION <= self.restitution <= 1.0:
            raise CaseError("restitution", f"must lie in [{MIN_RESTITUTION:g}, 1], got {self.restitution:g}")
        levels = self.levels
        wrong = CaseError("levels", f"must be two floor numbers >= 1 (building 1, building 2), got {quote(levels)}")
        if isinstance(levels, (str, bytes, dict)) or not hasattr(levels, "__len__") or len(levels) != 2:
            raise wrong
        if not all(isinstance(v, numbers.Integral) and not isinstance(v, bool) and v >= 1 for v in levels):
            raise wrong
        object.__setattr__(self, "levels", tuple(int(v) for v in levels))
        object.__setattr__(self, "between", _neighbours(self.between))

    @property
    def law(self) -> ContactLaw:
        """The impact law, from :data:`CONTACT_LAWS`."""
        return CONTACT_LAWS[self.model]

    @property
    def model_code(self) -> int:
        """The law's code in the compiled kernels."""
        return self.law.code

    @property
    def stiffness_exponent(self) -> float:
        """Exponent of the penetration in the elastic term: 1.5, or 1 for ``linear``."""
        return self.law.stiffness_exponent

    def damping_ratio(self) -> float:
        """The law's impact damping parameter for ``restitution`` [-]
        (Eq. 5 for ``jankowski``; 3 (1 - e^2) / 4 for ``hertzdamp``; 0 for ``hertz``)."""
        return self.law.damping(self.restitution)


def _neighbours(between) -> tuple[int, int]:
    """``between`` as two neighbouring buildings (i, i + 1), or :class:`CaseError` naming ``between``."""
    wrong = CaseError("between", f"must be two neighbouring buildings, left first, as [1, 2], got {quote(between)}")
    if isinstance(between, (str, bytes, dict)) or not hasattr(between, "__len__") or len(between) != 2:
        raise wrong
    if not all(isinstance(v, numbers.Integral) and not isinstance(v, bool) and v >= 1 for v in between):
        raise wrong
    left, right = (int(v) for v in between)
    if left == right + 1:
        raise CaseError("between", f"list the left building first: [{right}, {left}], and give levels in the same order")
    if right != left + 1:
        raise CaseError("between", f"buildings {left} and {right} are not neighbours; a contact joins building i and "
                                   f"building i + 1 (left to right), as [{left}, {left + 1}]")
    return left, right


def undamped_peak_force(contact: Contact, approach_velocity, reduced_mass: float):
    """Peak force of an impact without energy loss [N]: Hertz, beta delta_H^1.5
    with delta_H of Eq. 13 (approach velocity in place of Eq. 13's separation
    velocity, docs/errata.md, E11); ``linear``: v sqrt(k m)."""
    if not contact.law.hertzian:
        return approach_velocity * math.sqrt(contact.stiffness * reduced_mass)
    return contact.stiffness * hertz_peak_penetration(approach_velocity, contact.stiffness, reduced_mass) ** 1.5


# --- one impact: the peak force against the buildings' own forces ------------

_IMPACT_STEPS = 2000
"""RK4 steps per time scale of :func:`~pounding.mechanics.integrator.single_impact_peak`: the peak to about 1e-9."""
_OPPOSED_SCALE = 1e-3
_OPPOSED_GRID = np.linspace(0.0, math.asinh(1e6 / _OPPOSED_SCALE), 193)
"""asinh(phi / 1e-3) on which the opposed peak-force ratio is tabulated: linear
in phi near 0, logarithmic beyond (the ratio falls slowly, as a power of phi,
for a large phi), phi up to 1e6."""


@lru_cache(maxsize=256)
def _opposed_table(model: str, restitution: float) -> np.ndarray:
    contact = Contact(gap=0.0, stiffness=1.0, restitution=restitution, model=model)
    unit = undamped_peak_force(contact, 1.0, 1.0)
    ratios = np.empty(_OPPOSED_GRID.size)
    for i, phi in enumerate(_OPPOSED_SCALE * np.sinh(_OPPOSED_GRID)):
        ratios[i] = single_impact_peak(contact.model_code, contact.damping_ratio(), phi * unit, _IMPACT_STEPS) / unit
    ratios.setflags(write=False)
    return ratios


def peak_force_ratio(model: str, restitution: float) -> float:
    """Peak force of one impact of free masses over ``undamped_peak_force`` [-].

    Every law here is self-similar: scaling the penetration by the undamped
    peak and time by it over the approach velocity removes beta, the masses
    and the velocity, so the ratio depends on the law and the restitution
    alone: :func:`opposed_peak_force_ratio` at phi = 0.
    """
    return float(_opposed_table(model, float(restitution))[0])


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
    restitution by :func:`~pounding.mechanics.integrator.single_impact_peak` for phi up
    to 1e6, interpolated linearly in asinh(phi / 1e-3).

    Parameters
    ----------
    model : str
        One of :data:`CONTACT_MODELS`.
    restitution : float
    phi : array_like
        Opposing force over the undamped peak force, >= 0 [-].
    """
    phi = np.asarray(phi, dtype=float)
    if np.any(phi < 0.0) or not np.all(np.isfinite(phi)):
        raise ArgumentError("phi", "must be finite numbers >= 0 (a force opposing the approach)")
    return np.interp(np.arcsinh(phi / _OPPOSED_SCALE), _OPPOSED_GRID, _opposed_table(model, float(restitution)))


def impact_peak_force(contact: Contact, approach_velocity, reduced_mass: float, opposing_force=0.0):
    """Peak force of one impact of two masses meeting at ``approach_velocity`` [N]:
    ``peak_force_ratio`` times ``undamped_peak_force``, which grows as v^1.2
    (v for ``linear``). With an ``opposing_force`` [N] (the buildings' own
    forces braking the approach, constant over the impact; broadcast against
    the velocities) the ratio is :func:`opposed_peak_force_ratio`."""
    undamped = undamped_peak_force(contact, approach_velocity, reduced_mass)
    opposing = np.asarray(opposing_force, dtype=float)
    if np.any(opposing < 0.0) or not np.all(np.isfinite(opposing)):
        bad = opposing[~(np.isfinite(opposing) & (opposing >= 0.0))].ravel()[0]  # the first, never the whole array
        raise ArgumentError("opposing_force", f"must be finite and >= 0 N (it opposes the approach), got {quote(float(bad))} N")
    if not np.any(opposing):
        return peak_force_ratio(contact.model, contact.restitution) * undamped
    undamped, opposing = np.broadcast_arrays(np.asarray(undamped, dtype=float), opposing)
    moving = undamped > 0.0
    phi = np.divide(opposing, undamped, out=np.zeros(undamped.shape), where=moving)
    return np.where(moving, opposed_peak_force_ratio(contact.model, contact.restitution, phi), 0.0) * undamped
