"""The defaults of the library, the command line, the report and the
dashboard, each written once (they all read them from here)."""

from __future__ import annotations

__all__ = [
    "CASE",
    "DASHBOARD_RECORDS",
    "DESIGN_GAP_RECORDS",
    "INTEGRATOR_TOLERANCE",
    "MICHAELOV_N1",
    "MICHAELOV_N1_RANGE",
    "RECORDS",
    "REPORT_SEED",
    "SWEEP_RECORDS",
    "TARGET_PROBABILITY",
    "VALIDATION_RECORDS",
    "VALIDATION_SEED",
]

CASE = "section5-T2-0.4"
"""The built-in case the dashboard opens on: the paper's Section 5, T2 = 0.4 s."""
TARGET_PROBABILITY = 0.95
"""Target probability of *no* pounding during the record for the gap needed [-]."""
MICHAELOV_N1 = 3.0
"""Order n1 of Michaelov's moments (Eq. 29); the paper finds 3 or 4 usually within 10 % [-]."""
MICHAELOV_N1_RANGE = (0.5, 20.0)
"""Allowed n1: below 0.5 the moments weigh the long quiet tail of the record, above 20 only its peak instant."""
INTEGRATOR_TOLERANCE = 1e-6
"""Relative tolerance of the time-history integrator's local error per step [-]."""
RECORDS = 100
"""Records of a Monte Carlo study (``pounding simulate``, ``simulate``)."""
DASHBOARD_RECORDS = 50
"""Records of the dashboard's reduced-sample Monte Carlo and its Monte Carlo design gap."""
DESIGN_GAP_RECORDS = 400
"""Records of a Monte Carlo design gap (``design_gap``); 45 or more give the 90 % bound for 95 %."""
SWEEP_RECORDS = 100
"""Records per point of a parametric study (``pounding sweep``)."""
VALIDATION_RECORDS = 300
"""Records per case of ``pounding validate`` and of the accuracy grid."""
VALIDATION_SEED = 1
"""Seed of ``pounding validate``'s studies."""
REPORT_SEED = 1
"""Seed of the report's and the dashboard's Monte Carlo studies."""
