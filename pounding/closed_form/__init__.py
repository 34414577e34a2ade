"""The closed form: the expected extreme pounding force without a time history, by statistical linearization and
random vibration. Imports nothing from :mod:`pounding.simulation`.

Modules, in the order an estimate runs them: :mod:`.linearization` (the equivalent linear buildings, Eq. 19-21),
:mod:`.response` and :mod:`.covariance_history` (the relative response at the contact floors),
:mod:`.pair` (``LinearizedPair``: what both estimators take from the linearized buildings, computed once),
:mod:`.impact_damping` (what the impacts take out of the relative motion), :mod:`.paper_method` (Rahimi &
Soltani's method, Eq. 12-30), :mod:`.gap_aware` (the gap-aware estimator, G1-G22), :mod:`.force_distribution`
(the distribution of F_max, G31), :mod:`.separation` (the separation rules), :mod:`.regimes` (the regime and
its measured accuracy), :mod:`.estimator` (``estimate`` and ``force_versus_gap``: both side by side).
"""
