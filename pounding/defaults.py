"""The defaults of the library, the command line, the report and the
dashboard, each written once (they all read them from here); and the
resource limits every input is checked against before anything is allocated."""

from __future__ import annotations

import os

__all__ = [
    "ACCURACY_SEED",
    "CASE",
    "CHECK_FIRST_RECORDS",
    "CHECK_MAX_RECORDS",
    "CHECK_PRECISION",
    "CHECK_TOLERANCE",
    "CHECK_UNPOUNDED_RECORDS",
    "PAPER_VARIANCE",
    "PERIOD_RANGE",
    "SEED",
    "LIMITS_VARIABLE",
    "MAX_CASE_FILE_BYTES",
    "MAX_RECORD_FILE_BYTES",
    "MAX_GAPS",
    "MAX_CHUNK_SAMPLES",
    "MAX_HISTORY_VALUES",
    "MAX_RECORDS",
    "MAX_SAMPLES_PER_RECORD",
    "MAX_STOREYS",
    "MAX_BUILDINGS",
    "MAX_ROW_STOREYS",
    "MAX_SWEEP_POINTS",
    "MAX_TIME_HISTORIES",
    "MAX_SYNTHESIS_SAMPLES",
    "DASHBOARD_MAX_STOREYS",
    "DASHBOARD_RECORDS",
    "DESIGN_SYNTHESIS_FACTOR",
    "FORCE_QUANTILES",
    "FRAGILITY_MIN_RECORDS",
    "SPECTRUM_MIN_RECORDS",
    "DESIGN_GAP_RECORDS",
    "INTEGRATOR_TOLERANCE",
    "DISPLACEMENT_LIMIT",
    "MICHAELOV_N1",
    "MICHAELOV_N1_RANGE",
    "RECORDS",
    "SWEEP_RECORDS",
    "CHUNK_RECORDS",
    "TARGET_PROBABILITY",
    "VALIDATION_RECORDS",
    "VALIDATION_SEED",
    "limits_enabled",
]

CASE = "section5-T2-0.4"
"""The built-in case the dashboard opens on: the paper's Section 5, T2 = 0.4 s."""
SEED = 1
"""Seed of every Monte Carlo study unless one is given: the command line's (``simulate``, ``estimate --check``,
``sweep``, ``fragility``, ``spectrum``, ``records``, ``export``, ``report``), the library's (``simulate``,
``design_gap``, ``check_estimate``), the report's and the dashboard's; the same case gives the same records everywhere."""
PAPER_VARIANCE = "eq28"
"""How the paper's method takes sigma_V(t) under an envelope: Eq. 28, as published (or "exact")."""
PERIOD_RANGE = (1e-3, 1e3)
"""Fundamental periods [s] a building may be moved to (a force spectrum): from stiffer than any storey to softer than
any record is long; outside, the stiffness scales by more than 1e12 and the closed form loses its precision."""
TARGET_PROBABILITY = 0.95
"""Target probability of *no* pounding during the record for the gap needed [-]."""
MICHAELOV_N1 = 3.0
"""Order n1 of Michaelov's moments (Eq. 29); the paper finds 3 or 4 usually within 10 % [-]."""
MICHAELOV_N1_RANGE = (0.5, 20.0)
"""Allowed n1: below 0.5 the moments weigh the long quiet tail of the record, above 20 only its peak instant."""
INTEGRATOR_TOLERANCE = 1e-6
"""Relative tolerance of the time-history integrator's local error per step [-]."""
DISPLACEMENT_LIMIT = 10.0
"""A floor displacement beyond this [m] is a runaway response: a time history stops on it (``Settings``), and the
closed form refuses where 3 sigma passes it."""
DESIGN_SYNTHESIS_FACTOR = 4
"""synthesis_factor of the records of a design-spectrum case: at 1 a 20 s record carries the PSD on lines 0.31 rad/s
apart, as wide as a 5 % oscillator's band at 2 s, and the records' mean spectrum ripples by 5 % (docs/hazard.md)."""
FORCE_QUANTILES = ("0.5", "0.84", "0.95")
"""The fractiles of F_max that ``estimate --json`` and ``simulate --json`` give (``force_max_quantiles``)."""
FRAGILITY_MIN_RECORDS = 10
"""Fewest Monte Carlo records a point of a fragility curve takes: at 10, Wilson's 95 % interval of a fraction of 1/2
spans 0.24 to 0.76; fewer tell little."""
SPECTRUM_MIN_RECORDS = 22
"""Fewest Monte Carlo records a point of a force spectrum takes: the fewest for which the order statistics give both
ends of a 95 % interval of the 84th percentile (1 - 0.84^n >= 0.975)."""
RECORDS = 100
"""Records of a Monte Carlo study (``pounding simulate``, ``simulate``)."""
DASHBOARD_RECORDS = 50
"""Records of the dashboard's reduced-sample Monte Carlo and its Monte Carlo design gap."""
DASHBOARD_MAX_STOREYS = 10
"""Storeys per building the dashboard offers, half the library's :data:`MAX_STOREYS`: the dashboard recomputes the
closed form on every change of input, and a 10 + 10-storey case already takes 1.6 s of it (20 + 20: 14 s)."""
DESIGN_GAP_RECORDS = 400
"""Records of a Monte Carlo design gap (``design_gap``); 45 or more give the 90 % bound for 95 %."""
SWEEP_RECORDS = 100
"""Records per point of a parametric study (``pounding sweep``)."""
CHUNK_RECORDS = 100
"""Records per task of a study on Dask (a sweep, a fragility curve, a force spectrum): about 0.4 s of work for 20 s
records of two SDOF buildings, against a few milliseconds of overhead per task (``benchmarks/sweep.py``)."""
VALIDATION_RECORDS = 300
"""Records per case of ``pounding validate`` and of the accuracy grid."""
VALIDATION_SEED = 1
"""Seed of ``pounding validate``'s studies."""
CHECK_FIRST_RECORDS = 50
"""Records of the first chunk of a Monte Carlo check of an estimate (``check_estimate``, ``pounding estimate --check``)
when it names no count: later chunks are sized from the interval the records so far give."""
CHECK_PRECISION = 0.05
"""A Monte Carlo check without a count stops once the 95 % interval of the mean F_max is within this share of the
mean either side (+-5 %) [-]."""
CHECK_MAX_RECORDS = 400
"""A Monte Carlo check without a count stops at this many records, its precision reached or not (about 0.8 s of one
core for the Section 5 case)."""
CHECK_UNPOUNDED_RECORDS = 100
"""A Monte Carlo check without a count stops here if no record has pounded: 0 of 100 bounds the probability of
pounding below 3.0 % (95 % confidence, 1 - 0.05^(1/100))."""
CHECK_TOLERANCE = 0.10
"""The closed form agrees with a Monte Carlo check when it lies in the 95 % interval of the mean F_max or within this
share of the mean [-]."""

# --- resource limits ---------------------------------------------------------
# Chosen for a machine of 2 cores and 24 GB: each lets a case at the limit run
# in minutes and well inside the memory; one key beyond it is refused (CaseError
# naming the key, in well under a second) before anything is allocated.
# Costs measured on such a machine (docs/user-guide.md, "Limits").

LIMITS_VARIABLE = "POUNDING_LIMITS"
"""Environment variable: ``POUNDING_LIMITS=off`` lifts every limit below, knowingly, on a bigger machine."""
MAX_SAMPLES_PER_RECORD = 2**21
"""Samples per record, duration / time_step + 1: 2,097,152 (10,485 s at 0.005 s); a record of the Section 5 pair at the limit integrates in 1.4 s, its full history (simulate_record) in 1.8 s and 0.5 GB."""
MAX_SYNTHESIS_SAMPLES = 2**24
"""Length of a record's synthesis FFT (synthesis_factor times the power of two >= the samples): 16,777,216; one record at the limit is drawn in 3 s with 0.6 GB."""
MAX_RECORDS = 1_000_000
"""Records of one Monte Carlo study: the Section 5 case at the limit runs about 25 min on 2 cores (1.5 ms a record) and holds 0.3 GB of results."""
MAX_TIME_HISTORIES = 10_000_000
"""Time histories one study may ask for, points times records (a sweep, fragility curve or force spectrum): at about
2 ms each, a day on one core. Each factor has its own limit; their product 1e10 would run for months."""
MAX_STOREYS = 20
"""Storeys per building: the closed form of a 20 + 20-storey case takes 14 s and 1.8 GB (10 + 10: 1.6 s, 0.3 GB; it grows steeply: 50 + 50 takes minutes)."""
MAX_BUILDINGS = 8
"""Buildings in a row: a city block's frontage; the time histories' state grows with every floor of the row."""
MAX_ROW_STOREYS = 60
"""Storeys of all the buildings of a row together: three 20-storey buildings (the time histories integrate every
floor in one state, 3 x 60 values; the closed form takes each contact's two buildings, each within :data:`MAX_STOREYS`)."""
MAX_SWEEP_POINTS = 10_000
"""Points of a parametric study (the product of the --vary counts): 10,000 are checked and loaded in 2 s, 0.15 GB; their estimates take 2 min on one core, plus their records."""
MAX_CASE_FILE_BYTES = 1_000_000
"""Size of a case file [bytes] (a preset is 1 kB, a 20 + 20-storey case 6 kB)."""
MAX_RECORD_FILE_BYTES = 200_000_000
"""Size of a recorded motion's file [bytes] (a 100 s NGA record at 0.005 s is about 0.3 MB)."""
MAX_CHUNK_SAMPLES = 2**24
"""Ground-acceleration samples one thread holds at once, Settings.chunk_size x samples per record: 16,777,216 (0.13 GB; 8 records at the sample limit)."""
MAX_HISTORY_VALUES = 2**27
"""Values of a full time history kept by integrate and simulate_record, steps x (3 x floors + 2): 134,217,728 (1 GiB)."""


def limits_enabled() -> bool:
    """Whether the resource limits above apply: unless ``POUNDING_LIMITS=off`` (read at each check)."""
    return os.environ.get(LIMITS_VARIABLE, "").strip().lower() != "off"
ACCURACY_SEED = 11
"""Seed of the Monte Carlo studies of the accuracy grid (``pounding validate --grid``) and of the accuracy data."""
MAX_GAPS = 100_000
"""Gaps of one force-versus-gap curve (``Estimate.gap_curve``, ``force_versus_gap``): 100 gaps take about 4 ms, so
the limit about 4 s."""

FLOOR_MASS_RANGE = (1.0, 1.0e10)
"""[kg] The floor masses a case may give: from a floor of a model on a shake table to ten million tonnes, far
beyond any building's floor. A mass outside (often a stiffness or period mistyped by powers of ten) is refused
rather than answered with forces of 1e121 floor weights."""
CONTACT_STIFFNESS_RANGE = (1.0e3, 1.0e16)
"""[N/m or N/m^1.5, SI] The contact stiffnesses a case may give: rubber bumpers on a laboratory model (about 1e5)
to stiffer than any concrete contact measured (Jankowski 2005: 2.75e9 N/m^1.5); softer or stiffer is a typing
mistake, answered before with penetrations of 1e120 sigma."""
