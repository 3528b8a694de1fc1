"""Sphinx configuration of the loader-model documentation (`make docs`)."""

import importlib.util
import re
import shutil
from pathlib import Path

from sphinx.ext import autosummary

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
# Offline build: no intersphinx, and MathJax is served from the built site itself (no CDN). The
# docs extra installs a copy of MathJax 3.2.2 (PyPI: django-static-mathjax, package ``mathjax``);
# its single-file SVG build is copied into the site's _static folder.
_MATHJAX_FILE = "tex-svg-full.js"


def _mathjax_static_dir() -> str:
    spec = importlib.util.find_spec("mathjax")
    if spec is None or not spec.submodule_search_locations:
        raise RuntimeError(
            "MathJax is not installed: `pip install -e '.[docs]'` installs it "
            "(django-static-mathjax), so that equations render offline"
        )
    source = Path(spec.submodule_search_locations[0]) / "static" / "mathjax" / "es5" / _MATHJAX_FILE
    target = Path(__file__).parent / "_build" / "mathjax_static" / "mathjax"
    target.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(source, target / _MATHJAX_FILE)
    return str(target.parent)


html_static_path = [_mathjax_static_dir()]
mathjax_path = f"mathjax/{_MATHJAX_FILE}"

autodoc_default_options["ignore-module-all"] = True  # each object once, on its defining module

# The summary tables of the API pages show a docstring's first sentence; the docstrings cite the
# paper as "Eq. 43", "Fig. 13", "Tables 4, 5", so those abbreviations do not end a sentence.
autosummary.WELL_KNOWN_ABBREVIATIONS = (
    *autosummary.WELL_KNOWN_ABBREVIATIONS,
    "Eq.",
    "Eqs.",
    "Fig.",
    "Figs.",
    "No.",
    "cf.",
)


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


# The worked examples are executed when the guide is built: each docs/examples/NAME.py runs in its
# own folder under _build/examples/NAME, and its printed output and the PNG figures it writes are
# appended to the page (the page itself shows the code, so it reads on GitHub too). An example
# that fails fails the build.
_EXAMPLES = Path(__file__).parent / "examples"
_EXAMPLE_RUNS = Path(__file__).parent / "_build" / "examples"


def _run_example(name: str) -> str:
    import os
    import subprocess
    import sys

    script = _EXAMPLES / f"{name}.py"
    folder = _EXAMPLE_RUNS / name
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    env = {**os.environ, "MPLBACKEND": "Agg"}
    run = subprocess.run(
        [sys.executable, str(script)], cwd=folder, env=env, capture_output=True, text=True
    )
    if run.returncode != 0:
        raise RuntimeError(
            f"docs/examples/{name}.py failed while building the guide:\n{run.stderr}"
        )
    parts = ["\n## Output\n", "```text\n" + run.stdout.rstrip() + "\n```\n"]
    for figure in sorted(folder.glob("*.png")):
        parts.append(f"![{figure.stem}](/_build/examples/{name}/{figure.name})\n")
    return "\n".join(parts)


def _append_example_output(app, docname, source):
    if docname.startswith("examples/") and docname != "examples/index":
        name = docname.split("/", 1)[1]
        if (_EXAMPLES / f"{name}.py").is_file():
            source[0] += "\n" + _run_example(name)


def setup(app):
    app.connect("autodoc-process-docstring", _escape_bars)
    app.connect("source-read", _append_example_output)
