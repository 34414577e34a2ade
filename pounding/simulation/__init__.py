"""The "exact" method: nonlinear time histories of the two buildings over many seeded records (Monte Carlo).

Modules: :mod:`.monte_carlo` (``simulate``, ``design_gap``, ``integrate``, ``simulate_record``),
:mod:`.system` (``Settings`` and the case packed for the compiled kernel), :mod:`.ground_motion` (the records a
study integrates), :mod:`.result` (the per-record peaks and their summary).
"""
