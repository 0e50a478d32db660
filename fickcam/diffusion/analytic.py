"""The ``analytic`` model: Crank's exact step responses (``exact``) superposed over the
history in rescaled time (``duhamel``), for the Sheet, the Bar and the solid Disc."""
from __future__ import annotations

import numpy as np

from .duhamel import duhamel
from .exact import saturation_tau, step_field, step_response
from .geometry import Bar, Disc, Sheet
from .modal import modal_history
from .results import DiffusionResult, Plan


def exact_history(geometry, diffusivity, exposure, times, surface_layer_depth=5e-4):
    """Volume-mean and contact-layer-mean moisture (weight %) at ``times`` (s)
    for any ``Exposure`` of a part with an exact step response."""
    d0 = diffusivity.pre_exponential

    def kernel(tau):
        mean, layer = step_response(geometry, d0, tau, surface_layer_depth)
        return np.stack([mean, layer], axis=-1)

    result = (duhamel(kernel, diffusivity, exposure, times, saturation_tau(geometry, d0))
              + exposure.initial_moisture)
    return {"mean": result[:, 0], "surface": result[:, 1]}


def exact_history_field(geometry, diffusivity, exposure, times, points):
    """Moisture (weight %) at ``points`` (see ``exact.step_field``), shape
    (n_times, n_points)."""
    d0 = diffusivity.pre_exponential
    n_points = np.asarray(next(iter(points.values()))).size

    def kernel(tau):
        return step_field(geometry, d0, tau.ravel(), points).reshape(tau.shape + (n_points,))

    return duhamel(kernel, diffusivity, exposure, times, saturation_tau(geometry, d0),
                   chunk=8) + exposure.initial_moisture


def solve_analytic(geometry, diffusivity, exposure, times, depth, store_fields,
                   chosen: Plan, modal_accuracy: float | None = None) -> DiffusionResult:
    """The exact mean and contact-layer history (and fields on request); with
    ``modal_accuracy`` the modes are marched through the record (``modal``) and the
    result carries that march's error bound."""
    estimate = chosen.error_estimate
    if modal_accuracy is None:
        history = exact_history(geometry, diffusivity, exposure, times, surface_layer_depth=depth)
    else:
        history, estimate = modal_history(geometry, diffusivity, exposure, times, modal_accuracy,
                                          surface_layer_depth=depth)
    mean, surface = history["mean"], history["surface"]
    result = DiffusionResult(times, np.asarray(mean, float), np.asarray(surface, float),
                             "analytic", 0, 0, estimate, chosen.reason)
    if store_fields:
        fields, coordinates = _analytic_fields(geometry, diffusivity, exposure, times, depth)
        result.fields, result.cell_coordinates = fields, coordinates
        result.cells = fields.shape[1]
    return result


FIELD_POINTS = {Sheet: (40,), Disc: (24, 12), Bar: (16, 12, 8)}  # cell centres for exact fields


def _analytic_fields(geometry, diffusivity, exposure, times, depth):
    """Exact fields at the centres of a structured grid (``FIELD_POINTS`` cells per axis);
    cell_x/y/z are the coordinates (a Disc: x = r)."""
    def centres(length, count):
        return (np.arange(count) + 0.5) * length / count

    counts = FIELD_POINTS[type(geometry)]
    if isinstance(geometry, Sheet):
        axes = {"z": centres(geometry.thickness, counts[0])}
    elif isinstance(geometry, Disc):
        axes = {"r": centres(geometry.outer_radius, counts[0]),
                "z": centres(geometry.thickness, counts[1])}
    else:
        axes = {"x": centres(geometry.length, counts[0]), "y": centres(geometry.width, counts[1]),
                "z": centres(geometry.thickness, counts[2])}
    grids = np.meshgrid(*axes.values(), indexing="ij")
    points = {name: grid.ravel() for name, grid in zip(axes, grids)}
    fields = np.asarray(exact_history_field(geometry, diffusivity, exposure, times, points), float)
    coordinates = {("x" if name == "r" else name): values for name, values in points.items()}
    return fields, coordinates

