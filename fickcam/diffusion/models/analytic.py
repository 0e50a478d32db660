"""The ``analytic`` model: Crank's exact step responses (``exact``) superposed over the
history in rescaled time, for the Sheet, the Bar and the solid Disc: by Duhamel's panels
(``duhamel``) over a few segments, by the tabulated sum (``tabulated``, cost linear in
the rows) over a long record."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..exact.separable import saturation_tau, step_field, step_response
from ..problem.cache import RunCache, run_cache
from ..problem.definition import DiffusionProblem
from ..problem.geometry import LAYER_DEPTH
from ..problem.results import DiffusionResult, Plan
from ..superposition.duhamel import duhamel
from ..superposition.tabulated import LongRecord


def _mean_and_layer(geometry, d0, depth):
    def kernel(tau):
        mean, layer = step_response(geometry, d0, tau, depth)
        return np.stack([mean, layer], axis=-1)
    return kernel


def _at_points(geometry, d0, points):
    n_points = np.asarray(next(iter(points.values()))).size

    def kernel(tau):
        return step_field(geometry, d0, tau.ravel(), points).reshape(tau.shape + (n_points,))
    return kernel


def exact_history(geometry, diffusivity, exposure, times, surface_layer_depth=LAYER_DEPTH,
                  cache: RunCache | None = None):
    """Volume-mean and contact-layer-mean moisture (weight %) at ``times`` (s)
    for any ``Exposure`` of a part with an exact step response (``cache``: the run's).

    Parameters
    ----------
    geometry : Sheet, Bar or Disc
        A part with a separable exact step response, its lengths in [m].
    diffusivity : Diffusivity
        D(T) = D0 exp(-Ea/(R T)) [m^2/s].
    exposure : Exposure
        The surface history: temperature [K] and surface moisture [weight %].
    times : numpy.ndarray
        The output times [s], shape (n_times,).
    surface_layer_depth : float
        The depth of the contact layer whose mean is returned as ``surface`` [m].
    cache : RunCache, optional
        The run's cache of step-response tables; None: a fresh one.

    Returns
    -------
    dict
        ``mean`` and ``surface``: the volume mean and the contact-layer mean [weight %],
        each shape (n_times,).

    References
    ----------
    Crank, J., *The Mathematics of Diffusion*, 2nd ed., Oxford University Press, 1975
    (the step responses; superposed by Duhamel's theorem, see ``superposition.duhamel``).
    """
    d0 = diffusivity.pre_exponential
    result = (duhamel(_mean_and_layer(geometry, d0, surface_layer_depth), diffusivity, exposure,
                      times, saturation_tau(geometry, d0), cache=cache)
              + exposure.initial_moisture)
    return {"mean": result[:, 0], "surface": result[:, 1]}


def exact_history_field(geometry, diffusivity, exposure, times, points,
                        cache: RunCache | None = None):
    """Moisture (weight %) at ``points`` (see ``separable.step_field``), shape
    (n_times, n_points).

    Parameters
    ----------
    geometry : Sheet, Bar or Disc
        The part, a Sheet, Bar or solid Disc [m].
    diffusivity : Diffusivity
        Its Arrhenius D(T) [m^2/s]; D0 sets the step response.
    exposure : Exposure
        Temperature [K] and surface moisture [weight %] over time.
    times : numpy.ndarray
        When to read the field [s], shape (n_times,).
    points : dict of str to numpy.ndarray
        The points' coordinates [m] by axis name (``z``; ``r``, ``z``; ``x``, ``y``, ``z``).
    cache : RunCache, optional
        The run's cache; None: a fresh one.

    Returns
    -------
    numpy.ndarray
        The moisture [weight %] at each point, shape (n_times, n_points).
    """
    d0 = diffusivity.pre_exponential
    return duhamel(_at_points(geometry, d0, points), diffusivity, exposure, times,
                   saturation_tau(geometry, d0), chunk=8, cache=cache) + exposure.initial_moisture


def record_history(geometry, diffusivity, exposure, times, accuracy,
                   surface_layer_depth=LAYER_DEPTH, cache: RunCache | None = None):
    """``exact_history`` over a long record by the tabulated sum, with its error estimate
    (relative to the record's largest swing |Ms - M0|, as ``accuracy`` is) and the
    ``LongRecord`` the fields reuse.

    Parameters
    ----------
    geometry : Sheet, Bar or Disc
        A part with Crank's exact series (lengths [m]).
    diffusivity : Diffusivity
        The diffusivity D0 exp(-Ea / (R T)) [m^2/s].
    exposure : Exposure
        The long record of temperature [K] and surface moisture [weight %].
    times : numpy.ndarray
        Output times [s] within the record.
    accuracy : float
        The relative accuracy [-] the tabulated sum is sized for.
    surface_layer_depth : float
        The contact layer's depth [m].
    cache : RunCache, optional
        The run's cache; None: a fresh one.

    Returns
    -------
    history : dict
        ``mean`` and ``surface`` [weight %], each shape (n_times,).
    error : float
        The sum's error estimate [-], relative to the record's largest swing.
    record : LongRecord
        The tabulated record, reused for the fields.
    """
    d0 = diffusivity.pre_exponential
    record = LongRecord.of(diffusivity, exposure, times, saturation_tau(geometry, d0)[0],
                           accuracy, run_cache(cache))
    values, error, _ = record.superpose(_mean_and_layer(geometry, d0, surface_layer_depth))
    values = values + exposure.initial_moisture
    return {"mean": values[:, 0], "surface": values[:, 1]}, error, record


def solve_analytic(problem: DiffusionProblem, chosen: Plan, record_accuracy: float | None = None,
                   cache: RunCache | None = None) -> DiffusionResult:
    """The exact mean and contact-layer history (and fields on request) of a ``problem``;
    with ``record_accuracy`` (a long record) by the tabulated sum, and the result carries
    its error estimate; ``cache``: the run's.

    Parameters
    ----------
    problem : DiffusionProblem
        The part [m], D(T) [m^2/s], exposure, times [s] and contact-layer depth [m].
    chosen : Plan
        The plan (its reason and error estimate [-] are carried to the result).
    record_accuracy : float, optional
        The relative accuracy [-] of the tabulated sum over a long record; None: Duhamel's
        panels over the few segments.
    cache : RunCache, optional
        The run's cache; None: a fresh one.

    Returns
    -------
    DiffusionResult
        The mean and contact-layer moisture [weight %] at the times, fields when the
        problem stores them (at a structured grid's cell centres [m]).
    """
    geometry, diffusivity, exposure = problem.geometry, problem.diffusivity, problem.exposure
    times, depth = problem.times, problem.surface_layer_depth
    estimate, record = chosen.error_estimate, None
    if record_accuracy is None:
        history = exact_history(geometry, diffusivity, exposure, times, depth, cache)
    else:
        history, estimate, record = record_history(geometry, diffusivity, exposure, times,
                                                   record_accuracy, depth, cache)
    mean, surface = history["mean"], history["surface"]
    fields, coordinates = (_analytic_fields(geometry, diffusivity, exposure, times, record, cache)
                           if problem.store_fields else (None, {}))
    result = DiffusionResult(times, np.asarray(mean, float), np.asarray(surface, float),
                             "analytic", 0 if fields is None else fields.shape[1], 0, estimate,
                             chosen.reason, fields=fields, cell_coordinates=coordinates)
    if record is not None or problem.store_fields:
        return result

    def extend(at) -> DiffusionResult:
        """The result at its times and ``at`` together (the limit search's): Duhamel's sum
        at each new time is its own, and the plan does not depend on the times."""
        new = np.setdiff1d(np.asarray(at, float), times)
        if not new.size:
            return replace(result, extend=None)
        extra = exact_history(geometry, diffusivity, exposure, new, depth, cache)
        return result.merged(new, extra["mean"], extra["surface"])
    return replace(result, extend=extend)


FIELD_POINTS = {"sheet": (40,), "disc": (24, 12), "box": (16, 12, 8)}  # by ``exact_route``:
#   cell centres for exact fields


def _analytic_fields(geometry, diffusivity, exposure, times, record, cache):
    """Exact fields at the centres of a structured grid (``FIELD_POINTS`` cells per axis);
    cell_x/y/z are the coordinates (a Disc: x = r)."""
    def centres(length, count):
        return (np.arange(count) + 0.5) * length / count

    counts = FIELD_POINTS[geometry.exact_route]
    if geometry.exact_route == "sheet":
        axes = {"z": centres(geometry.thickness, counts[0])}
    elif geometry.exact_route == "disc":
        axes = {"r": centres(geometry.outer_radius, counts[0]),
                "z": centres(geometry.thickness, counts[1])}
    else:
        axes = {"x": centres(geometry.length, counts[0]), "y": centres(geometry.width, counts[1]),
                "z": centres(geometry.thickness, counts[2])}
    grids = np.meshgrid(*axes.values(), indexing="ij")
    points = {name: grid.ravel() for name, grid in zip(axes, grids)}
    if record is None:
        fields = exact_history_field(geometry, diffusivity, exposure, times, points, cache)
    else:
        kernel = _at_points(geometry, diffusivity.pre_exponential, points)
        fields = record.field(kernel) + exposure.initial_moisture
    coordinates = {("x" if name == "r" else name): values for name, values in points.items()}
    return fields, coordinates

