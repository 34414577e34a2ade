"""A row of alike buildings (issue 35): the end buildings' response amplified by pounding and the interior ones'
reduced (Anagnostopoulos 1988), on a small version of validation/row_amplification.py: five SDOF buildings
(5e5 kg, periods 0.5 s x exp(+-0.4) drawn per record), mildly yielding (yield drift 2 cm, about half their peak),
touching (gap 0), 40 Kanai-Tajimi records of PGA 0.3 g. docs/rows.md has the full run's numbers."""

import numpy as np
import pytest

from validation.row_amplification import (
    PERIOD,
    SEED,
    YIELD_DRIFT,
    building_ratios,
    draw_rows,
    pooled_ratios,
    ratio_interval,
    run_rows,
)


def test_identical_buildings_move_as_one_and_never_pound():
    """Under one ground motion a row of identical buildings has no relative motion: the amplification the
    script measures needs buildings that differ (here, in period)."""
    run = run_rows(3, 4, YIELD_DRIFT, gap=0.0, rows=np.full((4, 3), PERIOD))
    assert np.all(run.impacts == 0) and np.all(run.force == 0)
    np.testing.assert_array_equal(run.peak(True), run.peak(False))


def test_the_ratio_interval_is_the_delta_methods():
    a, b = np.array([2.0, 4.0, 6.0]), np.array([1.0, 2.0, 3.0])
    assert ratio_interval(a, b) == (2.0, 2.0, 2.0)  # exact proportion: no spread
    ratio, low, high = ratio_interval(np.array([1.0, 3.0, 2.0, 2.5]), np.array([1.0, 2.0, 2.0, 2.0]))
    assert ratio == pytest.approx(8.5 / 7.0) and low < ratio < high


def test_the_end_buildings_are_amplified_and_the_interior_ones_reduced():
    records = 40
    run = run_rows(5, records, YIELD_DRIFT, seed=SEED, gap=0.0, rows=draw_rows(5, records, spread=0.4))
    assert np.all(run.impacts.sum(axis=0) > 0)  # every contact pounds
    pooled = pooled_ratios(run)
    assert pooled["end |x|"][1] > 1.0, pooled["end |x|"]  # the 95 % interval above 1
    assert pooled["interior |x|"][2] < 1.0, pooled["interior |x|"]  # ... below 1
    assert pooled["end outward"][1] > 1.0 and pooled["end inward"][2] < 1.0  # pushed away from the row
    free, contacts = pooled["end residual outward"]
    assert contacts > free + 0.002  # and left there: yielding drift away from the row
    ratios = [r[0] for r in building_ratios(run)]
    assert min(ratios[0], ratios[-1]) > 1.0 > ratios[2]  # each end amplified, the middle building reduced
    assert min(ratios[0], ratios[-1]) > max(ratios[1:-1])


def test_the_docs_row_example_loads():
    """docs/rows.md's case file, as written: three buildings, the aligned floors expanded into two contacts."""
    import re
    import tomllib
    from pathlib import Path

    from pounding.case.case import case_from_dict

    page = (Path(__file__).resolve().parent.parent / "docs" / "rows.md").read_text()
    (block,) = re.findall(r"```toml\n(.*?)```", page, re.DOTALL)
    case = case_from_dict(tomllib.loads(block))
    assert len(case.buildings) == 3
    assert [(c.between, c.levels, c.restitution) for c in case.contacts] == [((1, 2), (2, 2), 0.65), ((2, 3), (1, 1), 0.5),
                                                                             ((2, 3), (2, 2), 0.5)]
