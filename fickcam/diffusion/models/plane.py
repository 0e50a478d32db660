"""The ``plane`` model of prismatic parts (CamPlate, LinkBar): a 2-D problem of the
outline times the through-thickness sheet.

For a prism whose every surface holds the same value g and which starts
uniform at c0, the unsaturated fraction u = (g - c)/(g - c0) of a unit step
is the product u_plane(x, y, tau) u_sheet(z, tau) (Crank 1975, §4.3.4,
eq. 4.51 for a rectangular block; the argument is the same for any planform
because the Laplacian separates). A history is then the Duhamel sum over the
surface history in rescaled time (``duhamel``; Crank 1975 §4.2.1, eq. 4.34): Duhamel's
panels for a few segments, the tabulated sum over a long record (``tabulated``), and a
stored solve read at more times (the limit search: ``extension`` over a record,
``PanelExtension`` over panels), all in ``PrismSuperposition``.

The planform's unit-step response comes from the exact short-time expansion of
the outline (``short_time``) up to a switch time and from P1 finite elements on
a triangle mesh graded from the outline after it (``triangles``, ``p1``). ``plan_plane``
sizes that mesh and the time steps with the error model the blend reports, so
``fickcam check`` shows the error ``solve`` will estimate. The errors are
measured against the exact product of three sheets (rectangle), the finite
cylinder, the annulus series (plate with a bore) and space-extrapolated fine
meshes (the demo cam) in tests/test_diffusion_plane.py.

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass, replace

import numpy as np

from ..accuracy.budget import (EXPANSION_SHARE, LAYER_TOLERANCE, PLANE_PLAN_MARGIN,
                               PLANE_TIME_SHARE, RECORD_SHARE)
from ..accuracy.error_model import (FIRST_STEP, GROWTH_REACH, MAX_CELLS, MESH_ERROR,
                                    MIN_CELLS_PER_AXIS, MIN_STEPS_PER_DOUBLING,
                                    PAIR_TO_TIME_ERROR, PLANE_PAIR, CellCaps, space_error)
from ..forcing.clock import scales as scales_of
from ..forcing.record import is_long_record
from ..operators import grids
from ..operators.grading import MAX_GROWTH
from ..operators.p1 import plane_operator
from ..planform.short_time import expansion_of, sheet_fraction, weighted
from ..planform.triangles import triangulate
from ..problem.cache import RunCache, run_cache
from ..problem.definition import DiffusionProblem

from ..problem.results import DiffusionResult, Plan
from ..problem.scaling import planar_scale, stretch_of
from ..stepping.step_plans import earliest_output, geometric_steps, output_ages
from ..stepping.step_response import blend, step_response
from ..superposition.duhamel import duhamel
from ..superposition.tabulated import KernelKey, LongRecord

log = logging.getLogger(__name__)

MESH_FIRST_STEP = 1 / 16  # the mesh's first step, in units of h0^2: earlier it resolves nothing
MESH_LEAD_DOUBLINGS = 7   # ... or this many doublings before the switch (six before its half)
FEATURE_POINTS = 16  # at least this many outline points round the tightest curve
FIELD_CHUNK = 8      # output times per Duhamel pass of the fields (memory)


def peak_weight(perimeter: float, area: float, ages: np.ndarray) -> float:
    """Largest planform uptake x sheet unsaturated fraction at ``ages``, the factor that
    turns a relative planform error into an error of the mean (``leading_uptake``); 0
    without ages.

    Parameters
    ----------
    perimeter : float
        The outline's perimeter in scaled units (lengths over the thickness) [-].
    area : float
        The planform's area in scaled units [-].
    ages : numpy.ndarray
        The scaled ages tau* the outputs read [-].

    Returns
    -------
    float
        max over the ages of the leading uptake times the sheet's unsaturated fraction [-].
    """
    if np.size(ages) == 0:
        return 0.0
    return float(np.max(leading_uptake(perimeter, area, ages) * sheet_fraction(ages)))


def leading_uptake(perimeter: float, area: float, tau):
    """min(1, 2 P sqrt(tau / pi) / A): the planform uptake's leading term (Crank 1975 eq. 4.20
    per unit edge), an upper bound for convex outlines.

    Parameters
    ----------
    perimeter : float
        P, the outline's length in thicknesses (anisotropy-scaled) [-].
    area : float
        A, the planform's area in thicknesses squared [-].
    tau : array_like
        Scaled time tau* = D t / h^2 [-].

    Returns
    -------
    numpy.ndarray
        The planform's fractional uptake, at most 1 [-].

    References
    ----------
    Crank (1975), eq. 4.20 (see the module docstring).
    """
    return np.minimum(1.0, 2.0 * perimeter * np.sqrt(np.asarray(tau, float) / np.pi) / area)


@dataclass(frozen=True)
class MeshSpacing:
    """The graded mesh for a target: finest spacing h0 and growth g (scaled units), the
    estimated number of nodes and the relative uptake error it leaves at ``start``.

    Parameters
    ----------
    finest : float
        The finest node spacing h0 in scaled units [-] (0 growth: the uniform spacing).
    growth : float
        The growth g of the spacing from row to row [-].
    nodes : int
        The estimated number of nodes [-].
    relative_error : float
        The relative error of the planform uptake it leaves at ``start`` [-].
    """

    finest: float
    growth: float
    nodes: int
    relative_error: float


def graded_spacing(target: float, start: float, perimeter: float, tightest: float,
                cap: int) -> MeshSpacing:
    """h0 and g meeting a relative uptake error ``target`` from scaled time ``start`` on.

    The error model r = MESH_ERROR (h0 / sqrt(t) + GROWTH_REACH g)^2 (``error_model``) and the
    node count ~ sum_k P / (h0 (1 + g)^k) ~ P / (g h0) (rows of P / s_k points) give the
    cheapest split at
    h0 / sqrt(t) = GROWTH_REACH g = S / 2, S = sqrt(target / MESH_ERROR); g is at most
    ``grading.MAX_GROWTH``, h0 gives ``FEATURE_POINTS`` points round the tightest curve
    (curvature ``tightest``), and both coarsen together when the nodes exceed ``cap``.

    Parameters
    ----------
    target : float
        The relative uptake error aimed at [-].
    start : float
        The scaled time tau* from which the target holds [-].
    perimeter : float
        The outline's scaled perimeter [-].
    tightest : float
        The largest curvature of the outline in scaled units [-].
    cap : int
        The most nodes [-].

    Returns
    -------
    MeshSpacing
        h0, g, the node count and the relative error the spacing leaves at ``start``.
    """
    reach = math.sqrt(max(target, 1e-300) / MESH_ERROR)
    growth = min(MAX_GROWTH, 0.5 * reach / GROWTH_REACH)
    finest = min((reach - GROWTH_REACH * growth) * math.sqrt(start),
                 2 * math.pi / (FEATURE_POINTS * max(tightest, 1e-9)))
    nodes = perimeter / (growth * finest)
    if nodes > cap:
        coarser = math.sqrt(nodes / cap)
        growth, finest = min(MAX_GROWTH, growth * coarser), finest * coarser
        nodes = perimeter / (growth * finest)
    error = MESH_ERROR * (finest / math.sqrt(start) + GROWTH_REACH * growth) ** 2
    return MeshSpacing(finest, growth, int(math.ceil(nodes)), error)


def uniform_spacing(target: float, start: float, area: float, tightest: float,
                   cap: int) -> MeshSpacing:
    """The uniform lattice of outlines without loops (``triangulate`` falls back to it):
    r = MESH_ERROR h^2 / t, about 2 area / (sqrt 3 h^2) nodes, at most ``cap``.

    Parameters
    ----------
    target : float
        The relative uptake error aimed at [-].
    start : float
        The scaled time tau* from which it holds [-].
    area : float
        The planform's scaled area [-].
    tightest : float
        The largest scaled curvature of the outline [-].
    cap : int
        The most nodes [-].

    Returns
    -------
    MeshSpacing
        The spacing h (``finest``), growth 0, nodes and the relative error at ``start``.
    """
    spacing = min(math.sqrt(max(target, 1e-300) * start / MESH_ERROR),
                  2 * math.pi / (FEATURE_POINTS * max(tightest, 1e-9)))
    spacing = max(spacing, math.sqrt(2 * area / (math.sqrt(3) * cap)))
    nodes = 2 * area / (math.sqrt(3) * spacing ** 2)
    return MeshSpacing(spacing, 0.0, int(math.ceil(nodes)), MESH_ERROR * spacing ** 2 / start)


def mesh_first_step(finest: float, switch: float) -> float:
    """First step of the mesh's march where the expansion serves the outputs before
    ``switch``: h0^2 / 16 (before that the mesh resolves nothing) or six doublings before
    half the switch, the larger (backward Euler damps the start: results moved by the time
    error only, 2e-5 on the fourbar link); the common first step without an expansion.

    Parameters
    ----------
    finest : float
        The mesh's finest scaled spacing h0 [-].
    switch : float
        The scaled time at which the expansion hands over to the mesh [-]; 0: none.

    Returns
    -------
    float
        The first step in scaled time tau* [-].
    """
    if switch <= 0:
        return FIRST_STEP
    return max(FIRST_STEP, MESH_FIRST_STEP * finest ** 2, switch / 2 ** MESH_LEAD_DOUBLINGS)


@dataclass(frozen=True)
class PlanformSize:
    """The outline's size in scaled coordinates.

    Parameters
    ----------
    perimeter : float
        The scaled perimeter [-].
    area : float
        The scaled area [-].
    tightest : float
        The largest curvature of the outline [-] (scaled).
    """

    perimeter: float
    area: float
    tightest: float


def _planform_size(part, d, expansion) -> PlanformSize:
    """Scaled perimeter, area and largest curvature of the outline (an outline without an
    expansion: bounding box and hole circumferences, area of the box)."""
    if expansion is not None:
        return PlanformSize(expansion.perimeter, expansion.area,
                            max(expansion.max_curvature, 1e-9))
    scale = np.asarray(planar_scale(part, d))
    width, height = np.asarray(part.extent()) * scale
    holes = 4 * math.pi * getattr(part, "boss_inner_radius", 0.0) * float(scale.max())
    radius = getattr(part, "boss_inner_radius", 0.0) or getattr(part, "boss_outer_radius", 1.0)
    return PlanformSize(2 * (width + height) + holes, width * height,
                        1.0 / (radius * float(scale.min())))



def planform_mesh(part, finest: float, growth: float, stretch: tuple[float, float],
                  cache: RunCache):
    """The triangle mesh plan and solve share (``triangles.triangulate``; ``finest`` scaled),
    made once per run (``cache``).

    Parameters
    ----------
    part : CamPlate or LinkBar
        The prismatic part, its lengths in [m].
    finest : float
        The finest spacing in thicknesses [-].
    growth : float
        The spacing's growth from row to row [-].
    stretch : tuple of float
        The planar axes' stretch sqrt(D_z / D_x), sqrt(D_z / D_y) of an anisotropic D [-].
    cache : RunCache
        The run's cache.

    Returns
    -------
    Triangulation
        The graded triangle mesh of the outline (points in [m]).
    """
    return cache.get(("planform mesh", part, finest, growth, stretch), lambda: triangulate(
        part, finest * part.thickness, growth=growth, stretch=stretch))


def planform_response(problem: DiffusionProblem, chosen: Plan, end: float, first_step: float,
                      cache: RunCache):
    """(P1 operator, unit-step response, time-error pair) of the planform: what ``solve_plane``
    marches, kept in the run's ``cache`` by the exact inputs that determine it (geometries
    compare by value), so re-runs at other output times (the limit search) and the cases of
    a sweep worker that share the part, its diffusivity ratios and its plan (a climate sweep
    at one temperature) march once. The response's arrays are read-only.

    Parameters
    ----------
    problem : DiffusionProblem
        The part (a CamPlate or LinkBar, lengths [m]), D0 along x, y, z [m^2/s], the
        contact layer's depth [m], whether to keep the response's nodal fields and the
        part's name (progress messages).
    chosen : Plan
        The plane plan: the mesh's finest spacing in thicknesses [-], the spacing's growth
        [-] and the backward-Euler steps per doubling of scaled time [-].
    end : float
        The last scaled time tau* the response covers [-].
    first_step : float
        The first step in scaled time [-].
    cache : RunCache
        The run's cache.

    Returns
    -------
    tuple
        The P1 operator, the unit-step response (uptake fractions [-] over scaled time)
        and the time-error pair [-].
    """
    geometry, layer_depth, keep_fields = (problem.geometry, problem.surface_layer_depth,
                                          problem.store_fields)
    d = tuple(float(v) for v in problem.diffusivity.pre_exponential)
    finest, growth, per_doubling = chosen.finest, chosen.growth, chosen.steps_per_doubling

    def build():
        mesh = planform_mesh(geometry, finest, growth, stretch_of(d), cache)
        planar = plane_operator(mesh, geometry, layer_depth, d)
        response, pair = step_response(planar, end, per_doubling, first_step,
                                       keep_fields=keep_fields, part=problem.part)
        return planar, response, pair
    return cache.get(("planform response", geometry, finest, growth, d, layer_depth, end,
                      per_doubling, first_step, keep_fields), build)


def expansion_error_at(expansion, ages: np.ndarray) -> float:
    """The expansion's error indicator x the sheet's unsaturated fraction, largest at the
    ``ages`` the outputs read (0 without ages).

    Parameters
    ----------
    expansion : ShortTime
        The outline's short-time expansion.
    ages : numpy.ndarray
        The scaled ages tau* the outputs read [-].

    Returns
    -------
    float
        The largest weighted error indicator [-].
    """
    if np.size(ages) == 0:
        return 0.0
    return float(np.max(weighted(expansion.uptake_error(ages), sheet_fraction(ages))))


def plan_plane(problem: DiffusionProblem, caps: CellCaps = MAX_CELLS,
               cache: RunCache | None = None):
    """What ``solve_plane`` will do and the error it will report, by the blend's error model
    at the ages the outputs read (``step_plans.output_ages``): the expansion up to its switch
    (error ``EXPANSION_SHARE`` x accuracy); after it a graded P1 mesh whose relative error
    at half the switch (``graded_spacing`` plus the expansion's own relative error there) times
    the largest uptake x sheet fraction at the later ages takes what the time error,
    PAIR_TO_TIME_ERROR (PLANE_PAIR F(end) / m)^2 (at most ``PLANE_TIME_SHARE`` of it),
    leaves of ``PLANE_PLAN_MARGIN`` x accuracy (a long record's sum takes ``RECORD_SHARE`` of it
    first).
    The cells are those of the mesh ``solve`` builds. The plan reads nothing of the contact
    layer: the problem's layer depth (the solve's) only lets plan and solve share the
    expansion (``expansion_of``); ``caps``: the most nodes of the mesh and cells of the
    sheet; ``cache``: the run's (None: a fresh one).

    Parameters
    ----------
    problem : DiffusionProblem
        The part [m], D(T) [m^2/s], exposure, output times [s] and relative accuracy [-].
    caps : CellCaps
        The most nodes [-] of the planform mesh and cells of the sheet.
    cache : RunCache, optional
        The run's cache; None: a fresh one.

    Returns
    -------
    Plan
        The mesh's nodes, the steps, the grading and the error estimate [-].
    """
    cache = run_cache(cache)
    geometry, diffusivity, exposure = problem.geometry, problem.diffusivity, problem.exposure
    scales = scales_of(geometry, diffusivity, exposure, cache)
    change, outputs = scales.tau_star(exposure.change_times), scales.tau_star(problem.times)
    ramp, layer_depth = exposure.ramp, problem.surface_layer_depth
    accuracy = (1.0 - RECORD_SHARE if is_long_record(exposure) else 1.0) * problem.accuracy
    d = tuple(float(v) for v in diffusivity.pre_exponential)
    tolerance = EXPANSION_SHARE * accuracy
    expansion = expansion_of(geometry, d, layer_depth, cache)
    end = max(float(np.max(outputs)), 10 * FIRST_STEP)
    ages = output_ages(change, outputs, ramp, cache=cache)
    t_lo = earliest_output(change, outputs)
    switch = 0.0 if expansion is None else expansion.switch(tolerance)
    size = _planform_size(geometry, d, expansion)
    pair = PLANE_PAIR * float(leading_uptake(size.perimeter, size.area, end))  # times 1 / m
    per_doubling = max(MIN_STEPS_PER_DOUBLING,
                       math.ceil(pair * math.sqrt(PAIR_TO_TIME_ERROR
                                                  / (PLANE_TIME_SHARE * accuracy))))
    time_error = PAIR_TO_TIME_ERROR * (pair / per_doubling) ** 2
    spacing, leak, peak = _mesh_spacing(expansion, switch, end, ages, size, accuracy,
                                        time_error, caps.plane)
    sheet = min(caps.slab, max(MIN_CELLS_PER_AXIS, math.ceil(
        1.0 / math.sqrt(0.5 * accuracy * max(t_lo, switch)
                        / (3 * space_error(max(t_lo, switch)))))))
    reason = (f"2-D outline x exact sheet: short-time expansion of the outline up to "
              f"tau*={switch:.2g}, then P1 elements on a mesh graded from the outline "
              f"(h0*={spacing.finest:.2g}, growth {spacing.growth:.2g}), backward Euler "
              f"{per_doubling} steps/doubling + Richardson")
    if expansion is not None and switch >= end:
        return Plan("plane", 0, 0, reason + " (the expansion covers every output: no mesh)",
                    expansion_error_at(expansion, ages), (0, sheet), per_doubling,
                    tolerance, finest=spacing.finest, growth=spacing.growth)
    at_switch = expansion_error_at(expansion, ages[ages <= switch]) if switch > 0 else 0.0
    estimate = max(at_switch, (spacing.relative_error + leak) * peak) + time_error
    if estimate > accuracy:
        reason += f"; capped at {caps.plane} nodes: error above the requested accuracy"
    mesh = planform_mesh(geometry, spacing.finest, spacing.growth, stretch_of(d), cache)
    nodes = int(np.count_nonzero(~mesh.on_outline))
    steps = geometric_steps(0.0, end, mesh_first_step(spacing.finest, switch), per_doubling)
    return Plan("plane", nodes + sheet, 3 * (steps.size - 1), reason, float(estimate),
                (nodes, sheet), per_doubling, tolerance, finest=spacing.finest,
                growth=spacing.growth)


def _mesh_spacing(expansion, switch, end, ages, size: PlanformSize, accuracy, time_error,
                  cap: int):
    """(MeshSpacing, leak, peak): the mesh meeting what the time error leaves of
    ``PLANE_PLAN_MARGIN`` x accuracy at every time from the switch (or the first output) to
    the last output (so the contact layer, which the spacing does not model, keeps its
    margin however sparse the outputs); ``leak`` is the expansion's relative error at half
    the switch (the blend's first bound), ``peak`` the weight at the ages the outputs read
    after the switch (for the estimate)."""
    perimeter, area, tightest = size.perimeter, size.area, size.tightest
    first = float(np.min(ages))
    start = 0.5 * min(switch, end) if switch > 0 else first
    span = np.geomspace(max(switch, first, 1e-9), max(end, switch, first, 1e-9), 200)
    peak = peak_weight(perimeter, area, ages[ages >= switch])
    leak = 0.0 if switch <= 0 else float(expansion.uptake_error(start) / expansion.uptake(start))
    target = max((PLANE_PLAN_MARGIN * accuracy - time_error)
                 / max(peak_weight(perimeter, area, span), 1e-300) - leak, 0.1 * accuracy)
    spacing = (graded_spacing if expansion is not None else uniform_spacing)(
        target, start, perimeter if expansion is not None else area, tightest, cap)
    return spacing, leak, peak


# ------------------------------------------------------------------ solve


def solve_plane(problem: DiffusionProblem, chosen: Plan, cache: RunCache | None = None):
    """Planform x sheet step responses of a CamPlate or LinkBar, Duhamel-superposed over the
    history (``PrismSuperposition``; Crank 1975 eqs. 4.34, 4.51, see the module docstring).

    Parameters
    ----------
    problem : DiffusionProblem
        The part [m], D(T) [m^2/s], exposure, times [s], accuracy [-], layer depth [m].
    chosen : Plan
        The plan of ``plan_plane``.
    cache : RunCache, optional
        The run's cache; None: a fresh one.

    Returns
    -------
    DiffusionResult
        Mean and contact-layer moisture [weight %]; error estimate [-] (+ the sum's own).
    """
    cache = run_cache(cache)
    geometry, diffusivity, exposure = problem.geometry, problem.diffusivity, problem.exposure
    times, accuracy, part = problem.times, problem.accuracy, problem.part
    surface_layer_depth, store_fields = problem.surface_layer_depth, problem.store_fields
    d = tuple(float(v) for v in diffusivity.pre_exponential)
    scales = scales_of(geometry, diffusivity, exposure, cache)
    outputs = scales.tau_star(times)
    end = max(float(outputs.max()), 10 * FIRST_STEP)
    expansion = expansion_of(geometry, d, surface_layer_depth, cache)
    tolerance = chosen.expansion_tolerance
    switch = expansion.switch(tolerance) if expansion is not None and tolerance > 0 else 0.0
    history = PrismSuperposition.of(geometry, diffusivity, exposure, times, accuracy, cache)
    if switch >= end and not store_fields:
        return _expansion_only(expansion, _ages(scales, exposure, times, cache), history,
                               chosen, part)
    planar, u_plane, pair_plane = planform_response(
        problem, chosen, end, mesh_first_step(chosen.finest, 0.0 if store_fields else switch),
        cache)
    (plane_mean, mean_error), (plane_layer, _) = (
        _planform_fractions(u_plane, values, expansion, which, tolerance)
        for values, which in ((u_plane.mean, "mean"), (u_plane.layer, "layer")))

    def mean_fraction(tau):
        return plane_mean(tau) * sheet_fraction(tau)

    def layer_fraction(tau):  # contact edge band x the whole thickness
        return plane_layer(tau) * sheet_fraction(tau)

    def same(which: str) -> KernelKey:  # the fractions are fixed by these (cached) objects
        return KernelKey((id(u_plane), id(expansion), tolerance, which), (u_plane, expansion))

    # (mean, its sum's error, layer, levels)
    def superposed(over: PrismSuperposition, levels=(0, 0)):
        (mean, error, mean_level), (layer, _, layer_level) = (
            over.superpose(mean_fraction, same=same("mean"), start=levels[0]),
            over.superpose(layer_fraction, looser=LAYER_TOLERANCE, same=same("layer"),
                           start=levels[1]))
        return mean, error, layer, (mean_level, layer_level)

    mean, sum_error, layer, levels = superposed(history)
    time_error = PAIR_TO_TIME_ERROR * pair_plane ** 2  # the sheet is exact
    observed_at = _observed(chosen, mean_error, time_error, scales, exposure, cache)
    observed = observed_at(times)
    estimate = max(chosen.error_estimate, observed) + sum_error
    log.debug("%s plane: error estimate %.2g (observed %.2g, sum %.2g)", part, estimate,
              observed, sum_error)
    n_z = chosen.cells_per_axis[-1]
    result = DiffusionResult(times, mean, layer, "plane", planar.cells + n_z,
                             3 * (u_plane.nodes.size - 1), float(estimate), chosen.reason)
    log.debug("%s plane: %d nodes x %d sheet cells", part, planar.cells, n_z)
    if store_fields:
        fields, coordinates = _plane_fields(geometry, history, u_plane, planar, chosen, end,
                                            surface_layer_depth, part)
        mesh = planform_mesh(geometry, chosen.finest, chosen.growth, stretch_of(d), cache)
        return replace(result, fields=fields, cell_coordinates=coordinates, planform=mesh)
    if history.record is not None:
        return replace(result, extend=extension(result, lambda at: superposed(history.at(at),
                                                                               levels)))
    return replace(result, extend=PanelExtension(
        result, chosen, lambda at: superposed(replace(history, times=np.asarray(at, float))),
        observed_at))


def _ages(scales, exposure, times, cache: RunCache) -> np.ndarray:
    """The scaled ages the output ``times`` [s] read (``step_plans.output_ages``)."""
    return output_ages(scales.tau_star(exposure.change_times), scales.tau_star(times),
                       exposure.ramp, cache=cache)


def _observed(chosen: Plan, mean_error, time_error: float, scales, exposure, cache: RunCache):
    """``observed(times)``: the plan's estimate, unless the blend's own bound (``mean_error``)
    at the ages ``times`` [s] read says more, with the time error (no expansion for this
    outline: the plan's model, with its time part)."""
    def observed(times) -> float:
        if mean_error is None:
            return chosen.error_estimate
        return float(np.max(mean_error(_ages(scales, exposure, times, cache)))) + time_error
    return observed


def _planform_fractions(response, values, expansion, which: str, tolerance: float):
    """(u_plane(tau*), error or None): the mesh response, blended with the expansion when
    the outline has one (the layer with ``LAYER_TOLERANCE`` x the tolerance)."""
    if expansion is None:
        return (lambda tau: response.at(tau, values)), None
    if which == "mean":
        return blend(response, values, expansion.uptake, expansion.uptake_error, tolerance,
                     sheet_fraction)
    return blend(response, values, expansion.layer_uptake, expansion.layer_error,
                 LAYER_TOLERANCE * tolerance, sheet_fraction)


def _plane_fields(geometry, history, u_plane, planar, chosen, end, depth, part):
    """Fields on the mid-thickness plane: planform fields x the sheet's field there."""
    sheet = grids.sheet(geometry.thickness, chosen.cells_per_axis[-1], depth)
    u_sheet, _ = step_response(sheet, end, chosen.steps_per_doubling, FIRST_STEP,
                               keep_fields=True, part=part)
    mid = int(np.argmin(np.abs(sheet.coordinates["z"] - 0.5 * geometry.thickness)))

    def field_fraction(tau):
        return u_plane.at(tau, u_plane.fields) * u_sheet.at(tau, u_sheet.fields[:, mid])[:, None]
    fields = history.superpose(field_fraction, FIELD_CHUNK, fields=True)[0]
    return fields, {"x": planar.coordinates["x"], "y": planar.coordinates["y"],
                    "z": np.full(planar.cells, sheet.coordinates["z"][mid])}


def _expansion_only(expansion, ages, history, chosen, part):
    """Every output lies where the short-time expansion meets the tolerance: no mesh;
    the error is ``expansion_error_at`` the ages the outputs read."""

    def mean_fraction(tau):
        return (1.0 - expansion.uptake(tau)) * sheet_fraction(tau)

    def layer_fraction(tau):
        return (1.0 - expansion.layer_uptake(tau)) * sheet_fraction(tau)

    (mean, sum_error, _), (layer, _, _) = (
        history.superpose(mean_fraction), history.superpose(layer_fraction, looser=LAYER_TOLERANCE))
    mean_error = max(chosen.error_estimate, expansion_error_at(expansion, ages)) + sum_error
    log.debug("%s plane: short-time expansion only, error %.2g", part, mean_error)
    return DiffusionResult(history.times, mean, layer, "plane", 0, 0, mean_error,
                           chosen.reason + "; no mesh needed")


def _kernel(fraction, scale: float):
    """K(tau) = 1 - u(tau*) for ``duhamel`` (rescaled s, any shape), tau* = scale tau."""
    def kernel(tau):
        tau = np.asarray(tau, float)
        u = np.asarray(fraction(tau.ravel() * scale), float)
        return 1.0 - u.reshape(tau.shape + u.shape[1:])
    return kernel


def _diffusion_times(geometry, d) -> tuple[float, float]:
    """(fastest, slowest) L^2 / D0 of a prism: the thickness and the planform extents."""
    sizes = (*geometry.extent(), geometry.thickness)
    times = [size ** 2 / d[i] for i, size in enumerate(sizes)]
    return min(times), max(times)


@dataclass(frozen=True)
class PrismSuperposition:
    """How ``solve_plane`` superposes over the exposure: Duhamel's panels (``duhamel``) for
    a few segments; for a long record (``record.is_long_record``) the tabulated sum of
    ``tabulated``, cost linear in the rows, shared by the mean, the layer and the fields,
    within ``RECORD_SHARE`` of the accuracy (``plan`` sizes the rest).

    Parameters
    ----------
    diffusivity : Diffusivity
        D(T) [m^2/s].
    exposure : Exposure
        The surface history [weight %] over time [s].
    times : numpy.ndarray
        The output times [s].
    geometry : CamPlate or LinkBar
        The part, its lengths in [m].
    record : LongRecord or None
        The tabulated sum of a long record; None: Duhamel's panels.
    cache : RunCache
        The run's cache.
    """

    diffusivity: object
    exposure: object
    times: np.ndarray
    geometry: object
    record: LongRecord | None
    cache: RunCache   # the run's

    @classmethod
    def of(cls, geometry, diffusivity, exposure, times, accuracy: float,
           cache: RunCache) -> "PrismSuperposition":
        d = tuple(float(v) for v in diffusivity.pre_exponential)
        record = (LongRecord.of(diffusivity, exposure, times, _diffusion_times(geometry, d)[0],
                                RECORD_SHARE * accuracy, cache)
                  if is_long_record(exposure) else None)
        return cls(diffusivity, exposure, np.asarray(times, float), geometry, record, cache)

    def at(self, times) -> "PrismSuperposition":
        """The same history read at other ``times`` inside the outputs' span (a long record
        only: ``LongRecord.at``)."""
        return replace(self, times=np.asarray(times, float), record=self.record.at(times))

    def superpose(self, fraction, chunk: int = 64, fields: bool = False,
                  looser: float = 1.0, same: KernelKey | None = None,
                  start: int = 0) -> tuple[np.ndarray, float, int]:
        """(c0 + Duhamel sum of the unit-step unsaturated fraction u(tau*), the error of the
        sum itself relative to the swing: 0 for the panels, whose quadrature is exact to
        ``error_model.ANALYTIC_ERROR``, the tables' points per decade: 0 for the panels).
        ``fields``: a wide kernel (``LongRecord.field``); ``looser``: a tolerance this many
        times the mean's (the contact layer); ``same``: which fraction this is
        (``tabulated.KernelKey``), to reuse its tables across solves; ``start``: the points per
        decade an earlier solve of this fraction refined to (``LongRecord.superpose``)."""
        d = tuple(float(v) for v in self.diffusivity.pre_exponential)
        kernel = _kernel(fraction, d[2] / self.geometry.thickness ** 2)
        if self.record is None:
            return self.exposure.initial_moisture + duhamel(
                kernel, self.diffusivity, self.exposure, self.times,
                _diffusion_times(self.geometry, d), chunk=chunk, cache=self.cache), 0.0, 0
        if fields:
            return self.exposure.initial_moisture + self.record.field(kernel), 0.0, 0
        if same is not None:
            same = KernelKey(same.key + (d[2] / self.geometry.thickness ** 2,), same.holds)
        values, error, level = self.record.superpose(kernel, looser=looser, same=same,
                                                     start=start)
        return self.exposure.initial_moisture + values, error, level


def extension(result: DiffusionResult, superposed):
    """``DiffusionResult.extend`` of a plane solve over a long record: the result at its
    times and ``at`` (inside their span) together, the new rows summed with the stored plan,
    planform response, forcing and tables (``PrismSuperposition.at``), the stored rows as they
    are.

    Parameters
    ----------
    result : DiffusionResult
        The stored solve, its times [s].
    superposed : callable
        ``superposed(times) -> (mean, _, layer, _)`` [weight %] at other times [s].

    Returns
    -------
    callable
        ``extend(at) -> DiffusionResult``: the result at its times and ``at`` [s].
    """

    def extend(at) -> DiffusionResult:
        at = np.asarray(at, float)
        new = np.setdiff1d(at, result.times)
        mean, _, layer, _ = superposed(new)
        return result.merged(new, mean, layer)
    return extend


#: what a plane plan fixes of the solve besides its estimate: the mesh, the sheet, the steps
#: and the expansion's share (the planform response ``planform_response`` keys on these)
def _solve_fixed(chosen: Plan) -> tuple:
    return (chosen.cells, tuple(chosen.cells_per_axis), chosen.steps, chosen.steps_per_doubling,
            chosen.expansion_tolerance, chosen.finest, chosen.growth)


@dataclass(frozen=True, eq=False)
class PanelExtension:
    """``DiffusionResult.extend`` of a plane solve by Duhamel's panels (a few exposure
    segments): the result at its times and ``at`` (inside their span) together, the new rows
    summed with the stored planform response and expansion (each output time's sum is its
    own: the rows are those a solve at both would give), the stored rows as they are. With
    ``replan`` (the dispatcher binds it), the plan of the stored and new times together must
    fix the solve as the stored plan did (``_solve_fixed``: e.g. a new time younger than
    every stored output sizes other cells), else ``resolve`` solves at both again; its
    estimate is then that plan's, or the blend's own bound at the ages the times read,
    the larger, as a solve at both reports.

    Parameters
    ----------
    result : DiffusionResult
        The stored solve, its times [s].
    chosen : Plan
        The plan it was solved on.
    superposed : callable
        ``superposed(times) -> (mean, _, layer, _)`` [weight %] at other times [s].
    observed : callable
        ``observed(times) -> float``: the blend's own estimate [-] at the ages ``times`` [s]
        read (the plan's where the outline has no expansion).
    replan : callable, optional
        ``replan(times) -> Plan``: the plan for ``times`` [s]; None: the stored plan holds.
    resolve : callable, optional
        ``resolve(times) -> DiffusionResult``: the solve at ``times`` [s] (with ``replan``).
    """

    result: DiffusionResult
    chosen: Plan
    superposed: object
    observed: object
    replan: object = None
    resolve: object = None

    def __call__(self, at) -> DiffusionResult:
        result = self.result
        new = np.setdiff1d(np.asarray(at, float), result.times)
        both = np.union1d(result.times, new)
        again = self.chosen if self.replan is None else self.replan(both)
        if _solve_fixed(again) != _solve_fixed(self.chosen):
            log.debug("%s: the plan at %d new times changes the solve: solved again",
                     result.model, new.size)
            return self.resolve(both)
        if not new.size:
            return replace(result, extend=None)
        mean, _, layer, _ = self.superposed(new)
        return replace(result.merged(new, mean, layer), reason=again.reason,
                       error_estimate=float(max(again.error_estimate, self.observed(both))))
