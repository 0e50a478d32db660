"""fickcam: moisture uptake in polymer and composite cams, followers and
four-bar linkages, and how the mechanisms drift out of spec as they age.

``import fickcam`` is light: FiPy, matplotlib and dask are imported only by
the modules that need them.
"""
from __future__ import annotations

import logging as _logging

from ._version import __version__
from .errors import FickcamWarning, InputError, SceneError
import importlib

__all__ = ["load_scene", "run", "save", "open_result", "compensate", "fit_weight_gain",
           "FickcamWarning", "SceneError", "InputError", "__version__"]

# notes (INFO) and details (DEBUG) go to the "fickcam" logger; silent until a user adds a
# handler (logging.basicConfig), never Python's last-resort bare lines
_logging.getLogger(__name__).addHandler(_logging.NullHandler())

#: sub-packages reached as attributes (``fickcam.plotting.plot(ds)``), imported on first use:
#: attribute -> module, relative to the package (the attribute ``query`` is ``results.query``)
_SUBMODULES = {"plotting": ".plotting", "query": ".results.query", "export": ".results.export",
               "scene": ".scene", "results": ".results", "messages": ".messages",
               "errors": ".errors"}


def __getattr__(name: str):
    """``fickcam.plotting`` and the other sub-packages of :data:`_SUBMODULES`, imported
    when first reached, so that ``import fickcam`` stays light."""
    if name in _SUBMODULES:
        return importlib.import_module(_SUBMODULES[name], __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def load_scene(source, *, file_name: str | None = None):
    """Read and validate a scene from a YAML path or a dict; values in SI after validation.

    Parameters
    ----------
    source : str, pathlib.Path, dict or Scene
        A YAML scene file, the scene as a dict (as ``yaml.safe_load`` gives it), or an
        already loaded :class:`fickcam.scene.load.Scene` (returned as is). Quantities are
        written with units ("3 mm", "60 d"), see the scene reference.
    file_name : str, optional
        The name that error messages give a dict scene (default ``<dict>``).

    Returns
    -------
    fickcam.scene.load.Scene
        The validated scene; every quantity in SI (m, s, K, Pa, rad), moisture in
        weight % and relative humidity in %.

    Raises
    ------
    fickcam.errors.SceneError
        When the file cannot be read or a key is missing, misspelt, out of range or
        in a wrong unit: one line per problem, naming file, line and key.
    """
    # deferred: keeps numpy, pydantic, yaml off the start-up path
    from .scene.load import load_scene as _load

    return _load(source, file_name=file_name)


def run(scene, *, accuracy: float | None = None, progress: bool = False, settings=None,
        cache=None):
    """Run one scene (a path, a dict or a loaded scene) and return an xarray.Dataset;
    ``settings``: the diffusion solvers' tuned limits (``fickcam.diffusion.SolverSettings``,
    e.g. its cell caps; None: the defaults); ``cache``: a ``fickcam.diffusion.RunCache`` to
    share between runs (None: a fresh one, dropped with the run).

    Parameters
    ----------
    scene : str, pathlib.Path, dict or Scene
        The scene, as :func:`load_scene` takes it.
    accuracy : float, optional
        The diffusion's relative accuracy [-] (a fraction of the moisture swing), in place
        of the scene's ``diffusion.accuracy``; None: the scene's (default 1e-3).
    progress : bool
        Show progress: a bar over the parts' diffusion, then one over the ageing times'
        mechanisms; at the end one line says what ran and how long it took
        (``fickcam: run NAME: 2 parts, 5 ageing times in 3.1 s``). On a terminal the bars
        are tqdm's, on stderr; in a Jupyter notebook they are one output, a widget with
        ipywidgets installed and text without, which the summary line replaces, so that a
        saved notebook keeps it. In a log file or a pipe only the summary is written.
    settings : fickcam.diffusion.SolverSettings, optional
        The diffusion solvers' tuned limits; None: the defaults.
    cache : fickcam.diffusion.RunCache, optional
        What the diffusion solves build once and read again (meshes, step responses,
        tables), read-only. Runs given the same cache reuse each other's solves (scenes
        that share a part, its material and its climate); None: a fresh one per run.

    Returns
    -------
    xarray.Dataset
        The result, SI but for ``time`` in days, angles in degrees and moisture in
        weight %; each variable carries its ``units`` attribute (see the result reference).

    Raises
    ------
    fickcam.errors.SceneError
        When the scene does not validate.
    fickcam.errors.SolverError
        When a diffusion solve fails (a linear solve or a concentration-dependent
        step does not converge). A part whose service temperature reaches its wet glass
        transition temperature is not an error: a notice says so, and that part's later
        values are NaN.
    """
    # deferred: keeps numpy, pydantic, yaml off the start-up path
    from .simulation.simulate import run as _run

    return _run(scene, accuracy=accuracy, progress=progress, settings=settings, cache=cache)


def compensate(scene, *, at=None, over=None, accuracy: float | None = None,
               keep_limits: bool = False, points: bool = False):
    """The dry dimensions to make so that the mechanism has its design geometry at ageing
    time ``at`` ("60 d") or stays closest to it over ``over`` = (T1, T2); ``keep_limits``
    (with ``at``): if that breaks one of the scene's limits from delivery to the end of the
    history, made for that whole life instead; ``points``: a parametric cam made as points.
    Returns a ``Compensation`` (``.made``,
    ``.iterations``, ``.residual``, ``.before`` and ``.after``: the runs of the design and
    of the made scene; its table, report and written scene come from
    ``fickcam.compensation.dimension_table``, ``report`` and ``write_scene``).

    Parameters
    ----------
    scene : str, pathlib.Path, dict or Scene
        The design, as :func:`load_scene` takes it.
    at : str or float, optional
        The ageing time [s] at which the mechanism must have its design geometry: a
        duration with units ("60 d") or seconds as a number (a bare number is judged as a
        scene's ageing time is: ``45`` is refused with '45 d' suggested).
    over : tuple of (str or float), optional
        The window (T1, T2) [s] over which the largest deviation is made smallest
        (durations with units, or seconds); exactly one of ``at`` and ``over``.
    accuracy : float, optional
        The diffusion's relative accuracy [-]; None: the scene's.
    keep_limits : bool
        With ``at``: when the made mechanism breaks a limit of the scene between
        delivery and the end of the history, compensate over that whole life instead.
    points : bool
        Make a cam given by its motion-law parameters as a cam given by points.

    Returns
    -------
    fickcam.compensation.Compensation
        The made dimensions and the runs before and after.

    Raises
    ------
    fickcam.errors.InputError
        When ``at`` and ``over`` are both given or both missing, a time is outside the
        scene's history, or ``keep_limits`` is given without ``at``.
    fickcam.errors.SceneError
        When the scene does not validate.
    """
    # deferred: keeps numpy, yaml off the start-up path
    from .compensation import compensate as _compensate

    return _compensate(scene, at=at, over=over, accuracy=accuracy, keep_limits=keep_limits,
                       points=points)


def save(dataset, path):
    """Write a result atomically (temporary file in the target folder, then rename).

    Parameters
    ----------
    dataset : xarray.Dataset
        A result of :func:`run` (or a selection of its variables).
    path : str or pathlib.Path
        The netCDF-4 (HDF5) file to write; its folder is created when missing.

    Returns
    -------
    pathlib.Path
        The path written.
    """
    # deferred: keeps the command's modules off the start-up path
    from .results.store import save as _save

    return _save(dataset, path)


def open_result(path):
    """Open a result file written by :func:`~fickcam.save` as an xarray.Dataset.

    Parameters
    ----------
    path : str or pathlib.Path
        The result file.

    Returns
    -------
    xarray.Dataset
        The result, loaded into memory, ``time`` in days [d].

    Raises
    ------
    fickcam.errors.InputError
        When the file is missing or is not a fickcam result.
    """
    # deferred: keeps the command's modules off the start-up path
    from .results.store import open_result as _open

    return _open(path)


def fit_weight_gain(data, matrix: str, **options):
    """Calibrate D0, Ea, a, b from ASTM D5229 weight-gain data (a CSV path); see
    :func:`fickcam.fit_weight_gain` for the options.

    Parameters
    ----------
    data : str or pathlib.Path
        The weight-gain CSV (see the materials guide for its columns).
    matrix : str
        The library matrix material the coupons are made of (its activation energy and
        humidity exponent stand in when the data hold one condition only).
    **options
        ``fiber``, ``fiber_volume_fraction`` and ``name``, passed to
        :func:`fickcam.fit_weight_gain`.

    Returns
    -------
    fickcam.fit.report.FitReport
        The fitted parameters with their 95 % intervals, per coupon and per condition.
    """
    # deferred: keeps numpy, scipy, scipy.optimize off the start-up path
    from .fit import fit_weight_gain as _fit

    return _fit(data, matrix, **options)
