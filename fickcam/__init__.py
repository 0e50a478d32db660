"""fickcam: moisture uptake in polymer and composite cams, followers and
four-bar linkages, and how the mechanisms drift out of spec as they age.

``import fickcam`` is light: FiPy, matplotlib and dask are imported only by
the modules that need them.
"""
from __future__ import annotations

from ._version import __version__

__all__ = ["load_scene", "run", "save", "open_result", "compensate", "fit_weight_gain",
           "__version__"]


def load_scene(source, *, file_name: str | None = None):
    """Read and validate a scene from a YAML path or a dict; values in SI after validation."""
    from .scene import load_scene as _load

    return _load(source, file_name=file_name)


def run(scene, *, accuracy: float | None = None, progress: bool = False, settings=None):
    """Run one scene (a path, a dict or a loaded scene) and return an xarray.Dataset;
    ``settings``: the diffusion solvers' tuned limits (``fickcam.diffusion.SolverSettings``,
    e.g. its cell caps; None: the defaults)."""
    from .simulate import run as _run

    return _run(scene, accuracy=accuracy, progress=progress, settings=settings)


def compensate(scene, *, at=None, over=None, accuracy: float | None = None,
               keep_limits: bool = False, points: bool = False):
    """The dry dimensions to make so that the mechanism has its design geometry at ageing
    time ``at`` ("60 d") or stays closest to it over ``over`` = (T1, T2); ``keep_limits``
    (with ``at``): if that breaks one of the scene's limits from delivery to the end of the
    history, made for that whole life instead; ``points``: a parametric cam made as points.
    Returns a ``Compensation`` (``.made``,
    ``.iterations``, ``.residual``, ``.before`` and ``.after``: the runs of the design and
    of the made scene; its table, report and written scene come from
    ``fickcam.compensation.dimension_table``, ``report`` and ``write_scene``)."""
    from .compensation import compensate as _compensate

    return _compensate(scene, at=at, over=over, accuracy=accuracy, keep_limits=keep_limits,
                       points=points)


def save(dataset, path):
    """Write a result atomically (temporary file in the target folder, then rename)."""
    from .store import save as _save

    return _save(dataset, path)


def open_result(path):
    """Open a result file written by :func:`save` as an xarray.Dataset."""
    from .store import open_result as _open

    return _open(path)


def fit_weight_gain(data, matrix: str, **options):
    """Calibrate D0, Ea, a, b from ASTM D5229 weight-gain data (a CSV path); see
    :func:`fickcam.fit.fit_weight_gain` for the options."""
    from .fit import fit_weight_gain as _fit

    return _fit(data, matrix, **options)
