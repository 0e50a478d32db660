"""Stored fields of the corrected product (``defect``): each coarse 3-D cell's own value
corrected as the mean and the layer are, cell by cell.

For Fick on a prism mesh (planform cells i x z widths k, a tensor product) the discrete
field is the product of the discrete sheet on the z widths and the discrete planform,
U_3d(i, k) = S_h(k) P_h(i) / (g - c0) (Crank 1975 §4.3, eq. 4.51 pointwise; U = g - c,
the unaccomplished uptake), so the same swap of each coarse factor for its reference
(``defectparts.corrected``) applies to every cell:

    U(i, k) = U_3d(i, k) [S_ref(z_k) / S_h(k)] [P_ref(x_i) / P_h(i)],

a ratio 1 where the coarse U is within round-off of zero. With constant D this is the
fine sheet x fine planform at the cell's point, whatever the 3-D mesh.

Point values, not cell averages: on the admissible cells the finite-volume value of a
cell approximates u at its circumcentre (``cellmoments``: Eymard, Gallouet & Herbin 2000
§9), O(h) from its centroid where the cells are graded, so a cell average of the
reference (an area overlap) would not be the quantity P_h(i) approximates and the ratio
would carry an O(h) error; the stored ``cell_coordinates`` are these points too. The
references are read at the coarse points to second order: the sheet by linear
interpolation between its cell centres and the surface value at the face (its cells are
not the 3-D mesh's z widths), the planform reference (a different graded planform, not
nested) by its cell value plus the least-squares gradient (``cellmoments.gradient_matrix``,
Barth 1991) times the offset from the nearest reference cell point.
"""
from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from .cellmoments import gradient_matrix

ROUND_OFF = 1e-9   # of the largest |surface value|: a coarse U this small keeps ratio 1
#                    (as ``defectparts.corrected``)


def planform_at(tess, unaccomplished: np.ndarray, points: np.ndarray) -> np.ndarray:
    """U (rows: times or layers; columns: the cells of ``tess``) read at ``points``
    (stretched coordinates, (n, 2)): the nearest cell point's value plus its least-squares
    gradient (zero surface value at the exposed sides) times the offset, second order."""
    _, nearest = cKDTree(tess.centres).query(points)
    gradient = (gradient_matrix(tess) @ unaccomplished.T).T   # rows: 2 cells (x, y)
    offset = points - tess.centres[nearest]
    return (unaccomplished[:, nearest] + gradient[:, 2 * nearest] * offset[:, 0]
            + gradient[:, 2 * nearest + 1] * offset[:, 1])


def sheet_at(z_sheet: np.ndarray, unaccomplished: np.ndarray, z: np.ndarray,
             thickness: float) -> np.ndarray:
    """The sheet's U (times, cells at ``z_sheet``, m from a face, the whole thickness)
    read at ``z`` by linear interpolation, U = 0 at both faces."""
    knots = np.concatenate([[0.0], z_sheet, [thickness]])
    values = np.pad(unaccomplished, ((0, 0), (1, 1)))
    return np.stack([np.interp(z, knots, row) for row in values])


def ratio(reference: np.ndarray, coarse: np.ndarray, floor: float) -> np.ndarray:
    small = np.abs(coarse) <= floor
    return np.where(small, 1.0, reference / np.where(small, 1.0, coarse))


def references(cells, sheet, planform, surface: np.ndarray, thickness: float):
    """(S_ref (times, z widths), P_ref (times, planform cells)): the fine sheet's U (a
    ``DiffusionResult`` with fields) at the z centres of ``cells`` (``defectparts.Cells``)
    and the planform reference's (``defectparts.Pair`` with fields and ``grid``) at its
    cell points."""
    g = surface[:, None]
    z_nodes = np.concatenate([[0.0], np.cumsum(cells.z)]) * thickness
    z_centres = 0.5 * (z_nodes[1:] + z_nodes[:-1])
    return (sheet_at(sheet.cell_coordinates["z"], g - sheet.fields, z_centres, thickness),
            planform_at(planform.grid, g - planform.fields, cells.tess.centres))


def corrected_fields(level, cells, sheet, planform, surface: np.ndarray,
                     thickness: float) -> np.ndarray:
    """(times, cells) c of a 3-D mesh's cells (``defectparts.Level`` marched with its fields
    kept on ``cells``, ``defectparts.Cells``) corrected by the fine sheet and the planform
    reference (``references``); ``surface``: g at the outputs (module docstring)."""
    g = surface[:, None]
    floor = ROUND_OFF * max(float(np.max(np.abs(surface))), 1e-300)
    sheet_ref, planform_ref = references(cells, sheet, planform, surface, thickness)
    through = ratio(sheet_ref, g - level.slab.fields, floor)
    across = ratio(planform_ref, g - level.planform.fields, floor)
    plate = (g - level.plate.fields).reshape(len(surface), cells.z.size, cells.tess.cells)
    return (g - (plate * through[:, :, None] * across[:, None, :]).reshape(len(surface), -1))


def restricted(fields: np.ndarray, cells, coarse) -> np.ndarray:
    """A field of U = g - c on ``cells`` (``Cells.refined`` of ``coarse``) read at
    ``coarse``'s cell points: each coarse z width is two fine ones (the mean of the two at
    their shared node, linear), the planform by ``planform_at``."""
    times = fields.shape[0]
    layers = fields.reshape(times, coarse.z.size, 2, cells.tess.cells).mean(axis=2)
    flat = layers.reshape(times * coarse.z.size, cells.tess.cells)
    return planform_at(cells.tess, flat, coarse.tess.centres).reshape(times, -1)


def unseparated_share(fields, cells, sheet, planform, surface, thickness):
    """(Q - 1, S_ref P_ref / |g|max) per cell: Q = U / (S_ref P_ref / |g|max), the part of a
    corrected field's U that the product of the references does not give (constant in
    space for Fick up to the marches' time error, Crank 1975 §4.3); Q - 1 = 0 where the
    product is within round-off of zero."""
    g = surface[:, None]
    sheet_ref, planform_ref = references(cells, sheet, planform, surface, thickness)
    product = (sheet_ref[:, :, None] * planform_ref[:, None, :]).reshape(len(surface), -1)
    scale = max(float(np.max(np.abs(surface))), 1e-300)
    return ratio(g - fields, product / scale, ROUND_OFF * scale) - 1.0, product / scale


def stored(run, reason: str) -> tuple[np.ndarray, str]:
    """(fields, reason): the finest nested mesh's cells corrected (``corrected_fields``) and
    ``reason`` with what is known of their error, relative to the swing: the largest
    correction (the coarse cells' own error, indicated) and the change of the corrected
    field from the next coarser nested mesh at its cell points. That change is read on
    Q - 1 (``unseparated_share``: near 0, smooth, where U itself is too steep on these
    coarse cells to be carried between the meshes by ``restricted``: the exact Fickian U so
    carried from the 4 x 3 x 2 mm plate's 1 200 cells to its 150 erred 0.11 of the swing at
    tau* = 0.01), times the references' product there. At order 1 the finer field's error
    is about that change (``defect.ORDER_ONE``), plus the references' own field errors.
    Neither is in the result's estimate, which is the mean's and the layer's."""
    setting = run.setting
    surface = np.asarray(setting.exposure.surface_before(setting.times), float)
    thickness = setting.geometry.thickness
    parts = (run.sheet, run.planform, surface, thickness)
    fields = corrected_fields(run.marched[-1], run.meshes[-1], *parts)
    correction = float(np.max(np.abs(fields - run.marched[-1].plate.fields))) / run.scale
    note = (f"; fields: the finest mesh's cells x the sheet's and the planform's ratios, "
            f"cell by cell (largest correction {correction:.1e}")
    if len(run.meshes) >= 2:
        coarse, fine = run.meshes[-2:]
        coarser = corrected_fields(run.marched[-2], coarse, *parts)
        share, product = unseparated_share(coarser, coarse, *parts)
        carried = restricted(unseparated_share(fields, fine, *parts)[0], fine, coarse)
        change = (carried - share) * product
        note += (f"; change from the coarser nested mesh {np.max(np.abs(change)) / run.scale:.1e}"
                 ", about the fields' error")
    return fields, reason + note + "; not in the estimate)"
