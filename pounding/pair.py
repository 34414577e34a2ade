"""The statistically linearized pair (Eq. 19-21) and everything the closed
forms take from it, computed once: :class:`LinearizedPair`.

Nothing here depends on the gap: one pair serves an estimate, its force
against the gap and the dashboard's plots.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .case import Case
from .covariance_history import time_varying_covariance
from .crossing_kernels import vanmarcke_bandwidth
from .errors import CaseError
from .impact_damping import ImpactDamping, impact_damping
from .linearization import (
    LinearizedBuilding,
    StateSpace,
    linearize_pair,
    pair_state_space,
)
from .linearization.residual import residual_response
from .response import (
    ContactResponse,
    FloorStatistics,
    contact_output_matrix,
    floor_response_and_receptance,
    frequency_response,
    relative_displacement_psd,
    response_frequency,
    spectral_grid,
    spectral_moments,
    trapezoid_weights,
)

__all__ = ["HISTORY_STEP", "LinearizedPair"]

HISTORY_STEP = 0.25
"""[s] time grid of the covariance from rest: the build-up takes seconds, and so does an envelope's change."""


@dataclass(frozen=True, eq=False)
class LinearizedPair:
    """A case's two buildings, statistically linearized under its excitation,
    with the quantities derived from them as cached properties (each computed
    once, on first use).

    Parameters
    ----------
    case : Case
    buildings : tuple of two LinearizedBuilding
        From :func:`~pounding.linearization.linearize_pair`; :meth:`of` linearizes.

    Notes
    -----
    The contact floors' outputs are :data:`~pounding.response.OUTPUTS`:
    x1, x2, v1, v2, a1, a2 relative to the ground (SI).
    """

    case: Case
    buildings: tuple[LinearizedBuilding, LinearizedBuilding]

    @classmethod
    def of(cls, case: Case, **linearization) -> LinearizedPair:
        """Linearize ``case``'s buildings (options of :func:`~pounding.linearization.linearize`)."""
        if not isinstance(case, Case):
            raise CaseError("case", f"must be a Case (from load_case), got {type(case).__name__}")
        return cls(case, tuple(linearize_pair(case, **linearization)))

    @property
    def floors(self) -> tuple[int, int]:
        """The contact floors, counted from 0 (= first floor) in each building."""
        return tuple(level - 1 for level in self.case.contact.levels)

    @cached_property
    def state_space(self) -> StateSpace:
        """Both linearized buildings and the ground filter (:func:`~pounding.linearization.pair_state_space`)."""
        return pair_state_space(self.case, self.buildings)

    @cached_property
    def contact_outputs(self) -> np.ndarray:
        """Rows mapping the state to :data:`~pounding.response.OUTPUTS`, (6, n)."""
        return contact_output_matrix(self.floors, self.state_space)

    @cached_property
    def stationary_response(self) -> ContactResponse:
        """Stationary response at the contact floors by the Lyapunov equation
        (Eq. 16-18, 25): the paper's. The pair and the ground filter form
        x' = A x + b w, w white noise of two-sided intensity G0; P solves
        A P + P A^T + 2 pi G0 b b^T = 0 and the outputs' covariance is C P C^T.
        A modulated case is taken by its stationary spectrum (sigma_inf)."""
        outputs = self.contact_outputs
        return ContactResponse(self.case.contact.levels, outputs @ self.state_space.covariance() @ outputs.T, "lyapunov")

    @cached_property
    def response_with_residual(self) -> ContactResponse:
        """:attr:`stationary_response` plus the response to the linearization's
        residual of the yielding storeys, an input independent of the ground
        motion to second order (one pass, :mod:`pounding.linearization.residual`):
        the gap-aware estimator's. Equal to the stationary response for elastic buildings."""
        residual = residual_response(self.state_space, self.buildings, self.contact_outputs)
        linear = self.stationary_response
        return ContactResponse(self.case.contact.levels, linear.covariance + residual, "lyapunov+residual")

    def response_frequency(self, rtol: float = 1e-10) -> ContactResponse:
        """The stationary response by frequency integrals (Eq. 17-18, 25): the
        independent route, slow (~0.1 s); :func:`~pounding.response.response_frequency`."""
        return response_frequency(self.case, self.buildings, self.state_space, rtol)

    @cached_property
    def contact_floor_frfs(self) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
        """Each contact floor's FRF per unit ground acceleration [s^2] and its
        receptance [m/N] on :func:`~pounding.response.spectral_grid`, building 1 then 2."""
        omega = spectral_grid()
        return tuple(floor_response_and_receptance(b, omega, f) for b, f in zip(self.buildings, self.floors))

    @cached_property
    def relative_displacement_psd(self) -> np.ndarray:
        """One-sided PSD G_X of X = x1 - x2 on :func:`~pounding.response.spectral_grid` [m^2 s/rad]."""
        (h1, _), (h2, _) = self.contact_floor_frfs
        return relative_displacement_psd(h1, h2, self.case.excitation.spectrum.psd(spectral_grid()))

    @cached_property
    def relative_displacement_moments(self) -> np.ndarray:
        """One-sided spectral moments lambda_0, lambda_1, lambda_2 of X (:attr:`relative_displacement_psd`)."""
        return spectral_moments(self.relative_displacement_psd)

    @cached_property
    def bandwidth(self) -> float:
        """Vanmarcke's q = sqrt(1 - lambda_1^2 / (lambda_0 lambda_2)) of X [-]:
        near 0 for a narrow-band (one-frequency) motion, up to 1 for a broad one."""
        return float(vanmarcke_bandwidth(*self.relative_displacement_moments))

    @cached_property
    def floor_bandwidths(self) -> np.ndarray:
        """Vanmarcke's q of each contact floor's displacement x1, x2 [-]."""
        ground = self.case.excitation.spectrum.psd(spectral_grid())
        return np.array([vanmarcke_bandwidth(*spectral_moments(2.0 * np.abs(h) ** 2 * ground)) for h, _ in self.contact_floor_frfs])

    def psd_relative_velocity(self, omega) -> np.ndarray:
        """Two-sided PSD of V = v1 - v2 at the contact floors, w^2 |H1 - H2|^2 S_g(w)
        [m^2/s], whose integral over (-inf, inf) is sigma_V^2 (Eq. 16-18);
        ``omega`` [rad/s]."""
        omega = np.asarray(omega, dtype=float)
        h1, h2 = (frequency_response(b, omega)[..., f] for b, f in zip(self.buildings, self.floors))
        return omega**2 * np.abs(h1 - h2) ** 2 * self.case.excitation.spectrum.psd(omega)

    def covariance_history(self, times=None, modulation: str = "bedrock") -> np.ndarray:
        """Covariance of :data:`~pounding.response.OUTPUTS` from rest under the
        case's envelope at ``times`` [s] (default: every 0.05 s over the
        record), shape (times, 6, 6); the buildings keep their stationary
        linearization (the paper's sigma_inf approach). ``modulation``:
        ``"bedrock"`` or ``"ground"`` (Eq. 8), see
        :func:`~pounding.covariance_history.time_varying_covariance`."""
        if times is None:
            times = np.arange(0.0, self.case.excitation.duration + 1e-9, 0.05)
        return time_varying_covariance(
            self.state_space, self.case.excitation.envelope, times, modulation=modulation, outputs=self.contact_outputs
        )

    @cached_property
    def history_from_rest(self) -> tuple[np.ndarray, np.ndarray]:
        """Trapezoid weights [s] of a grid every :data:`HISTORY_STEP` over the
        record and the outputs' covariance on it: the ground motion switched on
        at t = 0 on buildings at rest (stationary case), or modulated by the
        envelope."""
        excitation = self.case.excitation
        times = np.arange(0.0, excitation.duration + 1e-9, HISTORY_STEP)
        if times[-1] < excitation.duration - 1e-9:
            times = np.append(times, excitation.duration)
        modulation = "ground" if excitation.stationary else "bedrock"
        return trapezoid_weights(times), self.covariance_history(times, modulation)

    @cached_property
    def impact_damping(self) -> ImpactDamping:
        """The free relative motion's spectrum and memory, from which the
        impacts' dashpot follows at any gap (:mod:`pounding.impact_damping`)."""
        return impact_damping(self)

    @cached_property
    def floor_statistics(self) -> FloorStatistics:
        """Standard deviations of every floor and storey of the pair (Lyapunov route)."""
        model = self.state_space
        covariance = model.covariance()

        def sigma(rows):
            return np.sqrt(np.einsum("ij,jk,ik->i", rows, covariance, rows))

        pair = (0, 1)
        return FloorStatistics(
            tuple(sigma(model.displacement[b]) for b in pair),
            tuple(sigma(model.velocity[b]) for b in pair),
            tuple(sigma(model.drift(b)) for b in pair),
            tuple(sigma(model.drift_velocity(b)) for b in pair),
            tuple(sigma(model.hysteretic[b]) for b in pair),
        )

    @property
    def yielding(self) -> bool:
        """Whether a storey of either linearized building yields (k_e != 0)."""
        return any(np.any(building.k_e != 0.0) for building in self.buildings)

    @cached_property
    def residual_share(self) -> float:
        """How much the residual's response adds to sigma_X or sigma_V, the larger [-]."""
        full, linear = self.response_with_residual, self.stationary_response
        return max(
            full.sigma_relative_displacement / linear.sigma_relative_displacement,
            full.sigma_relative_velocity / linear.sigma_relative_velocity,
        ) - 1.0

    def check_relative_motion(self) -> None:
        """Raise :class:`CaseError` where there is no relative motion to count
        crossings of: no ground motion, or buildings that move alike (the
        variance of x1 - x2 within rounding of zero against the floors')."""
        c = self.stationary_response.covariance
        floors = max(c[0, 0], c[1, 1])
        if floors == 0.0:
            raise CaseError("excitation.G0", f"must be > 0 for the closed-form estimate, got {self.case.excitation.spectrum.G0:g}: "
                            "without ground motion nothing moves and nothing pounds")
        # c11 + c22 - 2 c12 of two identical buildings is rounding noise, up to ~1e-13 of c11 and of either sign.
        if c[0, 0] + c[1, 1] - 2.0 * c[0, 1] <= 1e-12 * floors:
            raise CaseError("buildings", "the two buildings move alike at the contact floors (x1 - x2 is 0): under one "
                            "ground motion they never approach each other, so there is no pounding to estimate")
