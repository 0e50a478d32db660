"""Concentration-dependent D on a CamPlate or LinkBar: the D(c) sheet x D(c) planform
product, corrected on coarse mirrored 3-D prisms (defect correction; Stetter 1978,
Numer. Math. 29:425-443; Böhmer, Hemker & Stetter 1984, Computing Suppl. 5:1-32).

For Fick on a prism (planform x thickness) the unaccomplished uptakes multiply,
U = g - c = U_sheet U_planform / (g - c0) (Crank 1975 §4.3, the product of eq. 4.51), and
on a prism mesh (planform cells x z widths, a tensor product) the same holds for the
discrete fields. So the 3-D cells' error splits into a sheet factor and a planform
factor, each measurable on its own grid: the D(c) sheet on the prisms' z widths
(``half_slab``) against a fine sheet, and the D(c) planform alone (``planform_disc``, the
prisms' cells without their faces) against the same planform refined twice and four
times (Richardson, second order: 1.25e-3 then 3.1e-4 on the demo cam's mean at 1 d).
The result takes the coarse 3-D U and swaps each factor's coarse value for its fine one:

    U = U_3d (U_sheet,ref / U_sheet,h) (U_planform,ref / U_planform,h)

for the mean, and for the contact layer with the planform's band in place of its mean
(the layer spans the thickness). With constant D this is the fine sheet x fine planform
(independent of the 3-D mesh); with D(c) the 3-D cells carry what does not separate,
and the change of the result between two 3-D meshes measures it (``MESH_LEVELS``).

Measured first and dropped: Fick at Crank's (1975 §9.3) weighted-mean D on the same
3-D mesh (c_h + v_exact - v_h). With f(surface value) on the exposed faces (before the
Kirchhoff face mean of ``sorption.mean_factor``) the Fickian and the D(c) sheets on the
demo cam's z widths erred with opposite signs, so the difference erred more than either.
Since that fix they err alike (plan 0.1, 1 d: -5.4e-3 both; the difference 3e-5, at most
8.9e-4 over the outputs; ``benchmarks/dc_defect_correction.py fickian-reference``): worth
a new trial on the 3-D cells.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from . import layout
from .calibration import MIN_STEPS_PER_DOUBLING, PAIR_TO_EXTRAPOLATED, TIME_ERROR
from .clock import scales as scales_of
from .direct import plan_direct, step_plan, swing
from .discretisation import Discretisation, assemble
from .fv import normalised
from .cellmoments import corrected_weights
from .fvprism import prism
from .gridcheck import taken, three_levels
from .geometry import Sheet
from .mirrored import half, mirrored
from .prism import band_share
from .nonlinear import (Faces, dries_to_a_skin, fastest, nonlinear_plan,
                        solve_nonlinear, spread, sweep_march, wettest)
from .planmodes import LAYER_TOLERANCE
from .results import DiffusionResult, Plan
from .scaling import stretch_of

MESH_LEVELS = (1.0, 0.5)   # accuracies of the two 3-D plans (coarse cells suffice)
REFINE = (2.0, 4.0)        # planform refinements (finest and growth / R) for Richardson
PLANFORM_CELLS = 60_000    # the finest planform tried
SHEET_SHARE = 0.1          # the fine sheet's accuracy: this share of the requested one
PLANFORM_SHARE = 0.5       # of the accuracy: the planform's Richardson estimate
SKIN_ESTIMATE_MARGIN = 1.0  # on the 3-D change of a drying part (``skin_margin``), the cells'
#   margin (``nonlinear.SKIN_CELLS_MARGIN``). Measured on the 4 x 3 x 2 mm plate drying at
#   1e-2 (benchmarks/dc_defect_correction.py plate-order, skin-margin): the 0.5 plan is
#   0.29 (k = 2) and 1.62 (k = 3: the changes stop shrinking as the plans' growth changes)
#   times the (1, 0.5) change from the 0.125 plan; the estimate / the distance to the stored
#   3-D runs (2.97e-3, 3.54e-3) is 2.54 and 1.31 with a margin 0, 4.01 and 2.28 with 1, 8.44
#   and 5.20 with the old 4 (set before the Kirchhoff face mean); a safety of 2 needs 0.71
TARGET = "; est. = the target: the run measures its own and warns above it"
ORDER_ONE = 1.0 / (math.sqrt(2.0) - 1.0)  # the finer 3-D plan's error / the change between
#   the two, at order 1 in w0 (w0 ~ sqrt(accuracy): ratio sqrt 2). Order 2 (a factor 1) is
#   not what these plans show: on the 4 x 3 x 2 mm plate (k = 2, plans 1, 0.5, 0.25, 0.125,
#   benchmarks/dc_defect_correction.py plate-order) the observed order of the successive
#   changes scatters from -10 to 12 over the outputs (the z cells step 4, 6, 6, 8: not a
#   nested refinement), and where the changes shrink steadily it is below 1 (absorbing,
#   tau* = 0.03: 0.37, 0.77). The 0.5 plan is 0.44 (absorbing) and 0.29 (drying) times the
#   change from the 0.125 plan, 0.79 and 2.8 times it from the stored 3-D runs (the latter
#   no closer on the 0.125 plan: not the 3-D cells' error); kept as an upper bound


@dataclass(frozen=True)
class Pair:
    """A Richardson-combined march (2 fine - coarse in time) and its time pair."""

    mean: np.ndarray
    layer: np.ndarray
    fields: np.ndarray | None = None
    steps: int = 0
    pair: float = 0.0   # largest |fine - coarse| of the mean (time error indicator)


def half_slab(z_widths: np.ndarray) -> Discretisation:
    """FiPy Grid1D of a half thickness on ``z_widths`` (scaled, from the exposed face at
    z = 0; the other end is the mid-plane mirror, insulated)."""
    from fipy import Grid1D

    mesh = Grid1D(dx=np.asarray(z_widths, float))
    exposed = np.asarray(mesh.exteriorFaces, bool) & np.isclose(
        np.asarray(mesh.faceCenters)[0], 0.0, atol=1e-12)
    volumes, stiffness, boundary = assemble(mesh, exposed=exposed)
    weights = normalised(volumes)
    return Discretisation(volumes, stiffness, boundary, weights, weights)


def planform_disc(geometry, d, finest: float, growth: float, depth: float):
    """(Discretisation, corrected weights): the planform alone (a prism of infinite
    thickness) on the graded admissible cells of (``finest``, ``growth``), one layer of
    the mirrored prisms with its exposed face's coupling 8 V (half-layer height 1/4
    scaled) taken out of the boundary vector (as ``planmodes.planform_operator``); its
    mean and layer weights the plate's (cell volumes, band shares: the same discrete
    product), and ``cellmoments``' second-order (mean, layer) weights on u - g beside."""
    tess = layout.planform_cells(geometry, finest, growth, stretch_of(d))
    disc = prism(tess, geometry.thickness, np.array([0.5 * geometry.thickness]),
                 band_share(tess, depth), d, mid_plane=True)
    return (replace(disc, boundary=disc.boundary - 8.0 * disc.volumes),
            corrected_weights(tess, depth))


def richardson_march(disc, law, top, exposure, times, scales, per_doubling, keep, part) -> Pair:
    """The swept backward-Euler march (``nonlinear``) on the plan's steps and on them
    bisected, combined 2 fine - coarse."""
    faces = Faces.of(disc)
    coarse, fine = (sweep_march(faces, disc, law, top,
                                step_plan(exposure, times, scales, per_doubling, bisect),
                                exposure.initial_moisture, keep, part)
                    for bisect in (False, True))
    fields = 2.0 * fine.fields - coarse.fields if keep else None
    return Pair(2.0 * fine.mean - coarse.mean, 2.0 * fine.layer - coarse.layer, fields,
                coarse.steps + fine.steps, float(np.max(np.abs(fine.mean - coarse.mean))))


def corrected(plate: Pair, sheet: tuple, planform: tuple, surface: np.ndarray):
    """(mean, layer): the plate's U = g - c times the ratio of the fine reference's U to the
    coarse grid's, for the sheet (the layer spans the thickness) and for the planform
    (its mean, its band for the layer). A ratio is 1 where the coarse grid's U is within
    round-off of zero. ``sheet``, ``planform``: (coarse Pair, fine reference Pair)."""
    floor = 1e-9 * max(float(np.max(np.abs(surface))), 1e-300)

    def ratio(fine, coarse):
        gap = surface - coarse
        small = np.abs(gap) <= floor
        return np.where(small, 1.0, (surface - fine) / np.where(small, 1.0, gap))
    (s_h, s_ref), (p_h, p_ref) = sheet, planform
    through = ratio(s_ref.mean, s_h.mean)
    return (surface - (surface - plate.mean) * through * ratio(p_ref.mean, p_h.mean),
            surface - (surface - plate.layer) * through * ratio(p_ref.layer, p_h.layer))


def steps_for(accuracy: float) -> int:
    """Steps per doubling for the time error TIME_ERROR / m^2 at half the accuracy
    (``direct.plan_direct``)."""
    return max(MIN_STEPS_PER_DOUBLING, math.ceil(math.sqrt(TIME_ERROR / (0.5 * accuracy))))


def level_plan(geometry, diffusivity, law, exposure, times, mesh_accuracy, per_doubling) -> Plan:
    """A 3-D plan: ``nonlinear_plan``'s cells at ``mesh_accuracy``, ``per_doubling`` steps."""
    def planner(d, a, outputs):
        s = scales_of(geometry, d, exposure)
        return plan_direct(geometry, d, "solid", s.tau_star(exposure.change_times),
                           s.tau_star(outputs), a, exposure, mirrored=True)
    chosen = nonlinear_plan(planner, diffusivity, law, exposure, times, mesh_accuracy)
    return replace(chosen, steps_per_doubling=per_doubling)


def sheet_reference(geometry, diffusivity, law, exposure, times, accuracy) -> DiffusionResult:
    """The D(c) sheet of the part's thickness at ``SHEET_SHARE`` x the accuracy (FiPy slab)."""
    sheet = Sheet(geometry.thickness)

    def planner(d, a, outputs):
        s = scales_of(sheet, d, exposure)
        return plan_direct(sheet, d, "slab", s.tau_star(exposure.change_times),
                           s.tau_star(outputs), a, exposure)
    chosen = nonlinear_plan(planner, diffusivity, law, exposure, times, SHEET_SHARE * accuracy)
    return solve_nonlinear(sheet, diffusivity, law, exposure, times, chosen)


@dataclass(frozen=True)
class Setting:
    """What every march of one solve shares: law, scaled D, its top factor, scales."""

    geometry: object
    law: object
    exposure: object
    times: np.ndarray
    d: tuple
    top: float
    scales: object
    depth: float
    per_doubling: int
    part: str

    @classmethod
    def of(cls, geometry, diffusivity, law, exposure, times, depth, per_doubling, part):
        scaled = fastest(diffusivity, law, exposure, times)
        return cls(geometry, law, exposure, np.asarray(times, float),
                   tuple(float(v) for v in scaled.pre_exponential),
                   law.largest_factor(wettest(exposure, times)),
                   scales_of(geometry, scaled, exposure), depth, per_doubling, part)

    def run(self, disc, keep: bool = False) -> Pair:
        return richardson_march(disc, self.law, self.top, self.exposure, self.times,
                                self.scales, self.per_doubling, keep, self.part)

    def planform(self, finest: float, growth: float) -> tuple[Pair, Pair, int]:
        """(the plate's weights, ``cellmoments``' weights, cells) of the planform's march."""
        disc, weights = planform_disc(self.geometry, self.d, finest, growth, self.depth)
        pair, g = self.run(disc, True), np.asarray(self.exposure.surface_before(self.times), float)
        mean, layer = (g + (pair.fields - g[:, None]) @ w for w in weights)
        return replace(pair, fields=None), replace(pair, mean=mean, layer=layer, fields=None), \
            disc.cells


@dataclass(frozen=True)
class Level:
    """One 3-D plan's marches: the plate, its z widths as a sheet, its planform alone."""

    plan: Plan
    plate: Pair
    slab: Pair
    planform: Pair
    moments: Pair   # the same march read with ``cellmoments``' weights
    cells: int
    planform_cells: int
    coordinates: dict


def three_d(setting: Setting, chosen: Plan, keep: bool) -> Level:
    disc = mirrored(setting.geometry, setting.d, chosen.cells_per_axis, chosen.finest,
                    chosen.growth, setting.depth)
    plate = setting.run(disc, keep)
    slab = setting.run(half_slab(half(layout.prism_widths(chosen.finest, chosen.growth))))
    planform, moments, planform_cells = setting.planform(chosen.finest, chosen.growth)
    return Level(chosen, plate, slab, planform, moments, disc.cells, planform_cells,
                 disc.coordinates)


def refined_reference(setting: Setting, level: Level, sheet: Pair, accuracy: float, scale):
    """(planform reference Pair, estimate, planform cells, factor R): the level's planform
    refined by R in ``REFINE`` (finest and growth / R) until the estimate is
    ``PLANFORM_SHARE`` of the accuracy or the next mesh would pass ``PLANFORM_CELLS``.
    After the first refinement: the Richardson extrapolation of the two (second order:
    p_2 + (p_2 - p_1) / 3), its estimate the whole change p_2 - p_1 (R = 1 may be short of
    the asymptotic range: on the demo cam with k = 1 the change the first extrapolation
    made, (p_2 - p_1) / 3, was half of what the next one found). After the second: the mean
    and the layer each by ``three_levels`` (the corrected result is affine in the planform
    reference, so its changes are the reference's).
    Before, the second extrapolation with a third of its change from the first (Romberg's
    check): on the demo cam (k = 2, 1e-3) an estimate 9.0e-4 for an error 1.8e-4."""
    surface = np.asarray(setting.exposure.surface_before(setting.times), float)

    def result(reference):
        return corrected(level.plate, (level.slab, sheet), (level.planform, reference), surface)
    planforms, cells, factor = [level.moments], 0, 1.0
    for refine in REFINE:
        if cells and level.planform_cells * refine ** 2 > PLANFORM_CELLS:
            break
        _, fine, cells = setting.planform(level.plan.finest / refine,
                                          level.plan.growth / refine)
        planforms.append(fine)
        weight, factor = 1.0 / ((refine / factor) ** 2 - 1.0), refine
        if len(planforms) == 2:
            reference = replace(fine, mean=fine.mean + weight * (fine.mean - planforms[0].mean),
                                layer=fine.layer + weight * (fine.layer - planforms[0].layer))
            estimate = gap(result(planforms[0]), result(fine), scale)
        else:
            (mean, mean_error), (layer, layer_error) = (
                three_levels(*(result(p)[i] for p in planforms[-3:])) for i in range(2))
            reference = replace(fine, mean=taken(mean, planforms[-2].mean, fine.mean),
                                layer=taken(layer, planforms[-2].layer, fine.layer))
            estimate = max(mean_error, layer_error / LAYER_TOLERANCE) / scale
        if estimate <= PLANFORM_SHARE * accuracy:
            break
    return reference, estimate, cells, factor


def gap(a, b, scale: float) -> float:
    """The larger of the mean's and the layer's (/ ``LAYER_TOLERANCE``) largest difference,
    relative to ``scale``."""
    return max(float(np.max(np.abs(a[0] - b[0]))),
               float(np.max(np.abs(a[1] - b[1]))) / LAYER_TOLERANCE) / scale


def skin_margin(law, exposure, times) -> float:
    """1 unless the surface dries to a skin (``nonlinear.dries_to_a_skin``); then
    1 + SKIN_ESTIMATE_MARGIN (sqrt(max f / min f) - 1), as the cells' margin of
    ``nonlinear_plan``: on the 4 x 3 x 2 mm plate drying the change between the plans need not
    shrink (k = 3: the 0.5 plan 1.6 times the change from the 0.125 one) and the result
    errs 3.0e-3 (k = 2) and 3.5e-3 (k = 3) against the stored 3-D runs at 1e-2, 4.0 and 2.3
    times below the estimate with it (``SKIN_ESTIMATE_MARGIN``;
    benchmarks/dc_defect_correction.py)."""
    if not dries_to_a_skin(law, exposure):
        return 1.0
    return 1.0 + SKIN_ESTIMATE_MARGIN * (math.sqrt(spread(law, exposure, times)) - 1.0)


@dataclass(frozen=True)
class Levels:
    """The corrected result on each 3-D plan of one solve, all with the same sheet and
    planform references (those refined from the finest plan)."""

    marched: list      # Level per plan, coarsest first
    results: list      # (mean, layer) corrected, per plan
    sheet: DiffusionResult
    planform: Pair     # the planform reference
    planform_error: float
    planform_cells: int
    factor: float      # the planform's refinement R
    scale: float       # the swing the estimates are relative to


def corrected_levels(geometry, diffusivity, law, exposure, times, accuracy: float,
                     levels=MESH_LEVELS, *, surface_layer_depth=5e-4, store_fields=False,
                     part="") -> Levels:
    """The corrected product (module docstring) on the 3-D plans of ``levels`` (accuracies
    of ``nonlinear_plan``, coarsest first); ``store_fields`` keeps the finest one's."""
    times = np.asarray(times, float)
    setting = Setting.of(geometry, diffusivity, law, exposure, times, surface_layer_depth,
                         steps_for(accuracy), part)
    sheet = sheet_reference(geometry, diffusivity, law, exposure, times, accuracy)
    reference = Pair(sheet.mean, sheet.surface)
    plans = [level_plan(geometry, diffusivity, law, exposure, times, a, setting.per_doubling)
             for a in levels]
    marched = [three_d(setting, p, store_fields and p is plans[-1]) for p in plans]
    scale = swing(exposure, times) or 1.0
    planform, planform_error, planform_cells, factor = refined_reference(
        setting, marched[-1], reference, accuracy, scale)
    surface = np.asarray(exposure.surface_before(times), float)  # g(t-): the state there
    results = [corrected(m.plate, (m.slab, reference), (m.planform, planform), surface)
               for m in marched]
    return Levels(marched, results, sheet, planform, planform_error, planform_cells, factor,
                  scale)


def solve_corrected(geometry, diffusivity, law, exposure, times, accuracy: float, *,
                    surface_layer_depth=5e-4, store_fields=False, part="",
                    reason="") -> DiffusionResult:
    """Mean and contact layer (weight %) at ``times``: the corrected product (module
    docstring) on the finer of two 3-D plans (``MESH_LEVELS``, their change the estimate of
    what does not separate), plus the sheet's and the planform's estimates and the time
    error of the marches (``PAIR_TO_EXTRAPOLATED`` pair^2). ``store_fields``: the finer
    3-D plan's own cells (not corrected)."""
    times = np.asarray(times, float)
    run = corrected_levels(geometry, diffusivity, law, exposure, times, accuracy,
                           surface_layer_depth=surface_layer_depth,
                           store_fields=store_fields, part=part)
    marched, results, sheet, scale = run.marched, run.results, run.sheet, run.scale
    unseparated = gap(results[0], results[-1], scale) * ORDER_ONE * skin_margin(
        law, exposure, times)
    pair = max(marched[-1].plate.pair, run.planform.pair) / scale
    estimate = (sheet.error_estimate + run.planform_error + unseparated
                + PAIR_TO_EXTRAPOLATED * pair ** 2)
    fine = marched[-1]
    note = (f"{reason.split(TARGET)[0]}; measured: sheet {sheet.error_estimate:.1e}, "
            f"planform x{run.factor:g} ({run.planform_cells} cells) {run.planform_error:.1e}, "
            f"3-D change {unseparated:.1e}")
    if estimate > accuracy:
        note += "; capped: error above the requested accuracy"
    result = DiffusionResult(times, results[-1][0], results[-1][1], "solid",
                             fine.cells + run.planform_cells,
                             sum(m.plate.steps for m in marched), float(estimate), note)
    if store_fields:
        result.fields, result.cell_coordinates = fine.plate.fields, fine.coordinates
    return result


def plan_corrected(geometry, diffusivity, law, exposure, times, accuracy: float) -> Plan:
    """What ``solve_corrected`` will start from: the finer 3-D plan, the planform refined
    up to ``PLANFORM_CELLS``, the requested accuracy as the target its measured estimate
    is held to (the solve reports the estimate)."""
    chosen = level_plan(geometry, diffusivity, law, exposure, times, MESH_LEVELS[-1],
                        steps_for(accuracy))
    reason = ("D(c) sheet x D(c) planform (each refined and checked), corrected on coarse 3-D "
              f"prisms on half the thickness (mid-plane mirror; the {MESH_LEVELS[0]:g} and "
              f"{MESH_LEVELS[-1]:g} plans; {chosen.steps_per_doubling} steps/doubling + "
              f"Richardson; defect correction){TARGET}")
    return replace(chosen, reason=reason, error_estimate=accuracy)
