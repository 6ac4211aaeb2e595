"""Sphinx configuration of the seahelm documentation (``make docs``).

Why Sphinx + numpydoc + pydata-sphinx-theme (and not MkDocs + mkdocstrings): seahelm's
docstrings are numpydoc (house style, checked by tests/test_docs.py), which numpydoc renders
natively; the pydata theme is the scientific-Python convention (numpy, scipy, xarray,
matplotlib), so the site reads like the libraries its users know; sphinx-gallery runs the
examples at every build and puts their figures in the pages, so an example that breaks fails
the build; and autodoc/autosummary take the API reference from the docstrings the code already
has. The scenario-file reference is generated from the pydantic schema by a small local
extension (_ext/scenario_reference.py). Warnings are errors (``make docs`` passes ``-W``).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
os.environ.setdefault("MPLBACKEND", "Agg")

import seahelm  # noqa: E402

project = "seahelm"
author = "seahelm developers"
copyright = "seahelm developers, BSD-3-Clause"
version = release = seahelm.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "scenario_reference",
    "ship_reference",
]

exclude_patterns = ["_build", "examples/README.rst"]
templates_path = ["_templates"]
default_role = "literal"  # `name` in the prose is code, as in the docstrings

# API reference: one page per module, generated from the docstrings
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_typehints = "none"  # numpydoc's Parameters sections carry the types
autodoc_member_order = "bysource"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_validation_checks: set[str] = set()
numpydoc_xref_param_type = False

# examples: run at every build, figures included
sphinx_gallery_conf = {
    "examples_dirs": ["examples"],
    "gallery_dirs": ["auto_examples"],
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    "abort_on_example_error": True,
    "show_memory": False,
    "reset_modules": ("matplotlib",),
}

html_theme = "pydata_sphinx_theme"
html_title = f"seahelm {release}"
# pages without sub-pages get no left sidebar (pydata's "Section Navigation" was empty there)
html_sidebars = {page: [] for page in ("index", "getting-started", "scenario-reference",
                                       "ship-file-reference", "api")}
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": [],
}
html_static_path = ["_static"]
html_css_files = ["seahelm.css"]  # long literals may break inside table cells
html_show_sourcelink = False
# no intersphinx: the build needs no network


# ------------------------------------------------------------------------------------------
# seahelm's docstrings are written to be read as plain text too: |x| is an absolute value
# (reST would take it for a substitution), `*args` a starred name, and a definition-list term
# may run over two lines. This hook makes them valid reST without touching their plain-text
# form; inline literals (``...``) are left as written.
import re  # noqa: E402

_LITERAL = re.compile(r"(``.+?``)")
_OPEN_STAR = re.compile(r"(?<![\w*`\\])(\*{1,2})(?=[\w(])")


def _escape_segment(text: str) -> str:
    text = text.replace("|", r"\|")
    out, pos = [], 0
    for m in _OPEN_STAR.finditer(text):
        stars = m.group(1)
        closed = re.search(r"(?<=\S)" + re.escape(stars) + r"(?!\w)", text[m.end():])
        if not closed:
            out.append(text[pos:m.start()] + "\\*" * len(stars))
            pos = m.end()
    out.append(text[pos:])
    return "".join(out)


def _escape_line(line: str) -> str:
    parts = _LITERAL.split(line)
    return "".join(p if i % 2 else _escape_segment(p) for i, p in enumerate(parts))


def _indent(line: str) -> int:
    return len(line) - len(line.lstrip())


def _plain_text_to_rest(app, what, name, obj, options, lines):  # noqa: ANN001
    lines[:] = [_escape_line(line) for line in lines]
    i = 1
    while i + 2 < len(lines) + 1 and i + 1 < len(lines):
        prev, term, more, body = lines[i - 1], lines[i], lines[i + 1], (
            lines[i + 2] if i + 2 < len(lines) else "")
        if (not prev.strip() and term.strip() and more.strip() and body.strip()
                and _indent(term) == _indent(more) < _indent(body)
                and not term.lstrip().startswith(("*", "-", ".."))):
            lines[i:i + 2] = [term.rstrip() + " " + more.strip()]  # a two-line term, joined
        i += 1


def setup(app):  # noqa: ANN001, ANN201
    app.connect("autodoc-process-docstring", _plain_text_to_rest, priority=400)
