"""Sphinx configuration of the loader-model documentation (`make docs`)."""

import re

import loader_model

project = "loader-model"
author = "loader-model authors"
copyright = "loader-model authors (MIT licence)"
release = loader_model.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "myst_parser",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "examples/*.py"]
templates_path = ["_templates"]

# The API reference: one page per module of loader_model, generated from the docstrings at build
# time into docs/api/ (not checked in).
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_member_order = "bysource"
autodoc_typehints = "description"
napoleon_numpy_docstring = True
napoleon_google_docstring = False

myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]

html_theme = "furo"
html_title = f"loader-model {release}"
# Offline build: no intersphinx, MathJax is loaded by the browser when a page is opened.

autodoc_default_options["ignore-module-all"] = True  # each object once, on its defining module


# The docstrings are written to be read as plain text too (``help()``), with |x| for absolute
# values and norms as in the paper; reST reads |x| as a substitution. Escape the bars outside
# literals, roles and math blocks before autodoc parses the docstring.
_LITERAL = re.compile(r"(:[a-z:]+:`[^`]*`|``[^`]*``|`[^`]*`)")


def _escape_bars(app, what, name, obj, options, lines):
    math_indent = None
    for i, line in enumerate(lines):
        stripped = line.lstrip()
        indent = len(line) - len(stripped)
        if math_indent is not None:
            if stripped and indent <= math_indent:
                math_indent = None
            else:
                continue
        if stripped.startswith(".. math::"):
            math_indent = indent
            continue
        if "|" not in line:
            continue
        parts = _LITERAL.split(line)
        lines[i] = "".join(p if k % 2 else p.replace("|", r"\|") for k, p in enumerate(parts))


def setup(app):
    app.connect("autodoc-process-docstring", _escape_bars)
