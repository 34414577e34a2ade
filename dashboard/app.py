"""The pounding dashboard (placeholder until the dashboard issue lands).

Serve with ``pounding dashboard`` or ``panel serve dashboard/app.py``. It shows
the default case (Rahimi & Soltani 2016, Section 5, T1 = 1.2 s, T2 = 0.4 s)
and runs a reduced-sample Monte Carlo study of it on request.
"""

import panel as pn

from pounding import load_case, simulate
from pounding.case import DEFAULT_PRESET

pn.extension()

case = load_case(DEFAULT_PRESET)
building_rows = "\n".join(
    f"| {number} | {building.periods[0]:.3f} s | {building.masses.sum() / 1e3:.2f} t | "
    f"{building.stiffnesses[0] / 1e6:.3f} MN/m | {building.damping_ratio:.2f} |"
    for number, building in enumerate(case.buildings, start=1)
)
inputs = pn.pane.Markdown(
    f"""### {case.name}

{case.description}

| building | period | mass | storey stiffness | damping ratio |
|---|---|---|---|---|
{building_rows}

Gap {case.contact.gap * 100:.2f} cm, contact stiffness {case.contact.stiffness / 1e9:.3f} GN/m^1.5,
restitution {case.contact.restitution:.2f}; records of {case.excitation.duration:g} s.
"""
)
records = pn.widgets.IntSlider(name="Records", start=10, end=200, step=10, value=40)
run = pn.widgets.Button(name="Run Monte Carlo", button_type="primary")
bar = pn.indicators.Progress(name="Progress", value=0, max=100, width=300)
result = pn.pane.Markdown("Press *Run Monte Carlo* for the 'exact' method on a reduced sample.")


def _run(_event):
    run.disabled = True
    try:
        outcome = simulate(case, records=records.value, seed=1, progress=lambda done, total: setattr(bar, "value", int(100 * done / total)))
        low, high = outcome.force_max_confidence_interval
        result.object = (
            f"**Mean extreme pounding force**: {outcome.force_max_mean / 1e6:.3f} MN "
            f"(95 % CI {low / 1e6:.3f} to {high / 1e6:.3f} MN) over {outcome.n_records} records; "
            f"pounding in {100 * outcome.pounding_fraction:.0f} % of records."
        )
    finally:
        run.disabled = False


run.on_click(_run)

pn.template.FastListTemplate(
    title="pounding: expected extreme pounding force",
    main=[inputs, pn.Row(records, run, bar), result],
).servable()
