r"""Concentration-dependent D on a CamPlate, LinkBar or Bar (the prism of its rectangular
section, ``corrected_pieces.as_prism``): the D(c) sheet x D(c) planform product, corrected on
coarse mirrored 3-D prisms (defect correction; Stetter 1978, Numer. Math. 29:425-443;
Böhmer, Hemker & Stetter 1984, Computing Suppl. 5:1-32).

For Fick on a prism (planform x thickness) the unaccomplished uptakes multiply,
U = g - c = U_sheet U_planform / (g - c0) (Crank 1975 §4.3, the product of eq. 4.51), and
on a prism mesh (planform cells x z widths, a tensor product) the same holds for the
discrete fields. So the 3-D cells' error splits into a sheet factor and a planform
factor, each measurable on its own grid: the D(c) sheet on the prisms' z widths
(``half_slab``) against a fine sheet, and the D(c) planform alone (``planform_disc``, the
prisms' cells without their faces) against the same planform refined twice and four
times (Richardson, second order: 1.25e-3 then 3.1e-4 on the demo cam's mean at 1 d).
The result takes the coarse 3-D U and swaps each factor's coarse value for its fine one:

.. math::

    U = U_{3d}\, \frac{U_{sheet,ref}}{U_{sheet,h}}\, \frac{U_{planform,ref}}{U_{planform,h}}

for the mean, and for the contact layer with the planform's band in place of its mean
(the layer spans the thickness). With constant D this is the fine sheet x fine planform
(independent of the 3-D mesh); with D(c) the 3-D cells carry what does not separate,
and the change of the result between nested 3-D meshes measures it (``PrismCells.refined``:
every planform edge and z width halved, so the meshes form a refinement by exactly 2 and
``grid_convergence.three_levels`` can read an order from three of them; ``unseparated``).
Measured (``benchmarks/dc_defect_correction.py nested``, gap norm of the swing): on the
4 x 3 x 2 mm plate with k = 2 the changes over the meshes 1x, 2x, 4x are 2.1e-3, 3.6e-4
absorbing (order 2.5) and 1.1e-3, 4.4e-4 drying (order 1.3); on the demo cam (k = 2, 1x =
the 1.0 plan, 3 507 cells) z alone 3.1e-4 then 2.5e-5, the planform alone 2.6e-4, both
5.2e-4. The graded plans 1, 0.5, 0.25, 0.125 used before are not nested (z cells 4, 6, 6,
8 on the plate) and their changes showed orders from -10 to 12.

The error splits by direction: on the 6 x 4 x 2 mm bar at 1e-3 (``nested bar-K-DIRECTION
1e-3``, P planform and Z z halvings) the changes along z were 4.9e-4, 1.3e-4 at P = 0 and
5.1e-4, 1.4e-4 at P = 1 (k = 2 absorbing), along the planform 4.3e-4, 1.3e-4 at Z = 0 and
4.4e-4, 1.4e-4 at Z = 1 (k = 1 drying: z 1.2e-4, 3.6e-5 at P = 0, 1). So where the next
diagonal mesh (8 x the cells) passes ``NESTED_CELLS``, the combination technique stands
in for it (``CorrectedMeshes.finer``, ``unseparated``): from the ``cross`` of meshes around the
finest (I, J), at most 2 x its cells, R(I, J) + [R(I-1, J+1) - R(I-1, J)] + [R(I+1, J-1) -
R(I, J-1)], each chain by ``three_levels``, plus the mixed difference. On a 3 x 2 x 2 mm
plate (k = 2, 1e-2; ``cross``) it came within 5.7e-5 (absorbing) and 6.9e-6 (drying) of
the 8 x mesh (estimates 4.1e-4, 3.4e-4), the finest 3.9e-4 and 3.4e-4; on the bar at
1e-3 (``dc_bar.py corrected``) the estimate fell from 1.3e-3 to 8.3e-4 (k = 1 drying, error
7.7e-5), 2.1e-3 to 6.8e-4 (k = 2 drying, 7.0e-5) and, with the planform also refined 8 x,
2.0e-3 to 4.8e-4 (k = 2 absorbing, 1.1e-4 where it was 5.6e-4), 3.1-4.3 x the CPU s.

Measured first and dropped: Fick at Crank's (1975 §9.3) weighted-mean D on the same
3-D mesh (c_h + v_exact - v_h). With f(surface value) on the exposed faces (before the
Kirchhoff face mean of ``sorption.mean_factor``) the Fickian and the D(c) sheets on the
demo cam's z widths erred with opposite signs, so the difference erred more than either.
Since that fix they err alike (plan 0.1, 1 d: -5.4e-3 both; the difference 3e-5, at most
8.9e-4 over the outputs; ``benchmarks/dc_defect_correction.py fickian-reference``): worth
a new trial on the 3-D cells.

The planform reference (``refined_reference``): the D(c) planform alone
(``corrected_pieces.planform_disc``) on a graded planform refined by 2, 4 and 8 (every
finest width and growth / R), Richardson-extrapolated (second order, then three meshes by
``grid_convergence.three_levels``; Richardson 1911, "The approximate arithmetical solution
by finite differences of physical problems involving differential equations", Phil. Trans.
R. Soc. A 210:307-357, doi:10.1098/rsta.1911.0009), and the norm every estimate of the
corrected product is measured in (``gap``).

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
- Stetter, H. J. (1978). The defect correction principle and discretization methods.
  Numerische Mathematik 29:425-443. doi:10.1007/BF01432879
- Böhmer, K., Hemker, P. W. & Stetter, H. J. (1984). The defect correction approach. Computing
  Supplementum 5:1-32. doi:10.1007/978-3-7091-7023-6_1
- Richardson, L. F. (1911). The approximate arithmetical solution by finite differences of
  physical problems involving differential equations, with an application to the stresses in a
  masonry dam. Philosophical Transactions of the Royal Society A 210:307-357.
  doi:10.1098/rsta.1911.0009
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import partial

import numpy as np

from ..accuracy.budget import LAYER_TOLERANCE, PLANFORM_SHARE, SKIN_ESTIMATE_MARGIN
from ..accuracy.error_model import PAIR_TO_EXTRAPOLATED
from ..accuracy.grid_convergence import taken, three_levels
from ..operators.sizing import prism_widths
from ..operators.symmetry_cuts import half
from ..problem.definition import DiffusionProblem
from ..problem.exposure import swing
from ..problem.results import DiffusionResult, Plan
from ..stepping.dense_output import Extension
from .concentration_dependent import SWEEPS, Sweeps, dries_to_a_skin, spread
from .corrected_fields import stored
from .corrected_pieces import (PrismCells, MeshMarches, CombinedMarch, SharedInputs, as_prism,
                               bar_coordinates,
                               combination, corrected, cross, level_plan, sheet_reference,
                               steps_for, three_d)

MESH_LEVELS = (4.0, 0.5)   # accuracies of the coarsest 3-D plan (then refined by 2, nested;
#                            ``base_level``: down to the second where the accuracy is tight)
#                            and of the plan whose graded planform the planform's refinement
#                            starts from
NESTED_CELLS = 30_000      # the finest nested 3-D mesh tried (cells on half the thickness)
CROSS_CELLS = 60_000       # the ``cross``'s largest (2 x the finest): half the solid cap
#   (``error_model.MAX_CELLS``; measured: benchmarks/results/tuned_constants.md)


@dataclass(frozen=True)
class MeshCaps:
    """The largest 3-D meshes the corrected product refines to.

    The largest 3-D meshes the corrected product refines to [cells on half the
    thickness]: the next nested mesh (8 x the finest) within ``nested``, the ``cross``'s
    largest (2 x the finest) within ``cross``. The defaults are the run's; tests pass
    smaller ones instead of changing the module's values.

    Parameters
    ----------
    nested : int
        The largest next nested mesh [cells on half the thickness].
    cross : int
        The largest mesh of the ``cross`` [cells on half the thickness].
    """

    nested: int = NESTED_CELLS
    cross: int = CROSS_CELLS


MESH_CAPS = MeshCaps()

BASE_PER_ACCURACY = 1.0 / 3e-3  # the coarsest 3-D plan's accuracy per requested accuracy,
#   within MESH_LEVELS (``base_level``): 0.5 at 1e-3 and below, 1.0 at 3e-3, 3.3 at 1e-2, 4.0
#   from 1.2e-2 up (measured: benchmarks/results/tuned_constants.md)
MIN_Z_WIDTHS = 2           # z widths on the half thickness of the coarsest 3-D plan at least
#   (``base_plan``; measured: benchmarks/results/tuned_constants.md)
TARGET = "; est. = the target: the run measures its own and warns above it"
ORDER_ONE = 1.0 / (2.0 - 1.0)  # the finer of two nested 3-D meshes' error / the change
#   between them at order 1 (refinement ratio 2; a higher order gives less; what it replaced:
#   benchmarks/results/tuned_constants.md)
REFINE = (2.0, 4.0, 8.0)   # planform refinements (finest and growth / R) for Richardson;
#   8 where 4 leaves more than ``PLANFORM_SHARE`` (measured:
#   benchmarks/results/tuned_constants.md)
PLANFORM_CELLS = 60_000    # the finest planform tried


def skin_margin(law, exposure, times) -> float:
    """The margin on the 3-D change of a part that dries to a skin (1 otherwise).

    1 unless the surface dries to a skin (``concentration_dependent.dries_to_a_skin``); then
    1 + SKIN_ESTIMATE_MARGIN (sqrt(max f / min f) - 1), as the cells' margin of
    ``nonlinear_plan``, on the change between two nested 3-D meshes (``unseparated``; three
    meshes measure their order and take no margin): drying converges at a lower order than
    absorbing (``SKIN_ESTIMATE_MARGIN``; benchmarks/dc_defect_correction.py nested).

    Parameters
    ----------
    law : ConcentrationDependent
        f(c/Mm_ref) [-], the law whose spread sets the margin.
    exposure : Exposure
        The exposure (surface moisture [weight %] over time [s]).
    times : numpy.ndarray
        Output times [s].

    Returns
    -------
    float
        The margin m [-] on the change between two nested meshes.
    """
    if not dries_to_a_skin(law, exposure):
        return 1.0
    return 1.0 + SKIN_ESTIMATE_MARGIN * (math.sqrt(spread(law, exposure, times)) - 1.0)


@dataclass(frozen=True)
class CorrectedMeshes:
    """The corrected result on each 3-D mesh of one solve, sharing its references.

    The corrected result on each 3-D mesh of one solve, all with the same sheet and
    planform references.

    Parameters
    ----------
    marched : list of MeshMarches
        The marches per mesh, the finest last.
    results : list of tuple
        The corrected (mean, layer) [weight %] per mesh.
    sheet : DiffusionResult
        The sheet reference.
    planform : CombinedMarch
        The planform reference.
    planform_error : float
        Its error estimate [-], relative to the swing.
    planform_cells : int
        Its cells.
    factor : float
        The planform's refinement R [-].
    scale : float
        The swing [weight %] the estimates are relative to.
    setting : SharedInputs
        What the marches share.
    meshes : list of PrismCells
        The cells per mesh.
    keys : list of tuple
        (planform, z) halvings of each mesh from the first; () for the diagonal.
    """

    marched: list      # MeshMarches per mesh, the finest last
    results: list      # (mean, layer) corrected, per mesh
    sheet: DiffusionResult
    planform: CombinedMarch     # the planform reference
    planform_error: float
    planform_cells: int
    factor: float      # the planform's refinement R
    scale: float       # the swing the estimates are relative to
    setting: SharedInputs
    meshes: list       # PrismCells per mesh
    keys: list = ()    # (planform, z) halvings of each mesh from the first; () = the diagonal

    @property
    def lattice(self) -> list:   # the keys, or the diagonal's
        return list(self.keys)[:len(self.results)] or [(i, i) for i in range(len(self.results))]

    def finer(self, store_fields: bool = False,
              caps: MeshCaps = MESH_CAPS) -> "CorrectedMeshes | None":
        """The next step of ``solve_corrected``, or None: the finest refined by 2 in every
        direction (``PrismCells.refined``, 8 x its cells) within ``caps.nested``; past it,
        once, the ``cross`` around it (its largest mesh 2 x its cells, within ``caps.cross``;
        ``combination``)."""
        (p, z), cells = self.lattice[-1], self.meshes[-1].cells
        if combination(self.lattice) is None:
            if cells * 8 <= caps.nested:
                return self.adding([], (p + 1, z + 1), store_fields)
            if p >= 1 and z >= 1 and cells * 2 <= caps.cross:
                along_z, along_planform = cross(p, z)
                return self.adding([*along_z, *along_planform], (p, z), store_fields)
        return None

    def adding(self, keys: list, top: tuple, store_fields: bool) -> "CorrectedMeshes":
        """These meshes and ``top`` (halvings of the first) added where missing, ``top`` the
        finest (the last), its fields kept with ``store_fields``."""
        have = dict(zip(self.lattice, zip(self.marched, self.results, self.meshes)))
        surface, reference = surface_of(self.setting), CombinedMarch(self.sheet.mean,
                                        self.sheet.surface)
        for key in [*keys, top]:
            if key not in have:
                cells = self.meshes[0].refined(*key)
                level = three_d(self.setting, self.marched[0].plan,
                                store_fields and key == top, cells)
                have[key] = (level, corrected(level.plate, (level.slab, reference),
                                              (level.planform, self.planform), surface,
                                              level.union), cells)
        order = [k for k in have if k != top] + [top]
        marched, results, meshes = (list(v) for v in zip(*(have[k] for k in order)))
        return replace(self, marched=marched, results=results, meshes=meshes, keys=order)


def base_level(accuracy: float) -> float:
    """The accuracy the coarsest 3-D plan is made for.

    The accuracy of the coarsest 3-D plan: ``BASE_PER_ACCURACY`` x the requested one, at
    most ``MESH_LEVELS[0]``, at least ``MESH_LEVELS[-1]``.

    Parameters
    ----------
    accuracy : float
        The solve's accuracy [-] (relative to the moisture swing).

    Returns
    -------
    float
        The coarsest plan's accuracy [-].
    """
    return min(MESH_LEVELS[0], max(MESH_LEVELS[-1], BASE_PER_ACCURACY * accuracy))


def base_plan(plan_at, accuracy: float, caps: MeshCaps = MESH_CAPS) -> tuple[float, Plan]:
    """The coarsest 3-D plan of the corrected product, and its accuracy.

    (its accuracy, the coarsest 3-D plan): ``plan_at(base_level(accuracy))``, the level
    doubled (up to ``MESH_LEVELS[0]``) while the ``cross`` around the pair (16 x the base's
    cells) would pass ``caps.cross`` (so a large part has a further mesh), then halved
    (down to ``MESH_LEVELS[-1]``) while the plan has fewer than ``MIN_Z_WIDTHS`` z widths on
    the half thickness. At 1e-3, k = 2 (benchmarks/dc_bar.py, auto): the 60 x 8 x 4 mm link
    drying on the 0.5 plan (7 904 cells) "capped" at 2.0e-3 in 334 CPU s, on the 1.0 plan
    (3 681) 6.7e-4 in 404 s with the cross; absorbing 6.4e-4 in 229 s, 8.1e-4 in 81 s. The
    demo cam (0.5 plan 7 272 cells) on the 1.0 plan: 7.2e-4 in 433 s, six meshes, against
    8.0e-4 in 309 s on the 0.5 plan's pair, 7.4e-5 apart (``gap``; dc_defect_correction.py).

    Parameters
    ----------
    plan_at : callable
        accuracy [-] -> the 3-D plan for it.
    accuracy : float
        What the solve must reach [-], relative to the swing.
    caps : MeshCaps
        The largest meshes allowed.

    Returns
    -------
    level : float
        The plan's accuracy [-].
    plan : Plan
        The coarsest 3-D plan.
    """
    level = base_level(accuracy)
    chosen = plan_at(level)
    while level < MESH_LEVELS[0] and 16 * chosen.cells > caps.cross:
        level = min(MESH_LEVELS[0], 2.0 * level)
        chosen = plan_at(level)
    while (level > MESH_LEVELS[-1]
           and half(prism_widths(chosen.finest, chosen.growth)).size < MIN_Z_WIDTHS):
        level = max(MESH_LEVELS[-1], 0.5 * level)
        chosen = plan_at(level)
    return level, chosen


def surface_of(setting: SharedInputs) -> np.ndarray:
    """The surface moisture just before each output.

    g(t-) at the outputs: the state the unaccomplished uptakes are measured from.

    Parameters
    ----------
    setting : SharedInputs
        The solve's exposure and output times [s].

    Returns
    -------
    numpy.ndarray
        g(t-) [weight %] at the outputs.
    """
    return np.asarray(setting.exposure.surface_before(setting.times), float)


def corrected_levels(problem: DiffusionProblem, meshes: int = 2, *, plans=None, base=None,
                     sweeps: Sweeps = SWEEPS) -> CorrectedMeshes:
    """The corrected product on nested (or given) 3-D meshes.

    The corrected product (module docstring) on ``meshes`` nested 3-D meshes: the graded
    cells of the ``base_plan`` plan, each next one refined by 2 in every direction
    (``PrismCells.refined``); or, with ``plans`` (accuracies of ``nonlinear_plan``, coarsest
    first), on those plans' graded cells (not nested; ``benchmarks/dc_defect_correction.py
    plate-order``). ``base``: the coarsest nested plan's accuracy instead of ``base_plan``'s.
    The planform reference is refined from the ``MESH_LEVELS[-1]`` plan's graded planform.
    The problem's ``store_fields`` keeps every mesh's fields and the references'
    (``corrected_fields``); ``sweeps``: when each step's sweeps stop, in every march.

    Parameters
    ----------
    problem : DiffusionProblem
        The part (a Bar, CamPlate or LinkBar, lengths [m]), its diffusivity ([m^2/s],
        [J/mol]), the history (times [s], temperature [K], moisture [weight %]), the output
        times [s], the requested error relative to the swing [-], the contact layer's depth
        [m], whether to keep the fields, the part's name and its ``sorption``, the
        ``ConcentrationDependent`` factor f(c/Mm_ref) [-].
    meshes : int
        The nested meshes marched.
    plans : sequence of float, optional
        Accuracies [-] of ``nonlinear_plan`` for non-nested meshes, coarsest first.
    base : float, optional
        The coarsest nested plan's accuracy [-] (None: ``base_plan``'s).
    sweeps : Sweeps
        The sweeps' stopping rule, for every march.

    Returns
    -------
    CorrectedMeshes
        The corrected results per mesh and their references.
    """
    law, exposure, times, accuracy = (problem.sorption, problem.exposure, problem.times,
                                      problem.accuracy)
    store_fields = problem.store_fields
    geometry, diffusivity, faces_layer = as_prism(problem.geometry, problem.diffusivity)
    setting = SharedInputs.of(problem, geometry, diffusivity, steps_for(accuracy), faces_layer,
                              sweeps)
    sheet = sheet_reference(problem, geometry, diffusivity, sweeps)
    reference = CombinedMarch(sheet.mean, sheet.surface)

    def planned(a):
        return level_plan(geometry, diffusivity, law, exposure, times, a, setting.per_doubling)
    if plans is None:
        chosen = [planned(base) if base else base_plan(planned, accuracy)[1]] * meshes
        cells = [PrismCells.of(geometry, setting.d, chosen[0])]
        while len(cells) < meshes:
            cells.append(cells[-1].refined())
    else:
        chosen = [planned(a) for a in plans]
        cells = [PrismCells.of(geometry, setting.d, c) for c in chosen]
    marched = [three_d(setting, c, store_fields, m) for c, m in zip(chosen, cells)]
    scale, surface = swing(exposure, times) or 1.0, surface_of(setting)

    def levels(planform, planform_error, planform_cells, factor) -> CorrectedMeshes:
        results = [corrected(m.plate, (m.slab, reference), (m.planform, planform), surface,
                             m.union) for m in marched]
        return CorrectedMeshes(marched, results, sheet, planform, planform_error, planform_cells,
                      factor, scale, setting, cells)

    def total(*planform) -> float:   # the solve's whole estimate with this planform reference
        return sum(estimate_parts(levels(*planform), skin_margin(law, exposure, times))[1:])
    return levels(*refined_reference(setting, planned(MESH_LEVELS[-1]), marched[-1], reference,
                                     accuracy, scale,
                                     total if plans is None and meshes > 1 else None))


def estimate_parts(run: CorrectedMeshes, margin: float) -> tuple[tuple, float, float]:
    """The corrected values and the two parts of their error estimate.

    ((mean, layer), 3-D term, rest): ``unseparated``'s values and estimate, and the rest
    of the estimate: the sheet's, the planform's and the marches' time error
    (``PAIR_TO_EXTRAPOLATED`` pair^2).

    Parameters
    ----------
    run : CorrectedMeshes
        The solve's meshes.
    margin : float
        The margin [-] on a two-mesh change (``skin_margin``).

    Returns
    -------
    values : tuple of numpy.ndarray
        (mean, layer) [weight %].
    three_d : float
        The 3-D term of the estimate [-].
    rest : float
        The rest of the estimate [-].
    """
    values, three_d_error = unseparated(run, margin)
    pair = max(run.marched[-1].plate.pair, run.planform.pair) / run.scale
    rest = run.sheet.error_estimate + run.planform_error + PAIR_TO_EXTRAPOLATED * pair ** 2
    return values, three_d_error, rest


def unseparated(run: CorrectedMeshes, margin: float) -> tuple[tuple, float]:
    """The 3-D cells' corrected values and the estimate of what does not separate.

    ((mean, layer), estimate) of the 3-D cells (``finest``). On the diagonal (each mesh
    refined by 2 in every direction), two meshes: the finer one's result, its estimate the
    change between them x ``ORDER_ONE`` x ``margin`` (``skin_margin``); three or more: the
    last three by ``three_levels`` (mean and layer each; the second-order extrapolation
    where it may be taken), the order measured, no margin. With the ``cross`` around the
    finest (I, J): the combination technique (Griebel, Schneider & Zenger 1992, in
    Iterative Methods in Linear Algebra, 263-281; its error splitting E = P(h_planform) +
    Z(h_z) + mixed): R(I, J) + [R(I-1, J+1) - R(I-1, J)] + [R(I+1, J-1) - R(I, J-1)],
    the planform and z errors of the mesh (I+1, J+1) without its cells, each direction's
    step and estimate by ``three_levels`` on its chain; plus the mixed difference M =
    R(I, J) - R(I, J-1) - R(I-1, J) + R(I-1, J-1) x ``margin``: for a mixed term c a^p b^z
    (a, b <= 1/2: order >= 1 in each direction) the combination's is c (ab + a^2 + b^2 -
    a - b), within |M| = |c| (1 - a)(1 - b).

    Parameters
    ----------
    run : CorrectedMeshes
        The solve's meshes.
    margin : float
        The margin [-] on a two-mesh change and on the mixed term.

    Returns
    -------
    values : tuple of numpy.ndarray
        (mean, layer) [weight %].
    estimate : float
        The 3-D cells' error estimate [-], relative to the swing.

    References
    ----------
    Griebel, M., Schneider, M. & Zenger, C. (1992). A combination technique for the solution
    of sparse grid problems. In de Groen, P. & Beauwens, R. (eds.), Iterative Methods in
    Linear Algebra, 263-281. Amsterdam: North-Holland (Elsevier).
    """
    values, checks = finest(run.results, run.lattice)
    if len(checks) == 1 and checks[0] is None:
        return values, gap(run.results[-2], values, run.scale) * ORDER_ONE * margin
    errors = [sum(checked[i][1] for checked in checks) for i in range(2)]
    if len(checks) == 2:
        (z, planform), top = combination(run.lattice), run.results[-1]
        for i in range(2):
            mixed = top[i] - run.results[planform[1]][i] - run.results[z[1]][i] + \
                run.results[z[0]][i]
            errors[i] += float(np.max(np.abs(mixed))) * margin
    return values, max(errors[0], errors[1] / LAYER_TOLERANCE) / run.scale


def finest(results: list, lattice: list | None = None) -> tuple[tuple, list]:
    """The values ``unseparated`` takes from the nested meshes' corrected results.

    ((mean, layer), [checks per chain] or [None]): what ``unseparated`` takes from the
    corrected results of the nested meshes (the finest last; ``lattice``: their keys): on
    the diagonal the last three's ``three_levels`` (the finest alone if fewer), or the
    ``combination``'s z and planform chains'.

    Parameters
    ----------
    results : list of tuple
        Corrected (mean, layer) [weight %] per mesh, the finest last.
    lattice : list of tuple, optional
        The meshes' (planform, z) keys (None: the diagonal).

    Returns
    -------
    values : tuple of numpy.ndarray
        (mean, layer) [weight %].
    checks : list
        ``three_levels``' checks per chain, or [None].
    """
    lattice = lattice or [(i, i) for i in range(len(results))]
    chains = combination(lattice[:len(results)])
    if chains is None:
        if len(results) < 3:
            return results[-1], [None]
        chains = ([len(results) - 3, len(results) - 2, len(results) - 1],)
    values, checks = list(results[-1]), []
    for chain in chains:
        checked = [three_levels(*(results[j][i] for j in chain)) for i in range(2)]
        checks.append(checked)
        for i, (extrapolate, _) in enumerate(checked):
            middle, fine = results[chain[1]][i], results[chain[2]][i]
            values[i] = values[i] + taken(extrapolate, middle, fine) - \
                (middle if len(chains) == 2 else fine)
    return tuple(values), checks


def extension(run: CorrectedMeshes, result: DiffusionResult, accuracy: float,
              resolve) -> Extension:
    """A corrected solve's ``extend``: its product read between the marches' steps.

    ``result.extend`` (``dense_output``): the corrected product of every nested mesh read
    between the marches' steps, combined as ``finest`` combines the solve's.

    Parameters
    ----------
    run : CorrectedMeshes
        The solve's meshes and references.
    result : DiffusionResult
        The solve's result.
    accuracy : float
        The requested error [-].
    resolve : callable
        times [s] -> the solve at them (the fallback).

    Returns
    -------
    Extension
        The result's ``extend``.
    """
    exposure, meshes = run.setting.exposure, run.marched
    tracks = [track for m in meshes for track in (m.plate.track, m.slab.track,
                                                  m.planform.track)]

    def product(values, at):   # the tracks' columns at ``at`` -> (mean, layer)
        pairs = [CombinedMarch(v[:, 0], v[:, 1]) for v in values]
        reference, sheet_at = pairs[-2:]
        surface = np.asarray(exposure.surface_before(at), float)
        per_mesh = [corrected(pairs[3 * i], (pairs[3 * i + 1], sheet_at),
                              (pairs[3 * i + 2], reference), surface, m.union)
                    for i, m in enumerate(meshes)]
        return finest(per_mesh, run.lattice)[0]
    return Extension(result, [*tracks, run.planform.track, run.sheet.extend.tracks[0]],
                     product, run.scale, accuracy, resolve, run.setting.part)


def refined_run(problem: DiffusionProblem,
                sweeps: Sweeps = SWEEPS) -> tuple[CorrectedMeshes, tuple, float, float]:
    """The nested meshes a corrected solve ends on, refined while that helps.

    The nested meshes ``solve_corrected`` ends on, with its (mean, layer) values, the
    3-D change's estimate and the rest of the estimate: ``corrected_levels``' two meshes,
    a further one while the total is above the accuracy and the rest below it.

    Parameters
    ----------
    problem : DiffusionProblem
        The part whose meshes are refined (a Bar, CamPlate or LinkBar, sizes [m]), D0 per
        axis [m^2/s] and the activation energy [J/mol], the exposure (change times [s],
        temperatures [K], surface moisture [weight %]), when the results are wanted [s], the
        error allowed [-] as a share of the moisture swing, how deep the contact layer
        reaches [m], whether to keep the finest mesh's fields, the part's name and its
        ``sorption``, the moisture dependence f(c/Mm_ref) [-] of D.
    sweeps : Sweeps
        When each step's sweeps stop.

    Returns
    -------
    run : CorrectedMeshes
        The meshes.
    values : tuple of numpy.ndarray
        (mean, layer) [weight %].
    three_d : float
        The 3-D change's estimate [-].
    rest : float
        The rest of the estimate [-].
    """
    accuracy, store_fields = problem.accuracy, problem.store_fields
    run = corrected_levels(problem, sweeps=sweeps)
    estimated = partial(estimate_parts, margin=skin_margin(problem.sorption, problem.exposure,
                                                           problem.times))
    values, three_d_error, rest = estimated(run)
    while rest < accuracy < rest + three_d_error:
        finer = run.finer(store_fields)
        if finer is None:
            break
        run = finer
        values, three_d_error, rest = estimated(run)
    return run, values, three_d_error, rest


def solve_corrected(problem: DiffusionProblem, reason: str = "",
                    sweeps: Sweeps = SWEEPS) -> DiffusionResult:
    """Solve a concentration-dependent prism part by the corrected product.

    Mean and contact layer (weight %) at the ``problem``'s times, its ``sorption`` a
    ``ConcentrationDependent`` law (``reason``: the plan's): the corrected product (module
    docstring) on two nested 3-D meshes (``corrected_levels``; their change the estimate
    of what does not separate, ``unseparated``), a further one (8 x the cells, or where
    that passes ``NESTED_CELLS`` once the ``cross`` around the finest) while the total is
    above the accuracy and the rest of the estimate below it (so a smaller 3-D term can meet
    it: the finer meshes cost only a run that would otherwise miss its accuracy); plus the sheet's and the planform's
    estimates and the time error of the marches (``PAIR_TO_EXTRAPOLATED`` pair^2).
    ``store_fields``: the finest 3-D mesh's cells corrected cell by cell
    (``corrected_fields.stored``; a Bar's in its own frame, ``bar_coordinates``).

    Parameters
    ----------
    problem : DiffusionProblem
        The part, material, exposure, output times [s] and accuracy [-]; its ``sorption`` a
        ``ConcentrationDependent`` law.
    reason : str
        The plan's reason.
    sweeps : Sweeps
        When each step's sweeps stop.

    Returns
    -------
    DiffusionResult
        Mean and contact-layer moisture [weight %], the error estimate [-].

    Raises
    ------
    SolverError
        When the sweeps of a step of one of the marches do not converge.
    """
    geometry, diffusivity = problem.geometry, problem.diffusivity
    times, accuracy, store_fields = problem.times, problem.accuracy, problem.store_fields
    run, values, three_d_error, rest = refined_run(problem, sweeps)
    sheet = run.sheet
    estimate = three_d_error + rest
    fine = run.marched[-1]
    note = (f"{reason.split(TARGET)[0]}; measured: sheet {sheet.error_estimate:.1e}, "
            f"planform x{run.factor:g} ({run.planform_cells} cells) {run.planform_error:.1e}, "
            f"3-D change {three_d_error:.1e} ({len(run.meshes)} nested meshes, "
            f"{fine.cells} cells)")
    if estimate > accuracy:
        note += "; capped: error above the requested accuracy"
    result = DiffusionResult(times, values[0], values[1], "solid",
                             fine.cells + run.planform_cells,
                             sum(m.plate.steps for m in run.marched), float(estimate), note)
    if store_fields:
        fields, note = stored(run, result.reason)
        coordinates = (bar_coordinates(geometry, diffusivity, fine.coordinates)
                       if not geometry.planform else fine.coordinates)
        return replace(result, fields=fields, reason=note, cell_coordinates=coordinates)
    # the limit search's extra times: read between the marches' steps (``dense_output``)
    return replace(result, extend=extension(run, result, accuracy, lambda both: solve_corrected(
        replace(problem.at(both), store_fields=False), reason, sweeps)))


def plan_corrected(problem: DiffusionProblem) -> Plan:
    """The plan a corrected solve starts from.

    What ``solve_corrected`` will start from for a D(c) ``problem``: the coarsest 3-D plan
    (refined by 2, nested, once or twice, or by direction: ``CorrectedMeshes.finer``), the
    planform refined up to ``PLANFORM_CELLS``, the accuracy as the target its measured
    estimate is held to (the solve reports the estimate).

    Parameters
    ----------
    problem : DiffusionProblem
        The part, material, exposure, output times [s] and accuracy [-].

    Returns
    -------
    Plan
        The coarsest 3-D plan, its estimate the requested accuracy [-].
    """
    law, exposure, times, accuracy = (problem.sorption, problem.exposure, problem.times,
                                      problem.accuracy)
    geometry, diffusivity, bar = as_prism(problem.geometry, problem.diffusivity)
    level, chosen = base_plan(partial(level_plan, geometry, diffusivity, law, exposure, times,
                                      per_doubling=steps_for(accuracy)), accuracy)
    section = (" (the bar as the prism of its rectangular section, its thickness the fastest "
               "axis)" if bar else "")
    reason = (f"D(c) sheet x D(c) planform{section} (each refined and checked), corrected on "
              "coarse 3-D "
              f"prisms on half the thickness (mid-plane mirror; the {level:.2g} plan "
              f"and it refined by 2, nested, twice or by direction where needed; "
              f"{chosen.steps_per_doubling} steps/doubling + Richardson; defect "
              f"correction){TARGET}")
    return replace(chosen, reason=reason, error_estimate=accuracy)


def refined_reference(setting: SharedInputs, start: Plan, level: MeshMarches, sheet: CombinedMarch,
                      accuracy: float, scale, total=None):
    """The planform reference, refined by Richardson steps until it is accurate enough.

    (planform reference CombinedMarch, estimate, planform cells, factor R): the graded planform
    of
    the plan ``start`` refined by R in ``REFINE`` (finest and growth / R) until the estimate
    is ``PLANFORM_SHARE`` of the accuracy, or ``total(reference, estimate, cells, R)`` (the
    whole estimate of the solve with this reference: ``corrected_levels``) is within the
    accuracy, or the next mesh would pass ``PLANFORM_CELLS`` (the estimate: the change of
    ``level``'s corrected result). The demo cam (k = 2) at 1e-2: the 2x planform's estimate
    6.3e-3 is above the share, but with the 3.3 plan's nested pair (3-D change 7.6e-4) and
    the sheet (8.6e-4) the whole is 8.3e-3: the 4x planform (27 303 cells, 59 CPU s alone)
    is not marched, the run takes 28 CPU s (143-153 on the 1.0 plan's pair with the 4x
    planform, estimate 2.0e-3; the two results 2.8e-3 apart in ``gap``'s norm;
    ``benchmarks/dc_defect_correction.py corrected cam-2 1e-2``).
    After the first refinement: the Richardson extrapolation of the two (second order:
    p_2 + (p_2 - p_1) / 3), its estimate the whole change p_2 - p_1 (R = 1 may be short of
    the asymptotic range: on the demo cam with k = 1 the change the first extrapolation
    made, (p_2 - p_1) / 3, was half of what the next one found). After the second: the mean
    and the layer each by ``three_levels`` (the corrected result is affine in the planform
    reference, so its changes are the reference's).
    Before, the second extrapolation with a third of its change from the first (Romberg's
    check): on the demo cam (k = 2, 1e-3) an estimate 9.0e-4 for an error 1.8e-4.

    Parameters
    ----------
    setting : SharedInputs
        What the marches share.
    start : Plan
        The plan whose graded planform is refined.
    level : MeshMarches
        The mesh whose corrected result measures the change.
    sheet : CombinedMarch
        The sheet reference.
    accuracy : float
        The requested error [-].
    scale : float
        The swing [weight %] the estimates are relative to.
    total : callable, optional
        (reference, estimate, cells, R) -> the solve's whole estimate [-].

    Returns
    -------
    tuple
        The planform reference (CombinedMarch), its estimate [-], its cells and R [-].
    """
    surface = np.asarray(setting.exposure.surface_before(setting.times), float)

    def result(reference):
        return corrected(level.plate, (level.slab, sheet), (level.planform, reference), surface,
                         level.union)
    _, first, start_cells = setting.planform(start.finest, start.growth)
    planforms, cells, factor = [first], 0, 1.0
    for refine in REFINE:
        if cells and start_cells * refine ** 2 > PLANFORM_CELLS:
            break
        _, fine, cells = setting.planform(start.finest / refine, start.growth / refine)
        planforms.append(fine)
        weight, factor = 1.0 / ((refine / factor) ** 2 - 1.0), refine
        if len(planforms) == 2:
            reference = combined(planforms, lambda coarse, f: f + weight * (f - coarse))
            estimate = gap(result(planforms[0]), result(fine), scale)
        else:
            (mean, mean_error), (layer, layer_error) = (
                three_levels(*(result(p)[i] for p in planforms[-3:])) for i in range(2))
            reference = combined(planforms[-2:], partial(taken, mean), partial(taken, layer))
            estimate = max(mean_error, layer_error / LAYER_TOLERANCE) / scale
        if estimate <= PLANFORM_SHARE * accuracy or (
                total is not None and total(reference, estimate, cells, factor) <= accuracy):
            break
    return replace(reference, coarser=(planforms[-2], weight)), estimate, cells, factor


def gap(a, b, scale: float) -> float:
    """The largest difference of two (mean, layer) results, the layer's scaled down.

    The larger of the mean's and the layer's (/ ``LAYER_TOLERANCE``) largest difference,
    relative to ``scale``.

    Parameters
    ----------
    a, b : tuple of numpy.ndarray
        (mean, layer) [weight %] of two results.
    scale : float
        The swing [weight %].

    Returns
    -------
    float
        The difference [-], relative to ``scale``.
    """
    return max(float(np.max(np.abs(a[0] - b[0]))),
               float(np.max(np.abs(a[1] - b[1]))) / LAYER_TOLERANCE) / scale


def combined(pairs, mean_rule, layer_rule=None):
    """The last march with its values combined from all of them.

    The last of ``pairs`` (marches with mean, layer and a ``StepRecord`` of the two, as
    ``corrected_product.CombinedMarch``) with its mean, layer and track ``mean_rule`` /
    ``layer_rule`` (pointwise
    in time: a Richardson or three-mesh combination) of ``pairs``' own.

    Parameters
    ----------
    pairs : sequence of CombinedMarch
        Marches with mean, layer [weight %] and a ``StepRecord``.
    mean_rule : callable
        Combines the marches' means pointwise in time.
    layer_rule : callable, optional
        Combines their layers (None: ``mean_rule``).

    Returns
    -------
    CombinedMarch
        The last march with the combined mean, layer and track [weight %].
    """
    layer_rule = layer_rule or mean_rule
    track = pairs[-1].track
    if track is not None:
        track = track.with_values(np.column_stack(
            [rule(*(p.track.values[:, i] for p in pairs))
             for i, rule in enumerate((mean_rule, layer_rule))]))
    return replace(pairs[-1], mean=mean_rule(*(p.mean for p in pairs)),
                   layer=layer_rule(*(p.layer for p in pairs)), track=track)
