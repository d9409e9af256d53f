"""Sphinx configuration of the lubedyn documentation (see docs/README.md for why Sphinx, and how to build).

Build: ``pip install -e ".[docs]" && sphinx-build -b html docs docs/_build/html`` (the API reference documents
the installed ``lubedyn``, so the checkout must be installed) (the examples gallery
executes every ``examples/*.py`` at smoke size, ``LUBEDYN_SMOKE=1``; ``-D plot_gallery=0`` skips that).
"""
from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
# the library is the installed ``lubedyn`` (the checkout installed editable: ``pip install -e .``); the
# checkout's root is not put on sys.path, where its folders would be importable under their own names
sys.path.insert(0, str(HERE / "_ext"))  # case_reference, methods_atlas
os.environ.setdefault("LUBEDYN_SMOKE", "1")  # the gallery runs the examples at smoke size (seconds each)
os.environ.setdefault("MPLBACKEND", "Agg")
os.environ.setdefault("PYVISTA_OFF_SCREEN", "true")

project = "lubedyn"
author = "the lubedyn developers"
copyright = "2026, the lubedyn developers"
try:
    from importlib.metadata import version as _version

    release = _version("lubedyn")
except Exception:  # not installed: building from a bare checkout
    release = "0.1.0"

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "sphinx_gallery.gen_gallery",
    "case_reference",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "README.md", "auto_examples/*.ipynb", "auto_examples/*.py",
                    "auto_examples/*.zip", "auto_examples/*.json", "auto_examples/*.md5"]
templates_path = ["_templates"]

myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3

# API reference: one page per module, generated from the docstrings at build time
autosummary_generate = True
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_member_order = "bysource"
autodoc_typehints = "none"          # the NumPy docstrings carry the types and units
autodoc_preserve_defaults = True
autodoc_use_type_comments = False  # the package has no "# type:" comments; reading them parsed every member's source
napoleon_numpy_docstring = True
napoleon_google_docstring = False
napoleon_use_rtype = False

sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/[a-z][a-z_]*\.py$",   # every example is executed (not only plot_*.py)
    "ignore_pattern": r"/_[^/]*\.py$",  # none today: every example imports only lubedyn and public packages
    "within_subsection_order": "FileNameSortKey",
    "download_all_examples": False,
    "remove_config_comments": True,
    "image_scrapers": ("matplotlib",),
    "default_thumb_file": None,
    "abort_on_example_error": True,
    "show_memory": False,
    "capture_repr": (),
    "write_computation_times": False,  # its page links every example, and breaks -W when they are not run
}

html_theme = "alabaster"
html_title = f"lubedyn {release}"
html_static_path = []
html_theme_options = {"description": "lubricant films, film maps and rolling-bearing dynamics",
                      "fixed_sidebar": True, "page_width": "1180px", "sidebar_width": "240px"}
# config.cache: sphinx_gallery_conf is not picklable.  ref.python: "more than one target found" for short
# type names in dataclass fields (``Gap`` is both lubedyn.lubrication.Gap and lubedyn.lubrication.gaps.Gap, the same class
# re-exported); the link goes to one of them, which is right.
suppress_warnings = ["config.cache", "ref.python"]


# ---------------------------------------------------------------------------------------------------------
# Docstrings.  The project writes its docstrings' math as plain text (STYLE.md, "Docs in the code"), where
# |x| is an absolute value or a norm; reStructuredText reads |x| as a substitution reference, which the
# project never uses.  So bars outside literal text are escaped before the docstring is parsed: inline
# literals (``...``), literal blocks (after "::") and doctest blocks are left as they are (the docstrings
# have no grid tables or line blocks, whose bars are markup).  Everything else in a docstring must be valid reStructuredText (the build runs with -W).
import re as _re

_INLINE_LITERAL = _re.compile(r"(``.*?``)")


def _escape_bars(line: str) -> str:
    parts = _INLINE_LITERAL.split(line)
    return "".join(p if p.startswith("``") else _re.sub(r"(?<!\\)\|", r"\\|", p) for p in parts)


def _escape_docstring_bars(app, what, name, obj, options, lines):
    literal_indent = None      # indentation of the paragraph that opened a literal block, while inside it
    in_doctest = False
    for i, line in enumerate(lines):
        stripped = line.strip()
        indent = len(line) - len(line.lstrip())
        if literal_indent is not None:
            if stripped and indent <= literal_indent:
                literal_indent = None
            else:
                continue
        if in_doctest:
            if not stripped:
                in_doctest = False
            continue
        if stripped.startswith(">>>"):
            in_doctest = True
            continue
        if "|" in line:
            lines[i] = _escape_bars(line)
        if stripped.endswith("::"):
            literal_indent = indent


def setup(app):
    app.connect("autodoc-process-docstring", _escape_docstring_bars)
