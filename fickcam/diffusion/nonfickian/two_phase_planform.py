"""The two-phase (Langmuir-type) planform of a CamPlate or LinkBar: the planform mesh
refined from the two-phase histories it measures, and the exact modal march on it.

The plan sizes a first mesh from the error model (``planform_modes.first_planform_mesh``),
then refines it until the histories of the mean, bound and contact-layer moisture on two
meshes agree within ``PLANFORM_SHARE`` of the accuracy (``planform_modes.refined_planform``);
the refinement is kept in the run's cache, so that the solve (and ``fickcam check``) use
the mesh the plan measured and a run pays for it once. The march in time takes the rest
of the accuracy. ``langmuir_modes`` solves a two-phase problem on the exact modes of a
separable part or on this refined planform.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..accuracy.budget import LAYER_TOLERANCE, PLANFORM_SHARE
from ..forcing.clock import RescaledTime
from ..forcing.clock import scales as scales_of
from ..problem.cache import RunCache
from ..problem.definition import DiffusionProblem
from ..problem.exposure import swing
from ..problem.results import DiffusionResult, Plan
from ..problem.sorption import describe
from ..stepping.step_plans import earliest_output
from .planform_modes import (PlanformMeasure, RefinedPlanform, Refinement, first_planform_mesh,
                             lanczos_spectrum, planform_operator, planform_source,
                             refined_planform)
from .two_phase_modes import langmuir_history


def plan_two_phase_planform(problem: DiffusionProblem, refinement: Refinement,
                            cache: RunCache) -> Plan:
    """The planform mesh the solve will use: the first mesh from the error model, refined
    from the two-phase histories it measures (``refined``, kept for the solve, so that
    ``fickcam check`` shows the refined mesh and a run pays for it once).

    Parameters
    ----------
    problem : DiffusionProblem
        A two-phase problem of a planform part, its contact layer given (lengths [m],
        times [s], accuracy [-]).
    refinement : Refinement
        The refinement's limits (``SolverSettings.planform``).
    cache : RunCache
        The run's cache, which keeps the refinement for the solve.

    Returns
    -------
    Plan
        The refined mesh's cells and the error estimate [-] (mesh and march).
    """
    first, refined = planform_refinement(problem, refinement, cache)
    _, estimate = refined.result
    capped = ("" if refined.error <= PLANFORM_SHARE * problem.accuracy else
              f"; capped at {refinement.cap} cells: error above the requested accuracy")
    return Plan("plane", refined.cells, 0, f"{describe(problem.sorption)}: the planform's FiPy "
                f"operator (first mesh {first.note}, about {int(np.prod(first.cells))} cells; "
                f"refined from the two-phase histories on {refined.levels} meshes to "
                f"{refined.cells} cells), its decay seen by the mean and layer as a "
                f"{refined.steps}-point shift-invert Lanczos quadrature, x the exact sheet "
                "modes, each a 2x2 free/bound system advanced exactly through the history"
                f"{capped}", estimate + refined.error, (refined.cells,),
                finest=refined.finest, growth=refined.growth)


def planform_refinement(problem: DiffusionProblem, refinement: Refinement, cache: RunCache):
    """(first mesh, ``_refined``) of a two-phase CamPlate or LinkBar, the refinement kept in
    the run's ``cache``: ``plan`` and ``solve`` share it.

    Parameters
    ----------
    problem : DiffusionProblem
        The two-phase problem (lengths [m], times [s], accuracy [-]).
    refinement : Refinement
        The refinement's limits.
    cache : RunCache
        The run's cache.

    Returns
    -------
    tuple
        The first mesh's ``sizing.Layout`` and the ``RefinedPlanform``.
    """
    geometry, diffusivity, exposure = problem.geometry, problem.diffusivity, problem.exposure
    scales = scales_of(geometry, diffusivity, exposure, cache)
    t_lo = earliest_output(scales.tau_star(exposure.change_times), scales.tau_star(problem.times))
    first = first_planform_mesh(geometry, diffusivity.pre_exponential, problem.accuracy, t_lo)
    key = ("two-phase planform refinement", geometry, diffusivity, exposure,
           problem.times.tobytes(), problem.accuracy, problem.sorption,
           problem.surface_layer_depth, first.finest, first.growth, refinement)
    return first, cache.get(key, lambda: _refined(problem, first.finest, first.growth,
                                                  refinement, cache))


def _refined(problem: DiffusionProblem, finest, growth, refinement: Refinement,
             cache: RunCache) -> RefinedPlanform:
    """``planform_modes.refined_planform`` of the two-phase history (the march on each mesh,
    most of whose cost is the planform operators): its mesh error is ``PLANFORM_SHARE`` of
    the accuracy, the march the rest."""
    geometry, diffusivity, exposure = problem.geometry, problem.diffusivity, problem.exposure
    times, accuracy, depth = problem.times, problem.accuracy, problem.surface_layer_depth
    share, scale = PLANFORM_SHARE * accuracy, 1.0 / max(swing(exposure), 1e-300)

    def measure(source):
        history, estimate = langmuir_history(geometry, diffusivity, problem.sorption, exposure,
                                             times, accuracy - share, depth, source)
        compared = [history["mean"], history["bound"], history["surface"] / LAYER_TOLERANCE]
        return np.stack(compared) * scale, (history, estimate)

    ages = read_ages(RescaledTime(diffusivity, exposure), exposure, times)
    task = PlanformMeasure(geometry, diffusivity.pre_exponential, depth, ages, share, measure)
    return refined_planform(task, finest, growth, refinement, cache)


def langmuir_modes(problem: DiffusionProblem, chosen: Plan, refinement: Refinement,
                    cache: RunCache):
    """The exact two-phase modal march; for a CamPlate or LinkBar on its planform's
    quadrature (``planform_modes``), the histories of the plan's refined mesh (``_refined``,
    from the run's ``cache``).

    Parameters
    ----------
    problem : DiffusionProblem
        The two-phase problem, its contact layer given (lengths [m], times [s],
        accuracy [-]).
    chosen : Plan
        Its plan (``plane``: on the refined planform; else the part's exact modes).
    refinement : Refinement
        The refinement's limits.
    cache : RunCache
        The run's cache, holding the plan's refinement.

    Returns
    -------
    DiffusionResult
        Mean, contact-layer and bound moisture [weight %] at the problem's times, with an
        ``extend`` for the limit search's extra times.
    """
    geometry, diffusivity, exposure = problem.geometry, problem.diffusivity, problem.exposure
    times, accuracy, depth = problem.times, problem.accuracy, problem.surface_layer_depth
    if chosen.model != "plane":
        history, estimate = langmuir_history(geometry, diffusivity, problem.sorption, exposure,
                                             times, accuracy, depth)
        return _langmuir_result(times, history, estimate, chosen)
    _, refined = planform_refinement(problem, refinement, cache)
    history, _ = refined.result
    stored = _langmuir_result(times, history, chosen.error_estimate, chosen)
    source = planform_source(geometry, diffusivity.pre_exponential, lanczos_spectrum(
        planform_operator(geometry, diffusivity.pre_exponential, depth, refined.finest,
                          refined.growth, cache), refined.steps))

    def extend(at) -> DiffusionResult:
        """The limit search's extra times on this refined mesh (no new refinement): the
        march through the stored and new times together, the new rows kept."""
        new = np.setdiff1d(np.asarray(at, float), times)
        both = np.union1d(times, new)
        extra, _ = langmuir_history(geometry, diffusivity, problem.sorption, exposure, both,
                                    (1.0 - PLANFORM_SHARE) * accuracy, depth, source)
        rows = np.searchsorted(both, new)
        return stored.merged(new, extra["mean"][rows], extra["surface"][rows],
                             extra["bound"][rows])
    return replace(stored, extend=extend)


def _langmuir_result(times, history, estimate, chosen) -> DiffusionResult:
    """The result of a two-phase modal history (a planform's: read-only, kept in the run's
    cache with its refinement for the next plan and solve)."""
    return DiffusionResult(times, history["mean"], history["surface"], chosen.model,
                           chosen.cells, 0, estimate, chosen.reason, bound=history["bound"])


def read_ages(clock, exposure, times, most: int = 256) -> np.ndarray:
    """Rescaled ages (s) the outputs read after each change of the exposure (at most
    ``most``, spread over their range, the least and largest kept).

    Parameters
    ----------
    clock : callable
        Wall time [s] -> rescaled time [s] (the Arrhenius-weighted clock of the exposure).
    exposure : Exposure
        The surface history; its ``change_times`` [s] start each age.
    times : array_like
        The output times [s].
    most : int
        The most ages returned [-].

    Returns
    -------
    numpy.ndarray
        The sorted, distinct, positive rescaled ages [s] of every output after every change.
    """
    changes = clock(np.asarray(exposure.change_times, float))
    ages = np.subtract.outer(clock(np.asarray(times, float)), changes).ravel()
    ages = np.unique(ages[ages > 0])
    if ages.size > most:
        ages = ages[np.unique(np.linspace(0, ages.size - 1, most).astype(int))]
    return ages
