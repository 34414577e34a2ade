"""Elastic 5 %-damped pseudo-acceleration design spectra, SI (m/s^2, s).

D1-D4, EN 1998-1 (Eurocode 8) Section 3.2.2.2, Eq. 3.2-3.5 with eta = 1 (5 % damping):

    D1  0 <= T <= TB:   Se = ag S (1 + T / TB (2.5 - 1))
    D2  TB <= T <= TC:  Se = 2.5 ag S
    D3  TC <= T <= TD:  Se = 2.5 ag S TC / T
    D4  TD <= T:        Se = 2.5 ag S TC TD / T^2

with S, TB, TC, TD of Table 3.2 (type 1) or Table 3.3 (type 2). EN 1998-1 gives
D4 up to 4 s; beyond, this module carries D4 on (the code leaves longer periods
to its Annex A).

D5-D8, ASCE 7-16 Section 11.4.6, T0 = 0.2 SD1 / SDS, TS = SD1 / SDS:

    D5  T < T0:         Sa = SDS (0.4 + 0.6 T / T0)
    D6  T0 <= T <= TS:  Sa = SDS
    D7  TS < T <= TL:   Sa = SD1 / T
    D8  TL < T:         Sa = SD1 TL / T^2

D9, a tabulated spectrum (periods T_j, accelerations S_j): linear in log-log
between points, ln Sa = ln S_j + (ln T - ln T_j) (ln S_(j+1) - ln S_j) /
(ln T_(j+1) - ln T_j); flat (S_1) below the first period; S_n (T_n / T)^2
beyond the last (constant spectral displacement, as D4 and D8).

The peak ground acceleration is each spectrum's value as T -> 0: ag S (D1),
0.4 SDS (D5), S_1 (D9).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pounding.errors import ArgumentError, CaseError, described, finite_number, finite_numbers, quote

__all__ = [
    "ASCE7Spectrum",
    "EUROCODE8_TYPE1",
    "EUROCODE8_TYPE2",
    "Eurocode8Spectrum",
    "TabulatedSpectrum",
]

EUROCODE8_TYPE1 = {  # ground type: (S, TB, TC, TD) [-, s, s, s], EN 1998-1 Table 3.2
    "A": (1.0, 0.15, 0.4, 2.0),
    "B": (1.2, 0.15, 0.5, 2.0),
    "C": (1.15, 0.20, 0.6, 2.0),
    "D": (1.35, 0.20, 0.8, 2.0),
    "E": (1.4, 0.15, 0.5, 2.0),
}
EUROCODE8_TYPE2 = {  # EN 1998-1 Table 3.3
    "A": (1.0, 0.05, 0.25, 1.2),
    "B": (1.35, 0.05, 0.25, 1.2),
    "C": (1.5, 0.10, 0.25, 1.2),
    "D": (1.8, 0.10, 0.30, 1.2),
    "E": (1.6, 0.05, 0.25, 1.2),
}


def _positive(instance, field: str) -> float:
    value = finite_number(field, getattr(instance, field))
    if not value > 0:
        raise CaseError(field, f"must be a finite number > 0, got {quote(value)}")
    object.__setattr__(instance, field, value)
    return value


def _periods(periods) -> np.ndarray:
    try:
        values = np.asarray(periods, dtype=float)
    except (TypeError, ValueError):
        raise ArgumentError("periods", f"must be numbers, got {quote(periods)}") from None
    if not (np.all(np.isfinite(values)) and np.all(values >= 0)):
        raise ArgumentError("periods", "must be finite numbers >= 0 s")
    return values


@dataclass(frozen=True)
class Eurocode8Spectrum:
    """EN 1998-1 horizontal elastic response spectrum, 5 % damping (D1-D4).

    Parameters
    ----------
    ag : float
        Design ground acceleration on type A ground [m/s^2], > 0.
    ground_type : str
        "A" to "E".
    spectrum_type : int
        1 (Table 3.2) or 2 (Table 3.3).
    """

    ag: float
    ground_type: str
    spectrum_type: int = 1

    def __post_init__(self):
        _positive(self, "ag")
        if not (isinstance(self.ground_type, str) and self.ground_type.upper() in EUROCODE8_TYPE1):
            raise CaseError("ground_type", f"must be one of A, B, C, D, E, got {described(self.ground_type)}")
        object.__setattr__(self, "ground_type", self.ground_type.upper())
        if self.spectrum_type not in (1, 2) or isinstance(self.spectrum_type, bool):
            raise CaseError("spectrum_type", f"must be 1 or 2, got {quote(self.spectrum_type)}")
        object.__setattr__(self, "spectrum_type", int(self.spectrum_type))

    @property
    def parameters(self) -> tuple[float, float, float, float]:
        """(S, TB, TC, TD) of Table 3.2 or 3.3 [-, s, s, s]."""
        table = EUROCODE8_TYPE1 if self.spectrum_type == 1 else EUROCODE8_TYPE2
        return table[self.ground_type]

    @property
    def peak_ground_acceleration(self) -> float:
        """ag S [m/s^2] (D1 at T = 0)."""
        return self.ag * self.parameters[0]

    def pseudo_acceleration(self, periods) -> np.ndarray:
        """Se(T) [m/s^2], D1-D4."""
        t = _periods(periods)
        s, tb, tc, td = self.parameters
        plateau = 2.5 * self.ag * s
        safe = np.maximum(t, 1e-12)  # only the branches beyond a corner use it
        return np.where(t <= tb, self.ag * s * (1.0 + t / tb * 1.5),
                        np.where(t <= tc, plateau, np.where(t <= td, plateau * tc / safe, plateau * tc * td / safe**2)))

    def describe(self) -> str:
        s, tb, tc, td = self.parameters
        return (f"EN 1998-1 type {self.spectrum_type}, ground {self.ground_type}: ag = {self.ag:.3g} m/s^2, "
                f"S = {s:g}, TB = {tb:g} s, TC = {tc:g} s, TD = {td:g} s, 5 % damping")


@dataclass(frozen=True)
class ASCE7Spectrum:
    """ASCE 7-16 design response spectrum, Section 11.4.6 (D5-D8).

    Parameters
    ----------
    SDS, SD1 : float
        Design spectral accelerations at short periods and at 1 s [m/s^2], > 0.
    TL : float
        Long-period transition period [s], >= TS = SD1 / SDS.
    """

    SDS: float
    SD1: float
    TL: float = 8.0

    def __post_init__(self):
        _positive(self, "SDS")
        _positive(self, "SD1")
        _positive(self, "TL")
        if self.TL < self.SD1 / self.SDS:
            raise CaseError("TL", f"must be >= TS = SD1/SDS = {self.SD1 / self.SDS:.4g} s, got {quote(self.TL)}")

    @property
    def T0(self) -> float:
        return 0.2 * self.SD1 / self.SDS

    @property
    def TS(self) -> float:
        return self.SD1 / self.SDS

    @property
    def peak_ground_acceleration(self) -> float:
        """0.4 SDS [m/s^2] (D5 at T = 0)."""
        return 0.4 * self.SDS

    def pseudo_acceleration(self, periods) -> np.ndarray:
        """Sa(T) [m/s^2], D5-D8."""
        t = _periods(periods)
        safe = np.maximum(t, 1e-12)  # only the branches beyond a corner use it
        return np.where(t < self.T0, self.SDS * (0.4 + 0.6 * t / self.T0),
                        np.where(t <= self.TS, self.SDS,
                                 np.where(t <= self.TL, self.SD1 / safe, self.SD1 * self.TL / safe**2)))

    def describe(self) -> str:
        return (f"ASCE 7-16: SDS = {self.SDS:.3g} m/s^2, SD1 = {self.SD1:.3g} m/s^2, TL = {self.TL:g} s "
                f"(T0 = {self.T0:.3g} s, TS = {self.TS:.3g} s), 5 % damping")


@dataclass(frozen=True)
class TabulatedSpectrum:
    """A 5 %-damped pseudo-acceleration spectrum given by points (D9).

    Parameters
    ----------
    periods : tuple of float
        [s], > 0, strictly increasing, at least 2.
    accelerations : tuple of float
        Sa at those periods [m/s^2], > 0.
    """

    periods: tuple[float, ...]
    accelerations: tuple[float, ...]

    def __post_init__(self):
        periods = finite_numbers("periods", self.periods)
        accelerations = finite_numbers("accelerations", self.accelerations)
        if len(periods) < 2:
            raise CaseError("periods", f"must hold at least 2 periods, got {len(periods)}")
        if not all(p > 0 for p in periods) or not all(b > a for a, b in zip(periods, periods[1:])):
            raise CaseError("periods", "must be > 0 s and strictly increasing")
        if len(accelerations) != len(periods):
            raise CaseError("accelerations", f"must have one value per period ({len(periods)}), got {len(accelerations)}")
        if not all(a > 0 for a in accelerations):
            raise CaseError("accelerations", "must be > 0 m/s^2")
        object.__setattr__(self, "periods", periods)
        object.__setattr__(self, "accelerations", accelerations)

    @property
    def peak_ground_acceleration(self) -> float:
        """The first acceleration [m/s^2]: D9 is flat below the first period."""
        return self.accelerations[0]

    def pseudo_acceleration(self, periods) -> np.ndarray:
        """Sa(T) [m/s^2], D9."""
        t = _periods(periods)
        log_t, log_a = np.log(self.periods), np.log(self.accelerations)
        inside = np.exp(np.interp(np.log(np.clip(t, self.periods[0], self.periods[-1])), log_t, log_a))
        beyond = self.accelerations[-1] * (self.periods[-1] / np.maximum(t, self.periods[-1])) ** 2
        return np.where(t > self.periods[-1], beyond, inside)

    def describe(self) -> str:
        return (f"tabulated: {len(self.periods)} points from {self.periods[0]:g} s to {self.periods[-1]:g} s, "
                f"Sa {min(self.accelerations):.3g} to {max(self.accelerations):.3g} m/s^2, 5 % damping")
