"""Calibrate a material's moisture parameters from ASTM D5229 weight-gain data.

``fit_weight_gain(csv, matrix=...)`` returns a :class:`~fickcam.fit.report.FitReport` (a dataclass;
``.to_dataset()`` gives an xarray Dataset); ``materials_yaml`` writes the
scene-ready ``materials:`` block, ``parameter_table`` the printed table,
``plot_fit`` the figure (matplotlib is imported only when it draws).
"""
from .data import Specimen, read_weight_gain
from .output import materials_yaml, parameter_table
from .report import FitReport, fit_weight_gain


def plot_fit(report, path=None, save=None):
    """Moisture gain vs sqrt(time) per condition with the fitted curves and residuals.

    Parameters
    ----------
    report : FitReport
        A fit (:func:`~fickcam.fit_weight_gain`).
    path : str or pathlib.Path, optional
        The figure file to write (PNG unless its suffix names another format); None: the
        figure is only returned.
    save : callable, optional
        ``save(fig, path) -> path`` writes the figure; default
        :func:`~fickcam.plotting.common.save_figure` (atomic).

    Returns
    -------
    fickcam.plotting.Figures
        The one figure, shown inline in a notebook; ``.paths``: the file written.
    """
    # deferred: keeps the command's modules off the start-up path
    from .plot import plot_fit as _plot

    return _plot(report, path, save)


__all__ = ["FitReport", "Specimen", "fit_weight_gain", "materials_yaml", "parameter_table",
           "plot_fit", "read_weight_gain"]
