"""What a diffusion solve plans (``Plan``) and returns (``DiffusionResult``)."""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Callable

import numpy as np

@dataclass(frozen=True)
class Plan:
    """What ``solve`` will do for one part (printed by ``fickcam check``).

    Parameters
    ----------
    model : str
        The model chosen.
    cells : int
        Its cells [-] (0 for a series).
    steps : int
        Its time steps [-] (0 for a series).
    reason : str
        Why this model, these cells and steps.
    error_estimate : float
        The estimated error [-], a fraction of the moisture swing.
    cells_per_axis : tuple of int
        The cells along each axis [-], where the mesh is a grid.
    steps_per_doubling : int
        Time steps per doubling of the (rescaled) time [-].
    expansion_tolerance : float
        Plane model: the short-time expansion's error allowance [-].
    finest : float
        Graded meshes: the finest spacing at the exposed faces, in units of the
        thickness [-]; 0 for a uniform grid.
    growth : float
        Graded meshes: the growth per cell away from the exposed faces [-].
    """

    model: str
    cells: int
    steps: int
    reason: str
    error_estimate: float
    cells_per_axis: tuple[int, ...] = ()
    steps_per_doubling: int = 0
    expansion_tolerance: float = 0.0  # plane: the short-time expansion's error allowance
    finest: float = 0.0      # graded meshes: finest spacing at the exposed faces/outline
    #                          (scaled units, thickness = 1); 0 for a uniform grid
    growth: float = 0.0      # graded meshes: growth per cell/row away from them


@dataclass(frozen=True)
class DiffusionResult:
    """Moisture of one part at the requested times (weight %), frozen at construction (a
    changed result is a new one, ``dataclasses.replace``).

    Parameters
    ----------
    times : numpy.ndarray
        The times [s].
    mean : numpy.ndarray
        The part's mean moisture at ``times`` [weight %].
    surface : numpy.ndarray
        The contact layer's mean moisture at ``times`` [weight %].
    model : str
        The model that solved.
    cells, steps : int
        Its cells and time steps [-].
    error_estimate : float
        The estimated error [-], a fraction of the moisture swing.
    reason : str
        Why this model.
    fields : numpy.ndarray, optional
        The moisture of every cell at every time [weight %], when asked for.
    bound : numpy.ndarray, optional
        Two-phase (Langmuir) sorption: the bound-water mean [weight %].
    cell_coordinates : dict of str to numpy.ndarray
        The cells' centres [m] per axis, with ``fields``.
    planform : fickcam.diffusion.planform.triangles.Triangulation, optional
        The plane model's triangle mesh [m], with ``fields``: the P1 field lives on its
        nodes, those off the outline carrying ``fields`` in order, those on it held at the
        surface value.
    extend : callable, optional
        ``extend(at)`` [s]: this result with rows at ``at`` added (a new result).
    """

    times: np.ndarray
    mean: np.ndarray
    surface: np.ndarray
    model: str
    cells: int
    steps: int
    error_estimate: float
    reason: str
    fields: np.ndarray | None = None
    bound: np.ndarray | None = None  # two-phase (Langmuir) sorption: bound-water mean, weight %
    cell_coordinates: dict[str, np.ndarray] = field(default_factory=dict)
    planform: object | None = field(default=None, repr=False)
    #: ``extend(at)``: this result at its times and ``at`` (inside their span) together,
    #: the new rows from the stored solve's plan and tables (the limit search); None where
    #: only a new solve can say
    extend: Callable[[np.ndarray], "DiffusionResult"] | None = field(default=None, repr=False)

    def merged(self, times, mean, surface, bound=None) -> "DiffusionResult":
        """This result with rows at ``times`` (none of its own) added, in time order (no
        fields: what ``extend`` gives; bound moisture where this result and ``bound`` give it)."""
        order = np.argsort(np.concatenate([self.times, times]), kind="stable")

        def rows(old, new):
            return np.concatenate([old, np.asarray(new, float)])[order]
        both = self.bound is not None and bound is not None
        return replace(self, times=rows(self.times, times), mean=rows(self.mean, mean),
                       surface=rows(self.surface, surface), fields=None,
                       bound=rows(self.bound, bound) if both else None, extend=None,
                       planform=None)

