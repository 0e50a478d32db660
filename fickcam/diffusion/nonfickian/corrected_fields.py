r"""Stored fields of the corrected product (``corrected_product``): each coarse 3-D cell's own value
corrected as the mean and the layer are, cell by cell.

For Fick on a prism mesh (planform cells i x z widths k, a tensor product) the discrete
field is the product of the discrete sheet on the z widths and the discrete planform,
U_3d(i, k) = S_h(k) P_h(i) / (g - c0) (Crank 1975 §4.3, eq. 4.51 pointwise; U = g - c,
the unaccomplished uptake), so the same swap of each coarse factor for its reference
(``corrected_pieces.corrected``) applies to every cell:

.. math::

    U(i, k) = U_{3d}(i, k)\, \frac{S_{ref}(z_k)}{S_h(k)}\, \frac{P_{ref}(x_i)}{P_h(i)},

a ratio 1 where the coarse U is within round-off of zero. With constant D this is the
fine sheet x fine planform at the cell's point, whatever the 3-D mesh.

Point values, not cell averages: on the admissible cells the finite-volume value of a
cell approximates u at its circumcentre (``cell_moments``: Eymard, Gallouet & Herbin 2000
§9), O(h) from its centroid where the cells are graded, so a cell average of the
reference (an area overlap) would not be the quantity P_h(i) approximates and the ratio
would carry an O(h) error; the stored ``cell_coordinates`` are these points too. The
references are read at the coarse points to second order: the sheet by linear
interpolation between its cell centres and the surface value at the face (its cells are
not the 3-D mesh's z widths), the planform reference (a different graded planform, not
nested) by linear interpolation on the Delaunay triangles of its cell points and the
exposed outline (``reading``).

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
- Eymard, R., Gallouët, T. & Herbin, R. (2000). Finite volume methods. Handbook of Numerical
  Analysis VII:713-1020. doi:10.1016/S1570-8659(00)07005-8
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import sparse
from scipy.spatial import Delaunay, cKDTree

from ..planform.polygon import unique_edges
from .corrected_pieces import ROUND_OFF, unaccomplished_ratio as ratio



def planform_at(tess, values: np.ndarray, points: np.ndarray, surface: bool = True):
    """Read planform cell values at points by linear interpolation.

    ``values`` (rows: times or layers; columns: the cells of ``tess``) read at ``points``
    (stretched coordinates, (n, 2)) by ``reading``.

    Parameters
    ----------
    tess : Tessellation
        The planform's cells (their centres in stretched coordinates [-]).
    values : numpy.ndarray
        Rows (times or layers) of cell values [weight %], shape (rows, cells).
    points : numpy.ndarray
        Where to read, stretched coordinates [-], shape (n, 2).
    surface : bool
        Add the exposed outline as nodes of value 0 (``reading``).

    Returns
    -------
    numpy.ndarray
        The values read [weight %], shape (rows, n).
    """
    return (reading(tess, points, surface) @ values.T).T


def reading(tess, points: np.ndarray, surface: bool = True) -> sparse.csr_matrix:
    """The sparse matrix that reads a planform's cell values at points.

    (points, cells): linear interpolation on the Delaunay triangles of the cell points
    (scipy.spatial / Qhull), mirrored across the tessellation's mirror lines (insulated:
    the field is even there), with ``surface`` the exposed outline's vertices and side
    midpoints as further nodes of value 0 (U = g - c vanishes there); a point outside them
    all takes its nearest cell's value. Second order for a smooth field. Measured on the
    6 x 4 x 2 mm bar's section (Fickian planform of 902 cells read at the 3-D mesh's 516):
    error 2.2e-2 of the swing at tau* = 0.01, against 6.8e-2 by the nearest cell's value
    plus its least-squares gradient (``cell_moments.gradient_matrix``).

    Parameters
    ----------
    tess : Tessellation
        The planform's cells, outline and mirror lines (stretched coordinates [-]).
    points : numpy.ndarray
        Where to read, stretched coordinates [-], shape (n, 2).
    surface : bool
        Add the exposed outline's vertices and side midpoints as nodes of value 0.

    Returns
    -------
    scipy.sparse.csr_matrix
        The interpolation weights [-], shape (points, cells).
    """
    nodes, cell = tess.centres, np.arange(tess.cells)
    if surface:
        boundary = exposed_points(tess)
        nodes, cell = np.vstack([nodes, boundary]), np.concatenate([cell, np.full(len(boundary),
                                                                                  -1)])
    for axis, value in tess.mirrors:
        image = nodes.copy()
        image[:, axis] = 2.0 * value - image[:, axis]
        nodes, cell = np.vstack([nodes, image]), np.concatenate([cell, cell])
    triangulation = Delaunay(nodes)
    simplex = triangulation.find_simplex(points)
    inside = simplex >= 0
    transform = triangulation.transform[simplex[inside]]
    first = np.einsum("kij,kj->ki", transform[:, :2], points[inside] - transform[:, 2])
    weights = np.column_stack([first, 1.0 - first.sum(axis=1)])
    columns = cell[triangulation.simplices[simplex[inside]]]
    rows = np.repeat(np.flatnonzero(inside), 3)
    _, nearest = cKDTree(tess.centres).query(points[~inside])
    keep = columns.ravel() >= 0
    return sparse.csr_matrix(
        (np.concatenate([weights.ravel()[keep], np.ones(nearest.size)]),
         (np.concatenate([rows[keep], np.flatnonzero(~inside)]),
          np.concatenate([columns.ravel()[keep], nearest]))), shape=(len(points), tess.cells))


def exposed_points(tess) -> np.ndarray:
    """The vertices and side midpoints of a planform's exposed outline.

    The vertices and side midpoints of the outline's exposed sides (not on a mirror
    line), stretched coordinates.

    Parameters
    ----------
    tess : Tessellation
        The planform's triangles and mirror lines.

    Returns
    -------
    numpy.ndarray
        The points, stretched coordinates [-], shape (n, 2).
    """
    edges, side = unique_edges(tess.triangles)
    outer = edges[np.bincount(side.ravel(), minlength=len(edges)) == 1]
    ends = tess.points[outer]                      # (sides, 2, 2)
    on_mirror = np.zeros(len(outer), bool)
    for axis, value in tess.mirrors:
        on_mirror |= np.all(ends[:, :, axis] == value, axis=1)
    ends = ends[~on_mirror]
    return np.vstack([np.unique(ends.reshape(-1, 2), axis=0), ends.mean(axis=1)])


def sheet_at(z_sheet: np.ndarray, unaccomplished: np.ndarray, z: np.ndarray,
             thickness: float) -> np.ndarray:
    """Read a sheet's unaccomplished moisture U at depths, linearly, U = 0 at its faces.

    The sheet's U (times, cells at ``z_sheet``, m from a face, the whole thickness)
    read at ``z`` by linear interpolation, U = 0 at both faces.

    Parameters
    ----------
    z_sheet : numpy.ndarray
        The sheet's cell centres, distance from a face [m].
    unaccomplished : numpy.ndarray
        The sheet's U = g - c [weight %], shape (times, cells).
    z : numpy.ndarray
        Where to read [m] from the same face.
    thickness : float
        The sheet's thickness [m].

    Returns
    -------
    numpy.ndarray
        U read at ``z`` [weight %], shape (times, len(z)).
    """
    knots = np.concatenate([[0.0], z_sheet, [thickness]])
    values = np.pad(unaccomplished, ((0, 0), (1, 1)))
    return np.stack([np.interp(z, knots, row) for row in values])


@dataclass(frozen=True)
class References:
    """The sheet's and the planforms' reference U at the cell points of a 3-D mesh.

    The references' U at the cell points of a 3-D mesh (``corrected_pieces.PrismCells``): the
    fine
    sheet's at its z centres (times, z widths), the finest planform's and the one refined
    once less at its planform cells (times, cells). The field takes the finest planform
    alone: the Richardson combination f + (f - c) / 3 the mean takes (``defect.
    refined_reference``) raised the Fickian field's error on the 4 x 3 x 2 mm plate at
    3e-2 from 5.7e-3 to 8.8e-3 of the swing (tau* = 0.01): point values read between
    non-nested cells are not in the asymptotic range there.

    Parameters
    ----------
    sheet : numpy.ndarray
        The fine sheet's U [weight %] at the mesh's z centres, shape (times, z widths).
    planform : numpy.ndarray
        The finest planform's U [weight %] at the mesh's planform cells, (times, cells).
    coarser : numpy.ndarray
        The planform refined once less, U [weight %], (times, cells).
    """

    sheet: np.ndarray
    planform: np.ndarray
    coarser: np.ndarray

    @classmethod
    def of(cls, cells, sheet, planform, surface: np.ndarray, thickness: float):
        """``sheet``: a ``DiffusionResult`` with fields; ``planform``: the reference
        ``corrected_pieces.CombinedMarch`` with fields, ``grid`` and ``coarser``."""
        g = surface[:, None]
        z_nodes = np.concatenate([[0.0], np.cumsum(cells.z)]) * thickness
        z_centres = 0.5 * (z_nodes[1:] + z_nodes[:-1])
        points = cells.tess.centres
        finest, once_less = (planform_at(p.grid, g - p.fields, points)
                             for p in (planform, planform.coarser[0]))
        return cls(sheet_at(sheet.cell_coordinates["z"], g - sheet.fields, z_centres, thickness),
                   finest, once_less)


def corrected_fields(level, cells, sheet_ref: np.ndarray, planform_ref: np.ndarray,
                     surface: np.ndarray) -> np.ndarray:
    """A 3-D mesh's cell moisture corrected by the sheet's and the planform's references.

    (times, cells) c of a 3-D mesh's cells (``corrected_pieces.MeshMarches`` marched with its
    fields
    kept on ``cells``, ``corrected_pieces.PrismCells``) corrected by the sheet's and the planform's
    reference U at its points (``References``); ``surface``: g at the outputs (module
    docstring).

    Parameters
    ----------
    level : MeshMarches
        The 3-D mesh's marches with their fields kept on ``cells``.
    cells : PrismCells
        The mesh's cells.
    sheet_ref : numpy.ndarray
        The sheet's reference U [weight %] at the z centres, (times, z widths).
    planform_ref : numpy.ndarray
        The planform's reference U [weight %] at the planform cells, (times, cells).
    surface : numpy.ndarray
        The surface moisture g [weight %] at the outputs.

    Returns
    -------
    numpy.ndarray
        The corrected moisture c [weight %], shape (times, cells).
    """
    g = surface[:, None]
    floor = ROUND_OFF * max(float(np.max(np.abs(surface))), 1e-300)
    through = ratio(sheet_ref, g - level.slab.fields, floor)
    across = ratio(planform_ref, g - level.planform.fields, floor)
    plate = (g - level.plate.fields).reshape(len(surface), cells.z.size, cells.tess.cells)
    return (g - (plate * through[:, :, None] * across[:, None, :]).reshape(len(surface), -1))


def restricted(fields: np.ndarray, cells, coarse) -> np.ndarray:
    """A field on refined prism cells read at the coarser cells' points.

    A field (times, cells) on ``cells`` (``PrismCells.refined`` of ``coarse``) read at
    ``coarse``'s cell points: each coarse z width is two fine ones (the mean of the two at
    their shared node, linear), the planform by ``planform_at`` without the outline's
    nodes (the field, Q - 1 in ``field_errors``, need not vanish there).

    Parameters
    ----------
    fields : numpy.ndarray
        Values on ``cells``, shape (times, cells), in any unit.
    cells : PrismCells
        The fine cells, ``coarse`` refined.
    coarse : PrismCells
        The cells to read at.

    Returns
    -------
    numpy.ndarray
        The values at ``coarse``'s cell points, shape (times, coarse cells), in the same unit.
    """
    times = fields.shape[0]
    layers = fields.reshape(times, coarse.z.size, 2, cells.tess.cells).mean(axis=2)
    flat = layers.reshape(times * coarse.z.size, cells.tess.cells)
    return planform_at(cells.tess, flat, coarse.tess.centres, surface=False).reshape(times, -1)


def unseparated_share(fields, references: References, surface) -> tuple:
    """The share of a corrected field's U that the references' product does not give.

    (Q - 1, S_ref P_ref / |g|max) per cell: Q = U / (S_ref P_ref / |g|max), the part of a
    corrected field's U that the product of the references does not give (constant in
    space for Fick up to the marches' time error, Crank 1975 §4.3); Q - 1 = 0 where the
    product is within round-off of zero.

    Parameters
    ----------
    fields : numpy.ndarray
        A corrected field c [weight %], shape (times, cells).
    references : References
        The sheet's and the planform's U [weight %].
    surface : numpy.ndarray
        The surface moisture g [weight %] at the outputs.

    Returns
    -------
    tuple of numpy.ndarray
        Q - 1 [-] and S_ref P_ref / |g|max [weight %] per cell, shape (times, cells).

    References
    ----------
    Crank (1975) §4.3, cited in the module docstring.
    """
    g = surface[:, None]
    product = (references.sheet[:, :, None] * references.planform[:, None, :]).reshape(
        len(surface), -1)
    scale = max(float(np.max(np.abs(surface))), 1e-300)
    return ratio(g - fields, product / scale, ROUND_OFF * scale) - 1.0, product / scale


@dataclass(frozen=True)
class FieldErrors:
    """What is known of a corrected field's error, each relative to the swing.

    What is known of a corrected field's error (``field_errors``), relative to the swing.

    Parameters
    ----------
    correction : float
        The largest |corrected - coarse| [-]: the coarse cells' own error, indicated.
    sheet : float
        The fine sheet's estimate [-] (its mean's).
    planform : float
        The finest planform's error [-], second order.
    three_d : float
        The change from the coarser nested mesh [-].
    """

    correction: float   # largest |corrected - coarse|: the coarse cells' own error, indicated
    sheet: float        # the fine sheet's estimate (its mean's)
    planform: float     # the finest planform's, second order: its change from the planform
    #                     refined once less / (R^2 - 1)
    three_d: float      # the change from the coarser nested mesh

    @property
    def total(self) -> float:
        return self.sheet + self.planform + self.three_d

    def note(self) -> str:
        return (f"; fields: the finest mesh's cells x the sheet's and the planform's ratios, "
                f"cell by cell (largest correction {self.correction:.1e}; sheet {self.sheet:.1e}, "
                f"planform {self.planform:.1e}, change from the coarser nested mesh "
                f"{self.three_d:.1e}: sum {self.total:.1e}, the fields' "
                "error indicated, not in the estimate)")


def field_errors(run) -> tuple[np.ndarray, FieldErrors]:
    """The finest nested mesh's corrected fields and what is known of their error.

    (fields, errors) of ``run`` (``corrected_product.CorrectedMeshes`` on nested meshes,
    ``store_fields``):
    the finest nested mesh's cells corrected (``corrected_fields``) and
    what is known of their error, relative to the swing: the largest correction (the
    coarse cells' own error, indicated); the fine sheet's estimate (its mean's; its cells'
    values read at the z centres erred 2.7e-3 where it estimated 2.2e-3, Fickian 4 x 3 x 2
    mm plate at 3e-2, tau* = 0.01); the finest planform's error at second order, the
    change of the corrected field from the planform refined once less x 1 / (R^2 - 1)
    (the weight ``corrected_product.refined_reference`` took, R the ratio of the two); and the
    change
    of the corrected field from the next coarser nested mesh at its cell points. That change is
    read on Q - 1 (``unseparated_share``: near 0, smooth, where U itself is too steep on
    these coarse cells to be carried between the meshes by ``restricted``: the exact
    Fickian U so carried from the 4 x 3 x 2 mm plate's 1 200 cells to its 150 erred 0.11
    of the swing at tau* = 0.01, by ``restricted`` with the outline's nodes), times the
    references' product there; at order 1 the
    finer field's error is about that change (``corrected_product.ORDER_ONE``). Their sum, the
    fields' error indicated, was 2.2 (plate) and 1.4 (6 x 4 x 2 mm bar) x the Fickian
    fields' largest error at 3e-2 (``benchmarks/dc_corrected_fields.py fickian``). None of
    it is in the result's estimate, which is the mean's and the layer's.

    Parameters
    ----------
    run : CorrectedMeshes
        The corrected product on nested meshes, solved with ``store_fields``.

    Returns
    -------
    fields : numpy.ndarray
        The finest mesh's corrected moisture [weight %], shape (times, cells).
    errors : FieldErrors
        What is known of their error [-].
    """
    setting = run.setting
    surface = np.asarray(setting.exposure.surface_before(setting.times), float)

    def on(index):
        cells = run.meshes[index]
        references = References.of(cells, run.sheet, run.planform, surface,
                                   setting.geometry.thickness)
        return (corrected_fields(run.marched[index], cells, references.sheet,
                                 references.planform, surface), references)
    fields, references = on(-1)
    level, cells = run.marched[-1], run.meshes[-1]
    once_less = corrected_fields(level, cells, references.sheet, references.coarser, surface)
    top = run.lattice[-1]   # the diagonal's next coarser mesh (not one of a ``cross``'s),
    below = run.lattice.index((top[0] - 1, top[1] - 1))   # its fields kept: there are two
    coarse, fine = run.meshes[below], run.meshes[-1]      # diagonal meshes or more
    coarser, coarse_references = on(below)
    share, product = unseparated_share(coarser, coarse_references, surface)
    carried = restricted(unseparated_share(fields, references, surface)[0], fine, coarse)
    three_d = float(np.max(np.abs((carried - share) * product))) / run.scale
    weight = run.planform.coarser[1]
    return fields, FieldErrors(float(np.max(np.abs(fields - level.plate.fields))) / run.scale,
                               run.sheet.error_estimate,
                               weight * float(np.max(np.abs(fields - once_less))) / run.scale,
                               three_d)


def stored(run, reason: str) -> tuple[np.ndarray, str]:
    """The corrected fields, and the result's reason with their errors.

    (fields, reason): ``field_errors``' fields, and ``reason`` with their errors.

    Parameters
    ----------
    run : CorrectedMeshes
        The corrected product on nested meshes, solved with ``store_fields``.
    reason : str
        The result's reason so far.

    Returns
    -------
    fields : numpy.ndarray
        The corrected moisture [weight %], shape (times, cells).
    reason : str
        ``reason`` with the fields' errors appended.
    """
    fields, errors = field_errors(run)
    return fields, reason + errors.note()
