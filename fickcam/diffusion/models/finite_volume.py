"""The direct models: ``slab`` (Sheet, 1-D), ``axisymmetric`` (Disc or annulus in (r, z))
and ``solid`` (Bar on a 3-D grid; CamPlate or LinkBar on prisms of Delaunay-admissible
cells), each a FiPy-assembled operator marching the history itself.

Backward Euler on geometric steps that restart at each environment change
(``step_plans``), twice: on the plan's steps and on the same steps bisected. The
difference measures the time error, and Richardson's extrapolation 2 c_fine - c_coarse
cancels its first-order part. Cells come from the spatial error model
(``error_model.space_error``, ``sizing``).
"""
from __future__ import annotations

import math

import numpy as np

from ..accuracy.error_model import (FIRST_STEP, MAX_CELLS, CellCaps, MIN_STEPS_PER_DOUBLING,
                                    PAIR_TO_EXTRAPOLATED, TIME_ERROR, space_error)
from ..forcing.clock import Scales
from ..forcing.clock import scales as scales_of
from ..operators import grids, sizing
from ..operators.prisms import prism
from ..operators.symmetry_cuts import halved_axes
from ..planform.admissible import band_share
from ..problem.cache import RunCache
from ..problem.definition import DiffusionProblem
from ..problem.exposure import Diffusivity, swing
from ..problem.results import DiffusionResult, Plan
from ..problem.scaling import stretch_of
from ..stepping import step_plans
from ..stepping.march import march
from ..stepping.step_plans import StepPlan

#: what the ``solid`` model builds, by the part's grid (``Geometry.grid``)
SOLID_GRIDS = {"box": "bar in 3-D",
               "prisms": "3-D prisms of the outline (Delaunay-admissible cells x graded thickness)"}


def plan_direct(problem: DiffusionProblem, model: str, mirrored: bool = False,
                caps: CellCaps = MAX_CELLS, cache: RunCache | None = None) -> Plan:
    """Cells from the spatial error model, steps per doubling from the time error model,
    each taking half the problem's accuracy. ``mirrored``: the solve keeps the part cut at
    its mirror planes (``symmetry_cuts``, the D(c) sweeps); the plan's cells and the cap
    (``caps``: cells of the linear system) count that cut part; ``cache``: the run's, which
    keeps a planform's cells for the solve.

    Parameters
    ----------
    problem : DiffusionProblem
        The part [m], D(T) [m^2/s], exposure, output times [s] and relative accuracy [-].
    model : str
        ``slab``, ``axisymmetric`` or ``solid``.
    mirrored : bool
        True where the solve keeps only the part cut at its mirror planes.
    caps : CellCaps
        The most cells [-] of each model's linear system.
    cache : RunCache, optional
        The run's cache; None: a fresh one.

    Returns
    -------
    Plan
        The cells per axis, the steps (coarse and bisected marches), steps per doubling of
        scaled time, the grading and the error estimate [-] (space + time).
    """
    geometry, diffusivity, exposure = problem.geometry, problem.diffusivity, problem.exposure
    accuracy = problem.accuracy
    scales = scales_of(geometry, diffusivity, exposure, cache)
    change, outputs = scales.tau_star(exposure.change_times), scales.tau_star(problem.times)
    t_lo = step_plans.earliest_output(change, outputs)
    cells = _cells(geometry, diffusivity, accuracy, t_lo, caps[model],
                   halved_axes(geometry) if mirrored else (), cache)
    per_doubling = max(MIN_STEPS_PER_DOUBLING, math.ceil(math.sqrt(TIME_ERROR / (0.5 * accuracy))))
    nodes = step_plans.step_nodes(change, outputs, FIRST_STEP, per_doubling, exposure.ramp)
    steps = 3 * (nodes.size - 1)  # coarse march + bisected march
    estimate = cells.space_error + TIME_ERROR / per_doubling ** 2
    why = {"slab": "sheet through the thickness, 1-D finite volumes",
           "axisymmetric": "disc/annulus in (r, z)" + (
               " (bore: no exact path)" if geometry.exact_route is None else ""),
           "solid": SOLID_GRIDS.get(geometry.grid, "")}[model]
    reason = (f"{why}; cells from accuracy ({cells.note}, earliest output "
              f"tau*={t_lo:.2g}), backward Euler {per_doubling} steps/doubling + Richardson")
    if estimate > accuracy:
        reason += f"; capped at {caps[model]} cells: error above the requested accuracy"
    return Plan(model, cells.solved, int(steps), reason, float(estimate), cells.cells,
                per_doubling, finest=cells.finest, growth=cells.growth)


def _cells(geometry, diffusivity, accuracy: float, t_lo: float, cap: int, halved=(),
           cache: RunCache | None = None):
    """The cells of a direct model (``sizing``): prisms for a CamPlate or LinkBar, graded
    or uniform for a Disc or Bar, uniform for the slab; at most ``cap`` solved; ``halved``:
    the axes the solve cuts at their mirror plane."""
    d = diffusivity.pre_exponential
    if geometry.planform:
        return sizing.prism_layout(geometry, d, accuracy, t_lo, cap, space_error(t_lo), halved,
                                   cache)
    return sizing.choose(geometry, sizing.extents(geometry, d), accuracy, t_lo, cap,
                         space_error(t_lo), halved)


def discretise(geometry, diffusivity: Diffusivity, cells: tuple[int, ...],
               surface_layer_depth: float, finest: float = 0.0, growth: float = 0.0,
               cache: RunCache | None = None):
    """The FiPy-assembled operator of a Sheet, Disc or Bar on ``cells`` (uniform), or
    graded from ``finest`` by ``growth`` (scaled units, ``sizing``); of a CamPlate or
    LinkBar on prisms (graded: ``finest`` > 0).

    Parameters
    ----------
    geometry : Sheet, Disc, Bar, CamPlate or LinkBar
        The part, its lengths in [m].
    diffusivity : Diffusivity
        Its D0 per axis [m^2/s] scales the grading.
    cells : tuple of int
        Cells per axis [-] of a uniform grid.
    surface_layer_depth : float
        The contact layer's depth [m] (its cells' weights are kept).
    finest : float
        The finest cell's width in scaled units [-]; 0: uniform.
    growth : float
        The ratio of neighbouring widths minus one [-].
    cache : RunCache, optional
        The run's cache (a planform's cells); None: a fresh one.

    Returns
    -------
    Discretisation
        The assembled operator, the cell volumes [m^3] and the contact-layer weights.

    Raises
    ------
    TypeError
        For a geometry none of the direct models take.
    """
    d = tuple(float(v) for v in diffusivity.pre_exponential)
    widths = (sizing.physical_widths(geometry, sizing.extents(geometry, d), d, finest,
                                     growth)
              if finest > 0 and geometry.grid in sizing.GRADED_GRIDS else None)
    if geometry.grid == "sheet":
        return grids.sheet(geometry.thickness, cells[0], surface_layer_depth)
    if geometry.grid == "disc":
        return grids.disc(geometry.outer_radius, geometry.thickness, geometry.inner_radius,
                       cells[0], cells[1], surface_layer_depth, d[0], d[2], widths=widths)
    if geometry.grid == "box":
        return grids.bar(geometry.length, geometry.width, geometry.thickness, cells,
                      surface_layer_depth, d, widths=widths)
    if geometry.grid == "prisms":
        tess = sizing.planform_cells(geometry, finest, growth, stretch_of(d), cache)
        return prism(tess, geometry.thickness, sizing.prism_widths(finest, growth)
                     * geometry.thickness, band_share(tess, surface_layer_depth), d)
    raise TypeError(f"no direct finite-volume model for {type(geometry).__name__}")


def step_plan(exposure, times, scales: Scales, per_doubling: int,
              bisect: bool = False) -> StepPlan:
    """Nodes of the march (``bisect``: every step halved, for the Richardson pair).

    Parameters
    ----------
    exposure : Exposure
        The surface history [weight %] and its change times [s].
    times : numpy.ndarray
        The output times [s].
    scales : Scales
        The problem's time scales (wall time [s] -> scaled time tau* [-]).
    per_doubling : int
        Geometric steps per doubling of scaled time [-].
    bisect : bool
        True: every step halved.

    Returns
    -------
    StepPlan
        The nodes, their times [s], surface values [weight %], outputs and restarts.
    """
    tau_star = scales.tau_star
    change = tau_star(exposure.change_times)
    outputs = tau_star(times)
    nodes = step_plans.step_nodes(change, outputs, FIRST_STEP, per_doubling, exposure.ramp)
    if bisect:
        nodes = np.sort(np.concatenate([nodes, 0.5 * (nodes[1:] + nodes[:-1])]))
    node_times = step_plans.inverse_time(nodes, tau_star, exposure.change_times)
    exact_nodes = np.isin(nodes, change)
    node_times[exact_nodes] = exposure.change_times[np.searchsorted(change, nodes[exact_nodes])]
    surface = np.asarray(exposure.surface_moisture(node_times), float)
    before = surface.copy()
    jumps = np.flatnonzero(exact_nodes)[1:]
    before[jumps] = exposure.surface_before(node_times[jumps])
    return StepPlan(nodes, node_times, surface, before, step_plans.nearest_nodes(nodes, outputs),
                    np.searchsorted(nodes, change[:-1]))


def solve_direct(problem: DiffusionProblem, chosen: Plan, *, extrapolate: bool = True,
                 disc=None, marcher=march, cache: RunCache | None = None) -> DiffusionResult:
    """March a Sheet, Disc, Bar or prisms of a CamPlate or LinkBar (``problem``) on its FiPy
    mesh (Richardson pair in time); ``disc``: an operator built by the caller instead;
    ``marcher``: ``march.march`` or one with its arguments (``two_phase_mesh``: two-phase, whose
    history also carries the bound-water mean); ``cache``: the run's.

    Parameters
    ----------
    problem : DiffusionProblem
        The part [m], D(T) [m^2/s], exposure, output times [s], contact-layer depth [m].
    chosen : Plan
        The plan of ``plan_direct``: cells, steps per doubling, grading.
    extrapolate : bool
        True: Richardson's 2 fine - coarse; False: the bisected march alone.
    disc : Discretisation, optional
        An operator built by the caller; None: ``discretise`` builds it.
    marcher : callable
        The march (``march.march`` or one with the same arguments).
    cache : RunCache, optional
        The run's cache; None: a fresh one.

    Returns
    -------
    DiffusionResult
        The mean and contact-layer moisture [weight %] at the times and the error
        estimate [-].

    References
    ----------
    Richardson, L. F., Gaunt, J. A., "The deferred approach to the limit", *Philosophical
    Transactions of the Royal Society A* 226, 299-349, 1927, doi:10.1098/rsta.1927.0008.
    """
    geometry, diffusivity, exposure = problem.geometry, problem.diffusivity, problem.exposure
    times, surface_layer_depth = problem.times, problem.surface_layer_depth
    store_fields, part = problem.store_fields, problem.part
    scales = scales_of(geometry, diffusivity, exposure, cache)
    if disc is None:
        disc = discretise(geometry, diffusivity, chosen.cells_per_axis, surface_layer_depth,
                          chosen.finest, chosen.growth, cache)
    runs = []
    for bisect in (False, True):
        steps = step_plan(exposure, times, scales, chosen.steps_per_doubling, bisect)
        runs.append(marcher(disc, steps, exposure.initial_moisture, keep_fields=store_fields,
                            part=part))
    coarse, fine = runs
    combine, estimate = richardson_pair(chosen, coarse, fine, swing(exposure, times) or 1.0,
                                    extrapolate)
    bound = getattr(coarse, "bound", None)
    return DiffusionResult(
        times, combine(coarse.mean, fine.mean), combine(coarse.layer, fine.layer), chosen.model,
        disc.cells, coarse.steps + fine.steps, estimate, chosen.reason,
        fields=combine(coarse.fields, fine.fields) if store_fields else None,
        bound=None if bound is None else combine(bound, fine.bound),
        cell_coordinates=disc.coordinates if store_fields else {})


def richardson_pair(chosen: Plan, coarse, fine, scale: float, extrapolate: bool):
    """(combine, estimate): 2 fine - coarse (or the fine march alone) and its error: the
    plan's estimate, unless the march's own indicator (space part of the plan + the pair's
    time error, ``PAIR_TO_EXTRAPOLATED`` d^2 extrapolated, d alone) says more.

    Parameters
    ----------
    chosen : Plan
        The plan: its error estimate [-] and steps per doubling.
    coarse, fine : object
        The marches on the plan's steps and on them bisected (``mean`` [weight %]).
    scale : float
        The swing |Ms - M0| the error is relative to [weight %].
    extrapolate : bool
        True: combine as 2 fine - coarse; False: take the fine march.

    Returns
    -------
    combine : callable
        ``combine(coarse_values, fine_values)``: the combined values.
    estimate : float
        The error estimate [-], relative to ``scale``.
    """
    pair = float(np.max(np.abs(fine.mean - coarse.mean))) / scale
    space = chosen.error_estimate - TIME_ERROR / chosen.steps_per_doubling ** 2
    if extrapolate:
        def combine(a, b):
            return 2.0 * b - a
        observed = space + PAIR_TO_EXTRAPOLATED * pair ** 2
        return combine, float(max(chosen.error_estimate, observed))

    def combine(a, b):
        return b
    return combine, float(max(space + pair, 0.0))
