"""The separation rules beside the design gap (docs/theory.md, G23-G25): SRSS,
ABS and DDC combinations of each contact floor's expected peak ``|x|``, the
linearized floor's sigmas from rest with Vanmarcke's clumps. The floors'
sigmas are the linearized ones, without the residual's response: chosen by
looking at Monte Carlo results, where with it the peaks went higher still
above the simulated ones (docs/theory.md)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pounding.random_vibration.peaks import expected_absolute_peak

__all__ = ["CodeCheck", "code_checks", "separation_rules"]


def separation_rules(pair) -> dict:
    """SRSS, ABS and DDC gaps [m] of a :class:`~pounding.closed_form.pair.LinearizedPair`
    from the expected peak ``|displacement|`` of each contact floor
    (``peak_displacement`` [m], :func:`~pounding.random_vibration.peaks.expected_absolute_peak`
    on the covariance history from rest) and their stationary correlation
    (``displacement_correlation`` [-], used by DDC)."""
    weights, history = pair.history_from_rest
    # history's outputs are x1, x2, v1, v2, ...; at rest a variance may round to just below 0.
    sigmas = np.sqrt(np.maximum(np.diagonal(history, axis1=1, axis2=2), 0.0))
    u1, u2 = (expected_absolute_peak(sigmas[:, floor], sigmas[:, 2 + floor], weights, q)
              for floor, q in enumerate(pair.floor_bandwidths))
    correlation = pair.stationary_response.correlation_displacement
    return {
        "srss": float(math.hypot(u1, u2)),
        "abs": float(u1 + u2),
        "ddc": float(math.sqrt(max(u1**2 + u2**2 - 2.0 * correlation * u1 * u2, 0.0))),
        "peak_displacement": [float(u1), float(u2)],
        "displacement_correlation": float(correlation),
    }


@dataclass(frozen=True)
class CodeCheck:
    """A design code's separation rule applied to the gap entered, in the code's words.

    Attributes
    ----------
    code, clause : str
        The code and its clause ("EN 1998-1", "4.4.2.7(3)").
    required_gap : float
        The separation the rule asks for [m].
    met : bool
        Whether the gap entered is at least ``required_gap``.
    rule : str
        What the rule combines, in words.
    assumption : str
        What this tool puts in place of the code's own displacements.
    """

    code: str
    clause: str
    required_gap: float
    met: bool
    rule: str
    assumption: str
    short_rule: str = ""
    """The rule in a few words, for a line of text."""

    @property
    def title(self) -> str:
        """The code and its clause as a line names them ("EN 1998-1 4.4.2.7(3)", "DDC rule")."""
        return self.code if self.code == "DDC rule" else f"{self.code} {self.clause.split(' (')[0]}"

    def to_dict(self) -> dict:
        """JSON-ready, SI units (``required_gap`` in m)."""
        return {"code": self.code, "clause": self.clause, "required_gap": self.required_gap, "met": self.met,
                "rule": self.rule, "assumption": self.assumption}


_PEAKS = ("the peak displacements are the closed form's expected peaks of each contact floor (its linearized "
          "inelastic response to the case's motion, from rest)")


def code_checks(rules: dict, gap: float) -> tuple[CodeCheck, ...]:
    """The separation rules of EN 1998-1 4.4.2.7(3), ASCE 7-16 12.12.3 (Eq. 12.12-2) and the DDC rule against the
    ``gap`` entered [m], from :func:`separation_rules`' peaks (``rules``). The codes' displacements are design
    values (EN 1998-1 4.3.4: d_s = q_d d_e; ASCE 7-16 Eq. 12.12-1: delta_M = C_d delta_max / I_e); here the
    expected peaks of the inelastic response take their place, which is what those formulas approximate."""
    srss, ddc = rules["srss"], rules["ddc"]
    return (
        CodeCheck("EN 1998-1", "4.4.2.7(3)", srss, gap >= srss,
                  "square root of the sum of the squares (SRSS) of the two buildings' peak displacements at the "
                  "level of contact", _PEAKS + " in place of d_s = q_d d_e (4.3.4); 4.4.2.7(4)'s factor 0.7 for "
                  "floors at equal heights is not applied", "SRSS of the peak displacements"),
        CodeCheck("ASCE 7-16", "12.12.3 (Eq. 12.12-2)", srss, gap >= srss,
                  "delta_MT = sqrt(delta_M1^2 + delta_M2^2), the buildings' maximum inelastic displacements",
                  _PEAKS + " in place of delta_M = C_d delta_max / I_e (Eq. 12.12-1)", "delta_MT, the SRSS of delta_M"),
        CodeCheck("DDC rule", "Jeng et al. (1992), Penzien (1997)", ddc, gap >= ddc,
                  "double difference combination: sqrt(u1^2 + u2^2 - 2 rho u1 u2), rho the floors' correlation",
                  _PEAKS + f"; rho = {rules['displacement_correlation']:.2f} from the linearized pair",
                  "double difference combination"),
    )
