"""The pieces ``corrected_product`` combines, each a swept backward-Euler march of the D(c)
equation
(``concentration_dependent``) on its own grid, Richardson-combined in time: the coarse 3-D prisms
(``PrismCells``, nested refinement by 2), their z widths as a sheet (``half_slab``), their
planform alone (``planform_disc``), the fine sheet reference (``sheet_reference``), and the
product that swaps each coarse factor's unaccomplished uptake for its reference's
(``corrected``; Crank 1975 §4.3, eq. 4.51 for Fick; Stetter 1978 for the correction).
Every march records its mean and layer at each step (``dense_output.StepRecord``: ``extend``).

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
- Stetter, H. J. (1978). The defect correction principle and discretization methods.
  Numerische Mathematik 29:425-443. doi:10.1007/BF01432879
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..accuracy.budget import SHEET_SHARE
from ..accuracy.error_model import MIN_STEPS_PER_DOUBLING, TIME_ERROR
from ..forcing.clock import scales as scales_of
from ..models.finite_volume import plan_direct, step_plan
from ..operators import sizing
from ..operators.discretisation import Discretisation
from ..operators.fipy_backend import assemble, interval_mesh
from ..operators.grids import interval_overlap, normalised
from ..operators.prisms import prism
from ..operators.symmetry_cuts import half
from ..planform.admissible import band_share, refine
from ..planform.cell_moments import corrected_weights
from ..problem.definition import DiffusionProblem
from ..problem.geometry import Bar, CamPlate, Sheet
from ..problem.results import DiffusionResult, Plan
from ..problem.scaling import stretch_of
from ..stepping.dense_output import StepRecord
from .concentration_dependent import (SWEEPS, Faces, Sweeps, fastest, nonlinear_plan,
                                      SweptMarch, solve_nonlinear, sweep_march, wettest)



@dataclass(frozen=True)
class CombinedMarch:
    """A Richardson-combined march (2 fine - coarse in time) and its time pair.

    Parameters
    ----------
    mean : numpy.ndarray
        The mean moisture [weight %] at the outputs.
    layer : numpy.ndarray
        The contact layer's mean moisture [weight %].
    fields : numpy.ndarray or None
        The cell moisture [weight %], (outputs, cells), when kept.
    steps : int
        Steps of both marches.
    pair : float
        The largest |fine - coarse| of the mean [weight %] (the time-error indicator).
    track : StepRecord or None
        (mean, layer) at every step, for ``extend``.
    grid : Tessellation or None
        A planform march's cells (for ``corrected_fields``).
    coarser : tuple or None
        The planform reference refined once less and the Richardson weight [-] on the change.
    """

    mean: np.ndarray
    layer: np.ndarray
    fields: np.ndarray | None = None
    steps: int = 0
    pair: float = 0.0   # largest |fine - coarse| of the mean (time error indicator)
    track: StepRecord | None = None   # (mean, layer) at every step (``dense_output``: ``extend``)
    # a planform march's cells (``admissible.Tessellation``: ``corrected_fields``)
    grid: object = None
    coarser: tuple | None = None   # the planform reference's (CombinedMarch refined once less, the
    #                               Richardson weight on the change): ``corrected_fields``


def as_prism(geometry, diffusivity):
    """A part as a prism: a Bar as the CamPlate of its section, others as they are.

    (prism, diffusivity, faces_layer): a Bar as the CamPlate of its rectangular section,
    its thickness the axis of the smallest size^2 / D (the sheet factor, measured on the
    finest grid, carries the fastest direction), D permuted to (in-plane x, y, thickness);
    ``faces_layer``: the Bar's contact layer is within the depth of any of its six faces
    (``symmetry_cuts.octant``), so its two faces count too. A CamPlate or LinkBar as it is.

    Parameters
    ----------
    geometry : Bar, CamPlate or LinkBar
        The part (lengths [m]).
    diffusivity : Diffusivity
        The material's diffusivity (pre-exponential factors [m^2/s] per axis).

    Returns
    -------
    prism : CamPlate or LinkBar
        The part as a prism (lengths [m]).
    diffusivity : Diffusivity
        D permuted to (in-plane x, y, thickness) [m^2/s].
    faces_layer : bool
        True for a Bar: its contact layer includes the two faces.
    """
    if geometry.planform:
        return geometry, diffusivity, False
    order = section_axes(geometry, diffusivity)
    a, b, h = bar_size(geometry)[order]
    plate = CamPlate(np.array([-a, a, a, -a]) / 2, np.array([-b, -b, b, b]) / 2, float(h), 0.0)
    d0 = diffusivity.pre_exponential
    return plate, replace(diffusivity, pre_exponential=tuple(float(d0[i]) for i in order)), True


def bar_size(bar: Bar) -> np.ndarray:
    """A Bar's three sizes.

    Parameters
    ----------
    bar : Bar
        The bar.

    Returns
    -------
    numpy.ndarray
        Its length, width and thickness [m].
    """
    return np.array([bar.length, bar.width, bar.thickness])


def section_axes(bar: Bar, diffusivity) -> list[int]:
    """A Bar's axes as (section x, section y, thickness), slowest first.

    The Bar's axes as (section x, section y, thickness): slowest first (``as_prism``).

    Parameters
    ----------
    bar : Bar
        The bar (sizes [m]).
    diffusivity : Diffusivity
        Its pre-exponential diffusivities per axis [m^2/s].

    Returns
    -------
    list of int
        The axis indices, by size^2 / D [s] from the slowest to the fastest.
    """
    size, d0 = bar_size(bar), np.asarray(diffusivity.pre_exponential, float)
    return sorted(range(3), key=lambda i: (size[i] ** 2 / d0[i], -i))[::-1]


def bar_coordinates(bar: Bar, diffusivity, coordinates: dict) -> dict:
    """Prism cell centres carried back into a Bar's own frame.

    The prism cells' centres (``as_prism``'s frame: the section centred, z from a face
    to the mid-plane) in the Bar's own x, y, z (from its corner: the section whole, the
    thickness axis its exposed half, as the octant's cells are from the exposed faces).

    Parameters
    ----------
    bar : Bar
        The bar the cells belong to (its sizes [m]).
    diffusivity : Diffusivity
        D0 along its three axes [m^2/s], which order them.
    coordinates : dict
        The prism cells' centres "x", "y", "z" [m] in ``as_prism``'s frame.

    Returns
    -------
    dict
        The centres "x", "y", "z" [m] in the Bar's own frame.
    """
    order, size = section_axes(bar, diffusivity), bar_size(bar)
    shifted = (coordinates["x"] + 0.5 * size[order[0]], coordinates["y"] + 0.5 * size[order[1]],
               coordinates["z"])
    return {"xyz"[axis]: value for axis, value in zip(order, shifted)}


def z_band(z_widths: np.ndarray, depth: float) -> np.ndarray:
    """The fraction of each z cell within a depth of the exposed face.

    Fraction of each z cell (m, from the exposed face) within ``depth`` of that face.

    Parameters
    ----------
    z_widths : numpy.ndarray
        The z cells' widths [m], from the exposed face.
    depth : float
        The contact layer's depth [m].

    Returns
    -------
    numpy.ndarray
        The fraction [-] of each cell within ``depth`` of the face.
    """
    nodes = np.concatenate([[0.0], np.cumsum(z_widths)])
    inside = interval_overlap(nodes[:-1], nodes[1:], -1.0, depth)
    return inside / z_widths


def half_slab(z_widths: np.ndarray) -> Discretisation:
    """The 1-D operator of a half thickness on given z widths.

    FiPy Grid1D of a half thickness on ``z_widths`` (scaled, from the exposed face at
    z = 0; the other end is the mid-plane mirror, insulated).

    Parameters
    ----------
    z_widths : numpy.ndarray
        The cell widths [-] (scaled by the thickness), from the exposed face.

    Returns
    -------
    Discretisation
        The operator, mean and layer weights the cell volumes.
    """
    mesh = interval_mesh(np.asarray(z_widths, float))
    exposed = np.asarray(mesh.exteriorFaces, bool) & np.isclose(
        np.asarray(mesh.faceCenters)[0], 0.0, atol=1e-12)
    volumes, stiffness, boundary = assemble(mesh, exposed=exposed)
    weights = normalised(volumes)
    return Discretisation(volumes, stiffness, boundary, weights, weights)


def planform_disc(geometry, d, tess, depth: float):
    """The planform alone as an operator, with second-order mean and layer weights.

    (Discretisation, corrected weights): the planform alone (a prism of infinite
    thickness) on the admissible cells ``tess``, one layer of the mirrored prisms with its
    exposed face's coupling 8 V (half-layer height 1/4 scaled) taken out of the boundary
    vector (as ``planform_modes.planform_operator``); its mean and layer weights the plate's
    (cell volumes, band shares: the same discrete product), and ``cell_moments``'
    second-order (mean, layer) weights on u - g beside.

    Parameters
    ----------
    geometry : CamPlate or LinkBar
        The prism part; its ``thickness`` [m] scales the coordinates.
    d : tuple of float
        The diffusivities (D_x, D_y, D_z) [m^2/s] of the march.
    tess : Tessellation
        The admissible planform cells.
    depth : float
        The contact layer's depth [m].

    Returns
    -------
    disc : Discretisation
        The planform's operator.
    weights : tuple of numpy.ndarray
        ``cell_moments``' second-order (mean, layer) weights [-] on u - g.
    """
    disc = prism(tess, geometry.thickness, np.array([0.5 * geometry.thickness]),
                 band_share(tess, depth), d, mid_plane=True)
    return (replace(disc, boundary=disc.boundary - 8.0 * disc.volumes),
            corrected_weights(tess, depth))


@dataclass(frozen=True)
class PrismCells:
    """A 3-D mesh of mirrored prisms: planform cells times z widths.

    A 3-D mesh of the mirrored prisms: admissible planform cells (``admissible.Tessellation``)
    x z widths (scaled, exposed face to mid-plane).

    Parameters
    ----------
    tess : Tessellation
        The admissible planform cells.
    z : numpy.ndarray
        The z widths [-] (scaled by the thickness), exposed face to mid-plane.
    """

    tess: object
    z: np.ndarray

    @classmethod
    def of(cls, geometry, d, chosen: Plan) -> "PrismCells":
        """The graded cells of a plan (``symmetry_cuts``'s prisms)."""
        return cls(sizing.planform_cells(geometry, chosen.finest, chosen.growth, stretch_of(d)),
                   half(sizing.prism_widths(chosen.finest, chosen.growth)))

    def refined(self, planform: int = 1, z: int = 1) -> "PrismCells":
        """Nested refinement by 2, ``planform`` times of every planform edge
        (``admissible.refine``: 4 x the cells each) and ``z`` times of every z width (2 x each);
        by default both once: 8 x the cells."""
        tess, widths = self.tess, self.z
        for _ in range(planform):
            tess = refine(tess)
        for _ in range(z):
            widths = np.repeat(0.5 * widths, 2)
        return PrismCells(tess, widths)

    @property
    def cells(self) -> int:
        return self.tess.cells * self.z.size


def cross(p: int, z: int) -> tuple[list, list]:
    """The meshes of the combination around mesh (p, z).

    The combination around mesh (p, z) (``corrected_product.combination``): its base (p-1, z-1)
    refined along z once and twice, and along the planform once and twice.

    Parameters
    ----------
    p, z : int
        The mesh's planform and z refinement levels.

    Returns
    -------
    tuple of list
        The z chain and the planform chain of (p, z) levels.
    """
    return ([(p - 1, z - 1), (p - 1, z), (p - 1, z + 1)],
            [(p - 1, z - 1), (p, z - 1), (p + 1, z - 1)])


def combination(lattice: list) -> tuple[list, list] | None:
    """Indices of the cross around the finest mesh, if all its meshes were marched.

    Indices (into ``lattice``) of the ``cross`` around the finest mesh (the last), or
    None where it is not all there.

    Parameters
    ----------
    lattice : list of tuple
        The (p, z) levels of the meshes marched, finest last.

    Returns
    -------
    tuple of list of int or None
        The indices of the two chains, or None.
    """
    index = {key: i for i, key in enumerate(lattice)}
    chains = cross(*lattice[-1])
    if not all(key in index for chain in chains for key in chain):
        return None
    return tuple([index[key] for key in chain] for chain in chains)


def richardson_march(setting: "SharedInputs", disc, keep: bool = False,
                     columns=()) -> CombinedMarch:
    """A swept march and the same on bisected steps, combined 2 fine - coarse.

    The swept backward-Euler march (``concentration_dependent``) on the plan's steps and on them
    bisected, combined 2 fine - coarse; its track: (mean, layer, ``columns``' sums).

    Parameters
    ----------
    setting : SharedInputs
        What every march of the solve shares: the law f [-], its largest factor top [-],
        the exposure (times [s], temperature [K], moisture [weight %]), the output times
        [s], the scales, the steps per doubling, the part's name and the sweeps' rule.
    disc : Discretisation
        The operator in scaled coordinates.
    keep : bool
        Keep the cell values.
    columns : tuple of numpy.ndarray
        More cell weight vectors to track.

    Returns
    -------
    CombinedMarch
        The combined means [weight %] and the time-error indicator.
    """
    exposure, scales = setting.exposure, setting.scales
    shared = SweptMarch(Faces.of(disc), setting.law, setting.top, setting.part, setting.sweeps)
    plans = [step_plan(exposure, setting.times, scales, setting.per_doubling, bisect)
             for bisect in (False, True)]
    coarse, fine = (sweep_march(shared, disc, steps, exposure.initial_moisture, keep, columns)
                    for steps in plans)
    fields = 2.0 * fine.fields - coarse.fields if keep else None
    return CombinedMarch(2.0 * fine.mean - coarse.mean, 2.0 * fine.layer - coarse.layer, fields,
                coarse.steps + fine.steps, float(np.max(np.abs(fine.mean - coarse.mean))),
                StepRecord.of(plans[0], coarse, fine, scales, exposure))


ROUND_OFF = 1e-9   # of the largest |surface value|: a coarse U this small keeps ratio 1


def unaccomplished_ratio(reference: np.ndarray, coarse: np.ndarray, floor: float) -> np.ndarray:
    """The ratio of two unaccomplished uptakes, 1 where the coarse one is round-off.

    reference / coarse (unaccomplished uptakes), 1 where |coarse| <= ``floor``.

    Parameters
    ----------
    reference : numpy.ndarray
        The reference's unaccomplished uptake U [weight %].
    coarse : numpy.ndarray
        The coarse grid's U [weight %].
    floor : float
        |coarse| at or below which the ratio is 1 [weight %].

    Returns
    -------
    numpy.ndarray
        The ratio [-].
    """
    small = np.abs(coarse) <= floor
    return np.where(small, 1.0, reference / np.where(small, 1.0, coarse))


def corrected(plate: CombinedMarch, sheet: tuple, planform: tuple, surface: np.ndarray,
              union=None):
    """The coarse plate's moisture corrected by its factors' references.

    (mean, layer): the plate's U = g - c times the ratio of the fine reference's U to the
    coarse grid's, for the sheet (the layer spans the thickness) and for the planform
    (its mean, its band for the layer). A ratio is 1 where the coarse grid's U is within
    round-off of zero. ``sheet``, ``planform``: (coarse CombinedMarch, fine reference
    CombinedMarch).
    ``union`` (a Bar's layer, ``MeshMarches.union``): (beta, zeta), the planform band's and the
    sheet layer's volume fractions; the layer is then the band through the thickness or
    the sheet's layer over the planform, whose U for the product of Fick (Crank 1975
    §4.3) is beta Ub S + zeta Sl (P - beta Ub) (P, Ub: the planform's mean and band; S,
    Sl: the sheet's mean and layer) with the coarse factors or the references.

    Parameters
    ----------
    plate : CombinedMarch
        The coarse 3-D march (moisture [weight %]).
    sheet : tuple of CombinedMarch
        The coarse grid's sheet and its fine reference.
    planform : tuple of CombinedMarch
        The coarse grid's planform and its fine reference.
    surface : numpy.ndarray
        The surface moisture g [weight %] at the outputs.
    union : tuple of float, optional
        A Bar's (beta, zeta) volume fractions [-].

    Returns
    -------
    mean, layer : numpy.ndarray
        The corrected mean and layer moisture [weight %].

    References
    ----------
    Crank (1975) §4.3; Stetter (1978) (module docstring).
    """
    floor = ROUND_OFF * max(float(np.max(np.abs(surface))), 1e-300)

    def ratio(fine, coarse):   # of the unaccomplished uptakes U = g - c
        return unaccomplished_ratio(surface - fine, surface - coarse, floor)
    (s_h, s_ref), (p_h, p_ref) = sheet, planform
    through = ratio(s_ref.mean, s_h.mean)
    mean = surface - (surface - plate.mean) * through * ratio(p_ref.mean, p_h.mean)
    if union is None:
        return mean, surface - (surface - plate.layer) * through * ratio(p_ref.layer, p_h.layer)
    beta, zeta = union

    def product(s, p):   # the layer's c (g - U / g-scale) from the factors' U = g - c
        s_u, s_l, p_u, p_b = (surface - v for v in (s.mean, s.layer, p.mean, p.layer))
        return surface - (beta * p_b * s_u + zeta * s_l * (p_u - beta * p_b)) / scale
    scale = max(float(np.max(np.abs(surface))), 1e-300)
    return mean, surface - (surface - plate.layer) * ratio(product(s_ref, p_ref),
                                                           product(s_h, p_h))


def steps_for(accuracy: float) -> int:
    """Steps per doubling for a time error of half the accuracy.

    Steps per doubling for the time error TIME_ERROR / m^2 at half the accuracy
    (``finite_volume.plan_direct``).

    Parameters
    ----------
    accuracy : float
        The accuracy [-] asked of the solve; the time error gets half.

    Returns
    -------
    int
        Steps per doubling m, at least ``MIN_STEPS_PER_DOUBLING``.
    """
    return max(MIN_STEPS_PER_DOUBLING, math.ceil(math.sqrt(TIME_ERROR / (0.5 * accuracy))))


def level_plan(geometry, diffusivity, law, exposure, times, mesh_accuracy, per_doubling) -> Plan:
    """A 3-D plan of the corrected product's coarse mesh.

    A 3-D plan: ``nonlinear_plan``'s cells at ``mesh_accuracy``, ``per_doubling`` steps.

    Parameters
    ----------
    geometry : CamPlate or LinkBar
        The part the 3-D mesh covers (sizes [m]).
    diffusivity : Diffusivity
        D0 of the material per axis [m^2/s].
    law : ConcentrationDependent
        How D scales with the local moisture, f [-].
    exposure : Exposure
        Temperatures [K] and surface moisture [weight %] over time [s].
    times : numpy.ndarray
        Times of the outputs [s].
    mesh_accuracy : float
        The accuracy [-] the cells are sized for.
    per_doubling : int
        Steps per doubling.

    Returns
    -------
    Plan
        The 3-D plan.
    """
    def planner(d, a, outputs):
        return plan_direct(DiffusionProblem(geometry, d, exposure, outputs, a), "solid",
                           mirrored=True)
    chosen = nonlinear_plan(planner, diffusivity, law, exposure, times, mesh_accuracy)
    return replace(chosen, steps_per_doubling=per_doubling)


def sheet_reference(problem: DiffusionProblem, geometry, diffusivity,
                    sweeps: Sweeps = SWEEPS) -> DiffusionResult:
    """The fine concentration-dependent sheet of the part's thickness.

    The D(c) sheet of the part's thickness at ``SHEET_SHARE`` x the accuracy (FiPy slab;
    its layer within the problem's contact-layer depth of a face; its cells' fields when the
    problem stores them).

    Parameters
    ----------
    problem : DiffusionProblem
        The sheet's moisture dependence f [-] (``sorption``), exposure (t [s], T [K],
        surface moisture [weight %]), output times [s], the requested accuracy [-] (the
        sheet takes ``SHEET_SHARE`` of it), the contact layer's depth [m] and whether to keep
        the cells' fields.
    geometry : CamPlate, LinkBar or Bar
        The part; its ``thickness`` [m] is the sheet's.
    diffusivity : Diffusivity
        D0 per axis [m^2/s]; the sheet takes the through-thickness one.
    sweeps : Sweeps
        When each step's sweeps stop.

    Returns
    -------
    DiffusionResult
        The sheet's mean and layer moisture [weight %].
    """
    law, exposure, times = problem.sorption, problem.exposure, problem.times
    sheet = Sheet(geometry.thickness)

    def planner(d, a, outputs):
        return plan_direct(DiffusionProblem(sheet, d, exposure, outputs, a), "slab")
    chosen = nonlinear_plan(planner, diffusivity, law, exposure, times,
                            SHEET_SHARE * problem.accuracy)
    return solve_nonlinear(DiffusionProblem(sheet, diffusivity, exposure, times,
                                            surface_layer_depth=problem.surface_layer_depth,
                                            store_fields=problem.store_fields,
                                            sorption=law), chosen, sweeps)


@dataclass(frozen=True)
class SharedInputs:
    """What every march of one corrected solve shares.

    What every march of one solve shares: law, scaled D, its top factor, scales.

    Parameters
    ----------
    geometry : CamPlate or LinkBar
        The prism every march meshes (sizes [m]).
    law : ConcentrationDependent
        The law f(c/Mm_ref) [-] every sweep reads.
    exposure : Exposure
        The shared exposure: t [s], T [K], surface moisture [weight %].
    times : numpy.ndarray
        The outputs every march records [s].
    d : tuple of float
        The scaled diffusivity D0 max f per axis [m^2/s].
    top : float
        The largest f met [-].
    scales : Scales
        The part's time and length scales.
    depth : float
        The contact layer's depth [m].
    per_doubling : int
        Steps per doubling.
    part : str
        The part's name, for errors.
    faces_layer : bool
        The layer includes the two faces (a Bar's).
    keep_fields : bool
        The planform marches keep their fields.
    sweeps : Sweeps
        When each step's sweeps stop.
    """

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
    faces_layer: bool = False   # the layer includes the two faces (a Bar's: ``as_prism``)
    keep_fields: bool = False   # the planform marches keep their fields (``corrected_fields``)
    sweeps: Sweeps = SWEEPS     # when each step's sweeps stop

    @classmethod
    def of(cls, problem: DiffusionProblem, geometry, diffusivity, per_doubling: int,
           faces_layer: bool = False, sweeps: Sweeps = SWEEPS) -> "SharedInputs":
        """What the marches of a corrected solve of ``problem`` share.

        Parameters
        ----------
        problem : DiffusionProblem
            The exposure, output times [s], contact-layer depth [m], whether the planform
            marches keep their fields, the part's name and the ``sorption`` law f [-].
        geometry : CamPlate or LinkBar
            The prism every march meshes (sizes [m]).
        diffusivity : Diffusivity
            Its D0 per axis [m^2/s] and activation energy [J/mol].
        per_doubling : int
            Steps per doubling [-].
        faces_layer : bool
            The layer includes the two faces (a Bar's).
        sweeps : Sweeps
            When each step's sweeps stop.

        Returns
        -------
        SharedInputs
            The shared inputs.
        """
        law, exposure, times = problem.sorption, problem.exposure, problem.times
        scaled = fastest(diffusivity, law, exposure, times)
        return cls(geometry, law, exposure, np.asarray(times, float),
                   tuple(float(v) for v in scaled.pre_exponential),
                   law.largest_factor(wettest(exposure, times)),
                   scales_of(geometry, scaled, exposure), problem.surface_layer_depth,
                   per_doubling, problem.part, faces_layer, problem.store_fields, sweeps)

    def run(self, disc, keep: bool = False, columns=()) -> CombinedMarch:
        return richardson_march(self, disc, keep, columns)

    def planform(self, finest: float, growth: float) -> tuple[CombinedMarch, CombinedMarch, int]:
        """(the plate's weights, ``cell_moments``' weights, cells) of the planform's march on
        the graded cells of (``finest``, ``growth``)."""
        return self.planform_on(sizing.planform_cells(self.geometry, finest, growth,
                                                      stretch_of(self.d)))

    def planform_on(self, tess) -> tuple[CombinedMarch, CombinedMarch, int]:
        """``planform`` on the admissible cells ``tess`` (both pairs with their cell values
        and ``tess`` when ``keep_fields``)."""
        disc, weights = planform_disc(self.geometry, self.d, tess, self.depth)
        pair = self.run(disc, True, weights)
        g = np.asarray(self.exposure.surface_before(self.times), float)
        mean, layer = (g + (pair.fields - g[:, None]) @ w for w in weights)
        track = pair.track   # its columns 2, 3: the sums of u on ``weights``, g added as above
        moments = track.values[:, 2:] + track.surface[:, None] * (
            1.0 - np.array([np.sum(w) for w in weights]))
        fields = pair.fields if self.keep_fields else None
        return (replace(pair, fields=fields, grid=tess,
                        track=track.with_values(track.values[:, :2])),
                replace(pair, mean=mean, layer=layer, fields=fields, grid=tess,
                        track=track.with_values(moments)), disc.cells)


@dataclass(frozen=True)
class MeshMarches:
    """One 3-D mesh's marches: the plate, its z widths as a sheet, its planform alone.

    One 3-D plan's marches: the plate, its z widths as a sheet, its planform alone.

    Parameters
    ----------
    plan : Plan
        The mesh's plan.
    plate, slab, planform : CombinedMarch
        The 3-D march, its z widths as a sheet, its planform alone (moisture [weight %]).
    moments : CombinedMarch
        The planform march read with ``cell_moments``' weights.
    cells : int
        The 3-D mesh's cells.
    planform_cells : int
        The planform's cells.
    coordinates : dict
        The cell centres [m].
    union : tuple of float or None
        A Bar's layer fractions (beta, zeta) [-].
    """

    plan: Plan
    plate: CombinedMarch
    slab: CombinedMarch
    planform: CombinedMarch
    moments: CombinedMarch   # the same march read with ``cell_moments``' weights
    cells: int
    planform_cells: int
    coordinates: dict
    union: tuple | None = None   # (beta, zeta) of a Bar's layer (``corrected``)


def three_d(setting: SharedInputs, chosen: Plan, keep: bool,
            cells: PrismCells | None = None) -> MeshMarches:
    """March one 3-D mesh, its sheet and its planform.

    The marches of one 3-D mesh: ``cells``, or the graded cells of ``chosen``.

    Parameters
    ----------
    setting : SharedInputs
        What the solve's marches share.
    chosen : Plan
        The plan whose graded cells are used when ``cells`` is None.
    keep : bool
        Keep the cell values.
    cells : PrismCells, optional
        The mesh's cells.

    Returns
    -------
    MeshMarches
        The mesh's marches (moisture [weight %]).
    """
    cells = cells or PrismCells.of(setting.geometry, setting.d, chosen)
    geometry = setting.geometry
    disc = prism(cells.tess, geometry.thickness, cells.z * geometry.thickness,
                 band_share(cells.tess, setting.depth), setting.d, mid_plane=True)
    slab, union = half_slab(cells.z), None
    if setting.faces_layer:   # a Bar: the band through the thickness or the faces' layer
        band = band_share(cells.tess, setting.depth)
        near = z_band(cells.z * geometry.thickness, setting.depth)
        share = 1.0 - np.outer(1.0 - near, 1.0 - band).ravel()   # cell k c + i (``admissible``)
        disc = replace(disc, layer_weights=normalised(disc.volumes * share))
        slab = replace(slab, layer_weights=normalised(slab.volumes * near))
        areas = disc.volumes[:cells.tess.cells]
        union = (float(areas @ band / areas.sum()), float(cells.z @ near / cells.z.sum()))
    plate = setting.run(disc, keep)
    slab = setting.run(slab, keep)
    planform, moments, planform_cells = setting.planform_on(cells.tess)
    return MeshMarches(chosen, plate, slab, planform, moments, disc.cells, planform_cells,
                 disc.coordinates, union)
