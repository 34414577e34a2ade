"""Shear buildings with Bouc-Wen storeys (Eq. 1-2, 31-32, 36-39).

A building is a chain of storeys from the ground up. Storey ``i`` joins floor
``i-1`` (the ground for the first) to floor ``i``, which carries the storey's
mass. Its restoring force is q = alpha k u + (1 - alpha) k z (Eq. 36) on the
storey drift u, with the hysteretic displacement z of Eq. 2. One storey is the
paper's SDOF building (Eq. 1); two storeys the unequal-height model (Eq. 31,
whose first line is garbled as printed: the drifts are the coordinates, as
Eq. 32 and 36-39 write them; docs/errata.md, E10).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import eigh

from pounding import defaults
from pounding.errors import CaseError, check_limit, described, finite_number
from pounding.mechanics.integrator import bouc_wen_rate, hysteretic_path

__all__ = ["BoucWen", "Building", "Storey", "bouc_wen_rate", "check_storey_count", "hysteresis"]


def _set(instance, **values) -> None:
    """Store checked, converted values (Python floats) on a frozen dataclass."""
    for name, value in values.items():
        object.__setattr__(instance, name, value)


@dataclass(frozen=True)
class BoucWen:
    """Bouc-Wen hysteresis parameters of one storey (Eq. 1-2).

    Parameters
    ----------
    alpha : float
        Post-yield to initial stiffness ratio [-], 0 <= alpha <= 1.
    A : float
        Amplitude of the hysteretic rate [-], > 0.
    beta, gamma : float
        Shape parameters [1/m^n]; beta + gamma > 0 gives a softening loop with
        the finite yield displacement (A / (beta + gamma))^(1/n) (Eq. 33).
    n : float
        Smoothness of the transition to yield [-], >= 1.
    """

    alpha: float = 0.05
    A: float = 1.0
    beta: float = 200.0
    gamma: float = -100.0
    n: float = 1.0

    def __post_init__(self):
        _set(self, **{name: finite_number(name, getattr(self, name)) for name in ("alpha", "A", "beta", "gamma", "n")})
        if not 0.0 <= self.alpha <= 1.0:
            raise CaseError("alpha", f"must lie in [0, 1], got {self.alpha:g}")
        if not self.A > 0:
            raise CaseError("A", f"must be > 0, got {self.A:g}")
        if not self.n >= 1:
            raise CaseError("n", f"must be >= 1, got {self.n:g}")
        if self.alpha < 1.0 and not self.beta + self.gamma > 0:
            raise CaseError(
                "beta",
                f"beta + gamma must be > 0 for a softening storey with a finite yield displacement, "
                f"got beta = {self.beta:g}, gamma = {self.gamma:g}",
            )
        if self.alpha < 1.0 and not self.beta - self.gamma >= 0:
            raise CaseError("gamma", f"beta - gamma must be >= 0 (else unloading softens), got beta = {self.beta:g}, gamma = {self.gamma:g}")

    @property
    def yield_displacement(self) -> float:
        """(A / (beta + gamma))^(1/n) [m], Eq. 33: the bound of ``|z|``."""
        return (self.A / (self.beta + self.gamma)) ** (1.0 / self.n)

    @classmethod
    def from_yield_drift(cls, yield_drift: float, post_yield_ratio: float, n: float = 1.0, beta_share: float = 0.5) -> BoucWen:
        """The Bouc-Wen law of a storey given as an engineer gives it (docs/theory.md, G28):
        A = 1, beta + gamma = 1 / yield_drift^n (so Eq. 33's yield displacement is
        ``yield_drift`` [m]), beta = beta_share (beta + gamma), alpha = post_yield_ratio.
        ``beta_share`` >= 0.5 (beta >= gamma): 0.5 gives gamma = beta, 1 gives gamma = 0, and above 1
        gamma < 0 (the paper's beta = 2, gamma = -1 is beta_share = 2)."""
        yield_drift = finite_number("yield_drift", yield_drift)
        if not yield_drift > 0:
            raise CaseError("yield_drift", f"must be > 0 m, got {yield_drift:g}")
        share = finite_number("beta_share", beta_share)
        if not share >= 0.5:
            raise CaseError("beta_share", f"must be >= 0.5 (beta >= gamma, else unloading softens), got {share:g}")
        ratio = finite_number("post_yield_ratio", post_yield_ratio)
        if not 0.0 <= ratio < 1.0:
            raise CaseError("post_yield_ratio", f"must lie in [0, 1) (1 would never yield), got {ratio:g}")
        n = finite_number("n", n)
        if not n >= 1:
            raise CaseError("n", f"must be >= 1, got {n:g}")
        try:
            total = yield_drift ** -n
        except OverflowError:  # a float power beyond 1.8e308 raises rather than giving inf
            total = math.inf
        if not (math.isfinite(total) and total > 0):
            raise CaseError("yield_drift", f"{yield_drift:g} m to the power {n:g} leaves the range of numbers")
        return cls(alpha=ratio, A=1.0, beta=share * total, gamma=(1.0 - share) * total, n=n)


@dataclass(frozen=True)
class Storey:
    """One storey: its initial stiffness, the mass of the floor above it, and
    its Bouc-Wen law.

    Parameters
    ----------
    mass : float
        Floor mass [kg].
    stiffness : float
        Initial storey stiffness k [N/m].
    bouc_wen : BoucWen
        Hysteresis law; ``BoucWen(alpha=1)`` is linear elastic.
    damping : float or None
        Explicit storey damping coefficient [N s/m]; None lets the building's
        ``damping_ratio`` decide.
    """

    mass: float
    stiffness: float
    bouc_wen: BoucWen = field(default_factory=BoucWen)
    damping: float | None = None

    def __post_init__(self):
        _set(self, mass=finite_number("mass", self.mass), stiffness=finite_number("stiffness", self.stiffness))
        if not self.mass > 0:
            raise CaseError("mass", f"must be > 0 kg, got {self.mass:g}")
        if not self.stiffness > 0:
            raise CaseError("stiffness", f"must be > 0 N/m, got {self.stiffness:g}")
        if not isinstance(self.bouc_wen, BoucWen):
            raise CaseError("bouc_wen", f"must be a BoucWen, got {described(self.bouc_wen)}")
        if self.damping is not None:
            _set(self, damping=finite_number("damping", self.damping))
            if not self.damping >= 0:
                raise CaseError("damping", f"must be >= 0 N*s/m, got {self.damping:g}")

    @property
    def yields(self) -> bool:
        """Whether the storey has a hysteretic part (alpha < 1)."""
        return self.bouc_wen.alpha < 1.0

    @property
    def yield_drift(self) -> float:
        """The storey's yield drift [m] (Eq. 33); inf for an elastic storey."""
        return self.bouc_wen.yield_displacement if self.yields else math.inf

    @property
    def yield_force(self) -> float:
        """stiffness x yield drift [N]; inf for an elastic storey."""
        return self.stiffness * self.yield_drift if self.yields else math.inf


@dataclass(frozen=True)
class Building:
    """A shear building: storeys from the ground up.

    Parameters
    ----------
    storeys : tuple of Storey
        At least one.
    damping_ratio : float
        Viscous damping ratio [-] of the first mode. One storey: c = 2 xi sqrt(k m).
        More storeys: stiffness-proportional damping C = (2 xi / omega_1) K, i.e.
        a damper c_i = 2 xi k_i / omega_1 in each storey. Ignored for storeys with
        an explicit ``damping``.
    """

    storeys: tuple[Storey, ...]
    damping_ratio: float = 0.05

    def __post_init__(self):
        storeys = self.storeys
        if isinstance(storeys, (str, bytes, dict)) or not hasattr(storeys, "__len__"):
            raise CaseError("storeys", f"must be a tuple of Storey, got {described(storeys)}")
        check_storey_count("storeys", len(storeys))
        _set(self, storeys=tuple(storeys))
        for number, storey in enumerate(self.storeys, start=1):
            if not isinstance(storey, Storey):
                raise CaseError(f"storeys.{number}", f"must be a Storey, got {described(storey)}")
        _set(self, damping_ratio=finite_number("damping_ratio", self.damping_ratio))
        if not 0.0 <= self.damping_ratio < 1.0:
            raise CaseError("damping_ratio", f"must lie in [0, 1), got {self.damping_ratio:g}")

    @property
    def n_storeys(self) -> int:
        return len(self.storeys)

    @property
    def masses(self) -> np.ndarray:
        """Floor masses [kg], from the first floor up."""
        return np.array([s.mass for s in self.storeys])

    @property
    def stiffnesses(self) -> np.ndarray:
        """Initial storey stiffnesses [N/m]."""
        return np.array([s.stiffness for s in self.storeys])

    def stiffness_matrix(self) -> np.ndarray:
        """Initial stiffness matrix on floor displacements [N/m]."""
        k = self.stiffnesses
        n = k.size
        matrix = np.zeros((n, n))
        for i in range(n):
            matrix[i, i] += k[i]
            if i > 0:
                matrix[i - 1, i - 1] += k[i]
                matrix[i - 1, i] -= k[i]
                matrix[i, i - 1] -= k[i]
        return matrix

    def mode_shapes(self) -> tuple[np.ndarray, np.ndarray]:
        """Initial (pre-yield) circular frequencies [rad/s] and mass-normalized
        mode shapes (columns), lowest first."""
        eigenvalues, shapes = eigh(self.stiffness_matrix(), np.diag(self.masses))
        return np.sqrt(eigenvalues), shapes

    @property
    def periods(self) -> np.ndarray:
        """Initial natural periods [s], longest first."""
        return 2.0 * np.pi / self.mode_shapes()[0]

    def storey_damping(self) -> np.ndarray:
        """Storey damping coefficients c_i [N s/m] (see ``damping_ratio``)."""
        if self.n_storeys == 1:
            storey = self.storeys[0]
            derived = [2.0 * self.damping_ratio * math.sqrt(storey.stiffness * storey.mass)]
        else:
            omega_1 = self.mode_shapes()[0][0]
            derived = 2.0 * self.damping_ratio * self.stiffnesses / omega_1
        return np.array([s.damping if s.damping is not None else c for s, c in zip(self.storeys, derived)])


def check_storey_count(field: str, count: int) -> None:
    """:class:`CaseError` naming ``field`` unless 1 <= ``count`` <= :data:`~pounding.defaults.MAX_STOREYS`
    (the limit lifted by ``POUNDING_LIMITS=off``)."""
    if count < 1:
        raise CaseError(field, "a building needs at least one storey")
    check_limit(field, count, defaults.MAX_STOREYS, "storeys", "lump storeys together")


def hysteresis(storey: Storey, drift) -> tuple[np.ndarray, np.ndarray]:
    """Restoring force of a storey under a prescribed drift history (Eq. 36).

    Integrates Eq. 2 along the path with the trapezoidal predictor-corrector on
    each increment; fine increments give the quasi-static loop.

    Parameters
    ----------
    storey : Storey
    drift : array_like
        Storey drift u at successive instants [m], starting from rest (z = 0).

    Returns
    -------
    z : ndarray
        Hysteretic displacement [m].
    force : ndarray
        Restoring force alpha k u + (1 - alpha) k z [N].
    """
    drift = np.asarray(drift, dtype=float)
    bw = storey.bouc_wen
    z = hysteretic_path(drift, bw.A, bw.beta, bw.gamma, bw.n)
    return z, bw.alpha * storey.stiffness * drift + (1.0 - bw.alpha) * storey.stiffness * z

