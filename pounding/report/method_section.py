"""The report's method: what each method does, with the paper's equation
numbers, and how accurate the recommended estimate was measured to be in
each regime, stated in the page itself (its reader has no project docs)."""

from __future__ import annotations

import html

from pounding.closed_form.regimes import accuracy_data

__all__ = ["accuracy_table", "method_notes"]

_REGIMES = {
    "frequent": "frequent pounding: gap below half the RMS relative displacement, broad-band motion, storeys not near elastic-perfectly plastic",
    "moderate gap": "moderate gap: 0.5 to 1 times the RMS relative displacement",
    "narrow band": "narrow-band relative motion (the buildings sway at nearly one frequency)",
    "large residual": "a large share of the response from the part of the Bouc-Wen law the linearization drops",
    "rare, yielding": "large gap (above the RMS relative displacement), yielding storeys",
    "rare, elastic": "large gap (above the RMS relative displacement), elastic storeys",
}


def accuracy_table(regime: str | None = None) -> str:
    """The measured error of the recommended E[F_max] against Monte Carlo by regime (Kanai-Tajimi cases),
    from pounding/data/accuracy.json; the row of ``regime`` marked as this case's."""
    table = accuracy_data()["force"]["kanai-tajimi"]
    rows = []
    for key, entry in table.items():
        mine = regime is not None and key.split(",")[0] == regime
        rows.append(
            f'<tr{" class=this-case" if mine else ""}><td>{html.escape(_REGIMES.get(key, key))}{" (this case)" if mine else ""}</td>'
            f'<td class="number">{entry["cases"]}</td><td class="number">{entry["within_10_percent"]}</td>'
            f'<td class="number">{100 * entry["median_abs_error"]:.1f} %</td>'
            f'<td class="number">{100 * entry["low"]:+.0f} % to {100 * entry["high"]:+.0f} %</td></tr>'
        )
    return ('<table class="accuracy"><thead><tr><th>regime</th><th>cases</th><th>within 10 %</th>'
            "<th>median |error|</th><th>range of error</th></tr></thead><tbody>" + "".join(rows) + "</tbody></table>")


def method_notes(regime: str | None = None) -> str:
    """The method note, and the accuracy measured by regime (``regime``: this case's, marked)."""
    frequent = accuracy_data()["force"]["kanai-tajimi"]["frequent"]
    statement = (f"Within 10 % of Monte Carlo on {frequent['within_10_percent']} of {frequent['cases']} tested cases "
                 "where pounding is frequent (gap below half the RMS relative displacement, broad-band motion).")
    return _METHOD_NOTES.replace("{frequent}", statement) + _ACCURACY.replace("{table}", accuracy_table(regime))


_METHOD_NOTES = """
<h2>5. Method</h2>
<p>Paper: Rahimi, S. and Soltani, M. (2016), "Expected extreme value of pounding force between two adjacent
buildings", <i>Structural Engineering and Mechanics</i>; equation numbers below are the paper's. RMS relative displacement and velocity are those of the contact
floors (their standard deviations); F<sub>max</sub> is the largest pounding force
of one record, E[F<sub>max</sub>] its expectation over records.</p>
<ul class="method-notes">
<li><b>Buildings.</b> Shear buildings with a Bouc-Wen law in every storey (Eq. 1-2, 36-39);
damping c = 2 xi sqrt(k m) for one storey, stiffness-proportional on the first mode for more.</li>
<li><b>Ground motion.</b> Gaussian records of the case's spectrum (Kanai-Tajimi, Eq. 7; Clough-Penzien; or, for a design
spectrum, a compatible bank of band-pass filtered white noises that both methods use), optionally modulated by the
Shinozuka-Sato envelope (Eq. 8-9), by spectral representation; record i of a study is seeded on its own. Recorded
motions are integrated as sampled, each once, and the closed form takes a spectrum fitted to them.</li>
<li><b>Contact.</b> Jankowski's nonlinear viscoelastic law (Eq. 3-5) with the impact damping
2 xi sqrt(beta sqrt(delta) m1 m2/(m1+m2)) (Eq. 4 as printed is dimensionally inconsistent).</li>
<li><b>Monte Carlo ("exact").</b> Nonlinear time histories (Eq. 10-11) integrated with an error-controlled
Dormand-Prince 5(4) scheme that locates every impact; halving its tolerance moves the mean F<sub>max</sub> by less than 0.1 %.</li>
<li><b>Paper's estimate.</b> Statistical linearization (Eq. 19-21), variances with cross terms (Eq. 16-18, 25),
Davenport's peak factor with the rate of Eq. 24 (Eq. 23), Michaelov's equivalent stationary process for modulated
motion (Eq. 26-30), force by Eq. 13-14 with delta^1.5.</li>
<li><b>Recommended estimate.</b> The same linearized pair, with its response to the part of the Bouc-Wen law
that the linearization drops (an input independent of the ground motion) added; impacts counted as crossings of
the gap (Rice) at the rate per unit time spent below the gap, with clumps (Vanmarcke), the response built up from
rest; the largest approach counted on the motion that the impacts before it leave (their damping, as much as the
pair remembers them); each impact's peak force is the contact law's own, K(e) times the undamped Hertz peak,
lowered by the buildings' own forces that brake the approach at the gap. The distribution of F<sub>max</sub>
(its fractiles) follows from the same counts: the probability of no impact, then the largest approach's speed.
{frequent} Less accurate in the other regimes, and not reliable where only the largest swings close the gap (warnings say so): the
table below gives the error measured in each.</li>
</ul>
"""

_ACCURACY = """
<h3>Measured accuracy of the recommended E[F<sub>max</sub>]</h3>
<p>Error = (closed form - Monte Carlo) / Monte Carlo over the tested cases of a Kanai-Tajimi ground motion,
each against a Monte Carlo study of its own; the regime is decided from the case's gap against the RMS relative
displacement, the motion's bandwidth and how far the storeys yield beyond the linearization.</p>
{table}
"""
