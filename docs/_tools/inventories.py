"""Write the intersphinx inventories of ``docs/_inventories/`` from the installed packages.

The documentation links names of numpy, SciPy, xarray, matplotlib, pint, FiPy, pydantic,
dask.distributed and the standard library to their projects' published pages. Sphinx reads each project's
``objects.inv`` to know where a name is documented; the machines that build these docs
may not reach those sites, so the inventories are committed here as small text files
(Sphinx's inventory format version 1: ``name role page``), one per project, holding the
names the docstrings and pages of fickcam use.

Run it after a docstring starts using a name of one of these projects::

    python docs/_tools/inventories.py

Each name is imported from the installed package, so a name that does not exist (a typo,
or one the project renamed) stops the script; its role (class, function, method,
attribute, module) is read from the object and its page follows the project's layout.
"""
from __future__ import annotations

import importlib
import inspect
from pathlib import Path

OUT = Path(__file__).resolve().parents[1] / "_inventories"

# project -> the names used in fickcam's documentation
NAMES = {
    "python": [
        "float", "int", "str", "bool", "dict", "list", "tuple", "bytes", "object",
        "Exception", "ValueError", "KeyError", "TypeError", "RuntimeError", "OSError",
        "pathlib.Path", "collections.abc.Callable", "collections.abc.Iterable",
        "collections.abc.Mapping", "collections.abc.Sequence", "argparse.ArgumentParser",
        "argparse.Namespace", "typing.Any", "logging.Logger", "os.PathLike",
        "concurrent.futures.Executor", "dataclasses.dataclass", "None", "True", "False",
        "callable", "contextlib.contextmanager", "collections.namedtuple",
        "collections.abc.Generator", "logging", "enum.IntEnum", "numbers.Number",
    ],
    "numpy": [
        "numpy.ndarray", "numpy.float64", "numpy.array", "numpy.asarray", "numpy.interp",
        "numpy.linalg.solve", "numpy.polynomial.chebyshev.chebval",
        "numpy.random.Generator", "numpy.random.default_rng", "numpy.typing.ArrayLike",
        "numpy.typing.NDArray", "numpy.errstate", "numpy.gradient", "numpy.trapezoid",
        "numpy", "numpy.inf", "numpy.nan", "numpy.random.RandomState",
    ],
    "scipy": [
        "scipy.optimize.brentq", "scipy.optimize.least_squares", "scipy.optimize.minimize",
        "scipy.optimize.minimize_scalar", "scipy.optimize.linprog",
        "scipy.optimize.OptimizeResult", "scipy.integrate.solve_ivp",
        "scipy.linalg.expm", "scipy.sparse.csr_matrix", "scipy.sparse.linalg.splu",
        "scipy.interpolate.CubicSpline", "scipy.interpolate.make_interp_spline",
        "scipy.interpolate.BSpline", "scipy.special.erfc", "scipy.stats.f",
        "scipy.interpolate.PPoly", "scipy.interpolate.PPoly.roots",
    ],
    "xarray": [
        "xarray.Dataset", "xarray.DataArray", "xarray.open_dataset", "xarray.load_dataset",
        "xarray.Dataset.sel", "xarray.Dataset.to_netcdf", "xarray.DataArray.sel",
        "xarray.DataArray.plot", "xarray.DataArray.interp", "xarray.concat",
    ],
    "matplotlib": [
        "matplotlib.figure.Figure", "matplotlib.axes.Axes", "matplotlib.pyplot.subplots",
        "matplotlib.pyplot.figure", "matplotlib.pyplot.show", "matplotlib.figure.Figure.savefig",
        "matplotlib.axes.Axes.legend",
    ],
    "pint": ["pint.UnitRegistry", "pint.Quantity", "pint.Unit", "pint.errors.DimensionalityError"],
    "pydantic": ["pydantic.BaseModel", "pydantic.functional_validators.BeforeValidator",
                 "pydantic.functional_validators.AfterValidator", "pydantic.types.Tag",
                 "pydantic.types.Discriminator"],
    "distributed": ["distributed.LocalCluster", "distributed.Client"],
    "fipy": ["fipy", "fipy.CellVariable", "fipy.TransientTerm", "fipy.DiffusionTerm",
             "fipy.Grid1D", "fipy.Grid2D", "fipy.Grid3D", "fipy.CylindricalGrid2D"],
}

#: (project, name prefix) -> the page of a name, relative to the project's URL
SPECIAL_PAGES = {
    ("numpy", "numpy.typing."): "reference/typing.html",
    ("numpy", "numpy.random.Generator"): "reference/random/generator.html",
    ("numpy", "numpy.random.RandomState"): "reference/random/legacy.html",
    ("numpy", "numpy.inf"): "reference/constants.html",
    ("numpy", "numpy.nan"): "reference/constants.html",
    ("matplotlib", "matplotlib.axes.Axes"): "api/_as_gen/matplotlib.axes.Axes.html",
    ("matplotlib", "matplotlib.figure.Figure"): "api/_as_gen/matplotlib.figure.Figure.html",
    ("pint", "pint."): "api/base.html",
}
PYTHON_PAGES = {
    "builtins": "library/functions.html", "exceptions": "library/exceptions.html",
    "pathlib": "library/pathlib.html", "collections": "library/collections.abc.html",
    "argparse": "library/argparse.html", "typing": "library/typing.html",
    "logging": "library/logging.html", "os": "library/os.html",
    "concurrent": "library/concurrent.futures.html", "dataclasses": "library/dataclasses.html",
    "contextlib": "library/contextlib.html", "enum": "library/enum.html",
    "numbers": "library/numbers.html",
}
PYTHON_CONSTANTS = {"None", "True", "False"}
BUILTIN_TYPES = {"float", "int", "str", "bool", "dict", "list", "tuple", "bytes", "object",
                 "callable"}


def resolve(name: str):
    """The object a dotted name stands for, imported from the installed package."""
    parts = name.split(".")
    for k in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:k]))
        except ImportError:
            continue
        for attr in parts[k:]:
            obj = getattr(obj, attr)
        return obj
    import builtins
    return getattr(builtins, name)


def role(name: str, obj) -> str:
    """The inventory role: mod, class, exception, function, method or data."""
    if inspect.ismodule(obj):
        return "mod"
    if name in PYTHON_CONSTANTS:
        return "data"
    if name.startswith("numpy.typing."):
        return "data"  # type aliases
    if inspect.isclass(obj):
        return "exception" if issubclass(obj, BaseException) else "class"
    if "." in name and inspect.isclass(resolve(name.rsplit(".", 1)[0])):
        return "method" if callable(obj) else "attribute"
    if callable(obj):
        return "function"
    return "data"


def page(project: str, name: str, kind: str) -> str:
    """The page of ``name`` in ``project``'s documentation."""
    for (where, prefix), special in SPECIAL_PAGES.items():
        if where == project and name.startswith(prefix) and kind != "method":
            return special
    if project == "python":
        if name in PYTHON_CONSTANTS:
            return "library/constants.html"
        if "." not in name:
            return PYTHON_PAGES["builtins" if name in BUILTIN_TYPES else "exceptions"]
        return PYTHON_PAGES[name.split(".")[0]]
    if project == "fipy":
        return "fipy/generated/fipy.html"
    if project == "distributed":
        return "api.html"
    if project == "pydantic":
        module = name.rsplit(".", 1)[0]
        return "api/base_model/" if module == "pydantic" else f"api/{module.split('.')[1]}/"
    if project == "matplotlib":
        return f"api/_as_gen/{name}.html"
    if project == "numpy":
        return "reference/index.html" if kind == "mod" else f"reference/generated/{name}.html"
    if project == "scipy":
        return f"reference/generated/{name}.html"
    return f"generated/{name}.html"  # xarray


def inventory(project: str, names: list[str]) -> str:
    """The inventory of ``project`` as text (format version 1)."""
    import importlib.metadata as metadata
    distribution = {"python": None}.get(project, project)
    version = metadata.version(distribution) if distribution else "3"
    lines = ["# Sphinx inventory version 1", f"# Project: {project}", f"# Version: {version}"]
    for name in sorted(names):
        kind = role(name, resolve(name))
        kind = {"exception": "exception"}.get(kind, kind)
        lines.append(f"{name} {kind} {page(project, name, kind)}")
    return "\n".join(lines) + "\n"


def main() -> None:
    OUT.mkdir(exist_ok=True)
    for project, names in NAMES.items():
        (OUT / f"{project}.txt").write_text(inventory(project, names))
        print(f"wrote {OUT / project}.txt ({len(names)} names)")


if __name__ == "__main__":
    main()
