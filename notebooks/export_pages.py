"""The teaching notebooks as HTML pages with their figures: each executed top to bottom, then exported.

The Sphinx build (``docs/conf.py``) writes them into the site's ``notebooks/`` folder, linked from its index, so
the lessons can be read with their plots without running Jupyter; the repository keeps the notebooks without
outputs. By hand::

    python3 notebooks/export_pages.py build/notebooks                # all six
    python3 notebooks/export_pages.py build/notebooks 3_random_vibration   # one

Each notebook runs in a fresh ``python3`` kernel in ``notebooks/`` (two at a time) with ``PANEL_INLINE=1``, so that
``pn.extension()`` writes BokehJS and Panel's JS into the notebook and the page draws its plots offline. The page
is nbconvert's lab template (Jupyter's "Export as HTML") less its two scripts from the network
(:class:`OfflineHTMLExporter`): the equations are written as MathML when the page is made (``latex2mathml``; the
browser draws them, no MathJax), and require.js, which nothing on the page uses, is left out. The pages run no
Python: a lesson's widgets show, but moving one recomputes nothing.

HoloViews draws its plots without Panel's inlining of style sheets: their layout and theme CSS would load from
Panel's CDN at run time, and ``hv.extension`` would fetch an ES-module shim that Panel's own script has already
written into the page. :func:`without_panel_cdn` writes those style sheets into the page from the installed Panel
and drops the shim's address, so the page asks the network for nothing (tests/test_notebooks.py opens it with every
request that leaves the file aborted).
"""

from __future__ import annotations

import json
import os
import re
import sys
import time
import warnings
from pathlib import Path

NOTEBOOKS = Path(__file__).resolve().parent
TIMEOUT = 600
"""[s] The longest a cell may run."""


def execute(path: Path, timeout: int = TIMEOUT):
    """The notebook at ``path`` executed in a fresh kernel with ``PANEL_INLINE=1``; a failing cell raises."""
    import nbformat
    from nbclient import NotebookClient

    notebook = nbformat.read(path, as_version=4)
    client = NotebookClient(notebook, timeout=timeout, kernel_name="python3", resources={"metadata": {"path": str(path.parent)}})
    client.execute(env={**os.environ, "PANEL_INLINE": "1"})
    return notebook


_OFFLINE_TEMPLATE = """{%- extends 'index.html.j2' -%}
{%- block html_head_js_requirejs -%}{%- endblock html_head_js_requirejs -%}
{%- block html_head_js_mathjax -%}{%- endblock html_head_js_mathjax -%}
"""
"""nbconvert's lab page without its ``<script src>`` of require.js and of MathJax."""


def mathml(tex: str, display: str = "inline") -> str:
    """The TeX of an equation as MathML (``display`` "inline" or "block"); the TeX itself, escaped, where
    ``latex2mathml`` cannot read it."""
    import html

    from latex2mathml.converter import convert

    try:
        return convert(tex, display=display)
    except Exception:  # noqa: BLE001 - any TeX it cannot read: shown as written, never a failed page
        return html.escape(f"${tex}$" if display == "inline" else f"$${tex}$$")


def _offline_exporter():
    """:class:`OfflineHTMLExporter` (made here: nbconvert is imported when a page is made)."""
    from jinja2 import DictLoader, pass_context
    from nbconvert import HTMLExporter
    from nbconvert.filters.markdown_mistune import IPythonRenderer, MarkdownWithMath

    class MathMLRenderer(IPythonRenderer):
        """Markdown with its equations as MathML."""

        def inline_math(self, body: str) -> str:
            return mathml(body)

        def block_math(self, body: str) -> str:
            return mathml(body, "block")

        def latex_environment(self, name: str, body: str) -> str:
            return mathml(rf"\begin{{{name}}}{body}\end{{{name}}}", "block")

    class OfflineHTMLExporter(HTMLExporter):
        """nbconvert's HTML export (the lab template) whose page loads no script from the network: equations as
        MathML, no MathJax, no require.js."""

        def __init__(self, **options):
            options.setdefault("extra_loaders", [DictLoader({"offline.html.j2": _OFFLINE_TEMPLATE})])
            options.setdefault("template_file", "offline.html.j2")
            super().__init__(**options)

        @pass_context
        def markdown2html(self, context, source):
            cell = context.get("cell", {})
            renderer = MathMLRenderer(escape=False, attachments=cell.get("attachments", {}), embed_images=self.embed_images,
                                      path=context.get("resources", {}).get("metadata", {}).get("path", ""),
                                      anchor_link_text=self.anchor_link_text,
                                      exclude_anchor_links=self.exclude_anchor_links, **self.lexer_options)
            return MarkdownWithMath(renderer=renderer).render(source)

    return OfflineHTMLExporter()


_PANEL_CDN = r"https://cdn\.holoviz\.org/panel/(?P<version>[\d.]+)/dist/"
_IMPORTED_STYLE = re.compile(r'\{"type":"object","name":"ImportedStyleSheet","id":"(?P<id>[^"]+)",'
                             r'"attributes":\{"url":"' + _PANEL_CDN + r'(?P<path>[\w/.-]+\.css)(\?v=[\d.]+)?"\}\}')
_SHIM_URL = re.compile(r'"' + _PANEL_CDN + r'bundled/reactiveesm/es-module-shims[^"]*",?\s*')


def without_panel_cdn(page: str) -> str:
    """``page`` with Panel's style sheets written in where its plots link them from Panel's CDN (the installed
    Panel's own files, when the links are of its version), and without the CDN's address of the ES-module shim
    that Panel's script (``PANEL_INLINE=1``) has already put in the page."""
    import panel

    dist = Path(panel.__file__).parent / "dist"

    def inline(found: re.Match) -> str:
        file = dist / found["path"]
        if found["version"] != panel.__version__ or not file.is_file():
            return found[0]
        css = json.dumps(file.read_text(encoding="utf-8")).replace("</", "<\\/")
        return f'{{"type":"object","name":"InlineStyleSheet","id":"{found["id"]}","attributes":{{"css":{css}}}}}'

    page = _IMPORTED_STYLE.sub(inline, page)
    if "es-module-shims" in _SHIM_URL.sub("", page):  # the shim itself is in the page: its address is not needed
        page = _SHIM_URL.sub("", page)
    return page


def html_page(notebook) -> str:
    """An executed notebook as one HTML page: nbconvert's lab template (as Jupyter's "Export as HTML") with its
    equations as MathML and no script from the network (:func:`_offline_exporter`)."""
    with warnings.catch_warnings():  # Panel leaves an empty display_data beside each live output
        warnings.filterwarnings("ignore", "Your element with mimetype", UserWarning)
        html, _ = _offline_exporter().from_notebook_node(notebook)
    return without_panel_cdn(html)


def write_page(path: Path, folder: Path) -> float:
    """The notebook at ``path`` executed and written as ``folder/<name>.html``; the seconds it took."""
    start = time.perf_counter()
    (folder / f"{path.stem}.html").write_text(html_page(execute(path)), encoding="utf-8")
    return time.perf_counter() - start


def write_pages(folder: Path, names: list[str] | None = None, workers: int = 2) -> dict[str, float]:
    """Each notebook (all, or those whose file name starts with one of ``names``) as ``folder/<name>.html``,
    ``workers`` at a time (one kernel each); the seconds each took, by name."""
    from concurrent.futures import ProcessPoolExecutor

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    paths = [path for path in sorted(NOTEBOOKS.glob("*.ipynb")) if not names or any(path.stem.startswith(n) for n in names)]
    with ProcessPoolExecutor(max_workers=max(1, min(workers, len(paths)))) as pool:
        took = pool.map(write_page, paths, [folder] * len(paths))
        return {path.stem: seconds for path, seconds in zip(paths, took)}


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for name, seconds in write_pages(Path(sys.argv[1]), sys.argv[2:]).items():
        print(f"{name}: {seconds:.0f} s")
