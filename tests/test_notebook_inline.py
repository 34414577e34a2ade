"""The dashboard shown inline by a notebook renders in a real browser.

A notebook of two cells, ``pn.extension()`` then ``PoundingDashboard()``, is executed headless (nbclient) and
exported to HTML (nbconvert's HTMLExporter, as JupyterLab's "Save and Export Notebook As > HTML"); headless
Chromium opens the file with every request that leaves the file aborted.

What a static export of Panel's inline output needs: the output is a Bokeh document with the script that
embeds it, which the exported page keeps and runs. But ``pn.extension()`` loads BokehJS and Panel's JS from
their CDNs by default, and offline the page then stays blank ("Unable to run Panel code because Bokeh or
Panel library is missing"). Executed with ``PANEL_INLINE=1`` in the kernel's environment (or with
``pn.extension(inline=True)``), the JS and CSS are written into the notebook and the export renders offline.
Only nbconvert's own template asks the network for something (require.js and MathJax), which the dashboard
does not need. The export runs no Python: its widgets show, but changing one recomputes nothing.

Inline, the dashboard lays out at the cell's width: the inputs, the headline and the force-against-gap plot side
by side where they fit, else wrapped under each other, the plot never squeezed under its legend and title.
"""

import os

import nbformat
import pytest
from nbclient import NotebookClient

from tests.browser import LOAD_TIMEOUT, offline

pytestmark = [
    pytest.mark.browser,
    # Panel leaves an empty display_data beside each live output, which nbconvert says it cannot show.
    pytest.mark.filterwarnings("ignore:Your element with mimetype:UserWarning"),
]

CELLS = ("import panel as pn\npn.extension()", "from dashboard import PoundingDashboard\n\nPoundingDashboard()")
NBCONVERT_TEMPLATE = ("https://cdnjs.cloudflare.com/ajax/libs/require.js/", "https://cdnjs.cloudflare.com/ajax/libs/mathjax/")
"""What nbconvert's page asks of the network whatever the notebook holds."""

# Canvases of at least 50 x 50 px with something painted on them (a pixel neither transparent nor white),
# through the shadow roots.
PAINTED_CANVASES_JS = """() => { let n = 0; const walk = (root) => { for (const el of root.querySelectorAll('*')) {
  if (el.tagName === 'CANVAS' && el.width > 50 && el.height > 50) { const ctx = el.getContext('2d');
    if (ctx) { const d = ctx.getImageData(0, 0, el.width, el.height).data;
      for (let i = 0; i < d.length; i += 4) { if (d[i + 3] > 0 && (d[i] < 250 || d[i + 1] < 250 || d[i + 2] < 250)) { n++; break; } } } }
  if (el.shadowRoot) walk(el.shadowRoot); } }; walk(document); return n; }"""


# The force-against-gap plot, the headline and the output area on the page, through Bokeh's views: the plot's box,
# its frame's and its legend's (canvas px), and its title's width in its own font.
GAP_PLOT_LAYOUT_JS = """() => {
  const views = [];
  const walk = (v) => { if (!v || views.includes(v)) return; views.push(v);
    for (const c of (v.child_views ?? [])) walk(c);
    if (v.renderer_views) for (const r of v.renderer_views.values()) walk(r); };
  for (const root of Bokeh.index) walk(root);
  const plot = views.find(v => v.model.type === "Figure" && v.model.title && v.model.title.text.startsWith("Expected extreme pounding force against the gap"));
  const legend = plot.renderer_views.get(plot.model.below.find(r => r.type === "Legend"));
  const box = (el) => { const r = el.getBoundingClientRect(); return {left: r.left, top: r.top, right: r.right, bottom: r.bottom, width: r.width, height: r.height}; };
  let headline = null;
  const find = (root) => { for (const el of root.querySelectorAll('*')) { if (!headline && el.classList.contains('headline')) headline = el;
    if (el.shadowRoot) find(el.shadowRoot); } };
  find(document);
  const output = [...document.querySelectorAll('.jp-OutputArea-output')].map(box).filter(b => b.height > 100).pop();
  const title = plot.model.title, ctx = document.createElement('canvas').getContext('2d');
  ctx.font = `${title.text_font_style} ${title.text_font_size} ${title.text_font}`;
  return {plot: box(plot.el), headline: box(headline), output, canvas_width: plot.bbox.width, title_width: ctx.measureText(title.text).width,
          frame: {left: plot.frame.bbox.left, right: plot.frame.bbox.right}, legend: {left: legend.bbox.left, right: legend.bbox.right}};
}"""


@pytest.fixture(scope="module")
def exported_notebook(tmp_path_factory):
    """The two-cell notebook executed with its resources inline, as an HTML file."""
    from nbconvert import HTMLExporter

    notebook = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(source) for source in CELLS])
    NotebookClient(notebook, timeout=120, kernel_name="python3").execute(env={**os.environ, "PANEL_INLINE": "1"})
    errors = [o for cell in notebook.cells for o in cell.outputs if o.output_type == "error"]
    assert not errors, errors
    html, _ = HTMLExporter().from_notebook_node(notebook)
    path = tmp_path_factory.mktemp("notebook") / "dashboard.html"
    path.write_text(html, encoding="utf-8")
    return path


def test_inline_dashboard_renders_offline(browser, exported_notebook):
    from pounding import estimate, load_case
    from pounding.display_units import display

    expected = display("SI").force(estimate(load_case("section5-T2-0.4")).force_expected)
    context = browser.new_context(viewport={"width": 1500, "height": 1100})
    page = context.new_page()
    errors: list[str] = []
    requests: list[str] = []
    page.on("pageerror", lambda e: errors.append(f"page error: {e}"))
    offline(page, requests)
    try:
        page.goto(exported_notebook.as_uri())
        headline = page.locator(".fe-recommended")
        headline.wait_for(timeout=LOAD_TIMEOUT)
        assert headline.inner_text() == expected
        page.get_by_text("gap [mm]").first.wait_for(timeout=LOAD_TIMEOUT)  # the inputs beside it
        page.wait_for_function(f"({PAINTED_CANVASES_JS})() >= 1", timeout=LOAD_TIMEOUT)  # the force-against-gap plot drew
    finally:
        context.close()
    assert not errors
    blocked = [r.removeprefix("blocked request: ") for r in requests]
    assert all(url.startswith(NBCONVERT_TEMPLATE) for url in blocked), blocked


@pytest.mark.parametrize("width", [900, 1100, 1400])
def test_inline_dashboard_lays_out_at_notebook_width(browser, exported_notebook, width):
    """At a narrow, a laptop's and a wide window [px], the gap plot is as wide as its legend and title need, as tall
    as served, inside the cell's output, clear of the headline (its warnings); its legend inside its canvas.
    Measured before the layout wrapped: at 900 px the plot was 0 px wide, at 1100 px 188 px with its legend
    reaching 358 px left of the plot, over the headline."""
    context = browser.new_context(viewport={"width": width, "height": 1000})
    page = context.new_page()
    offline(page, [])
    try:
        page.goto(exported_notebook.as_uri())
        page.locator(".fe-recommended").wait_for(timeout=LOAD_TIMEOUT)
        page.wait_for_function(f"({PAINTED_CANVASES_JS})() >= 1", timeout=LOAD_TIMEOUT)
        layout = page.evaluate(GAP_PLOT_LAYOUT_JS)
    finally:
        context.close()
    plot, headline, output = layout["plot"], layout["headline"], layout["output"]
    assert plot["width"] >= 560 and plot["height"] >= 340, layout
    assert output["left"] - 1 <= plot["left"] and plot["right"] <= output["right"] + 1, layout  # inside the cell's output
    overlap = min(plot["right"], headline["right"]) > max(plot["left"], headline["left"]) and \
        min(plot["bottom"], headline["bottom"]) > max(plot["top"], headline["top"])
    assert not overlap, layout
    assert 0 <= layout["legend"]["left"] and layout["legend"]["right"] <= layout["canvas_width"], layout  # the legend is not cut
    assert layout["title_width"] <= layout["frame"]["right"] - layout["frame"]["left"], layout  # nor the title
