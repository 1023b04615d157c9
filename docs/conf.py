"""Sphinx configuration of shroudnet's documentation site.

Built by ``python -m sphinx -W -b html docs docs/_build/html`` from the repository root
(warnings are errors). Pages are Markdown (MyST); the API reference is generated from the
docstrings (numpydoc) by autosummary.
"""

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the working tree's packages, installed or not

project = "shroudnet"
author = "the shroudnet developers"
copyright = "the shroudnet developers"
release = version = "0.1.0"

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "gallery/README.md"]
templates_path = ["_templates"]

# MyST: GitHub-style anchors, so that a page's links work on GitHub and in the site alike.
myst_heading_anchors = 3


# The reference: one page per public name, from its docstring.
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"member-order": "bysource"}
autodoc_typehints = "none"  # the numpydoc Parameters sections say the types
numpydoc_show_class_members = False  # the class template lists the members
numpydoc_class_members_toctree = False

html_theme = "pydata_sphinx_theme"
html_title = "shroudnet"
html_theme_options = {
    "navigation_depth": 2,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": [],
}
html_static_path = []
html_show_sourcelink = False


# ---- docstrings as the package writes them -------------------------------------------------
#
# The docstrings write absolute values as in print, |v| and |f| ≤ μ_s N, which
# reStructuredText would read as substitution references. They are escaped here, outside
# inline literals (``...``), literal blocks (after "::") and doctests, rather than in
# the source, where the plain notation reads best at the terminal (help()).

_INLINE_LITERAL = re.compile(r"(``.+?``)")


def _escape_bars(line: str) -> str:
    """``line`` with every | outside inline literals escaped."""
    pieces = _INLINE_LITERAL.split(line)
    return "".join(piece if k % 2 else piece.replace("|", r"\|")
                   for k, piece in enumerate(pieces))


def _indent(line: str) -> int:
    return len(line) - len(line.lstrip())


def escape_absolute_values(app, what, name, obj, options, lines):
    """Escape the bars of absolute values in a docstring's ``lines``, in place."""
    literal_from = None  # the indentation of the paragraph that opened a literal block
    doctest = False
    for k, line in enumerate(lines):
        stripped = line.strip()
        if literal_from is not None:
            if not stripped or _indent(line) > literal_from:
                continue
            literal_from = None
        if stripped.startswith(">>>"):
            doctest = True
        if doctest:
            doctest = bool(stripped)
            continue
        lines[k] = _escape_bars(line)
        if stripped.endswith("::"):
            literal_from = _indent(line)


def setup(app):
    app.connect("autodoc-process-docstring", escape_absolute_values)
