"""Sphinx configuration of the fickcam documentation: MyST Markdown, the PyData theme,
numpydoc for the docstrings, autosummary over the package, the example gallery by
sphinx-gallery from ``examples/``, reference pages generated from the code by
``_ext/fickcam_reference.py``, tables of measurements rendered from
``benchmarks/results/`` by ``_ext/fickcam_results.py``."""
import importlib.util
import re
import sys
from pathlib import Path

import fickcam

project = "fickcam"
author = "the fickcam authors"
copyright = "the fickcam authors, MIT license"
release = fickcam.__version__
version = release


def _load_local_extension(name: str):
    """A local extension, loaded from its file in ``_ext/`` (no ``sys.path`` edits); it is
    registered under its name so that objects of it in the configuration can be pickled
    with Sphinx's environment."""
    path = Path(__file__).parent / "_ext" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


_reference = _load_local_extension("fickcam_reference")
_results = _load_local_extension("fickcam_results")
_gallery = _load_local_extension("fickcam_gallery")

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "numpydoc",
    "sphinx.ext.mathjax",
    "sphinx.ext.intersphinx",
    "sphinx_gallery.gen_gallery",
]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3
exclude_patterns = ["_build", "_tools", "examples", "Thumbs.db", ".DS_Store"]

# The example gallery: one script per example scene in ``examples/``, run when the docs
# build; each page shows the printed summary and the figures, with the script and a
# notebook to download.
sphinx_gallery_conf = {
    "image_scrapers": (_gallery.TightFigures(),),
    "examples_dirs": "examples",
    "gallery_dirs": "gallery",
    "filename_pattern": r"/plot_",
    "within_subsection_order": "ExampleTitleSortKey",
    "download_all_examples": False,
    "remove_config_comments": True,
    "line_numbers": False,
    "show_memory": False,
    "show_signature": False,
    "min_reported_time": 3600,
    "backreferences_dir": None,
    "thumbnail_size": (400, 300),
    "image_srcset": [],
}
templates_path = ["_templates"]

autosummary_generate = True
autosummary_imported_members = False
# scipy's cKDTree, imported by several modules, is documented by scipy
autodoc_default_options = {"members": True, "ignore-module-all": True, "exclude-members": "cKDTree"}
autodoc_typehints = "none"
# numpydoc renders the docstrings; a parameter's type links when it is one of these names
# (the other words of a type, "optional", "array_like", "of", stay text)
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = True
numpydoc_xref_ignore = "all"
_LINKED_TYPES = ["numpy.ndarray", "xarray.Dataset", "xarray.DataArray", "pathlib.Path",
                 "matplotlib.figure.Figure", "matplotlib.axes.Axes", "pint.Quantity",
                 "numpy.random.Generator", "scipy.sparse.csr_matrix"]
numpydoc_xref_aliases = {
    **{name: name for name in _LINKED_TYPES},
    **{name.rsplit(".", 1)[1]: name for name in _LINKED_TYPES},
    "None": "None", "True": "True", "False": "False", "bool": "bool", "boolean": "bool",
    "str": "str", "string": "str", "int": "int", "float": "float", "dict": "dict",
    "list": "list", "tuple": "tuple", "callable": "callable",
    "iterable": "collections.abc.Iterable", "sequence": "collections.abc.Sequence",
    "contextmanager": "contextlib.contextmanager", "namedtuple": "collections.namedtuple",
    "generator": "collections.abc.Generator", "array_like": "numpy.typing.ArrayLike",
    "array-like": "numpy.typing.ArrayLike", "scalar": "numbers.Number", "numpy": "numpy",
    "np.inf": "numpy.inf", "np.nan": "numpy.nan",
}

# A unit-parsed type (``Length = Annotated[float, BeforeValidator(read), ...]``) is shown
# as the alias it is; the validators in it are local functions of fickcam.quantities.types.quantity,
# documented there, with no page of their own to link to.
nitpick_ignore_regex = [("py:class", r"fickcam\.quantities\.types\.quantity\.<locals>\..*"), ("py:class", "lambda")]

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
# the wide tables of the reference and measurement pages get the width of the left sidebar
html_sidebars = {page: [] for page in ("index", "changelog", "reference/scene", "reference/results",
                                       "reference/cli", "benchmarks", "validation",
                                       "validation-record", "architecture")}
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
        "pydantic": "https://docs.pydantic.dev/latest/",
        "distributed": "https://distributed.dask.org/en/stable/",
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


def _reference_entries(lines: list[str]) -> list[str]:
    """The entries under a module docstring's ``References`` heading, one paragraph each:
    an entry starts at the margin and its continuation lines are indented."""
    out, inside = [], False
    for line in lines:
        if line.strip() == "References":
            inside = True
        elif set(line.strip()) == {"-"} and out and out[-1].strip() != "References":
            inside = False  # the next section's heading
            if len(out) > 1 and out[-2].strip():  # its title was joined as an entry's line
                out.insert(len(out) - 1, "")
        elif inside and line.strip() and not set(line.strip()) <= {"-"}:
            if _indent(line) > 0:  # a continuation of the entry above
                out[-1] = f"{out[-1]} {line.strip()}"
                continue
            if out and out[-1].strip() and not set(out[-1].strip()) <= {"-"}:
                out.append("")
        out.append(line)
    return out


def _separate_indented_blocks(lines: list[str]) -> list[str]:
    """A blank line wherever the indentation changes between two text lines (module
    docstrings indent formulas and lists as plain text)."""
    out = []
    for line in _reference_entries(lines):
        comment = out and out[-1].strip() == ".."  # numpydoc's comment keeps its body
        if (out and out[-1].strip() and line.strip() and _indent(line) != _indent(out[-1])
                and not comment):
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
    _results.setup(app)
    _gallery.setup(app)
    app.connect("autodoc-process-docstring", plain_text_docstring)
