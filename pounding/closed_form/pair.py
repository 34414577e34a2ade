"""The statistically linearized pair (Eq. 19-21) and everything the closed
forms take from it, computed once: :class:`LinearizedPair`.

Nothing here depends on the gap: one pair serves an estimate, its force
against the gap and the dashboard's plots.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from pounding import defaults
from pounding.case.case import Case
from pounding.closed_form.covariance_history import time_varying_covariance
from pounding.closed_form.impact_damping import ImpactDamping, impact_damping, jump_modes
from pounding.closed_form.linearization import (
    LinearizedBuilding,
    StateSpace,
    linearize_pair,
    pair_state_space,
)
from pounding.closed_form.linearization.residual import residual_response
from pounding.closed_form.response import (
    ContactResponse,
    FloorStatistics,
    band_covariance,
    contact_output_matrix,
    floor_responses,
    frequency_response,
    relative_displacement_psd,
    response_frequency,
    spectral_grid,
    spectral_moments,
    trapezoid_weights,
)
from pounding.errors import ArgumentError, CaseError, ConvergenceError
from pounding.random_vibration.crossing_kernels import vanmarcke_bandwidth

__all__ = ["CUTOFF_NEGLIGIBLE", "HISTORY_STEP", "RUNAWAY_PEAK_FACTOR", "LinearizedPair"]

HISTORY_STEP = 0.25
"""[s] time grid of the covariance from rest: the build-up takes seconds, and so does an envelope's change."""
CUTOFF_NEGLIGIBLE = 1e-5
"""Share of the variance of the contact floors' x1, x2 or of X, V above the records' cutoff below which the closed
form is not cut there [-]: it would move a sigma by under 5e-6, no printed digit. The default cutoff, 157 rad/s,
removes under 2e-6 on the presets and the 433 measured cases of docs/accuracy.md (the floors' own velocities lose
up to 1e-4, the ground's velocity above 157 rad/s, which only the separation rules see)."""
RUNAWAY_PEAK_FACTOR = 3.0
"""A floor's peak taken as this many sigmas [-] when set against the time histories' runaway limit
(``defaults.DISPLACEMENT_LIMIT``, 10 m): the closed form refuses where 3 sigma passes it."""


@dataclass(frozen=True, eq=False)
class LinearizedPair:
    """A case's two buildings, statistically linearized under its excitation,
    with the quantities derived from them as cached properties (each computed
    once, on first use).

    Parameters
    ----------
    case : Case
    buildings : tuple of two LinearizedBuilding
        From :func:`~pounding.closed_form.linearization.linearize_pair`; :meth:`of` linearizes.

    Notes
    -----
    The contact floors' outputs are :data:`~pounding.closed_form.response.OUTPUTS`:
    x1, x2, v1, v2, a1, a2 relative to the ground (SI).
    """

    case: Case
    buildings: tuple[LinearizedBuilding, LinearizedBuilding]

    @classmethod
    def of(cls, case: Case, **linearization) -> LinearizedPair:
        """Linearize ``case``'s buildings (options of :func:`~pounding.closed_form.linearization.linearize`)."""
        if not isinstance(case, Case):
            raise ArgumentError("case", f"must be a Case (from load_case), got {type(case).__name__}")
        case.contact  # noqa: B018 -- CaseError naming ``contacts`` for a case of several (pounding.closed_form.row)
        case = case.pair(0)  # the contact's two buildings: a row of them with one contact
        return cls(case, tuple(linearize_pair(case, **linearization)))

    def for_contact(self, case: Case) -> LinearizedPair:
        """The same two linearized buildings with ``case``'s contact (another pair of floors, gap or law): the
        state space, its stationary covariance and its modes, and the floors' FRFs, which do not depend on the
        contact, are shared."""
        other = LinearizedPair(case, self.buildings)
        for shared in ("state_space", "floor_frfs"):  # cached_property slots: computed once for the buildings
            other.__dict__[shared] = getattr(self, shared)
        return other

    @property
    def floors(self) -> tuple[int, int]:
        """The contact floors, counted from 0 (= first floor) in each building."""
        return tuple(level - 1 for level in self.case.contact.levels)

    @cached_property
    def state_space(self) -> StateSpace:
        """Both linearized buildings and the ground filter (:func:`~pounding.closed_form.linearization.pair_state_space`)."""
        return pair_state_space(self.case, self.buildings)

    @cached_property
    def contact_outputs(self) -> np.ndarray:
        """Rows mapping the state to :data:`~pounding.closed_form.response.OUTPUTS`, (6, n)."""
        return contact_output_matrix(self.floors, self.state_space)

    @cached_property
    def stationary_response(self) -> ContactResponse:
        """Stationary response at the contact floors by the Lyapunov equation
        (Eq. 16-18, 25): the paper's. The pair and the ground filter form
        x' = A x + b w, w white noise of two-sided intensity G0; P solves
        A P + P A^T + 2 pi G0 b b^T = 0 and the outputs' covariance is C P C^T.
        A modulated case is taken by its stationary spectrum (sigma_inf).

        The records carry nothing above ``excitation.cutoff_frequency``: where
        that removes more than :data:`CUTOFF_NEGLIGIBLE` of a variance, the part
        above it (:func:`~pounding.closed_form.response.band_covariance`) is taken out, and
        the spectra and the history from rest are cut alike (:attr:`cutoff_shares`)."""
        if not self.cut_at_cutoff:
            return ContactResponse(self.case.contact.levels, self._lyapunov_covariance, "lyapunov")
        cutoff = self.case.excitation.cutoff_frequency
        if self.cutoff_shares[5] > 0.5:  # most of sigma_V^2 is above: the part below, directly
            covariance = band_covariance(self.case, self.buildings, spectral_grid()[0], cutoff, self.floor_frfs)
        else:
            covariance = self._lyapunov_covariance - self._above_cutoff
        return ContactResponse(self.case.contact.levels, covariance, "lyapunov, cut at the records' cutoff")

    @cached_property
    def _lyapunov_covariance(self) -> np.ndarray:
        outputs = self.contact_outputs
        return outputs @ self.state_space.covariance() @ outputs.T

    @cached_property
    def _above_cutoff(self) -> np.ndarray:
        """The outputs' covariance carried by frequencies above the records' cutoff (0 beyond the spectral grid)."""
        cutoff, top = self.case.excitation.cutoff_frequency, spectral_grid()[-1]
        return band_covariance(self.case, self.buildings, cutoff, top, self.floor_frfs) if cutoff < top else np.zeros((6, 6))

    @cached_property
    def cutoff_shares(self) -> np.ndarray:
        """Shares of the variances of x1, x2, v1, v2, X and V of the linearized
        pair (full spectrum) carried by frequencies above the records' cutoff [-]."""
        above, full = self._above_cutoff, self._lyapunov_covariance

        def variances(c):
            return np.array([c[0, 0], c[1, 1], c[2, 2], c[3, 3], c[0, 0] + c[1, 1] - 2 * c[0, 1], c[2, 2] + c[3, 3] - 2 * c[2, 3]])

        removed, total = variances(above), variances(full)
        return np.clip(np.divide(removed, total, out=np.zeros(6), where=total > 0.0), 0.0, 1.0)

    @property
    def cut_at_cutoff(self) -> bool:
        """Whether the closed form is cut at the records' cutoff (:data:`CUTOFF_NEGLIGIBLE`)."""
        return bool(self.cutoff_shares[[0, 1, 4, 5]].max() > CUTOFF_NEGLIGIBLE)

    def _cut_history(self, history: np.ndarray) -> np.ndarray:
        """A covariance history of the outputs, cut at the records' cutoff as the stationary response is:
        each variance, and x1 - x2's and v1 - v2's, scaled by its stationary ratio (as G3 carries the residual's);
        the cross terms of a displacement and a velocity by the two floors' ratios (approximate; no estimator uses them)."""
        if not self.cut_at_cutoff:
            return history
        full, cut = self._lyapunov_covariance, self.stationary_response.covariance
        scale = np.sqrt(np.divide(np.diagonal(cut), np.diagonal(full), out=np.ones(6), where=np.diagonal(full) > 0.0))
        out = history * np.outer(scale, scale)
        for i, j in ((0, 1), (2, 3)):  # the difference's variance keeps its own ratio: exact once stationary
            total, kept = (c[i, i] + c[j, j] - 2 * c[i, j] for c in (full, cut))
            difference = (kept / total if total > 0.0 else 1.0) * (history[:, i, i] + history[:, j, j] - 2 * history[:, i, j])
            out[:, i, j] = out[:, j, i] = 0.5 * (out[:, i, i] + out[:, j, j] - difference)
        return out

    def _records_band(self, omega) -> np.ndarray:
        """1 where the records carry frequency ``omega`` [rad/s], 0 above their cutoff (1 everywhere when not cut)."""
        omega = np.asarray(omega, dtype=float)
        if not self.cut_at_cutoff:
            return np.ones(omega.shape)
        return (omega <= self.case.excitation.cutoff_frequency).astype(float)

    @cached_property
    def response_with_residual(self) -> ContactResponse:
        """:attr:`stationary_response` plus the response to the linearization's
        residual of the yielding storeys, an input independent of the ground
        motion to second order (one pass, :mod:`pounding.closed_form.linearization.residual`):
        the gap-aware estimator's. Equal to the stationary response for elastic buildings."""
        residual = residual_response(self.state_space, self.buildings, self.contact_outputs)
        linear = self.stationary_response
        return ContactResponse(self.case.contact.levels, linear.covariance + residual, "lyapunov+residual")

    def response_frequency(self, rtol: float = 1e-10) -> ContactResponse:
        """The stationary response by frequency integrals (Eq. 17-18, 25): the
        independent route, slow (~0.1 s); :func:`~pounding.closed_form.response.response_frequency`.
        Under the full spectrum: not cut at the records' cutoff."""
        return response_frequency(self.case, self.buildings, self.state_space, rtol)

    @cached_property
    def floor_frfs(self) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
        """Each building's floors' FRFs and receptances on :func:`~pounding.closed_form.response.spectral_grid`
        (:func:`~pounding.closed_form.response.floor_responses`), building 1 then 2: whatever floors meet."""
        omega = spectral_grid()
        return tuple(floor_responses(b, omega) for b in self.buildings)

    @cached_property
    def contact_floor_frfs(self) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
        """Each contact floor's FRF per unit ground acceleration [s^2] and its
        receptance [m/N] on :func:`~pounding.closed_form.response.spectral_grid`, building 1 then 2."""
        return tuple((frf[:, f], receptance[:, f, f]) for (frf, receptance), f in zip(self.floor_frfs, self.floors))

    @cached_property
    def relative_displacement_psd(self) -> np.ndarray:
        """One-sided PSD G_X of X = x1 - x2 on :func:`~pounding.closed_form.response.spectral_grid` [m^2 s/rad]."""
        (h1, _), (h2, _) = self.contact_floor_frfs
        return relative_displacement_psd(h1, h2, self._records_psd)

    @cached_property
    def _records_psd(self) -> np.ndarray:
        """The ground's two-sided PSD on :func:`~pounding.closed_form.response.spectral_grid`, 0 above the records' cutoff."""
        grid = spectral_grid()
        return self.case.excitation.spectrum.psd(grid) * self._records_band(grid)

    @cached_property
    def relative_displacement_moments(self) -> np.ndarray:
        """One-sided spectral moments lambda_0, lambda_1, lambda_2 of X (:attr:`relative_displacement_psd`)."""
        return _resolved(spectral_moments(self.relative_displacement_psd), "the relative displacement")

    @cached_property
    def bandwidth(self) -> float:
        """Vanmarcke's q = sqrt(1 - lambda_1^2 / (lambda_0 lambda_2)) of X [-]:
        near 0 for a narrow-band (one-frequency) motion, up to 1 for a broad one."""
        return float(vanmarcke_bandwidth(*self.relative_displacement_moments))

    @cached_property
    def floor_bandwidths(self) -> np.ndarray:
        """Vanmarcke's q of each contact floor's displacement x1, x2 [-]."""
        ground = self._records_psd
        return np.array([vanmarcke_bandwidth(*_resolved(spectral_moments(2.0 * np.abs(h) ** 2 * ground), f"floor {b}'s displacement"))
                         for b, (h, _) in enumerate(self.contact_floor_frfs, start=1)])

    def psd_relative_velocity(self, omega) -> np.ndarray:
        """Two-sided PSD of V = v1 - v2 at the contact floors, w^2 ``|H1 - H2|^2`` S_g(w)
        [m^2/s], whose integral over (-inf, inf) is sigma_V^2 (Eq. 16-18);
        ``omega`` [rad/s]."""
        omega = np.asarray(omega, dtype=float)
        h1, h2 = (frequency_response(b, omega)[..., f] for b, f in zip(self.buildings, self.floors))
        return omega**2 * np.abs(h1 - h2) ** 2 * self.case.excitation.spectrum.psd(omega) * self._records_band(omega)

    def covariance_history(self, times=None, modulation: str = "bedrock") -> np.ndarray:
        """Covariance of :data:`~pounding.closed_form.response.OUTPUTS` from rest under the
        case's envelope at ``times`` [s] (default: every 0.05 s over the
        record), shape (times, 6, 6); the buildings keep their stationary
        linearization (the paper's sigma_inf approach), and the history is cut
        at the records' cutoff as :attr:`stationary_response` is. ``modulation``:
        ``"bedrock"`` or ``"ground"`` (Eq. 8), see
        :func:`~pounding.closed_form.covariance_history.time_varying_covariance`."""
        if times is None:
            times = np.arange(0.0, self.case.excitation.duration + 1e-9, 0.05)
        return self._cut_history(time_varying_covariance(
            self.state_space, self.case.excitation.envelope, times, modulation=modulation, outputs=self.contact_outputs
        ))

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
        impacts' dashpot follows at any gap (:mod:`pounding.closed_form.impact_damping`)."""
        response, case = self.response_with_residual, self.case
        (_, r1), (_, r2) = self.contact_floor_frfs
        modes = jump_modes(self.state_space, self.buildings, self.floors, case.contact_masses)
        return impact_damping(response.sigma_relative_displacement, response.sigma_relative_velocity,
                              self.relative_displacement_psd, self.relative_displacement_moments, (r1, r2), self.bandwidth,
                              case.reduced_mass, case.contact.restitution, modes)

    @cached_property
    def floor_statistics(self) -> FloorStatistics:
        """Standard deviations of every floor and storey of the pair (Lyapunov route, the full spectrum)."""
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
        crossings of: no ground motion, records that carry none (a cutoff below
        their lowest frequency), or buildings that move alike (the variance of
        x1 - x2 within rounding of zero against the floors'); and
        :class:`ConvergenceError` where the floors would run away (3 sigma past
        the time histories' runaway limit, :data:`RUNAWAY_PEAK_FACTOR`)."""
        excitation = self.case.excitation
        if excitation.spectrum.G0 == 0.0:
            raise CaseError("excitation.G0", "must be > 0 for the closed-form estimate, got 0: without ground motion nothing "
                            "moves and nothing pounds")
        lowest = max(2.0 * math.pi / (excitation.fft_length * excitation.time_step), spectral_grid()[0])
        if excitation.cutoff_frequency < lowest:
            raise CaseError("excitation.cutoff_frequency", f"must be at least the records' lowest frequency, {lowest:.3g} rad/s, "
                            f"for the closed-form estimate, got {excitation.cutoff_frequency:g}: the records carry no ground motion")
        self.check_runaway()
        c = self.stationary_response.covariance
        floors = max(c[0, 0], c[1, 1])
        if floors == 0.0:
            raise CaseError("excitation.G0", f"must be > 0 for the closed-form estimate, got {excitation.spectrum.G0:g}: "
                            "without ground motion nothing moves and nothing pounds")
        if self.moves_alike:
            raise CaseError("buildings", "the two buildings move alike at the contact floors (x1 - x2 is 0): under one "
                            "ground motion they never approach each other, so there is no pounding to estimate")

    @property
    def moves_alike(self) -> bool:
        """Whether x1 - x2 at the contact floors is 0: two identical buildings (or no ground motion), which never
        approach each other."""
        c = self.stationary_response.covariance
        # c11 + c22 - 2 c12 of two identical buildings is rounding noise, up to ~1e-13 of c11 and of either sign.
        return bool(c[0, 0] + c[1, 1] - 2.0 * c[0, 1] <= 1e-12 * max(c[0, 0], c[1, 1]))

    def check_runaway(self) -> None:
        """Raise :class:`ConvergenceError` where 3 sigma of a floor's displacement (linearized, every floor of
        both buildings) passes the time histories' runaway limit: a motion no building survives and a
        simulation stops on, not an answer (:data:`RUNAWAY_PEAK_FACTOR`)."""
        limit = defaults.DISPLACEMENT_LIMIT
        for number, sigmas in enumerate(self.floor_statistics.displacement, start=1):
            sigma = float(np.max(sigmas))
            if not RUNAWAY_PEAK_FACTOR * sigma <= limit:
                raise ConvergenceError(
                    f"building {number}'s floors move {sigma:.3g} m (sigma): their peaks, about 3 sigma, pass the {limit:g} m "
                    "at which a time history runs away, so there is no estimate; lower G0 or check the storeys")


def _resolved(moments: np.ndarray, what: str) -> np.ndarray:
    """``moments`` (lambda_0, lambda_1, lambda_2), unless lambda_0 or lambda_2 rounds to 0 or overflows."""
    if not (np.all(np.isfinite(moments)) and moments[0] * moments[2] > 0.0):
        raise ConvergenceError(f"the spectrum of {what} underflows or overflows in double precision: "
                               "the ground motion's G0 is out of reach of the method")
    return moments
