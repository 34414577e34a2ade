"""Sphinx configuration: the API reference from the docstrings, and the Markdown pages of docs/ (MyST).

Build (warnings are errors, as in CI):

    python3 -m pip install -e ".[docs]"
    python3 -m sphinx -W --keep-going -b html docs build/docs

The HTML build also executes the teaching notebooks and writes them, with their figures, as
``build/docs/notebooks/*.html`` (notebooks/export_pages.py; 70 to 90 s of the build on 2 shared cores, see
:data:`NOTEBOOK_PAGES`).
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))  # the source tree, installed or not

project = "pounding"
author = "the pounding authors"
copyright = "the pounding authors, MIT licence"
release = version = __import__("pounding").__version__

extensions = ["sphinx.ext.autodoc", "sphinx.ext.napoleon", "myst_parser"]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build"]

autodoc_member_order = "bysource"
# A module documents what it defines; a name its __all__ re-exports is documented where it is defined.
autodoc_default_options = {"ignore-module-all": True}
autodoc_typehints = "none"  # the docstrings give the types in words, with units
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False

myst_heading_anchors = 3  # the pages link to each other's sections by their GitHub anchors

html_theme = "alabaster"
html_title = "pounding"
html_show_sourcelink = False



# ``.. public-names::`` lists ``from pounding import ...`` (pounding._EXPORTS), each linked to where it is defined.
import inspect  # noqa: E402

from docutils import nodes  # noqa: E402
from docutils.statemachine import StringList  # noqa: E402
from sphinx.util.docutils import SphinxDirective  # noqa: E402


class PublicNames(SphinxDirective):
    def run(self):
        import pounding

        lines = []
        for name in sorted(pounding._EXPORTS, key=str.lower):
            value = getattr(pounding, name)
            role = ("exc" if issubclass(value, BaseException) else "class") if inspect.isclass(value) else "func"
            lines.append(f"- ``{name}``: :{role}:`{value.__module__}.{name}`")
        node = nodes.container()
        self.state.nested_parse(StringList(lines, source="pounding._EXPORTS"), self.content_offset, node)
        return node.children


NOTEBOOK_PAGES = "notebooks"
"""The site's folder of the executed notebooks (docs/index.rst links to them)."""


def _notebook_pages(app, exception):
    """After an HTML build: the notebooks executed into the site, with their figures (a failing cell fails the build)."""
    if exception is not None or app.builder.format != "html":
        return
    from sphinx.util import logging

    sys.path.insert(0, str(ROOT / "notebooks"))
    from export_pages import write_pages

    took = write_pages(Path(app.outdir) / NOTEBOOK_PAGES)
    logging.getLogger(__name__).info(f"notebooks executed into {NOTEBOOK_PAGES}/ in {sum(took.values()):.0f} s")


def setup(app):
    app.add_directive("public-names", PublicNames)
    app.connect("build-finished", _notebook_pages)
