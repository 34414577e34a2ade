"""Studies made of many estimates and simulations: an estimate checked against the Monte Carlo of its case,
fragility curves, the force spectrum, parametric sweeps on Dask, and the paper's tables against this project's two
methods.

Modules: :mod:`.check` (``check_estimate``: the verdict of ``pounding estimate``'s check), :mod:`.fragility`,
:mod:`.force_spectrum`, :mod:`.monte_carlo_study` (their Monte Carlo side), :mod:`.sweeps` (resumable parametric
studies), :mod:`.paper_tables` (``pounding validate``).
"""
