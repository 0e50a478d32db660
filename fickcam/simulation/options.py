"""What a run asks of every diffusion solve, as one frozen value built once per run.

:class:`RunOptions` gathers the scene's ``diffusion:`` section (its model, per part or for
all, and the depth of the contact layer), the accuracy (the caller's in place of the
scene's), the solvers' tuned limits and the run's cache. A run builds it once and passes it
whole to the plans, the solves, the limit search, compensation and the sweeps' cases, each
of which asks it for a part's :class:`~fickcam.diffusion.problem.definition.DiffusionProblem`.
"""
from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType
from typing import Mapping

from ..diffusion import DiffusionProblem, RunCache, SolverSettings, run_cache
from ..diffusion.accuracy.budget import check_accuracy


@dataclass(frozen=True)
class RunOptions:
    """The diffusion options of one run.

    Parameters
    ----------
    accuracy : float
        The relative accuracy asked of each part's mean moisture [-], a fraction of the
        moisture swing.
    model : str or mapping of str to str
        The diffusion model of every part, or one per part name (parts not named: ``auto``).
    surface_layer_depth : float
        The depth of the contact layer whose mean moisture is the surface's [m].
    settings : fickcam.diffusion.SolverSettings
        The solvers' tuned limits.
    cache : fickcam.diffusion.RunCache
        What the run's plans and solves build once and share (its limit search too).
    """

    accuracy: float
    model: str | Mapping[str, str]
    surface_layer_depth: float
    settings: SolverSettings
    cache: RunCache

    @classmethod
    def for_scene(cls, scene, accuracy: float | None = None,
                  settings: SolverSettings | None = None,
                  cache: RunCache | None = None) -> "RunOptions":
        """The options of a run of ``scene``: its ``diffusion:`` section, with the caller's
        accuracy, settings and cache where given.

        Parameters
        ----------
        scene : fickcam.scene.load.Scene
            The loaded scene.
        accuracy : float, optional
            Relative accuracy of the diffusion [-] in place of the scene's, in (0, 0.1]
            (``check_accuracy``); None: the scene's.
        settings : SolverSettings, optional
            The solvers' tuned limits; None: the defaults.
        cache : RunCache, optional
            The run's cache; None: a fresh one.

        Returns
        -------
        RunOptions
            The options, frozen.
        """
        section = scene.model.diffusion
        model = section.model
        return cls(accuracy=section.accuracy if accuracy is None else check_accuracy(accuracy),
                   model=MappingProxyType(dict(model)) if isinstance(model, dict) else model,
                   surface_layer_depth=section.surface_layer_depth,
                   settings=SolverSettings() if settings is None else settings,
                   cache=run_cache(cache))

    def model_for(self, part: str) -> str:
        """The diffusion model asked for the part named ``part``.

        Parameters
        ----------
        part : str
            The part's name.

        Returns
        -------
        str
            A name of ``fickcam.diffusion.MODELS`` (``auto`` where the scene names none).
        """
        return self.model.get(part, "auto") if isinstance(self.model, Mapping) else self.model

    def problem(self, part, exposure, times, store_fields: bool = False) -> DiffusionProblem:
        """The diffusion problem of ``part`` under ``exposure`` at ageing ``times``.

        Parameters
        ----------
        part : fickcam.mechanisms.part.Part
            The part (its diffusion geometry [m] and material).
        exposure : fickcam.diffusion.Exposure
            Its surface history (temperature [K], surface moisture [weight %]).
        times : numpy.ndarray
            The ageing times [s].
        store_fields : bool
            Whether the moisture field is kept at each time.

        Returns
        -------
        DiffusionProblem
            The problem, with this run's accuracy, model and contact layer.
        """
        return DiffusionProblem(part.geometry, part.material.diffusivity_for(part.geometry),
                                exposure, times, self.accuracy, self.model_for(part.name),
                                self.surface_layer_depth, store_fields, part.name,
                                part.material.sorption_law())
