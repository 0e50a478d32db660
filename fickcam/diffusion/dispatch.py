"""The dispatcher: ``plan_problem`` (which model, cells and steps a solve will use, and
why) and ``solve_problem`` (run that plan) of a ``DiffusionProblem``; ``plan`` and ``solve``
are their keyword conveniences. The registry ``ROUTES`` holds each law's routes (Fick,
Langmuir, concentration-dependent D), each saying why it does not take a problem, planning
and solving; ``auto`` takes the first that does (``route_of``).

Models (``diffusion.model``), each a ``FickModel`` of the registry ``FICK_MODELS``, which
says which parts it applies to, why not where it does not, and plans and solves:

- ``analytic``: Crank's series with Duhamel superposition in rescaled time
  (``analytic``): Sheet, Bar (product of three sheets), solid Disc.
- ``slab``, ``axisymmetric``, ``solid``: FiPy-assembled operators marching the history
  (``finite_volume``): a Sheet through its thickness; a Disc or annulus in (r, z); a Bar in
  3-D or a CamPlate / LinkBar on prisms, the independent check of ``plane``.
- ``plane``: CamPlate or LinkBar: the planform's response times the exact sheet,
  superposed over the history (``plane``); ``auto`` picks it (cheaper than prisms).

Concentration-dependent D (``sorption``) under ``auto``: Fick with D f where f is constant
over the moisture met; on a CamPlate, LinkBar or Bar (the prism of its rectangular section,
``corrected_pieces.as_prism``; a Bar from ``BAR_CORRECTED_FROM`` down, above it its octant's
cells) the D(c) sheet x planform product corrected on coarse 3-D prisms (``corrected_product``);
``solid`` keeps the 3-D cells alone (a Bar's octant), the check.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from ..errors import InputError
from .accuracy.budget import check_accuracy
from .accuracy.error_model import ANALYTIC_ERROR, MAX_CELLS, CellCaps
from .forcing.record import is_long_record
from .models.analytic import solve_analytic
from .models.finite_volume import plan_direct, solve_direct
from .models.plane import PanelExtension, plan_plane, solve_plane
from .nonfickian.concentration_dependent import (SWEEPS, Sweeps, nonlinear_plan, solve_nonlinear,
                                                 spread)
from .nonfickian.corrected_product import plan_corrected, solve_corrected
from .nonfickian.planform_modes import REFINEMENT, Refinement
from .nonfickian.two_phase_mesh import two_phase_marcher
from .nonfickian.two_phase_planform import langmuir_modes, plan_two_phase_planform
from .problem.cache import RunCache, run_cache
from .problem.definition import MODELS, DiffusionProblem
from .problem.exposure import Diffusivity, Exposure
from .problem.geometry import LAYER_DEPTH
from .problem.results import DiffusionResult, Plan
from .problem.sorption import describe, is_langmuir, is_nonlinear
from .stepping.dense_output import held_to_plan

log = logging.getLogger(__name__)

BAR_CORRECTED_FROM = 1e-2  # accuracy from which ``auto`` takes a D(c) Bar's corrected product.
#   6 x 4 x 2 mm bar, k = 1, 2, both directions (benchmarks/dc_bar.py small vs corrected, CPU
#   s, the errors against a method of lines): at 1e-2 corrected 11-27 s, the octant 13-91 s;
#   at 3e-3 14-58 s against 54-1 188 s; at 1e-3 29-90 s (estimate 8.4e-4-2.1e-3, error
#   0.8-5.6e-4) where the octant is capped (est. 1.0-1.9e-3, not run: > 15 CPU min). At 3e-2
#   and 0.1 the octant takes 0.7-6.9 s, corrected 10-23 s (its floor: fine sheet, two
#   nested meshes, planform refined x4)


@dataclass(frozen=True)
class FickModel:
    """One Fickian model of the registry: the parts it applies to, why it does not apply to
    a part (``refusal``), its plan and its solve.

    ``plan(problem, caps, cache) -> Plan`` and ``solve(problem, chosen, cache) ->
    DiffusionResult`` (problem: a ``DiffusionProblem``; caps: the ``CellCaps`` of the run's
    ``SolverSettings``; chosen: the plan; cache: the run's ``RunCache``).

    Parameters
    ----------
    name : str
        The model's name, as ``diffusion.model`` spells it.
    grids : tuple of str
        The geometries it applies to, by the grid each names (``Geometry.grid``: ``sheet``,
        ``disc``, ``box``, ``prisms``).
    plan : callable
        ``plan(problem, caps, cache) -> Plan``: cells, steps and error estimate [-].
    solve : callable
        ``solve(problem, chosen, cache) -> DiffusionResult``.
    exact : bool
        True for a model that needs a separable exact solution (refused elsewhere).
    """

    name: str
    grids: tuple[str, ...]
    plan: Callable
    solve: Callable
    exact: bool = False   # only where a separable exact solution exists

    def applies(self, geometry) -> bool:
        return geometry.grid in self.grids

    def refusal(self, geometry) -> str | None:
        """Why this model cannot solve ``geometry`` (None where it can)."""
        if not self.applies(geometry):
            return f"does not apply to a {type(geometry).__name__}"
        return geometry.exact_refusal() if self.exact else None


def _plan_analytic(problem: DiffusionProblem, caps, cache) -> Plan:
    exposure = problem.exposure
    if is_long_record(exposure):
        return Plan("analytic", 0, 0, f"exact Crank series, tabulated once and superposed "
                    f"over the {exposure.ramp.size}-segment record in closed form per row "
                    "(cost linear in the rows)", problem.accuracy)
    return Plan("analytic", 0, 0, "exact Crank series with Duhamel superposition in "
                "rescaled time (linear, one Arrhenius factor): cheapest and exact",
                ANALYTIC_ERROR)


def _solve_analytic(problem: DiffusionProblem, chosen: Plan, cache) -> DiffusionResult:
    record = problem.accuracy if is_long_record(problem.exposure) else None
    return solve_analytic(problem, chosen, record, cache)


def _finite_volume(name: str, grids: tuple[str, ...]) -> FickModel:
    """A finite-volume model (``models.finite_volume``) of the parts on these grids."""
    def planned(problem: DiffusionProblem, caps, cache) -> Plan:
        return plan_direct(problem, name, caps=caps, cache=cache)

    def solved(problem: DiffusionProblem, chosen: Plan, cache) -> DiffusionResult:
        return solve_direct(problem, chosen, cache=cache)
    return FickModel(name, grids, planned, solved)


# The Fickian models, in the order ``diffusion.model`` lists them; ``auto`` takes the exact
# series where the part has one, else the first numerical model that applies (``solid``
# CamPlate / LinkBar: prisms of admissible cells, the check of ``plane``).
FICK_MODELS = {model.name: model for model in (
    FickModel("analytic", ("sheet", "box", "disc"), _plan_analytic, _solve_analytic, exact=True),
    _finite_volume("slab", ("sheet",)),
    _finite_volume("axisymmetric", ("disc",)),
    FickModel("plane", ("prisms",), plan_plane, solve_plane),
    _finite_volume("solid", ("box", "prisms")))}
GRIDS = ("sheet", "disc", "box", "prisms")  # every grid some model builds


def numerical_model(geometry) -> str:
    """The first mesh model that applies to the part: slab, axisymmetric, plane, solid.

    Parameters
    ----------
    geometry : Sheet, Disc, Bar, CamPlate or LinkBar
        The part to mesh (dimensions in [m]).

    Returns
    -------
    str
        The name of the first non-exact model of ``FICK_MODELS`` whose parts include it.
    """
    return next(name for name, model in FICK_MODELS.items()
                if not model.exact and model.applies(geometry))


def _validate(problem: DiffusionProblem) -> None:
    geometry, model, accuracy = problem.geometry, problem.model, problem.accuracy
    if model not in MODELS:
        raise InputError(f"diffusion.model {model!r}: one of {', '.join(MODELS)}")
    if getattr(geometry, "grid", None) not in GRIDS:
        raise InputError(f"unsupported diffusion geometry {type(geometry).__name__}")
    check_accuracy(accuracy, "diffusion.accuracy")
    if model != "auto" and not FICK_MODELS[model].applies(geometry):
        allowed = sorted(name for name, m in FICK_MODELS.items() if m.applies(geometry))
        raise InputError(f"diffusion.model {model!r} does not apply to a "
                         f"{type(geometry).__name__} (use one of {', '.join(allowed)} or auto)")


def _fick_model(geometry, model: str) -> FickModel:
    """The registry's model for ``model`` (``auto``: the exact series where it applies, else
    ``numerical_model``); a model that cannot solve the part says why."""
    if model == "auto":
        exact = FICK_MODELS["analytic"]
        return exact if exact.refusal(geometry) is None else FICK_MODELS[numerical_model(geometry)]
    why = FICK_MODELS[model].refusal(geometry)
    if why is not None:
        raise InputError(f"diffusion.model {model} is not available for this "
                         f"{type(geometry).__name__}: {why}")
    return FICK_MODELS[model]


@dataclass(frozen=True)
class SolverSettings:
    """The solvers' tuned limits, frozen. The defaults are the run's; a caller (a test)
    passes others (``fickcam.run(scene, settings=...)``, ``plan``, ``solve``) instead of
    changing module values.

    Parameters
    ----------
    sweeps : Sweeps
        When a concentration-dependent step's sweeps stop.
    planform : Refinement
        How a two-phase planform is refined (its cap in cells, refinement apart).
    cells : CellCaps
        The most cells [-] of the linear system each mesh model may assemble
        (e.g. ``SolverSettings(cells=CellCaps(plane=300))``).
    """

    sweeps: Sweeps = SWEEPS
    planform: Refinement = REFINEMENT
    cells: CellCaps = MAX_CELLS


SETTINGS = SolverSettings()


def plan(geometry, diffusivity: Diffusivity, exposure: Exposure, times: np.ndarray,
         accuracy: float = 1e-3, model: str = "auto", sorption=None,
         surface_layer_depth: float | None = None, settings: SolverSettings = SETTINGS,
         cache: RunCache | None = None) -> Plan:
    """The model, cells and steps ``solve`` will use, and why, without solving
    (``sorption``: a law of ``problem.sorption``, None for Fick; ``surface_layer_depth``:
    the solve's, so that a plane plan and its solve share one outline expansion;
    ``settings``: the solve's; ``cache``: the run's, which the solve then reads).

    Parameters
    ----------
    geometry, diffusivity, exposure, times, accuracy, model, sorption
        The part [m], its D(T) [m^2/s], its surface history, the times [s], the relative
        accuracy [-] and the model asked for: the fields of :class:`~fickcam.diffusion.problem.definition.DiffusionProblem`.
    surface_layer_depth : float, optional
        The depth of the contact layer [m]; None: not given (a Fickian plan does not
        read it; a sorption plan takes ``LAYER_DEPTH``, 5e-4 m).
    settings : SolverSettings
        The solvers' tuned limits.
    cache : RunCache, optional
        What the run's plans and solves build once and share (meshes, step responses,
        tables); None: a fresh one, kept only for this call.

    Returns
    -------
    Plan
        The model, its cells and steps, the error estimate [-] and why.

    Raises
    ------
    fickcam.errors.InputError
        When the model is unknown or does not apply to the part, the geometry is not
        one of the five, or the accuracy is outside (0, 0.1].
    """
    return plan_problem(DiffusionProblem(geometry, diffusivity, exposure, times, accuracy, model,
                                         surface_layer_depth, sorption=sorption),
                        settings, cache)


def refuse(problem: DiffusionProblem) -> None:
    """Refuse, before any work, a problem that no model can plan: an unknown model, a
    model that does not apply to the part's shape or has no solution for it, an accuracy
    outside (0, 0.1] (``accuracy.budget.check_accuracy``), no route of its sorption law. A
    run checks every part so before it plans or solves the first (a refusal costs nothing
    then).

    Parameters
    ----------
    problem : DiffusionProblem
        The part [m], diffusivity [m^2/s], exposure, times [s], accuracy [-] and model.

    Raises
    ------
    fickcam.errors.InputError
        With the reason, in the words ``plan`` gives it.
    """
    _validate(problem)
    _fick_model(problem.geometry, problem.model)
    route_of(problem)


def plan_problem(problem: DiffusionProblem, settings: SolverSettings = SETTINGS,
                 cache: RunCache | None = None) -> Plan:
    """:func:`plan` of a ``DiffusionProblem`` (its ``store_fields`` and ``part`` unread): the
    registry's route for the problem (``route_of``) plans it.

    Parameters
    ----------
    problem : DiffusionProblem
        The part, its diffusivity, exposure and times [s], and how they are asked for.
    settings : SolverSettings
        The solvers' tuned limits.
    cache : RunCache, optional
        The run's cache; None: a fresh one.

    Returns
    -------
    Plan
        The model, its cells and steps, the error estimate [-] and why.
    """
    _validate(problem)
    return route_of(problem).plan(problem, settings, run_cache(cache))


def _as_fick(call, problem: DiffusionProblem, settings: SolverSettings, cache: RunCache):
    """``call`` (plan or solve of a problem) for Fick with D f(c0): f is constant where the
    part goes."""
    sorption, diffusivity = problem.sorption, problem.diffusivity
    factor = float(sorption.factor(problem.exposure.initial_moisture))
    scaled = Diffusivity(tuple(d * factor for d in diffusivity.pre_exponential),
                         diffusivity.activation_energy)
    done = call(replace(problem, diffusivity=scaled, sorption=None), settings, cache)
    return replace(done, reason=f"{describe(sorption)} is {factor:g} over the moisture met: "
                                f"Fick with D x {factor:g}; {done.reason}")


def solve(geometry, diffusivity: Diffusivity, exposure: Exposure, times: np.ndarray, *,
          accuracy: float = 1e-3, model: str = "auto", surface_layer_depth: float = LAYER_DEPTH,
          store_fields: bool = False, part: str = "", sorption=None,
          settings: SolverSettings = SETTINGS, cache: RunCache | None = None) -> DiffusionResult:
    """Moisture (weight %) of one part at ``times`` (s) under ``exposure``; with a
    ``sorption`` law (``problem.sorption``) the mean and surface are the total (free +
    bound) moisture and, for Langmuir, ``bound`` the bound-water mean. ``settings``: the
    solvers' tuned limits (``SolverSettings``); ``cache``: the run's (``RunCache``).

    Parameters
    ----------
    geometry, diffusivity, exposure
        The part [m], its D(T) [m^2/s] and its surface history, as in :func:`plan`.
    times : array_like
        The times [s] at which the moisture is wanted, from 0 (the start of the history).
    accuracy : float
        The relative accuracy [-], in (0, 0.1], a fraction of the moisture swing.
    model : str
        One of ``MODELS``; "auto" chooses (the exact series where it applies).
    surface_layer_depth : float
        The depth of the contact layer whose mean is reported as ``surface`` [m].
    store_fields : bool
        Keep the moisture field of every cell at every time (``fields``).
    part : str
        The part's name, for log messages.
    sorption : optional
        A sorption law of ``fickcam.diffusion.problem.sorption``; None: Fick's law.
    settings : SolverSettings
        The solvers' tuned limits.
    cache : RunCache, optional
        What the run's plans and solves build once and share (meshes, step responses,
        tables; read-only); None: a fresh one, kept only for this call (and the result's
        ``extend``).

    Returns
    -------
    DiffusionResult
        Mean and contact-layer moisture [weight %] at ``times``, with the model used and
        its error estimate [-].

    Raises
    ------
    fickcam.errors.InputError
        When the model is unknown or does not apply to the part, or the accuracy is
        outside (0, 0.1].
    """
    return solve_problem(DiffusionProblem(geometry, diffusivity, exposure, times, accuracy, model,
                                          surface_layer_depth, store_fields, part, sorption),
                         settings, cache)


def solve_problem(problem: DiffusionProblem, settings: SolverSettings = SETTINGS,
                  cache: RunCache | None = None) -> DiffusionResult:
    """:func:`solve` of a ``DiffusionProblem``: the registry's route for the problem
    (``route_of``) plans and solves it.

    Parameters
    ----------
    problem, settings
        As in :func:`plan_problem`.
    cache : RunCache, optional
        The run's cache; None: a fresh one (kept by the result's ``extend``).

    Returns
    -------
    DiffusionResult
        Mean and contact-layer moisture [weight %] at the problem's times.
    """
    _validate(problem)
    return route_of(problem).solve(problem, settings, run_cache(cache))


# ---------------------------------------------------------------- the routes' registry


@dataclass(frozen=True)
class Route:
    """One way of solving a problem, an entry of ``ROUTES``: why it does not take a problem
    (``refusal(problem)``: a sentence a user can read; None where it does), its plan and
    its solve. ``plan(problem, settings, cache) -> Plan``; ``solve(problem, settings,
    cache) -> DiffusionResult`` (it plans first where it needs the plan).

    Parameters
    ----------
    name : str
        The route's name (as logged and shown in a plan).
    refusal : callable
        ``refusal(problem) -> str | None``: why the route does not take the problem.
    plan : callable
        ``plan(problem, settings, cache) -> Plan``.
    solve : callable
        ``solve(problem, settings, cache) -> DiffusionResult``.
    """

    name: str
    refusal: Callable
    plan: Callable
    solve: Callable


def route_of(problem: DiffusionProblem) -> Route:
    """The first route of the problem's law (``ROUTES``, in the order ``auto`` prefers them)
    that takes the problem; an ``InputError`` with the last refusal where none does.

    Parameters
    ----------
    problem : DiffusionProblem
        The part [m], diffusivity [m^2/s], exposure, times [s] and sorption law.

    Returns
    -------
    Route
        The first route of ``ROUTES[law_of(problem.sorption)]`` whose refusal is None.

    Raises
    ------
    fickcam.errors.InputError
        When every route of the law refuses the problem (the message is the last refusal).
    """
    why = None
    for route in ROUTES[law_of(problem.sorption)]:
        why = route.refusal(problem)
        if why is None:
            return route
    raise InputError(why)


def law_of(sorption) -> str:
    """The registry's key of a sorption law: fick (None), langmuir or nonlinear.

    Parameters
    ----------
    sorption : object or None
        A law of ``problem.sorption``; None for Fick.

    Returns
    -------
    str
        ``"nonlinear"`` (a concentration-dependent D), ``"langmuir"`` or ``"fick"``.
    """
    if is_nonlinear(sorption):
        return "nonlinear"
    return "langmuir" if is_langmuir(sorption) else "fick"


def _with_layer(problem: DiffusionProblem) -> DiffusionProblem:
    """The problem with its contact layer given (a plan alone may leave it None)."""
    if problem.surface_layer_depth is None:
        return replace(problem, surface_layer_depth=LAYER_DEPTH)
    return problem


def _planned(problem: DiffusionProblem, settings: SolverSettings, cache: RunCache) -> Plan:
    """The problem's plan, logged."""
    chosen = plan_problem(problem, settings, cache)
    log.debug("%s: %s, %d cells, %d steps (%s)", problem.name, chosen.model, chosen.cells,
              chosen.steps, chosen.reason)
    return chosen


def _always(problem: DiffusionProblem) -> None:
    return None


# Fick: the Fickian model of ``FICK_MODELS`` that ``auto`` or ``diffusion.model`` picks
def _plan_fick(problem: DiffusionProblem, settings: SolverSettings, cache: RunCache) -> Plan:
    return _fick_model(problem.geometry, problem.model).plan(problem, settings.cells, cache)


def _solve_fick(problem: DiffusionProblem, settings: SolverSettings,
                cache: RunCache) -> DiffusionResult:
    chosen = _planned(problem, settings, cache)
    result = FICK_MODELS[chosen.model].solve(problem, chosen, cache)
    if isinstance(result.extend, PanelExtension):  # its plan at new times: this run's settings
        return replace(result, extend=replace(
            result.extend, replan=lambda at: plan_problem(problem.at(at), settings, cache),
            resolve=lambda at: solve_problem(problem.at(at), settings, cache)))
    return result


# Langmuir (two-phase): the Fickian model that ``auto`` or ``diffusion.model`` picks decides
# how: its exact modes, a CamPlate's or LinkBar's planform quadrature x the exact sheet
# (``planform_modes``), else the direct finite volumes (``two_phase_mesh``)
def _two_phase_refusal(fickian: str):
    """Refuses a problem whose Fickian model is not ``fickian``."""
    def refusal(problem: DiffusionProblem) -> str | None:
        chosen = _fick_model(problem.geometry, problem.model).name
        return None if chosen == fickian else f"the part's Fickian model is {chosen}"
    return refusal


def _plan_two_phase_modes(problem, settings, cache) -> Plan:
    return Plan("analytic", 0, 0, f"{describe(problem.sorption)}: exact Fickian modes of the "
                "part, each a 2x2 free/bound system advanced exactly through the history",
                problem.accuracy)


def _plan_two_phase_planform(problem, settings, cache) -> Plan:
    return plan_two_phase_planform(_with_layer(problem), settings.planform, cache)


def _solve_two_phase_modes(problem, settings, cache) -> DiffusionResult:
    return langmuir_modes(_with_layer(problem), _planned(problem, settings, cache),
                          settings.planform, cache)


def _plan_two_phase_mesh(problem, settings, cache) -> Plan:
    chosen = _fick_model(problem.geometry, problem.model).name
    direct = plan_direct(_with_layer(problem), chosen, caps=settings.cells, cache=cache)
    return replace(direct, reason=f"{describe(problem.sorption)}; {direct.reason}")


def _solve_two_phase_mesh(problem, settings, cache) -> DiffusionResult:
    return solve_direct(problem, _planned(problem, settings, cache), cache=cache,
                        marcher=two_phase_marcher(problem.sorption, problem.exposure))


# Concentration-dependent D: Fick with D f where f is one number, the corrected product
# (auto on a Bar, CamPlate or LinkBar), else the part's own mesh swept per step
def _prism_under_auto(problem: DiffusionProblem) -> str | None:
    if problem.model != "auto" or not problem.geometry.mirror_axes:
        return "auto on a Bar, CamPlate or LinkBar only"
    return None


def _constant_factor_refusal(problem: DiffusionProblem) -> str | None:
    """Fick with D f takes a D(c) problem where f is one number over the moisture the part
    meets (k = 0: the Fickian models' own result)."""
    why = _prism_under_auto(problem)
    if why is None and spread(problem.sorption, problem.exposure, problem.times) > 1.0 + 1e-12:
        return "D(c) changes over the moisture the part meets"
    return why


def _corrected_refusal(problem: DiffusionProblem) -> str | None:
    """The D(c) sheet x planform corrected on coarse 3-D cells (``corrected_product``) is far
    cheaper than the 3-D cells alone at the same accuracy; for a Bar (the prism of its
    rectangular section) from ``BAR_CORRECTED_FROM`` down, above it its octant's cells."""
    if problem.geometry.grid == "box" and problem.accuracy > BAR_CORRECTED_FROM:
        return f"a Bar's octant is cheaper above accuracy {BAR_CORRECTED_FROM:g}"
    return _prism_under_auto(problem)


def _swept_refusal(problem: DiffusionProblem) -> str | None:
    """No exact series and no planform x sheet product exist for D(c) (the Laplacian no
    longer separates): ``plane`` is refused (``analytic`` means the mesh model)."""
    if problem.model == "plane":
        return (f"diffusion.model plane has no concentration-dependent form (D(c) does not "
                f"separate); use solid or auto for a {type(problem.geometry).__name__}")
    return None


def _plan_corrected(problem, settings, cache) -> Plan:
    corrected = plan_corrected(problem)
    return replace(corrected, reason=f"{describe(problem.sorption)}; {corrected.reason}")


def _solve_corrected(problem, settings, cache) -> DiffusionResult:
    chosen = plan_problem(problem, settings, cache)
    return _held(problem, settings, cache, chosen,
                 solve_corrected(problem, chosen.reason, settings.sweeps))


def _swept_mesh(geometry, model: str) -> str:
    """The D(c) sweeps' mesh: the slab (Sheet), the (r, z) grid (Disc), 3-D cells cut at
    the mirror planes (Bar, CamPlate, LinkBar: ``symmetry_cuts``)."""
    if geometry.mirror_axes:
        return "solid"
    return numerical_model(geometry) if model in ("auto", "analytic") else model


MIRRORS = {(0, 1, 2): "; solved on one octant (mirror planes)",  # by ``Geometry.mirror_axes``
           (1,): "; solved on half the thickness (mid-plane mirror)"}


def _plan_swept(problem, settings, cache) -> Plan:
    problem = _with_layer(problem)
    chosen = _swept_mesh(problem.geometry, problem.model)
    mirror_cut = chosen == "solid"   # the 3-D cells cut at the mirror planes
    direct = nonlinear_plan(
        lambda d, a, at: plan_direct(replace(problem, diffusivity=d, accuracy=a, times=at),
                                     chosen, mirror_cut, settings.cells, cache),
        problem.diffusivity, problem.sorption, problem.exposure, problem.times, problem.accuracy)
    return replace(direct, reason=f"{describe(problem.sorption)}; {direct.reason}"
                                  f"{MIRRORS.get(problem.geometry.mirror_axes, '')}")


def _solve_swept(problem, settings, cache) -> DiffusionResult:
    chosen = _planned(problem, settings, cache)
    return _held(problem, settings, cache, chosen,
                 solve_nonlinear(problem, chosen, settings.sweeps, cache))


def _held(problem, settings, cache, chosen: Plan, result: DiffusionResult) -> DiffusionResult:
    """A D(c) result whose ``extend`` reads between the steps where the cells stay and
    solves again where a plan at the new times has other cells (``dense_output``)."""
    def again(at):
        return plan_problem(problem.at(at), settings, cache)

    def resolve(at):
        return solve_problem(replace(problem.at(at), store_fields=False), settings, cache)
    return held_to_plan(result, chosen, again, resolve)


def _plan_as_fick(problem, settings, cache) -> Plan:
    return _as_fick(plan_problem, problem, settings, cache)


def _solve_as_fick(problem, settings, cache) -> DiffusionResult:
    return _as_fick(solve_problem, problem, settings, cache)


# Each law's routes, in the order ``auto`` prefers them (``route_of`` takes the first that
# takes the problem)
ROUTES = {
    "fick": (Route("fick", _always, _plan_fick, _solve_fick),),
    "langmuir": (
        Route("two-phase modes", _two_phase_refusal("analytic"), _plan_two_phase_modes,
              _solve_two_phase_modes),
        Route("two-phase planform", _two_phase_refusal("plane"), _plan_two_phase_planform,
              _solve_two_phase_modes),
        Route("two-phase mesh", _always, _plan_two_phase_mesh, _solve_two_phase_mesh)),
    "nonlinear": (
        Route("Fick with D f", _constant_factor_refusal, _plan_as_fick, _solve_as_fick),
        Route("corrected product", _corrected_refusal, _plan_corrected, _solve_corrected),
        Route("swept mesh", _swept_refusal, _plan_swept, _solve_swept)),
}
