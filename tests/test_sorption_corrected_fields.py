"""Stored fields of the corrected product (``diffusion.nonfickian.corrected_fields``): the finest
nested 3-D mesh's cells corrected cell by cell by the sheet's and the planform's reference/coarse
ratios, against the exact Fickian block (k = 0: Crank 1975 eq. 4.51 pointwise, the
product of three sheets) and, with k = 2, against the corrected mean they must be
consistent with."""
import json
from pathlib import Path

import numpy as np
import pytest

from fickcam.diffusion import Bar, CamPlate, DiffusionProblem, Diffusivity, Exposure, Sheet, solve
from fickcam.diffusion.models.analytic import exact_history_field
from fickcam.diffusion.nonfickian import corrected_product
from fickcam.diffusion.nonfickian.corrected_fields import field_errors
from fickcam.diffusion.nonfickian.corrected_pieces import bar_coordinates
from fickcam.diffusion.nonfickian.corrected_product import corrected_levels, refined_run
from fickcam.diffusion.planform.admissible import cell_areas
from fickcam.diffusion.problem.sorption import ConcentrationDependent

pytest.importorskip("fipy")

H, D, MM = 2e-3, 5e-12, 2.0
ISOTROPIC = Diffusivity((D, D, D), 0.0)
TIMES = np.array([0.0, 0.01, 0.03, 0.1, 0.3]) * H ** 2 / D
PLATE = CamPlate(np.array([0, 4e-3, 4e-3, 0.0]), np.array([0, 0, 3e-3, 3e-3]), H)
BAR = Bar(*json.loads((Path(__file__).parent / "data" / "dc_bar_reference.json")
                      .read_text())["size"])   # 6 x 4 x 2 mm
WET = Exposure.piecewise([0.0, TIMES[-1]], [330.0], [MM], initial_moisture=0.0)


def law(k):
    return ConcentrationDependent(MM, exponent=k)


def volume_mean(run, fields):
    """The cell-volume-weighted mean of a field on the finest mesh of ``run``."""
    cells = run.meshes[-1]
    volumes = np.outer(cells.z, cell_areas(cells.tess)).ravel()
    return fields @ volumes / volumes.sum()


@pytest.mark.slow
@pytest.mark.parametrize("part", [PLATE, BAR], ids=["plate", "bar"])
def test_fickian_corrected_fields_are_the_exact_block_at_the_cell_points(part):
    """k = 0 through the corrected path at 3e-2: the corrected fields at the cells' points
    are the exact block (a Bar's in its own frame, ``bar_coordinates``) within the fields'
    indicated error, and far closer than the coarse cells' own values. Measured
    (``benchmarks/dc_corrected_fields.py fickian``): plate 5.7e-3 of the swing against
    9.3e-2 (indicated 1.3e-2), bar 2.2e-2 against 9.5e-2 (indicated 3.1e-2), both at
    tau* = 0.01; the plate's volume means within 4.2e-4 of the exact point values'."""
    run = corrected_levels(DiffusionProblem(part, ISOTROPIC, WET, TIMES, 3e-2, store_fields=True,
                                            sorption=law(0.0)))
    fields, errors = field_errors(run)
    coordinates = run.marched[-1].coordinates
    if isinstance(part, Bar):
        exact = exact_history_field(BAR, ISOTROPIC, WET, TIMES,
                                    bar_coordinates(BAR, ISOTROPIC, coordinates))
    else:
        exact = exact_history_field(Bar(4e-3, 3e-3, H), ISOTROPIC, WET, TIMES, coordinates)
    corrected = np.max(np.abs(fields - exact)) / MM
    coarse = np.max(np.abs(run.marched[-1].plate.fields - exact)) / MM
    assert corrected <= errors.total
    assert corrected <= coarse / 4.0
    # the coarse cells erred by about the correction made to them
    assert 0.5 * errors.correction <= coarse <= 2.0 * errors.correction
    if isinstance(part, CamPlate):
        # point values: their volume mean is the exact field's (same points), not the mean
        gap = volume_mean(run, fields) - volume_mean(run, exact)
        assert np.max(np.abs(gap)) / MM <= run.sheet.error_estimate + run.planform_error


@pytest.mark.slow
def test_dc_fields_under_auto_are_corrected_and_consistent_with_the_mean():
    """k = 2 absorbing on the 4 x 3 x 2 mm plate, ``auto`` with fields stored: the
    corrected product's fields (``corrected_product.solve_corrected`` hands its run,
    ``refined_run``, to ``corrected_fields.stored``), their error told in the reason.
    Their volume mean is the corrected mean to the point values' quadrature (for Fick the
    exact field's own: 1.6e-2 of the swing at tau* = 0.01 on these 1 200 cells), at most
    half the coarse cells' distance to it (measured 0.26-0.38 of it where that exceeds
    1e-5), within the fields' indicated error."""
    result = solve(PLATE, ISOTROPIC, WET, TIMES, accuracy=3e-2, sorption=law(2.0),
                   store_fields=True)
    assert "fields: the finest mesh's cells x the sheet's and the planform's" in result.reason
    run = refined_run(DiffusionProblem(PLATE, ISOTROPIC, WET, TIMES, 3e-2, store_fields=True,
                                       sorption=law(2.0)))[0]
    fields, errors = field_errors(run)
    np.testing.assert_array_equal(result.fields, fields)
    corrected = np.abs(volume_mean(run, fields) - result.mean) / MM
    coarse = np.abs(volume_mean(run, run.marched[-1].plate.fields) - result.mean) / MM
    seen = coarse > 1e-5
    assert np.all(corrected[seen] <= 0.5 * coarse[seen])
    assert np.max(corrected) <= errors.total


@pytest.mark.slow
def test_the_planform_reading_is_second_order_and_holds_mirrors_and_the_surface():
    """``corrected_fields.planform_at`` (linear on the Delaunay triangles of the cell points, the
    exposed outline at 0, images across mirror lines): a smooth U vanishing on the outline
    of the 4 x 3 x 2 mm plate, read at another graded mesh's points (some on the mirror
    line), converges at second order under nested refinement (from the 0.3 plan refined
    once: 160, 648, 2 608 cells, measured ratios of the errors 4.2, 3.3), the same on the
    half cut at its mirror line x = 2 mm (4.4, 5.7), and is 0 on the exposed outline."""
    from fickcam.diffusion.operators.sizing import planform_cells, triangulate
    from fickcam.diffusion.planform.admissible import admissible, refine
    from fickcam.diffusion.nonfickian.corrected_fields import exposed_points, planform_at

    def unaccomplished(tess, points):
        x, y = tess.physical(points).T
        return x * (4e-3 - x) * y * (3e-3 - y) / (2e-3 * 1.5e-3) ** 2

    whole = planform_cells(PLATE, 0.3, 0.3, (1.0, 1.0))
    half = admissible(triangulate(PLATE, 0.3 * H, growth=0.3, stretch=(1.0, 1.0)), PLATE,
                      (1.0, 1.0), mirrors=((0, 2e-3),))
    assert half.mirrors and np.all(half.centres[:, 0] >= 2e-3)
    points = planform_cells(PLATE, 0.5, 0.5, (1.0, 1.0)).centres
    for tess, at in ((whole, points), (half, points[points[:, 0] >= 2e-3])):
        exact = unaccomplished(tess, at)
        errors = []
        for level in (refine(tess), refine(refine(tess)), refine(refine(refine(tess)))):
            read = planform_at(level, unaccomplished(level, level.centres)[None, :], at)[0]
            errors.append(np.max(np.abs(read - exact)))
        assert errors[0] / errors[1] > 2.8 and errors[1] / errors[2] > 2.8   # 4 at order 2
        outline = exposed_points(tess)
        on_outline = planform_at(tess, unaccomplished(tess, tess.centres)[None, :], outline)
        np.testing.assert_allclose(on_outline, 0.0, atol=1e-12)
    assert np.any(points[:, 0] == 2e-3)   # read on the mirror line itself


@pytest.mark.slow
def test_dc_fields_at_the_centre_of_a_wide_plate_are_the_dc_sheet():
    """k = 2 absorbing, an 8 x 8 x 2 mm plate up to tau* = 0.01: more than 2.5 mm from every
    edge (4.6 diffusion lengths at the wettest D, e^2 D) the part is the D(c) sheet (Crank
    1975 ch. 9), here solved alone at 1e-3 on its own grid. The corrected fields there
    are that sheet within their indicated error and far closer than the coarse cells'.
    Measured (``benchmarks/dc_corrected_fields.py wide``): 2.7e-3 of the swing at tau* =
    0.01 against 3.4e-2, indicated 5.3e-2 (8-9 CPU s)."""
    side = 8e-3
    wide = CamPlate(np.array([0, side, side, 0.0]), np.array([0, 0, side, side]), H)
    times = TIMES[:2]
    wet = Exposure.piecewise([0.0, times[-1]], [330.0], [MM], initial_moisture=0.0)
    run = corrected_levels(DiffusionProblem(wide, ISOTROPIC, wet, times, 3e-2, store_fields=True,
                                            sorption=law(2.0)))
    fields, errors = field_errors(run)
    sheet = solve(Sheet(H), ISOTROPIC, wet, times, accuracy=1e-3, sorption=law(2.0),
                  model="slab", store_fields=True)
    at = run.marched[-1].coordinates
    centre = ((np.minimum(at["x"], side - at["x"]) > 2.5e-3)
              & (np.minimum(at["y"], side - at["y"]) > 2.5e-3))
    reference = np.stack([np.interp(at["z"][centre], sheet.cell_coordinates["z"], row)
                          for row in sheet.fields])
    corrected = np.max(np.abs(fields[:, centre] - reference)) / MM
    coarse = np.max(np.abs(run.marched[-1].plate.fields[:, centre] - reference)) / MM
    assert corrected + sheet.error_estimate <= errors.total
    assert corrected <= coarse / 5.0


@pytest.mark.slow
def test_fields_after_the_cross_are_the_diagonal_finest_meshs_and_its_coarser_neighbours():
    """Where the 8x mesh passes the cap, ``CorrectedMeshes.finer`` adds the ``cross`` (meshes
    refined along one direction, their fields not kept) around the finest: the stored fields and
    their indicated errors still come from the finest mesh and the next coarser one on the
    diagonal, so they are the two-mesh run's exactly (k = 2 absorbing, 3 x 2 x 2 mm plate)."""
    small = CamPlate(np.array([0, 3e-3, 3e-3, 0.0]), np.array([0, 0, 2e-3, 2e-3]), H)
    run = corrected_levels(DiffusionProblem(small, ISOTROPIC, WET, TIMES[:4], 1e-2,
                                            store_fields=True, sorption=law(2.0)), 2, base=1.0)
    caps = corrected_product.MeshCaps(nested=4 * run.meshes[1].cells,
                                      cross=2 * run.meshes[1].cells)
    crossed = run.finer(store_fields=True, caps=caps)
    assert crossed.keys[-1] == (1, 1) and len(crossed.meshes) == 6
    assert [m.plate.fields is None for m in crossed.marched] == [False] + [True] * 4 + [False]
    (two, two_errors), (cross, cross_errors) = field_errors(run), field_errors(crossed)
    np.testing.assert_array_equal(cross, two)
    assert cross_errors == two_errors
