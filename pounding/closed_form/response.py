"""Stationary response of a linearized pair at its contact floors
(Eq. 15-18, 22, 24-25): :class:`ContactResponse`, the buildings' frequency
response functions, and the spectral grid and moments.

Two independent routes give the covariance of the contact floors'
displacements, velocities and accelerations (all relative to the ground):

- :attr:`pounding.closed_form.pair.LinearizedPair.stationary_response`, the default and
  fast one: the stationary covariance of the joint state-space model (both
  buildings and the ground filter) from the Lyapunov equation;
- :func:`response_frequency`: integrals over frequency of the complex
  frequency response functions (FRFs) of the linearized buildings against
  the ground spectrum, E[Y1 Y2] = int H1 conj(H2) S_g d omega over (-inf, inf),
  as Eq. 17-18 and 25 write them.

Their agreement checks the state-space model, the FRFs and the 2 pi factor of
the white-noise intensity. Units: SI; PSDs two-sided per [rad/s].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import quad_vec

from pounding.closed_form.linearization import LinearizedBuilding, StateSpace

__all__ = [
    "OUTPUTS",
    "ContactResponse",
    "band_covariance",
    "FloorStatistics",
    "contact_output_matrix",
    "floor_responses",
    "frequency_response",
    "relative_displacement_psd",
    "response_frequency",
    "spectral_grid",
    "spectral_moments",
    "spectral_weights",
    "trapezoid_weights",
]

OUTPUTS = ("x1", "x2", "v1", "v2", "a1", "a2")
"""Order of :attr:`ContactResponse.covariance`: displacement, velocity and
acceleration of the contact floor of building 1 and of building 2, relative to
the ground [m, m/s, m/s^2]."""

_X1, _X2, _V1, _V2, _A1, _A2 = range(6)


@dataclass(frozen=True, eq=False)
class ContactResponse:
    """Stationary second moments at the contact floors of a linearized pair.

    Parameters
    ----------
    levels : tuple of int
        The contact floors (building 1, building 2), counted from 1.
    covariance : ndarray, (6, 6)
        Covariance of the variables :data:`OUTPUTS` (SI).
    method : str
        ``"lyapunov"`` or ``"frequency"``.

    Notes
    -----
    The relative displacement is X = x1 - x2 (positive closes the gap) and the
    relative velocity V = dX/dt = v1 - v2 (Eq. 15).
    """

    levels: tuple[int, int]
    covariance: np.ndarray
    method: str = "lyapunov"

    def _sigma(self, i: int) -> float:
        return math.sqrt(self.covariance[i, i])

    def _sigma_difference(self, i: int, j: int) -> float:
        c = self.covariance
        return math.sqrt(c[i, i] + c[j, j] - 2.0 * c[i, j])

    @property
    def sigma_displacement(self) -> tuple[float, float]:
        """Standard deviations of the contact floors' displacements [m] (Eq. 25)."""
        return self._sigma(_X1), self._sigma(_X2)

    @property
    def sigma_velocity(self) -> tuple[float, float]:
        """Standard deviations of the contact floors' velocities [m/s] (Eq. 17)."""
        return self._sigma(_V1), self._sigma(_V2)

    @property
    def sigma_acceleration(self) -> tuple[float, float]:
        """Standard deviations of the contact floors' accelerations relative to the ground [m/s^2]."""
        return self._sigma(_A1), self._sigma(_A2)

    @property
    def covariance_displacement(self) -> float:
        """E[x1 x2] [m^2] (Eq. 25)."""
        return float(self.covariance[_X1, _X2])

    @property
    def correlation_displacement(self) -> float:
        """Correlation of the two contact floors' displacements x1 and x2 [-]: near 1,
        X = x1 - x2 is the small part in which the buildings do not move together."""
        return self.covariance_displacement / (self._sigma(_X1) * self._sigma(_X2))

    @property
    def covariance_velocity(self) -> float:
        """E[v1 v2] [m^2/s^2] (Eq. 18)."""
        return float(self.covariance[_V1, _V2])

    @property
    def sigma_relative_displacement(self) -> float:
        """sigma of X = x1 - x2 [m]: sigma_x1^2 + sigma_x2^2 - 2 E[x1 x2] (Eq. 25)."""
        return self._sigma_difference(_X1, _X2)

    @property
    def sigma_relative_velocity(self) -> float:
        """sigma of V = v1 - v2 [m/s]: sigma_v1^2 + sigma_v2^2 - 2 E[v1 v2] (Eq. 16; the terms Eq. 16-17
        call standard deviations are variances, docs/errata.md, E4)."""
        return self._sigma_difference(_V1, _V2)

    @property
    def sigma_relative_acceleration(self) -> float:
        """sigma of dV/dt = a1 - a2 [m/s^2]."""
        return self._sigma_difference(_A1, _A2)

    @property
    def zero_crossing_rate(self) -> float:
        """nu = sigma_V / (pi sigma_X) [1/s], Eq. 24: the mean rate of zero
        crossings of X in *both* directions (twice Rice's upcrossing rate).
        The paper uses it in Davenport's formula for the peak of V."""
        return self.sigma_relative_velocity / (math.pi * self.sigma_relative_displacement)

    @property
    def upcrossing_rate(self) -> float:
        """Rice's zero-upcrossing rate of X, nu0+ = sigma_V / (2 pi sigma_X) [1/s]
        (one direction)."""
        return self.sigma_relative_velocity / (2.0 * math.pi * self.sigma_relative_displacement)

    @property
    def velocity_upcrossing_rate(self) -> float:
        """Rice's zero-upcrossing rate of V itself, sigma_dV/dt / (2 pi sigma_V) [1/s]:
        the rate Davenport's formula calls for when the peak of V is sought."""
        return self.sigma_relative_acceleration / (2.0 * math.pi * self.sigma_relative_velocity)

    @property
    def correlation_relative(self) -> float:
        """Correlation of X and V at one instant [-]: zero for a stationary process."""
        c = self.covariance
        cov = c[_X1, _V1] - c[_X1, _V2] - c[_X2, _V1] + c[_X2, _V2]
        return float(cov / (self.sigma_relative_displacement * self.sigma_relative_velocity))


def contact_output_matrix(floors: tuple[int, int], model: StateSpace) -> np.ndarray:
    """Rows mapping the state of the pair model to :data:`OUTPUTS`, (6, n); ``floors``: the
    contact floor of each building counted from 0."""
    f1, f2 = floors
    return np.array(
        [
            model.displacement[0][f1],
            model.displacement[1][f2],
            model.velocity[0][f1],
            model.velocity[1][f2],
            model.acceleration(0)[f1],
            model.acceleration(1)[f2],
        ]
    )



def _storey_stiffness(linearized: LinearizedBuilding, w: np.ndarray) -> np.ndarray:
    """Complex storey stiffness k_dyn(w) = alpha k + (1 - alpha) k c_e i w / (i w - k_e) + i w c
    of each storey [N/m], shape (frequencies, storeys); ``w`` of shape (frequencies, 1)."""
    building = linearized.building
    iw = 1j * w
    k = building.stiffnesses
    alpha = np.array([s.bouc_wen.alpha for s in building.storeys])
    # An elastic storey (k_e = 0) has z = c_e u at every frequency, omega = 0 included.
    with np.errstate(invalid="ignore", divide="ignore"):
        z_ratio = np.where(linearized.hysteretic, linearized.c_e * iw / (iw - linearized.k_e), linearized.c_e + 0j)
    return alpha * k + (1.0 - alpha) * k * z_ratio + iw * building.storey_damping()


def _floor_response(linearized: LinearizedBuilding, omega, loads: np.ndarray) -> np.ndarray:
    """Floor displacements [m] under harmonic floor forces ``loads`` [N], shape
    (floors, cases): the solutions H of (-w^2 M + T^T diag(k_dyn) T) H = load,
    one factorization for all cases; shape omega.shape + (floors, cases)."""
    omega = np.asarray(omega, dtype=float)
    building = linearized.building
    w = omega.reshape(-1, 1)
    storey = _storey_stiffness(linearized, w)
    masses = building.masses
    N = building.n_storeys
    if N == 1:
        response = (loads[0] / (-(w**2) * masses[0] + storey))[:, None, :]
    else:
        drift = np.eye(N) - np.eye(N, k=-1)
        dynamic = np.einsum("ji,fj,jk->fik", drift, storey, drift) - (w**2)[:, :, None] * np.diag(masses)
        response = np.linalg.solve(dynamic, np.broadcast_to(loads, (w.shape[0],) + loads.shape).astype(complex))
    return response.reshape(omega.shape + loads.shape)


def frequency_response(linearized: LinearizedBuilding, omega) -> np.ndarray:
    """Complex FRF of the floor displacements relative to the ground per unit
    ground acceleration [s^2], from Eq. 1 (36-39) and Eq. 19.

    Eq. 19 gives z = c_e i w u / (i w - k_e) per storey, so the storey force is
    k_dyn(w) u with k_dyn = alpha k + (1 - alpha) k c_e i w / (i w - k_e) + i w c;
    then (-w^2 M + T^T diag(k_dyn) T) H = -M 1. For one storey ``|H|^2`` is Eq. 22,
    which prints only the modulus: the cross terms of Eq. 18 and 25 need the
    complex H of each building (docs/errata.md, E7).

    Parameters
    ----------
    linearized : LinearizedBuilding
    omega : array_like
        Circular frequencies [rad/s].

    Returns
    -------
    ndarray, complex, shape omega.shape + (n_storeys,)
    """
    return _floor_response(linearized, omega, -linearized.building.masses[:, None])[..., 0]


def floor_responses(linearized: LinearizedBuilding, omega) -> tuple[np.ndarray, np.ndarray]:
    """Every floor's FRF per unit ground acceleration [s^2] (:func:`frequency_response`) and the receptances between
    the floors [m/N] (column j: the floors' displacements under a harmonic force of 1 N on floor j, counted from 0),
    from one factorization per frequency; shapes omega.shape + (floors,) and omega.shape + (floors, floors). A
    floor's own receptance is the diagonal."""
    building = linearized.building
    loads = np.concatenate([-building.masses[:, None], np.eye(building.n_storeys)], axis=1)
    response = _floor_response(linearized, omega, loads)
    return response[..., 0], response[..., 1:]


def _outputs_frf(h1: np.ndarray, h2: np.ndarray, omega) -> np.ndarray:
    """FRFs of the OUTPUTS from the contact floors' displacement FRFs, shape omega.shape + (6,)."""
    iw = 1j * np.asarray(omega, dtype=float)
    return np.stack([h1, h2, iw * h1, iw * h2, iw**2 * h1, iw**2 * h2], axis=-1)


def _contact_frf(case, linearized, omega) -> np.ndarray:
    """FRFs of the OUTPUTS per unit ground acceleration, shape omega.shape + (6,)."""
    f1, f2 = (level - 1 for level in case.contact.levels)
    return _outputs_frf(frequency_response(linearized[0], omega)[..., f1], frequency_response(linearized[1], omega)[..., f2], omega)


def band_covariance(case, linearized, low: float, high: float, floor_frfs=None) -> np.ndarray:
    """Covariance of :data:`OUTPUTS` carried by the ground motion's frequencies from ``low`` to ``high``
    [rad/s], 2 int Re(H_i conj(H_j)) S_g d omega by the trapezoid rule on the points of
    :func:`spectral_grid` between them and the two ends, shape (6, 6) (SI): the part of the stationary
    covariance a band of the spectrum makes (the records' cutoff, :class:`~pounding.closed_form.pair.LinearizedPair`).
    ``floor_frfs``: both buildings' :func:`floor_responses` on :func:`spectral_grid`, whose points inside the band
    are then not solved again."""
    grid = spectral_grid()
    inside = (grid > low) & (grid < high)
    omega = np.concatenate([[low], grid[inside], [high]])
    if floor_frfs is None:
        frf = _contact_frf(case, linearized, omega)
    else:
        f1, f2 = (level - 1 for level in case.contact.levels)
        ends = _contact_frf(case, linearized, omega[[0, -1]])
        middle = _outputs_frf(floor_frfs[0][0][inside, f1], floor_frfs[1][0][inside, f2], grid[inside])
        frf = np.concatenate([ends[:1], middle, ends[1:]])
    density = case.excitation.spectrum.psd(omega) * trapezoid_weights(omega)
    return 2.0 * np.real(np.einsum("k,ki,kj->ij", density, frf, frf.conj()))


def response_frequency(case, linearized, model: StateSpace, rtol: float = 1e-10) -> ContactResponse:
    """Contact-floor response by frequency-domain integrals (Eq. 17-18, 25)::

        E[Y_i Y_j] = int_(-inf)^(inf) H_i conj(H_j) S_g d omega
                   = 2 int_0^inf Re(H_i conj(H_j)) S_g d omega,

    since H(-w) = conj(H(w)); velocities and accelerations have FRFs i w H and
    -w^2 H. Integrated adaptively (``scipy.integrate.quad_vec``) over [0, inf)
    with breakpoints at the natural frequencies of the linearized pair and the
    filter. A reference for the Lyapunov route, not fast (~0.1 s).

    Parameters
    ----------
    case : Case
    linearized : tuple of two LinearizedBuilding
    model : StateSpace
        Their :func:`~pounding.closed_form.linearization.pair_state_space` (for the poles).
    rtol : float
        Relative tolerance of the integration (max-norm over the outputs, each
        scaled to acceleration units).
    """
    spectrum = case.excitation.spectrum
    poles = np.linalg.eigvals(model.matrix)
    points = np.unique(np.concatenate([np.abs(poles.imag), np.abs(poles)]))
    points = points[points > 0.0]
    # Scale displacements and velocities to acceleration units so the
    # max-norm error control treats every output alike.
    reference = math.sqrt(np.prod([lb.building.mode_shapes()[0][0] for lb in linearized]))
    scale = np.array([reference**2, reference**2, reference, reference, 1.0, 1.0])
    rows, cols = np.triu_indices(6)

    def integrand(w):
        y = _contact_frf(case, linearized, np.array([w]))[0] * scale
        return (np.real(y[rows] * np.conj(y[cols])) * spectrum.psd(w)).astype(float)

    upper, _ = quad_vec(integrand, 0.0, np.inf, epsrel=rtol, epsabs=0.0, norm="max", points=points, limit=20000)
    covariance = np.empty((6, 6))
    covariance[rows, cols] = covariance[cols, rows] = 2.0 * upper
    return ContactResponse(case.contact.levels, covariance / np.outer(scale, scale), "frequency")


@dataclass(frozen=True, eq=False)
class FloorStatistics:
    """Stationary standard deviations of every floor and storey of both
    buildings, one array per building, floors and storeys from the ground up.

    Parameters
    ----------
    displacement, velocity : tuple of ndarray
        Floor displacements relative to the ground [m], velocities [m/s].
    drift, drift_velocity, hysteretic : tuple of ndarray
        Storey drifts [m], their rates [m/s], hysteretic displacements z [m].
    """

    displacement: tuple[np.ndarray, np.ndarray]
    velocity: tuple[np.ndarray, np.ndarray]
    drift: tuple[np.ndarray, np.ndarray]
    drift_velocity: tuple[np.ndarray, np.ndarray]
    hysteretic: tuple[np.ndarray, np.ndarray]


_SPECTRAL_GRID = np.geomspace(1e-4, 2.0e3, 2001)
_SPECTRAL_GRID.setflags(write=False)


def trapezoid_weights(grid) -> np.ndarray:
    """Trapezoid-rule weights of an increasing ``grid``: ``weights @ f`` is the
    integral of f sampled on it (in the grid's units)."""
    steps = np.diff(np.asarray(grid, dtype=float))
    return 0.5 * (np.r_[steps, 0.0] + np.r_[0.0, steps])


_SPECTRAL_WEIGHTS = trapezoid_weights(_SPECTRAL_GRID)
_SPECTRAL_WEIGHTS.setflags(write=False)
# Rows w^0, w^1, w^2 times the trapezoid weights: the spectral moments as one product.
_TRAPEZOID_POWERS = _SPECTRAL_GRID ** np.arange(3)[:, None] * _SPECTRAL_WEIGHTS


def spectral_grid() -> np.ndarray:
    """The fixed logarithmic frequency grid [rad/s] of the spectral moments of X
    (read-only): fine enough for damping ratios down to 1 %; the yielded storeys
    keep response down to very low frequencies, hence it starts at 1e-4 rad/s."""
    return _SPECTRAL_GRID


def spectral_weights() -> np.ndarray:
    """Trapezoid weights [rad/s] of :func:`spectral_grid` (read-only): a
    spectral moment is ``spectral_weights() @ (omega**k * spectrum)``."""
    return _SPECTRAL_WEIGHTS


def spectral_moments(spectrum, orders=(0, 1, 2)) -> np.ndarray:
    """One-sided spectral moments lambda_k = int_0^inf w^k G(w) dw of a
    ``spectrum`` G sampled on :func:`spectral_grid`, for each k of ``orders``."""
    if tuple(orders) == (0, 1, 2):
        return _TRAPEZOID_POWERS @ spectrum
    return (_SPECTRAL_GRID ** np.asarray(orders, dtype=float)[:, None] * _SPECTRAL_WEIGHTS) @ spectrum


def relative_displacement_psd(h1: np.ndarray, h2: np.ndarray, ground_psd: np.ndarray) -> np.ndarray:
    """One-sided PSD G_X = 2 S_X of the relative displacement X = x1 - x2
    [m^2 s/rad] from the contact floors' FRFs per unit ground acceleration
    ``h1``, ``h2`` [s^2] and the two-sided ground PSD [m^2/s^3], at the same
    frequencies (Eq. 25's integrand)."""
    return 2.0 * np.abs(h1 - h2) ** 2 * ground_psd
