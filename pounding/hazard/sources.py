"""Where a case's ground motion comes from, when it is not a random process
given by its parameters: a code design spectrum, or a suite of recorded
accelerograms.

A case always holds an :class:`~pounding.hazard.excitation.Excitation`, the random
process the closed form takes. For a design spectrum it is the spectrum-
compatible filter bank, and the Monte Carlo records are drawn from it too;
for recorded motions it is the filter bank and envelope fitted to the suite
(S1-S5, :mod:`pounding.hazard.suite_spectrum`), and the Monte Carlo integrates
the records themselves (:class:`RecordedMotions`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from pounding.errors import CaseError, described

if TYPE_CHECKING:  # loaded with the case forms that need them
    from pounding.hazard.accelerograms import Accelerogram
    from pounding.hazard.compatible_psd import CompatibleSpectrum
    from pounding.hazard.excitation import Excitation
    from pounding.hazard.fit_quality import FitQuality, SpectrumComparison
    from pounding.hazard.motion_fit import FittedExcitation
    from pounding.hazard.suite_spectrum import SuiteSpectrum

__all__ = ["DesignSpectrum", "RecordedMotions"]


@dataclass(frozen=True, eq=False)
class DesignSpectrum:
    """A code's 5 %-damped design spectrum and the compatible PSD drawn from it.

    Attributes
    ----------
    code : str
        ``"ec8"``, ``"asce7-16"`` or ``"table"``, as the case file writes it.
    target : object
        The design spectrum (:mod:`pounding.hazard.design_spectra`): ``pseudo_acceleration(periods)`` [m/s^2].
    compatible : CompatibleSpectrum
        The filter bank whose records reproduce it (:mod:`pounding.hazard.compatible_psd`).
    """

    code: str
    target: object
    compatible: CompatibleSpectrum

    def to_dict(self) -> dict:
        """JSON-ready: the code, the control periods, the target and the random-vibration spectrum there (SI)."""
        return {
            "code": self.code,
            "description": self.target.describe(),
            "periods": np.asarray(self.compatible.periods).tolist(),
            "target": np.asarray(self.compatible.target).tolist(),
            "expected": np.asarray(self.compatible.expected).tolist(),
            "units": {"periods": "s", "target": "m/s^2", "expected": "m/s^2"},
        }


@dataclass(frozen=True, eq=False)
class RecordedMotions:
    """A suite of recorded accelerograms, scaled as the case asks, and the spectra fitted to it.

    Attributes
    ----------
    records : tuple of Accelerogram
        In the sorted order of the expanded file names; the Monte Carlo integrates each once.
    fitted : FittedExcitation
        The Kanai-Tajimi or Clough-Penzien spectrum fitted to the suite (R1-R6): a description in an
        engineer's terms.
    scaling : str
        How the records were scaled, in words (``"as recorded"``, ``"x 1.3"``, ``"each to a PGA of 0.3 g"``,
        or to a design spectrum).
    suite : SuiteSpectrum or None
        The filter bank and envelope the closed form takes (S1-S5); None: the case takes ``fitted``.
    source : str
        Where the records came from, in words (a FEMA P695 set and its events; files).
    spectrum_scaling : SpectrumScaling or None
        How the suite was scaled to a design spectrum (:mod:`pounding.hazard.record_scaling`), if it was.
    """

    records: tuple[Accelerogram, ...]
    fitted: FittedExcitation
    scaling: str = "as recorded"
    suite: SuiteSpectrum | None = None
    source: str = ""
    spectrum_scaling: object = None

    def __post_init__(self):
        from pounding.hazard.accelerograms import Accelerogram

        records = tuple(self.records)
        if not records or not all(isinstance(r, Accelerogram) for r in records):
            raise CaseError("excitation.records", f"must be a non-empty sequence of Accelerogram, got {described(self.records)}")
        object.__setattr__(self, "records", records)

    @classmethod
    def fit(cls, records, cutoff_frequency: float, scaling: str = "as recorded", source: str = "",
            spectrum_scaling=None) -> RecordedMotions:
        """``records`` with both fits below ``cutoff_frequency`` [rad/s]: R1-R6 and S1-S5; ``source`` and
        ``spectrum_scaling`` as the attributes."""
        from pounding.hazard.motion_fit import fit_excitation
        from pounding.hazard.suite_spectrum import fit_suite_spectrum

        records = tuple(records)
        return cls(records, fit_excitation(records, cutoff_frequency), scaling, fit_suite_spectrum(records, cutoff_frequency),
                   source, spectrum_scaling)

    def excitation(self) -> Excitation:
        """The process the closed form takes: the suite's bank and envelope (S1-S5), or the fitted spectrum over
        the mean significant duration when there is no bank."""
        from pounding.hazard.excitation import Excitation

        if self.suite is not None:
            return self.suite.excitation()
        return Excitation(self.fitted.spectrum, self.fitted.duration, None, time_step=max(r.time_step for r in self.records))

    def scaled(self, factor: float, scaling: str) -> RecordedMotions:
        """Every record times ``factor`` [-]; the fits scaled with them (the PSDs by its square), not refitted."""
        import dataclasses

        spectrum = self.fitted.spectrum
        fitted = dataclasses.replace(self.fitted, spectrum=dataclasses.replace(spectrum, G0=spectrum.G0 * factor**2),
                                     periodogram=self.fitted.periodogram * factor**2)
        suite = None if self.suite is None else self.suite.scaled(factor)
        out = RecordedMotions(tuple(record.scaled(factor) for record in self.records), fitted, scaling, suite, self.source)
        if "comparison" in self.__dict__:  # computed once: the ratios do not change with the scale
            out.__dict__["comparison"] = self.comparison.scaled(factor)
        return out

    @cached_property
    def comparison(self) -> SpectrumComparison:
        """S6-S7: the records' mean Sa and PGA against the closed form's process (computed once)."""
        from pounding.hazard.fit_quality import compare_spectra

        return compare_spectra(self.records, self.excitation())

    def fit_quality(self, building_periods) -> FitQuality:
        """S8 at the buildings' fundamental periods [s]."""
        return self.comparison.at(building_periods)

    @property
    def names(self) -> list[str]:
        return [record.name for record in self.records]

    @property
    def metadata(self) -> list[dict]:
        """Each record's metadata (event, year, station...; empty for a file)."""
        return [dict(record.metadata) for record in self.records]

    def to_dict(self) -> dict:
        """JSON-ready: the records, their source, metadata and scaling, and the fitted spectra (SI)."""
        out = {"records": self.names, "source": self.source, "metadata": self.metadata, "scaling": self.scaling,
               "fitted_excitation": self.fitted.to_dict()}
        if self.suite is not None:
            out["suite_spectrum"] = self.suite.to_dict()
        if self.spectrum_scaling is not None:
            out["spectrum_scaling"] = self.spectrum_scaling.to_dict()
        return out
