"""Research scripts: how the estimator's accuracy was measured; run with
`python3 -m validation.<name>` from the repository root.

They import only the public API of :mod:`pounding`; each has a ``main``
taking its sizes (cases, records, seeds), which ``tests/test_validation_scripts.py``
runs small. validation/HISTORY.md records what they measured.
"""
