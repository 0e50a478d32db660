"""Sphinx configuration of the fickcam documentation (MyST Markdown, napoleon for the
numpydoc docstrings, autosummary over the package, reference pages generated from the
code by ``_ext/fickcam_reference.py``, tables of measurements rendered from
``benchmarks/results/`` by ``_ext/fickcam_results.py``)."""
import importlib.util
import re
from pathlib import Path

import fickcam

project = "fickcam"
author = "the fickcam authors"
copyright = "the fickcam authors, MIT license"
release = fickcam.__version__
version = release


def _load_local_extension(name: str):
    """A local extension, loaded from its file in ``_ext/`` (no ``sys.path`` edits)."""
    path = Path(__file__).parent / "_ext" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_reference = _load_local_extension("fickcam_reference")
_gallery = _load_local_extension("fickcam_gallery")
_results = _load_local_extension("fickcam_results")

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.intersphinx",
]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3
exclude_patterns = ["_build", "_tools", "Thumbs.db", ".DS_Store"]
templates_path = ["_templates"]

autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "ignore-module-all": True}
autodoc_typehints = "none"
napoleon_numpy_docstring = True
napoleon_google_docstring = False

html_theme = "pydata_sphinx_theme"
html_title = f"fickcam {release}"
html_static_path = ["_static"]
html_css_files = ["fickcam.css"]
html_theme_options = {
    "navbar_start": ["navbar-logo", "version"],
    "navbar_align": "left",
    "header_links_before_dropdown": 6,
    "show_toc_level": 2,
    "show_prev_next": True,
    "secondary_sidebar_items": ["page-toc", "sourcelink"],
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version", "theme-version"],
    "navigation_with_keys": False,
    "logo": {"text": "fickcam"},
}
html_sidebars = {"index": [], "changelog": []}
html_show_sourcelink = False

# Intersphinx: the inventories are text files committed in ``_inventories/`` (generated
# from the installed packages by ``_tools/inventories.py``), so the build never downloads
# them; the links point to each project's published documentation.
_INVENTORIES = Path(__file__).parent / "_inventories"
intersphinx_mapping = {
    name: (url, str(_INVENTORIES / f"{name}.txt"))
    for name, url in {
        "python": "https://docs.python.org/3/",
        "numpy": "https://numpy.org/doc/stable/",
        "scipy": "https://docs.scipy.org/doc/scipy/",
        "xarray": "https://docs.xarray.dev/en/stable/",
        "matplotlib": "https://matplotlib.org/stable/",
        "pint": "https://pint.readthedocs.io/en/stable/",
        "fipy": "https://www.ctcms.nist.gov/fipy/",
    }.items()
}


_TRAILING_UNDERSCORE = re.compile(r"(?<=\w)_(?=[\s,.;:)'\"]|$)")


def _escape_text(text: str) -> str:
    """``|`` and a trailing ``_`` outside inline literals, escaped."""
    pieces = text.split("``")
    for k in range(0, len(pieces), 2):
        pieces[k] = _TRAILING_UNDERSCORE.sub(r"\\_", pieces[k].replace("|", "\\|"))
        if k and pieces[k][:1].isalnum():  # ``track``s: a literal joined to a word
            pieces[k] = "\\ " + pieces[k]
    return "``".join(pieces)


def _indent(line: str) -> int:
    return len(line) - len(line.lstrip())


def _separate_indented_blocks(lines: list[str]) -> list[str]:
    """A blank line wherever the indentation changes between two text lines (module
    docstrings indent formulas and lists as plain text)."""
    out = []
    for line in lines:
        if out and out[-1].strip() and line.strip() and _indent(line) != _indent(out[-1]):
            out.append("")
        out.append(line)
    return out


def plain_text_docstring(app, what, name, obj, options, lines):
    """fickcam's docstrings are written as plain text: |x| is an absolute value, names
    such as ``surface_`` end in an underscore, module docstrings indent formulas. Escape
    them so that reStructuredText reads them as text."""
    text = [_escape_text(line) for line in lines]
    if what == "module":
        text = _separate_indented_blocks(text)
    lines[:] = text


def setup(app):
    _reference.setup(app)
    _gallery.setup(app)
    _results.setup(app)
    app.connect("autodoc-process-docstring", plain_text_docstring)
