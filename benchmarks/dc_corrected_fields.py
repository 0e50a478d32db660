"""Stored fields of the corrected product (``diffusion/nonfickian/corrected_fields.py``): the
finest nested 3-D mesh's cells corrected cell by cell, against the exact Fickian block
and against the corrected mean, and what keeping them costs.

    python benchmarks/dc_corrected_fields.py fickian [ACCURACY]
        # k = 0 on the 4 x 3 x 2 mm plate and the 6 x 4 x 2 mm bar (default 3e-2): the
        # corrected and the coarse cells' fields against the exact block (Crank 1975 eq.
        # 4.51 at the cells' points), the indicated error (``defectfields.FieldErrors``),
        # the volume means of the corrected and of the exact point values; on the plate
        # also: the fine sheet read at the z centres, the field with the planform reference
        # Richardson-combined (f + w (f - c)), the exact U carried by ``restricted`` from
        # the finer nested mesh to the coarser one; on the bar the planform reference read
        # by ``planform_at`` and by the nearest cell's value + its least-squares gradient
    python benchmarks/dc_corrected_fields.py dc [K] [ACCURACY]
        # k (default 2) on the plate, absorbing and drying: the fields' volume mean against
        # the corrected mean, for the corrected and the coarse cells, and the indication
    python benchmarks/dc_corrected_fields.py wide [K] [SIDE_MM] [MARGIN_MM] [OUTPUTS]
        # k (default 2) absorbing on a SIDE x SIDE x 2 mm plate (default 8, at 3e-2) up to
        # the OUTPUTS-th output (default 2: tau* = 0.01): the corrected and the coarse cells'
        # fields more than MARGIN (2.5) mm from every edge against the D(c) sheet alone at
        # 1e-3 (Crank 1975 ch. 9)
    python benchmarks/dc_corrected_fields.py cam [K] [ACCURACY]
        # the demo cam (configs/singh2017_cam.yaml, exponent K, default 2, at 1e-2): the
        # fields' indicated error and the CPU of the run and of the fields' correction
    python benchmarks/dc_corrected_fields.py cost [K] [ACCURACY]
        # CPU of solve_corrected on the plate (absorbing) without and with store_fields

Errors: |field - reference| / Mm (the swing) per output (tau* = D t / h^2 = 0, 0.01, 0.03,
0.1, 0.3). CPU: time.process_time, one BLAS thread (OMP_NUM_THREADS=1
OPENBLAS_NUM_THREADS=1).
"""
from __future__ import annotations

import importlib.util
import sys
import time
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

from fickcam.diffusion import Bar, CamPlate, DiffusionProblem, Diffusivity, Exposure, Sheet, solve
from fickcam.diffusion.models.analytic import exact_history_field
from fickcam.diffusion.nonfickian.corrected_product import corrected_levels, solve_corrected
from fickcam.diffusion.planform.cell_moments import gradient_matrix
from fickcam.diffusion.nonfickian.corrected_fields import (References, corrected_fields,
                                                           field_errors, planform_at)
from fickcam.diffusion.nonfickian.corrected_pieces import bar_coordinates
from fickcam.diffusion.planform.admissible import cell_areas
from fickcam.diffusion.problem.sorption import ConcentrationDependent

H, D, MM = 2e-3, 5e-12, 2.0
ISOTROPIC = Diffusivity((D, D, D), 0.0)
TIMES = np.array([0.0, 0.01, 0.03, 0.1, 0.3]) * H ** 2 / D
PLATE = CamPlate(np.array([0, 4e-3, 4e-3, 0.0]), np.array([0, 0, 3e-3, 3e-3]), H)
BAR = Bar(6e-3, 4e-3, H)


def exposure(start, surface):
    return Exposure.piecewise([0.0, TIMES[-1]], [330.0], [surface], initial_moisture=start)


def volume_mean(run, fields):
    cells = run.meshes[-1]
    volumes = np.outer(cells.z, cell_areas(cells.tess)).ravel()
    return fields @ volumes / volumes.sum()


def row(name, values):
    print(f"  {name:<34}" + " ".join(f"{v:9.2e}" for v in values), flush=True)


def fickian():
    accuracy = float(sys.argv[2]) if len(sys.argv) > 2 else 3e-2
    wet = exposure(0.0, MM)
    for part, block in ((PLATE, Bar(4e-3, 3e-3, H)), (BAR, BAR)):
        began = time.process_time()
        run = corrected_levels(part, ISOTROPIC, ConcentrationDependent(MM, exponent=0.0), wet,
                               TIMES, accuracy, store_fields=True)
        fields, errors = field_errors(run)
        coordinates = run.marched[-1].coordinates
        if isinstance(part, Bar):
            coordinates = bar_coordinates(BAR, ISOTROPIC, coordinates)
        exact = exact_history_field(block, ISOTROPIC, wet, TIMES, coordinates)
        print(f"{type(part).__name__} at {accuracy:g}: {run.meshes[-1].cells} cells, planform "
              f"reference {run.planform.grid.cells} cells, {time.process_time() - began:.1f} "
              f"CPU s; {errors}")
        row("corrected - exact", np.max(np.abs(fields - exact), axis=1) / MM)
        row("coarse cells - exact", np.max(np.abs(run.marched[-1].plate.fields - exact),
                                           axis=1) / MM)
        if not isinstance(part, Bar):
            row("volume means: corrected - exact",
                (volume_mean(run, fields) - volume_mean(run, exact)) / MM)
            row("exact's volume mean - mean", (volume_mean(run, exact) - run.results[-1][0])
                / MM)
            plate_extras(run, exact, wet)
        else:
            bar_reading(run, wet)


def plate_extras(run, exact, wet):
    """The plate's rows of ``fickian`` beyond the fields' errors (module docstring)."""
    surface = np.asarray(wet.surface_before(TIMES), float)
    g = surface[:, None]
    level, cells = run.marched[-1], run.meshes[-1]
    references = References.of(cells, run.sheet, run.planform, surface, H)
    z_centres = np.unique(level.coordinates["z"])
    sheet = exact_history_field(Sheet(H), ISOTROPIC, wet, TIMES, {"z": z_centres})
    row("sheet read at z - exact", np.max(np.abs(g - references.sheet - sheet), axis=1) / MM)
    print(f"  (the sheet's estimate {run.sheet.error_estimate:.2e})")
    weight = run.planform.coarser[1]
    combined = references.planform + weight * (references.planform - references.coarser)
    row("Richardson planform field - exact",
        np.max(np.abs(corrected_fields(level, cells, references.sheet, combined, surface)
                      - exact), axis=1) / MM)
    coarse = run.meshes[-2]
    coarse_exact = exact_history_field(Bar(4e-3, 3e-3, H), ISOTROPIC, wet, TIMES,
                                       run.marched[-2].coordinates)
    layers = (g - exact).reshape(len(TIMES), coarse.z.size, 2, -1).mean(axis=2)
    carried = planform_at(cells.tess, layers.reshape(len(TIMES) * coarse.z.size, -1),
                          coarse.tess.centres).reshape(len(TIMES), -1)
    row(f"exact U {cells.cells} -> {coarse.cells} - exact",
        np.max(np.abs(carried - (g - coarse_exact)), axis=1) / MM)


def bar_reading(run, wet):
    """The bar's planform reference read at the 3-D mesh's cell points, two ways, against
    the exact rectangle (the block's section, Crank 1975 eq. 4.51 of two sheets)."""
    surface = np.asarray(wet.surface_before(TIMES), float)
    g = surface[:, None]
    reference, points = run.planform, run.meshes[-1].tess.centres
    physical = run.meshes[-1].tess.physical(points)
    exact = exact_history_field(Bar(6e-3, 4e-3, 1.0), ISOTROPIC, wet, TIMES,
                                {"x": physical[:, 0] + 3e-3, "y": physical[:, 1] + 2e-3,
                                 "z": np.full(len(points), 0.5)})
    values = g - reference.fields
    row("planform_at - exact", np.max(np.abs(g - planform_at(reference.grid, values, points)
                                             - exact), axis=1) / MM)
    _, nearest = cKDTree(reference.grid.centres).query(points)
    gradient = (gradient_matrix(reference.grid) @ values.T).T
    offset = points - reference.grid.centres[nearest]
    read = (values[:, nearest] + gradient[:, 2 * nearest] * offset[:, 0]
            + gradient[:, 2 * nearest + 1] * offset[:, 1])
    row("nearest + gradient - exact", np.max(np.abs(g - read - exact), axis=1) / MM)
    print(f"  ({reference.grid.cells} reference cells read at {len(points)} points)")


def dc():
    k = float(sys.argv[2]) if len(sys.argv) > 2 else 2.0
    accuracy = float(sys.argv[3]) if len(sys.argv) > 3 else 3e-2
    for name, start, surface in (("absorbing", 0.0, MM), ("drying", MM, 0.0)):
        began = time.process_time()
        run = corrected_levels(PLATE, ISOTROPIC, ConcentrationDependent(MM, exponent=k),
                               exposure(start, surface), TIMES, accuracy, store_fields=True)
        fields, errors = field_errors(run)
        print(f"plate k = {k:g} {name} at {accuracy:g}: {run.meshes[-1].cells} cells, "
              f"{time.process_time() - began:.1f} CPU s; {errors}")
        mean = run.results[-1][0]
        row("volume mean corrected - mean", (volume_mean(run, fields) - mean) / MM)
        row("volume mean coarse - mean",
            (volume_mean(run, run.marched[-1].plate.fields) - mean) / MM)


def wide():
    k = float(sys.argv[2]) if len(sys.argv) > 2 else 2.0
    side = (float(sys.argv[3]) if len(sys.argv) > 3 else 8.0) * 1e-3
    margin = (float(sys.argv[4]) if len(sys.argv) > 4 else 2.5) * 1e-3
    plate = CamPlate(np.array([0, side, side, 0.0]), np.array([0, 0, side, side]), H)
    times = TIMES[:int(sys.argv[5]) if len(sys.argv) > 5 else 2]
    wet = Exposure.piecewise([0.0, times[-1]], [330.0], [MM], initial_moisture=0.0)
    law = ConcentrationDependent(MM, exponent=k)
    began = time.process_time()
    run = corrected_levels(plate, ISOTROPIC, law, wet, times, 3e-2, store_fields=True)
    fields, errors = field_errors(run)
    spent = time.process_time() - began
    sheet = solve(Sheet(H), ISOTROPIC, wet, times, accuracy=1e-3, sorption=law, model="slab",
                  store_fields=True)
    at = run.marched[-1].coordinates
    centre = ((np.minimum(at["x"], side - at["x"]) > margin)
              & (np.minimum(at["y"], side - at["y"]) > margin))
    reference = np.stack([np.interp(at["z"][centre], sheet.cell_coordinates["z"], row)
                          for row in sheet.fields])
    print(f"plate {side * 1e3:g} mm k = {k:g} absorbing at 3e-2: {run.meshes[-1].cells} cells "
          f"({centre.sum()} central), {spent:.1f} CPU s; sheet at 1e-3 estimate "
          f"{sheet.error_estimate:.1e}; {errors} (sum {errors.total:.2e})")
    row("corrected - sheet", np.max(np.abs(fields[:, centre] - reference), axis=1) / MM)
    row("coarse cells - sheet", np.max(np.abs(run.marched[-1].plate.fields[:, centre]
                                              - reference), axis=1) / MM)


def cam():
    k = float(sys.argv[2]) if len(sys.argv) > 2 else 2.0
    accuracy = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-2
    spec = importlib.util.spec_from_file_location(
        "dc_defect_correction", Path(__file__).with_name("dc_defect_correction.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    geometry, diffusivity, wet, times, law = module.demo_cam(k)
    began = time.process_time()
    run = corrected_levels(geometry, diffusivity, law, wet, times, accuracy, store_fields=True)
    marched = time.process_time()
    fields, errors = field_errors(run)
    print(f"demo cam k = {k:g} at {accuracy:g}: {[m.cells for m in run.meshes]} cells, planform "
          f"reference {run.planform.grid.cells} cells, {len(times)} outputs; run "
          f"{marched - began:.1f} CPU s, fields {time.process_time() - marched:.2f} CPU s; "
          f"{errors}", flush=True)


def cost():
    k = float(sys.argv[2]) if len(sys.argv) > 2 else 2.0
    accuracy = float(sys.argv[3]) if len(sys.argv) > 3 else 3e-2
    for store in (False, True):
        began = time.process_time()
        result = solve_corrected(DiffusionProblem(
            PLATE, ISOTROPIC, exposure(0.0, MM), TIMES, accuracy, store_fields=store,
            sorption=ConcentrationDependent(MM, exponent=k)))
        print(f"plate k = {k:g} at {accuracy:g} store_fields={store}: "
              f"{time.process_time() - began:.1f} CPU s, {result.cells} cells; "
              f"{result.reason.split('; measured: ')[-1]}", flush=True)


if __name__ == "__main__":
    commands = {"fickian": fickian, "dc": dc, "wide": wide, "cam": cam, "cost": cost}
    if len(sys.argv) < 2 or sys.argv[1] not in commands:
        sys.exit(f"usage: {sys.argv[0]} {' | '.join(commands)}")
    commands[sys.argv[1]]()
