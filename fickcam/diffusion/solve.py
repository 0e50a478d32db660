"""Public diffusion entry points: ``plan`` (what a solve will do) and ``solve``.

Models (``diffusion.model``):

- ``analytic``: Crank's series with Duhamel superposition in rescaled time
  (``fickcam.diffusion.exact``): Sheet, Bar (product of three sheets), solid Disc.
- ``slab``: Sheet through its thickness, 1-D finite volumes.
- ``axisymmetric``: Disc or annulus in (r, z), FiPy CylindricalGrid2D.
- ``solid``: Bar, FiPy Grid3D; CamPlate or LinkBar, FiPy prisms of the outline on
  Delaunay-admissible cells (``prism``, ``fv.prism``): genuinely 3-D, marching the
  history itself, the independent check of ``plane`` (which ``auto`` picks: cheaper).
  Widths graded towards exposed faces where that saves cells (``layout``).
- ``plane``: CamPlate or LinkBar: 2-D triangle mesh of the outline times the
  through-thickness sheet (product solution, Crank 1975 §4.3.4 / eq. 4.51
  generalised: for a prism with a uniform surface value the unsaturated
  fraction is the product of the planform and the sheet fractions), with
  Duhamel superposition over the surface history (Crank 1975 §4.2.1, eq. 4.34).

Numerical models march backward Euler on geometric steps that restart at each
environment change (``timesteps``), twice: on the plan's steps and on the same
steps bisected. The difference measures the time error, and Richardson's
extrapolation 2 c_fine - c_coarse cancels its first-order part. Cells come from
the spatial error model ``SPACE_ERROR`` (dx/L)^2 / tau*_lo, calibrated against
Crank's series (notes/fipy-measured.md: (dx/h)^2/(16 t) upper bound).
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from .exposure import Diffusivity, Exposure
from .geometry import Bar, CamPlate, Disc, LinkBar, Sheet
from . import timesteps

log = logging.getLogger(__name__)

MODELS = ("auto", "analytic", "slab", "axisymmetric", "plane", "solid")
NUMERICAL_MODEL = {Sheet: "slab", Disc: "axisymmetric", Bar: "solid", CamPlate: "plane",
                   LinkBar: "plane"}
ALLOWED_MODELS = {Sheet: {"analytic", "slab"}, Disc: {"analytic", "axisymmetric"},
                  Bar: {"analytic", "solid"}, CamPlate: {"plane", "solid"},
                  LinkBar: {"plane", "solid"}}  # solid CamPlate/LinkBar: prisms (prism.py)
SPACE_ERROR = 1.4e-2     # err ~ SPACE_ERROR (dx/L)^2 / tau*_lo, measured on the sheet
TIME_ERROR = 6.3e-3      # extrapolated BE error ~ TIME_ERROR / m^2 (m = steps per doubling)
PAIR_TO_EXTRAPOLATED = 7.0  # extrapolated error ~ 7 (c_fine - c_coarse)^2 (measured)
FIRST_STEP = 1e-6        # first step after a change, scaled time tau D / L^2
MAX_CELLS = {"slab": 4000, "axisymmetric": 40_000, "solid": 120_000, "plane": 40_000}
MIN_CELLS_PER_AXIS = 4
EXPANSION_SHARE = 0.25  # plane: share of the accuracy allowed to the short-time expansion
ANALYTIC_ERROR = 1e-8    # series truncation + ramp quadrature of exact.py


@dataclass(frozen=True)
class Plan:
    """What ``solve`` will do for one part (printed by ``fickcam check``)."""

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


@dataclass
class DiffusionResult:
    """Moisture of one part at the requested times (weight %)."""

    times: np.ndarray
    mean: np.ndarray
    surface: np.ndarray
    model: str
    cells: int
    steps: int
    error_estimate: float
    reason: str
    fields: np.ndarray | None = None
    cell_coordinates: dict[str, np.ndarray] = field(default_factory=dict)


# ----------------------------------------------------------------- scales


@dataclass(frozen=True)
class _Scales:
    """Rescaled time and the length scale of the non-dimensional problem."""

    a_ref: float
    d_ref: float      # through-thickness D at the reference (hottest) temperature, m^2/s
    length: float     # thickness, m

    def star(self, tau_seconds: np.ndarray) -> np.ndarray:
        """tau* = tau D_ref / L^2 (Fourier number of the rescaled time)."""
        return np.asarray(tau_seconds) * self.d_ref / self.length ** 2


def _scales(geometry, diffusivity: Diffusivity, exposure: Exposure) -> _Scales:
    a_ref = timesteps.reference_factor(diffusivity, exposure)
    return _Scales(a_ref, float(diffusivity.pre_exponential[2]) * a_ref, float(geometry.thickness))


def _extents(geometry, diffusivity: Diffusivity) -> tuple[float, ...]:
    """Scaled extents (x_i / L) sqrt(D_z / D_i) of the numerical model's axes."""
    dx, dy, dz = (float(v) for v in diffusivity.pre_exponential)
    h = float(geometry.thickness)
    if isinstance(geometry, Sheet):
        return (1.0,)
    if isinstance(geometry, Disc):
        return ((geometry.outer_radius - geometry.inner_radius) / h * math.sqrt(dz / dx), 1.0)
    if isinstance(geometry, Bar):
        return (geometry.length / h * math.sqrt(dz / dx),
                geometry.width / h * math.sqrt(dz / dy), 1.0)
    from .planform import outline_extent

    ex, ey = outline_extent(geometry)
    return (ex / h * math.sqrt(dz / dx), ey / h * math.sqrt(dz / dy), 1.0)


def _earliest_output(change_stars: np.ndarray, output_stars: np.ndarray) -> float:
    """Smallest positive time from an environment change to a later output (scaled)."""
    gaps = []
    for tau in output_stars:
        before = change_stars[change_stars < tau]
        if before.size:
            gaps.append(tau - before[-1])
    return max(min(gaps), 1e3 * FIRST_STEP) if gaps else 1.0


# ------------------------------------------------------------------- plan


def _validate(geometry, model: str, accuracy: float) -> None:
    if model not in MODELS:
        raise InputError(f"diffusion.model {model!r}: one of {', '.join(MODELS)}")
    if type(geometry) not in NUMERICAL_MODEL:
        raise InputError(f"unsupported diffusion geometry {type(geometry).__name__}")
    if not (0 < accuracy < 1):
        raise InputError(f"diffusion.accuracy {accuracy!r}: must lie in (0, 1)")
    if model != "auto" and model not in ALLOWED_MODELS[type(geometry)]:
        raise InputError(f"diffusion.model {model!r} does not apply to a "
                         f"{type(geometry).__name__} (use one of "
                         f"{', '.join(sorted(ALLOWED_MODELS[type(geometry)]))} or auto)")


def analytic_available(geometry) -> bool:
    """The exact path covers Sheet, Bar and the solid Disc when ``exact.py`` provides
    ``exact_history`` (and, if it has one, its own ``exact_available`` agrees)."""
    if isinstance(geometry, Disc) and geometry.inner_radius > 0:
        return False
    if not isinstance(geometry, (Sheet, Bar, Disc)):
        return False
    try:
        from . import exact
    except ImportError:
        return False
    if not hasattr(exact, "exact_history"):
        return False
    check = getattr(exact, "exact_available", None)
    return bool(check(geometry)) if check is not None else True


def _no_exact_reason(geometry) -> str:
    if isinstance(geometry, Disc) and geometry.inner_radius > 0:
        return "an annulus has no product solution (use axisymmetric)"
    if not isinstance(geometry, (Sheet, Bar, Disc)):
        return "no separable exact solution (use plane)"
    return "fickcam.diffusion.exact provides no exact_history"


def plan(geometry, diffusivity: Diffusivity, exposure: Exposure, times: np.ndarray,
         accuracy: float = 1e-3, model: str = "auto") -> Plan:
    """The model, cells and steps ``solve`` will use, and why, without solving."""
    _validate(geometry, model, accuracy)
    if model in ("auto", "analytic") and analytic_available(geometry):
        return Plan("analytic", 0, 0, "exact Crank series with Duhamel superposition in "
                    "rescaled time (linear, one Arrhenius factor): cheapest and exact",
                    ANALYTIC_ERROR)
    if model == "analytic":
        raise InputError(f"diffusion.model analytic is not available for this "
                         f"{type(geometry).__name__}: {_no_exact_reason(geometry)}")
    chosen = NUMERICAL_MODEL[type(geometry)] if model == "auto" else model
    scales = _scales(geometry, diffusivity, exposure)
    change = scales.star(timesteps.rescaled_time(diffusivity, exposure, exposure.change_times,
                                                 scales.a_ref))
    outputs = scales.star(timesteps.rescaled_time(diffusivity, exposure, np.asarray(times, float),
                                                  scales.a_ref))
    t_lo = _earliest_output(change, outputs)
    if chosen == "plane":  # expansion of the outline, then a graded mesh (planform)
        from .planform import plan_plane

        return plan_plane(geometry, diffusivity, change, outputs, accuracy)
    cells = _cells(geometry, diffusivity, chosen, accuracy, t_lo)
    per_doubling = max(4, math.ceil(math.sqrt(TIME_ERROR / (0.5 * accuracy))))
    nodes = timesteps.step_nodes(change, outputs, FIRST_STEP, per_doubling, exposure.ramp)
    steps = 3 * (nodes.size - 1)  # coarse march + bisected march
    estimate = cells.space_error + TIME_ERROR / per_doubling ** 2
    why = {"slab": "sheet through the thickness, 1-D finite volumes",
           "axisymmetric": "disc/annulus in (r, z)" + (
               " (bore: no exact path)" if isinstance(geometry, Disc) and geometry.inner_radius > 0
               else ""),
           "solid": "bar in 3-D" if isinstance(geometry, Bar) else
           "3-D prisms of the outline (Delaunay-admissible cells x graded thickness)"}[chosen]
    reason = (f"{why}; cells from accuracy ({cells.note}, earliest output "
              f"tau*={t_lo:.2g}), backward Euler {per_doubling} steps/doubling + Richardson")
    if model == "auto" and isinstance(geometry, (Sheet, Bar, Disc)):
        reason += "; exact path unavailable"
    if estimate > accuracy:
        reason += f"; capped at {MAX_CELLS[chosen]} cells: error above the requested accuracy"
    return Plan(chosen, cells.total, int(steps), reason, float(estimate), cells.cells,
                per_doubling, finest=cells.finest, growth=cells.growth)


def _cells(geometry, diffusivity, model: str, accuracy: float, t_lo: float):
    """The cells of a direct model (``layout``): prisms for a CamPlate or LinkBar, graded
    or uniform for a Disc or Bar, uniform for the slab."""
    from . import layout

    if isinstance(geometry, (CamPlate, LinkBar)):
        return layout.prism_layout(geometry, diffusivity.pre_exponential, accuracy, t_lo,
                                   MAX_CELLS[model], SPACE_ERROR)
    return layout.choose(geometry, _extents(geometry, diffusivity), accuracy, t_lo,
                         MAX_CELLS[model], SPACE_ERROR)


# ------------------------------------------------------------------ solve


def solve(geometry, diffusivity: Diffusivity, exposure: Exposure, times: np.ndarray, *,
          accuracy: float = 1e-3, model: str = "auto", surface_layer_depth: float = 5e-4,
          store_fields: bool = False, part: str = "") -> DiffusionResult:
    """Moisture (weight %) of one part at ``times`` (s) under ``exposure``."""
    times = np.asarray(times, float)
    chosen = plan(geometry, diffusivity, exposure, times, accuracy, model)
    log.debug("%s: %s, %d cells, %d steps (%s)", part or type(geometry).__name__, chosen.model,
             chosen.cells, chosen.steps, chosen.reason)
    if chosen.model == "analytic":
        return _solve_analytic(geometry, diffusivity, exposure, times, surface_layer_depth,
                               store_fields, chosen)
    if chosen.model == "plane":
        from .planform import solve_plane

        return solve_plane(geometry, diffusivity, exposure, times, chosen,
                           surface_layer_depth=surface_layer_depth, store_fields=store_fields,
                           part=part)
    return solve_direct(geometry, diffusivity, exposure, times, chosen,
                        surface_layer_depth=surface_layer_depth, store_fields=store_fields,
                        part=part)


def _solve_analytic(geometry, diffusivity, exposure, times, depth, store_fields,
                    chosen: Plan) -> DiffusionResult:
    from .exact import exact_history

    history = exact_history(geometry, diffusivity, exposure, times, surface_layer_depth=depth)
    mean, surface = (_field_of(history, "mean"), _field_of(history, "surface"))
    result = DiffusionResult(times, np.asarray(mean, float), np.asarray(surface, float),
                             "analytic", 0, 0, chosen.error_estimate, chosen.reason)
    if store_fields:
        fields, coordinates = _analytic_fields(geometry, diffusivity, exposure, times, depth)
        result.fields, result.cell_coordinates = fields, coordinates
        result.cells = fields.shape[1]
    return result


def _field_of(history, name):
    return history[name] if isinstance(history, dict) else getattr(history, name)


FIELD_POINTS = {Sheet: (40,), Disc: (24, 12), Bar: (16, 12, 8)}  # cell centres for exact fields


def _analytic_fields(geometry, diffusivity, exposure, times, depth):
    """Exact fields at the centres of a structured grid (``FIELD_POINTS`` cells per axis);
    cell_x/y/z are the coordinates (a Disc: x = r)."""
    from .exact import exact_history_field

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


# -------------------------------------------------------- direct marching


def discretise(geometry, diffusivity: Diffusivity, cells: tuple[int, ...],
               surface_layer_depth: float, finest: float = 0.0, growth: float = 0.0):
    """The FiPy-assembled operator of a Sheet, Disc or Bar on ``cells`` (uniform), or
    graded from ``finest`` by ``growth`` (scaled units, ``layout``); of a CamPlate or
    LinkBar on prisms (graded: ``finest`` > 0)."""
    from . import fv, layout

    d = tuple(float(v) for v in diffusivity.pre_exponential)
    widths = (layout.physical_widths(geometry, _extents(geometry, diffusivity), d, finest,
                                     growth)
              if finest > 0 and isinstance(geometry, (Disc, Bar)) else None)
    if isinstance(geometry, Sheet):
        return fv.sheet(geometry.thickness, cells[0], surface_layer_depth)
    if isinstance(geometry, Disc):
        return fv.disc(geometry.outer_radius, geometry.thickness, geometry.inner_radius,
                       cells[0], cells[1], surface_layer_depth, d[0], d[2], widths=widths)
    if isinstance(geometry, Bar):
        return fv.bar(geometry.length, geometry.width, geometry.thickness, cells,
                      surface_layer_depth, d, widths=widths)
    if isinstance(geometry, (CamPlate, LinkBar)):
        from .planform import stretch_of
        from .prism import band_share

        tess = layout.planform_cells(geometry, finest, growth, stretch_of(d))
        return fv.prism(tess, geometry.thickness, layout.prism_widths(finest, growth)
                        * geometry.thickness, band_share(tess, surface_layer_depth), d)
    raise InputError(f"no direct finite-volume model for {type(geometry).__name__}")


@dataclass(frozen=True)
class StepPlan:
    """Step boundaries in scaled time with the surface value at each and the outputs."""

    nodes: np.ndarray
    times: np.ndarray       # s, the physical time of each node
    surface: np.ndarray     # weight %, g(t) at each node (right-continuous)
    surface_before: np.ndarray  # weight %, g(t-) at each node (left limit: a step ending there)
    outputs: np.ndarray     # node index of each requested time
    restarts: np.ndarray    # node index of each environment change


def step_plan(diffusivity, exposure, times, scales: _Scales, per_doubling: int,
              bisect: bool = False) -> StepPlan:
    """Nodes of the march (``bisect``: every step halved, for the Richardson pair)."""
    def tau_star(t):
        return scales.star(timesteps.rescaled_time(diffusivity, exposure, t, scales.a_ref))

    change = tau_star(exposure.change_times)
    outputs = tau_star(times)
    nodes = timesteps.step_nodes(change, outputs, FIRST_STEP, per_doubling, exposure.ramp)
    if bisect:
        nodes = np.sort(np.concatenate([nodes, 0.5 * (nodes[1:] + nodes[:-1])]))
    node_times = timesteps.inverse_time(nodes, tau_star, exposure.change_times)
    exact_nodes = np.isin(nodes, change)
    node_times[exact_nodes] = exposure.change_times[np.searchsorted(change, nodes[exact_nodes])]
    surface = np.asarray(exposure.surface_moisture(node_times), float)
    before = surface.copy()
    jumps = np.flatnonzero(exact_nodes)[1:]
    if jumps.size:
        backwards = node_times[jumps] - 1e-9 * (node_times[jumps] - node_times[jumps - 1])
        before[jumps] = exposure.surface_moisture(backwards)
    return StepPlan(nodes, node_times, surface, before, timesteps.nearest_nodes(nodes, outputs),
                    np.searchsorted(nodes, change[:-1]))


def swing(exposure: Exposure, times: np.ndarray) -> float:
    """Largest |g(t) - c0| over the history: the scale of the relative error."""
    t = np.concatenate([timesteps._sample_times(exposure), np.asarray(times, float)])
    return float(np.max(np.abs(np.asarray(exposure.surface_moisture(t)) -
                               exposure.initial_moisture)))


def solve_direct(geometry, diffusivity, exposure, times, chosen: Plan, *,
                 surface_layer_depth: float = 5e-4, store_fields: bool = False,
                 part: str = "", extrapolate: bool = True, disc=None) -> DiffusionResult:
    """March a Sheet, Disc, Bar or prisms of a CamPlate or LinkBar on its FiPy mesh
    (Richardson pair in time); ``disc``: an operator built by the caller instead."""
    from . import fv

    scales = _scales(geometry, diffusivity, exposure)
    if disc is None:
        disc = discretise(geometry, diffusivity, chosen.cells_per_axis, surface_layer_depth,
                          chosen.finest, chosen.growth)
    runs = []
    for bisect in (False, True):
        steps = step_plan(diffusivity, exposure, times, scales, chosen.steps_per_doubling, bisect)
        runs.append(fv.march(disc, steps.nodes, steps.surface, exposure.initial_moisture,
                             steps.outputs, steps.times, keep_fields=store_fields, part=part,
                             surface_before=steps.surface_before))
    coarse, fine = runs
    scale = swing(exposure, times) or 1.0
    pair = float(np.max(np.abs(fine.mean - coarse.mean))) / scale
    space = chosen.error_estimate - TIME_ERROR / chosen.steps_per_doubling ** 2
    if extrapolate:
        def combine(a, b):
            return 2.0 * b - a
        estimate = space + PAIR_TO_EXTRAPOLATED * pair ** 2
    else:
        def combine(a, b):
            return b
        estimate = space + pair
    result = DiffusionResult(
        times, combine(coarse.mean, fine.mean), combine(coarse.layer, fine.layer), chosen.model,
        disc.cells, coarse.steps + fine.steps, float(max(estimate, 0.0)), chosen.reason)
    if store_fields:
        result.fields = combine(coarse.fields, fine.fields)
        result.cell_coordinates = disc.coordinates
    return result
