"""Concentration-dependent D on cam plates: the corrected product (``diffusion/nonfickian/corrected_product.py``)
against independent references, and the measurement that dropped the Fickian D_ref
correction.

    python benchmarks/dc_defect_correction.py plate-reference [K [absorption|desorption]]
                                   # tests/data/dc_plate_reference.json (K = 2), _k3.json (3)
    python benchmarks/dc_defect_correction.py plate              # auto against them
    python benchmarks/dc_defect_correction.py plate-order [K [absorption|desorption]]
                                                  # the 3-D plans' order (exponent K, 2)
    python benchmarks/dc_defect_correction.py skin-margin [M ...] # drying: estimate / error
    python benchmarks/dc_defect_correction.py demo-cam           # the validation table
    python benchmarks/dc_defect_correction.py fickian-reference  # why not Fick at Crank's mean D
    python benchmarks/dc_defect_correction.py planform-sequence [K [A]]  # 1x-8x planforms
    python benchmarks/dc_defect_correction.py soak-dry           # wetted, then dried: plans, CPU
    python benchmarks/dc_defect_correction.py march-cost         # CPU of one swept march pair
    python benchmarks/dc_defect_correction.py soak-dry-solid K A # auto at 0.1 vs solid at A
    python benchmarks/dc_defect_correction.py nested CASE A[@B] [PZ ...]  # nested meshes
    python benchmarks/dc_defect_correction.py corrected CASE A[@B]  # one corrected run
    python benchmarks/dc_defect_correction.py cross CASE A       # the cross vs the 8x mesh

``plate-reference``: the 4 x 3 x 2 mm plate of the tests (D = 5e-12 m^2/s exp(2 c/Mm),
Mm = 2 %, absorption 0 -> Mm and desorption Mm -> 0) by the 3-D cells alone (``model:
solid``, FiPy prisms on half the thickness) at ``REFERENCE_ACCURACY``: a brute-force run,
once, with its own estimate stored beside it; ``plate-reference 3 desorption``: the same
drying with k = 3 (tests/data/dc_plate_reference_k3.json, 297 CPU s). ``demo-cam``: configs/singh2017_cam.yaml
with ``exponent`` k = 0, 1, 2 at accuracies 1e-2, 3e-3, 1e-3: cells, CPU s, estimate;
k = 0 against the Fickian plane model at 1e-5 (the exact reference), k = 1, 2 against the
corrected run at 1e-3 (self-consistency) and the 3-D cells alone at ``CAM_SOLID``.
``plate-order``: the same plate, the corrected result (``corrected_product.corrected_levels``, one
sheet and one planform reference for all) on the 3-D plans of ``ORDER_LEVELS``: the
changes between successive plans, their observed order in the finest cell width w0, and
each plan's error against the stored brute-force runs; the 3-D cells alone beside it.
``skin-margin``: the drying plates' estimate / error for several ``SKIN_ESTIMATE_MARGIN``.
``fickian-reference``: the demo cam's z widths as a 1-D slab, the D(c) sheet and the
Fickian sheet at Crank's weighted-mean D (1975 §9.3) against fine references.
``soak-dry``: the plate wetted to Mm for 1.5 h^2/D, then dried (``SOAK_DRY_TAU`` outputs,
the first at 1e-3 h^2/D), k = 3 and 5: the cells of the first two nested 3-D meshes,
then ``auto`` at 0.1 (CPU s, cells, estimate and its parts) against ``auto`` at 0.03
(self-consistency).
``soak-dry-solid K A``: the same case with exponent K, ``auto`` at 0.1 against the 3-D cells
alone (``model: solid``) at accuracy A, an independent march (CPU s, cells, estimates).
``march-cost``: the Richardson pair of swept marches (``corrected_product.SharedInputs.run``) on the plate's
z widths as a sheet and on its coarse 3-D plan, k = 5, wetted to Mm then stepped down to
0.4 Mm at 0.15 h^2/D (outputs 0.02-0.3 h^2/D): CPU s and the results (to compare two
versions, run it with each one's PYTHONPATH).
``nested CASE A[@B] [PZ ...]``: CASE is cam-K (the demo cam, exponent K), plate-K-absorption,
plate-K-desorption, soak-K or bar-K-absorption / bar-K-desorption (``dc_bar.py``'s 6 x 4 x 2 mm
bar, its layer the six faces'); the corrected result (sheet and planform references of a run
at accuracy A) on the 3-D mesh of the ``corrected_product.base_plan`` plan (or the plan of accuracy
B) with its planform refined P times and its z widths Z times (``corrected_product.PrismCells.refined``'s
two halves apart; default 00 01 10 11 02): cells, CPU s, the distances between all of
them (``corrected_product.gap``), and the ratios of successive changes along z (00 01 02 ...), the
planform (00 10 20) and both (00 11 22).
``cross CASE A`` (CASE also small-K-DIRECTION: the tests' 3 x 2 x 2 mm plate, outputs to
0.1 h^2/D): the three diagonal nested meshes, and the ``corrected_product.cross`` around the second
(``CorrectedMeshes.finer`` where the third passes the cap): the combination against the third.
``corrected CASE A[@B]``: ``corrected_product.solve_corrected`` (what ``auto`` runs; B: on the nested
pair of the plan of accuracy B): CPU s, cells, the estimate and its parts; a plate against
its stored 3-D run (``plate``'s norm).
CPU time: time.process_time, one BLAS thread (set OPENBLAS_NUM_THREADS=1).
"""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np
import yaml

from fickcam.diffusion import DiffusionProblem

ROOT = Path(__file__).resolve().parents[1]
REFERENCE = ROOT / "tests" / "data" / "dc_plate_reference.json"
REFERENCE_ACCURACY = {"absorption": 1e-2, "desorption": 3e-2}  # desorption: 106 CPU s already
CAM_SOLID = 1e-2
H, D, MM = 2e-3, 5e-12, 2.0
TAU = [0.0, 0.01, 0.03, 0.1, 0.3]
ORDER_LEVELS = (1.0, 0.5, 0.25, 0.125)   # plan accuracies of ``plate-order``
GRADED_PAIR = (1.0, 0.5)   # the two graded 3-D plans of the corrected path before nesting
ORDER_ACCURACY = 1e-2   # ``plate-order``'s sheet reference and steps: those of ``plate`` at 1e-2


def plate_case(direction: str, exponent: float = 2.0, size=(4e-3, 3e-3), outputs=None):
    from fickcam.diffusion import CamPlate, Diffusivity, Exposure
    from fickcam.diffusion.problem.sorption import ConcentrationDependent

    times = np.array(TAU[:outputs]) * H ** 2 / D
    start, surface = (0.0, MM) if direction == "absorption" else (MM, 0.0)
    exposure = Exposure.piecewise([0.0, TAU[-1] * H ** 2 / D], [330.0], [surface],
                                  initial_moisture=start)
    a, b = size
    plate = CamPlate(np.array([0, a, a, 0.0]), np.array([0, 0, b, b]), H)
    law = ConcentrationDependent(MM, exponent=exponent)
    return plate, Diffusivity((D, D, D), 0.0), exposure, times, law


SOAK_DRY_TAU = [1e-3, 1e-2, 0.1, 0.5, 1.0, 1.6, 2.0, 3.0]


def soak_dry_case(k: float):
    """(plate, diffusivity, exposure, times, law): wetted to Mm for 1.5 h^2/D, then dried."""
    from fickcam.diffusion import CamPlate, Diffusivity, Exposure
    from fickcam.diffusion.problem.sorption import ConcentrationDependent

    tau = H ** 2 / D
    exposure = Exposure.piecewise([0.0, 1.5 * tau, 3.0 * tau], [330.0, 330.0], [MM, 0.0])
    plate = CamPlate(np.array([0, 4e-3, 4e-3, 0.0]), np.array([0, 0, 3e-3, 3e-3]), H)
    return (plate, Diffusivity((D, D, D), 0.0), exposure, np.array(SOAK_DRY_TAU) * tau,
            ConcentrationDependent(MM, exponent=k))


def soak_dry(exponents=(3.0, 5.0), accuracy=0.1, reference_accuracy=0.03) -> None:
    """``reference_accuracy`` None: no reference run (e.g. to time an older fickcam, run
    with its PYTHONPATH: soak_dry((3.0,), 0.1, None))."""
    from fickcam.diffusion import solve
    from fickcam.diffusion.nonfickian.corrected_product import base_plan
    from fickcam.diffusion.nonfickian.corrected_pieces import PrismCells, SharedInputs, level_plan, steps_for

    for k in exponents:
        plate, d, exposure, times, law = soak_dry_case(k)
        level, chosen = base_plan(lambda a: level_plan(plate, d, law, exposure, times, a,
                                                       steps_for(accuracy)), accuracy)
        cells = PrismCells.of(plate, SharedInputs.of(DiffusionProblem(plate, d, exposure, times, sorption=law), plate, d, 4).d, chosen)
        print(f"k {k:g}, 3-D plan {level:g}: {cells.cells} cells, 2x {cells.refined().cells}, "
              f"w0 {chosen.finest:.3g}, growth {chosen.growth:.3g}", flush=True)
        runs = []
        for a in (accuracy, reference_accuracy)[:2 if reference_accuracy else 1]:
            start = time.process_time()
            result = solve(plate, d, exposure, times, accuracy=a, sorption=law)
            runs.append(result)
            print(f"k {k:g}, accuracy {a:g}: {time.process_time() - start:.1f} CPU s, "
                  f"{result.cells} cells, estimate {result.error_estimate:.2e} "
                  f"({result.reason.split('measured: ')[-1]})", flush=True)
        if not reference_accuracy:
            continue
        mean = np.max(np.abs(runs[0].mean - runs[1].mean)) / MM
        layer = np.max(np.abs(runs[0].surface - runs[1].surface)) / MM
        print(f"k {k:g}: {accuracy:g} vs {reference_accuracy:g}: mean {mean:.2e}, "
              f"layer {layer:.2e}", flush=True)


def soak_dry_solid(exponent: str, reference_accuracy: str) -> None:
    from fickcam.diffusion import solve

    k, reference_accuracy = float(exponent), float(reference_accuracy)
    plate, d, exposure, times, law = soak_dry_case(k)
    runs = []
    for model, accuracy in (("auto", 0.1), ("solid", reference_accuracy)):
        start = time.process_time()
        runs.append(solve(plate, d, exposure, times, accuracy=accuracy, model=model,
                          sorption=law))
        print(f"k {k:g}, {model} at {accuracy:g}: {time.process_time() - start:.1f} CPU s, "
              f"{runs[-1].cells} cells, estimate {runs[-1].error_estimate:.2e}", flush=True)
    mean = np.abs(runs[0].mean - runs[1].mean) / MM
    layer = np.abs(runs[0].surface - runs[1].surface) / MM
    print(f"k {k:g}: |auto - solid| / Mm at tau {SOAK_DRY_TAU}: mean {np.round(mean, 5)}, "
          f"layer {np.round(layer, 5)}; largest {mean.max():.2e}, {layer.max():.2e}")


def march_cost() -> None:
    from fickcam.diffusion import CamPlate, Diffusivity, Exposure
    from fickcam.diffusion.operators import sizing
    from fickcam.diffusion.nonfickian.corrected_pieces import SharedInputs, half_slab, level_plan
    from fickcam.diffusion.operators.symmetry_cuts import half, mirrored
    from fickcam.diffusion.problem.sorption import ConcentrationDependent

    times = np.array([0.02, 0.1, 0.2, 0.3]) * H ** 2 / D
    exposure = Exposure.piecewise([0.0, 0.5 * times[-1], times[-1]], [330.0, 330.0],
                                  [MM, 0.4 * MM])
    plate = CamPlate(np.array([0, 4e-3, 4e-3, 0.0]), np.array([0, 0, 3e-3, 3e-3]), H)
    law, d = ConcentrationDependent(MM, exponent=5.0), Diffusivity((D, D, D), 0.0)
    setting = SharedInputs.of(DiffusionProblem(plate, d, exposure, times, sorption=law), plate, d,
                              4)
    chosen = level_plan(plate, d, law, exposure, times, 1.0, 4)
    for name, disc in (("sheet", half_slab(half(sizing.prism_widths(0.07, 0.229)))),
                       ("3-D", mirrored(plate, setting.d, chosen.cells_per_axis, chosen.finest,
                                        chosen.growth, 5e-4))):
        start = time.process_time()
        pair = setting.run(disc)
        print(f"{name}: {disc.cells} cells, {pair.steps} steps, "
              f"{time.process_time() - start:.2f} CPU s, mean {np.round(pair.mean, 12)}",
              flush=True)


def reference_file(exponent: float) -> Path:
    """The stored brute-force runs of exponent k (k = 2: the tests' main file)."""
    return REFERENCE if exponent == 2.0 else REFERENCE.with_name(
        f"dc_plate_reference_k{exponent:g}.json")


def plate_reference(exponent: str = "2", *directions: str) -> None:
    from fickcam.diffusion import solve

    k = float(exponent)
    out = {"tau": TAU, "exponent": k, "mm": MM,
           "made_by": "benchmarks/dc_defect_correction.py plate-reference "
                      + " ".join([exponent, *directions])}
    for direction in directions or ("absorption", "desorption"):
        plate, d, exposure, times, law = plate_case(direction, k)
        start = time.process_time()
        result = solve(plate, d, exposure, times, accuracy=REFERENCE_ACCURACY[direction],
                       model="solid", sorption=law)
        out[direction] = {"accuracy": REFERENCE_ACCURACY[direction],
                          "mean": result.mean.tolist(), "layer": result.surface.tolist(),
                          "estimate": result.error_estimate, "cells": result.cells,
                          "cpu_s": time.process_time() - start}
        print(direction, out[direction], flush=True)
    reference_file(k).write_text(json.dumps(out, indent=1) + "\n")


def plate_record() -> None:
    """``auto`` (the corrected product) on the plate against the stored brute-force runs
    (k = 2 both ways, k = 3 drying), in ``corrected_product.gap``'s norm (the layer / 4) beside."""
    from fickcam.diffusion import solve
    from fickcam.diffusion.nonfickian.corrected_product import gap

    for k, direction in ((2.0, "absorption"), (2.0, "desorption"), (3.0, "desorption")):
        plate, d, exposure, times, law = plate_case(direction, k)
        reference = json.loads(reference_file(k).read_text())[direction]
        truth = (np.asarray(reference["mean"]), np.asarray(reference["layer"]))
        for accuracy in (3e-2, 1e-2):
            start = time.process_time()
            result = solve(plate, d, exposure, times, accuracy=accuracy, sorption=law)
            cpu = time.process_time() - start
            mean = np.max(np.abs(result.mean - reference["mean"])) / MM
            layer = np.max(np.abs(result.surface - reference["layer"])) / MM
            error = gap((result.mean, result.surface), truth, MM)
            print(f"| {k:g} | {direction} | {accuracy:g} | {result.error_estimate:.1e} | "
                  f"{mean:.1e} | {layer:.1e} | {result.error_estimate / error:.1f} | "
                  f"{result.cells} | {cpu:.1f} |", flush=True)


def skin_margins(*margins: str) -> None:
    """The drying plates (k = 2, 3) at accuracy 1e-2 with ``corrected_product.SKIN_ESTIMATE_MARGIN`` set
    to each of ``margins`` (default 0, 1, 4): the estimate / the distance to the stored run."""
    from fickcam.diffusion.nonfickian import corrected_product

    kept = corrected_product.SKIN_ESTIMATE_MARGIN
    try:
        for margin in [float(m) for m in margins or ("0", "1", "4")]:
            corrected_product.SKIN_ESTIMATE_MARGIN = margin
            for k in (2.0, 3.0):
                plate, d, exposure, times, law = plate_case("desorption", k)
                stored = json.loads(reference_file(k).read_text())["desorption"]
                result = corrected_product.solve_corrected(
                    DiffusionProblem(plate, d, exposure, times, 1e-2, sorption=law))
                error = corrected_product.gap((result.mean, result.surface),
                                   (np.asarray(stored["mean"]), np.asarray(stored["layer"])), MM)
                print(f"| {margin:g} | {k:g} | {result.error_estimate:.2e} | {error:.2e} | "
                      f"{result.error_estimate / error:.2f} |", flush=True)
    finally:
        corrected_product.SKIN_ESTIMATE_MARGIN = kept


def plate_order(exponent: str = "2", *directions: str) -> None:
    """The corrected plate on the plans of ``ORDER_LEVELS`` (module docstring), D = D(T)
    exp(k c/Mm) with k = ``exponent``: per output, of the swing, each plan's error against
    the stored runs (k = 2 only; theirs: their estimate), the changes d_i between successive
    plans and p_i = log(|d_i| / |d_i+1|) / log(w0_i / w0_i+1); the same for the 3-D cells
    alone ("3-D"). Then, in ``corrected_product.gap``'s norm (largest over the outputs, the layer / 4),
    the change between the 1 and 0.5 plans (``GRADED_PAIR``: the two meshes whose change
    ``solve_corrected`` multiplied by 2.4 before the nested meshes) beside the finer plan's
    distance to the finest plan (its unseparated error, less the finest plan's own) and to
    the stored run."""
    from fickcam.diffusion.nonfickian.corrected_product import corrected_levels, gap

    stored = json.loads(REFERENCE.read_text())
    k = float(exponent)
    for direction in directions or ("absorption", "desorption"):
        plate, d, exposure, times, law = plate_case(direction, k)
        start = time.process_time()
        run = corrected_levels(DiffusionProblem(plate, d, exposure, times, ORDER_ACCURACY,
                                                sorption=law), plans=ORDER_LEVELS)
        widths = np.array([m.plan.finest for m in run.marched])
        known = k == stored["exponent"]
        print(f"## k = {k:g}, {direction}, accuracy {ORDER_ACCURACY:g}: "
              f"{time.process_time() - start:.1f} CPU s; plans {ORDER_LEVELS}, cells "
              f"{[m.cells for m in run.marched]}, (planform, z) cells "
              f"{[m.plan.cells_per_axis for m in run.marched]}, w0 "
              f"{np.round(widths, 4).tolist()}, growth {[m.plan.growth for m in run.marched]}; "
              f"sheet est. {run.sheet.error_estimate:.1e}, planform x{run.factor:g} est. "
              f"{run.planform_error:.1e}" + (f"; stored run's est. "
                                            f"{stored[direction]['estimate']:.1e}" if known else ""),
              flush=True)
        for index, quantity in ((0, "mean"), (1, "layer")):
            corrected = np.array([r[index] for r in run.results]) / MM
            alone = np.array([(m.plate.mean, m.plate.layer)[index] for m in run.marched]) / MM
            truth = (np.asarray(stored[direction][quantity]) / MM if known
                     else np.full(len(TAU), np.nan))
            for label, values in (("corrected", corrected), ("3-D", alone)):
                order_table(f"{direction} {quantity} {label}", values, truth, widths)
        coarse, fine = (run.results[ORDER_LEVELS.index(a)] for a in GRADED_PAIR)
        change = gap(coarse, fine, MM)
        line = (f"gap norm: change {GRADED_PAIR} {change:.2e}; plan {GRADED_PAIR[-1]:g} to plan "
                f"{ORDER_LEVELS[-1]:g} {gap(fine, run.results[-1], MM):.2e} "
                f"(x{gap(fine, run.results[-1], MM) / change:.2f} the change)")
        if known:
            truth = (np.asarray(stored[direction]["mean"]), np.asarray(stored[direction]["layer"]))
            line += (f"; to the stored run: plan {GRADED_PAIR[-1]:g} {gap(fine, truth, MM):.2e} "
                     f"(x{gap(fine, truth, MM) / change:.2f}), plan {ORDER_LEVELS[-1]:g} "
                     f"{gap(run.results[-1], truth, MM):.2e}")
        print(line, flush=True)


def order_table(title: str, values: np.ndarray, truth: np.ndarray, widths: np.ndarray) -> None:
    """Rows per output time (tau*): errors of each plan, changes, observed orders."""
    changes = values[:-1] - values[1:]
    print(f"### {title}\n| tau* | " + " | ".join(f"err {a:g}" for a in ORDER_LEVELS)
          + " | " + " | ".join(f"d{i + 1}" for i in range(changes.shape[0])) + " | "
          + " | ".join(f"p{i + 1}" for i in range(changes.shape[0] - 1)) + " |")
    ratios = np.log(widths[:-1] / widths[1:])
    for j, tau in enumerate(TAU):
        if tau == 0.0:
            continue
        orders = [np.log(abs(changes[i, j]) / abs(changes[i + 1, j])) / ratios[i]
                  if changes[i + 1, j] != 0.0 else np.nan for i in range(changes.shape[0] - 1)]
        print(f"| {tau:g} | " + " | ".join(f"{v:+.2e}" for v in values[:, j] - truth[j])
              + " | " + " | ".join(f"{v:+.2e}" for v in changes[:, j]) + " | "
              + " | ".join(f"{v:.2f}" for v in orders) + " |", flush=True)


def demo_cam(k: float):
    """(geometry, diffusivity, exposure, times, law) of the cam of configs/singh2017_cam.yaml
    with ``sorption: {model: concentration_dependent, exponent: k}``."""
    from fickcam.scene.load import load_scene
    from fickcam.simulation.times import ageing_times

    raw = yaml.safe_load((ROOT / "configs" / "singh2017_cam.yaml").read_text())
    raw["materials"]["cfrp"]["sorption"] = {"model": "concentration_dependent", "exponent": k}
    scene = load_scene(raw)
    environment = scene.environment
    part = next(p for p in scene.parts if p.name == "cam")
    return (part.geometry, part.material.diffusivity_for(part.geometry),
            environment.exposure(part.material.saturation_moisture),
            ageing_times(scene, environment), part.material.sorption_law())


def cam_table(exponents=(0.0, 1.0, 2.0), accuracies=(1e-2, 3e-3, 1e-3)) -> None:
    from fickcam.diffusion import solve
    from fickcam.diffusion.nonfickian.corrected_product import solve_corrected

    for k in exponents:
        geometry, d, exposure, times, law = demo_cam(k)
        swing = float(exposure.surface_moisture(times[-1:])[0] - exposure.initial_moisture)
        if k == 0:
            exact = solve(geometry, d, exposure, times, accuracy=1e-5, model="plane")
            reference, label = (exact.mean, exact.surface), "plane 1e-5"
        else:
            fine = solve_corrected(DiffusionProblem(geometry, d, exposure, times, 1e-3,
                                                    sorption=law))
            reference, label = (fine.mean, fine.surface), "corrected 1e-3"
        for accuracy in accuracies:
            start = time.process_time()
            result = solve_corrected(DiffusionProblem(geometry, d, exposure, times, accuracy,
                                                      sorption=law))
            cpu = time.process_time() - start
            mean = np.max(np.abs(result.mean - reference[0])) / swing
            layer = np.max(np.abs(result.surface - reference[1])) / swing
            print(f"| {k:g} | {accuracy:g} | {result.error_estimate:.1e} | {mean:.1e} | "
                  f"{layer:.1e} | {label} | {result.cells} | {cpu:.1f} |", flush=True)


def planform_sequence(exponent: str = "2", accuracy: str = "1e-3") -> None:
    """The demo cam's D(c) planform on the finer 3-D plan refined 1x, 2x, 4x and 8x (the 8x
    past ``PLANFORM_CELLS``): each quantity's changes, their ratios rho, ``three_levels``'
    choice and estimate on the first three against the 8x mesh (relative to the swing; the
    layer / ``LAYER_TOLERANCE``)."""
    from fickcam.diffusion.nonfickian import corrected_product
    from fickcam.diffusion.problem.exposure import swing
    from fickcam.diffusion.accuracy.grid_convergence import three_levels
    from fickcam.diffusion.accuracy.budget import LAYER_TOLERANCE

    k, accuracy = float(exponent), float(accuracy)
    geometry, d, exposure, times, law = demo_cam(k)
    problem = DiffusionProblem(geometry, d, exposure, times, accuracy, part="cam", sorption=law)
    setting = corrected_product.SharedInputs.of(problem, geometry, d,
                                                corrected_product.steps_for(accuracy))
    sheet = corrected_product.sheet_reference(problem, geometry, d)
    chosen = corrected_product.level_plan(geometry, d, law, exposure, times, corrected_product.MESH_LEVELS[-1],
                               setting.per_doubling)
    level = corrected_product.three_d(setting, chosen, False)
    surface = np.asarray(exposure.surface_before(times), float)
    scale = swing(exposure, times)
    through = (level.slab, corrected_product.CombinedMarch(sheet.mean, sheet.surface))
    results = {1.0: corrected_product.corrected(level.plate, through, (level.planform, level.moments),
                                     surface)}
    for refine in (2.0, 4.0, 8.0):
        start = time.process_time()
        _, fine, cells = setting.planform(chosen.finest / refine, chosen.growth / refine)
        results[refine] = corrected_product.corrected(level.plate, through, (level.planform, fine),
                                           surface)
        print(f"planform x{refine:g}: {cells} cells, {time.process_time() - start:.1f} CPU s",
              flush=True)
    for index, name, divisor in ((0, "mean", 1.0), (1, "layer", LAYER_TOLERANCE)):
        coarse, middle, fine, finest = (results[r][index] for r in (1.0, 2.0, 4.0, 8.0))
        extrapolate, estimate = three_levels(coarse, middle, fine)
        taken = fine + (fine - middle) / 3.0 if extrapolate else fine
        with np.errstate(divide="ignore", invalid="ignore"):
            rho = (middle - coarse) / (fine - middle)
        print(f"{name}: rho {np.round(rho, 2)}, extrapolated {extrapolate}, estimate "
              f"{estimate / divisor / scale:.2e}, |taken - x8| "
              f"{np.max(np.abs(taken - finest)) / divisor / scale:.2e}, |x4 - x8| "
              f"{np.max(np.abs(fine - finest)) / divisor / scale:.2e}, |x4 extrapolated - x8| "
              f"{np.max(np.abs(fine + (fine - middle) / 3.0 - finest)) / divisor / scale:.2e}")


def slab(widths):
    from fickcam.diffusion.nonfickian.corrected_pieces import half_slab
    return half_slab(np.asarray(widths, float))


def fickian_reference() -> None:
    """The 1-D measurement of the module docstring of ``defect``."""
    from fickcam.diffusion.nonfickian.corrected_pieces import SharedInputs, level_plan
    from fickcam.diffusion.operators.sizing import prism_widths
    from fickcam.diffusion.operators.symmetry_cuts import half
    from fickcam.diffusion.nonfickian.concentration_dependent import wettest

    geometry, d, exposure, times, law = demo_cam(2.0)
    mm = float(exposure.surface_moisture(times[-1:])[0])
    factor = crank_mean_factor(law, 0.0, mm)
    top = law.largest_factor(wettest(exposure, times))
    setting = SharedInputs.of(DiffusionProblem(geometry, d, exposure, times, sorption=law),
                              geometry, d, 4)
    constant = Constant(factor)
    fine = np.full(1000, 0.5 / 1000)
    tau = setting.scales.tau_star(np.asarray(times, float))
    u_ref = setting.run(slab(fine)).mean
    v_ref = mm * sheet_uptake_series(factor / top * tau)
    print(f"Crank's weighted-mean D / D(T) = {factor:.3f} (top {top:.3f})")
    for accuracy in (0.3, 0.1, 0.03):
        chosen = level_plan(geometry, d, law, exposure, times, accuracy, 4)
        widths = half(prism_widths(chosen.finest, chosen.growth))
        u = setting.run(slab(widths)).mean
        v = replace_law(setting, constant).run(slab(widths)).mean
        print(f"plan {accuracy:g}, {widths.size} z cells: D(c) {np.round((u - u_ref) / mm, 5)}, "
              f"Fick D_ref {np.round((v - v_ref) / mm, 5)}, difference "
              f"{np.round((u - v - u_ref + v_ref) / mm, 5)}")


class Constant:
    """D / D(T) one number (the linear Fickian problem at D_ref)."""

    def __init__(self, value):
        self.value = value

    def factor(self, moisture):
        return np.full(np.shape(moisture), self.value)

    def mean_factor(self, low, high):
        return np.full(np.broadcast(low, high).shape, self.value)

    def largest_factor(self, moisture):
        return self.value


def replace_law(setting, law):
    from dataclasses import replace
    return replace(setting, law=law)


def crank_mean_factor(law, start: float, end: float) -> float:
    """Crank 1975 §9.3 weighted-mean D / D(T): absorption (5/3) ∫ s^(2/3) f ds over the
    swing fraction s (wet side weighted)."""
    s = np.linspace(0.0, 1.0, 2001)
    weight = 5.0 / 3.0 * s ** (2.0 / 3.0)
    return float(np.trapezoid(weight * law.factor(start + s * (end - start)), s))


def sheet_uptake_series(tau):
    """Crank 1975 eq. 4.18, fraction of the sheet's uptake at D t / h^2 = tau (thickness h)."""
    n = np.arange(400)
    rates = (2 * n + 1) ** 2 * np.pi ** 2
    return 1.0 - np.sum(8.0 / rates[:, None] * np.exp(-np.outer(rates, tau)), axis=0)


def named_case(case: str):
    """(geometry, diffusivity, exposure, times, law) of cam-K, plate-K-DIRECTION, soak-K or
    bar-K-DIRECTION (``dc_bar.py``'s 6 x 4 x 2 mm bar)."""
    kind, exponent, *direction = case.split("-")
    if kind == "bar":
        from dc_bar import SMALL, case as bar_case   # benchmarks/ (the script's directory)
        bar, d, exposure, times, law, _, _ = bar_case(SMALL, direction[0], float(exponent))
        return bar, d, exposure, times, law
    if kind == "cam":
        return demo_cam(float(exponent))
    if kind == "small":   # tests/test_sorption_corrected.py's nested_plate: 3 x 2 x 2 mm
        return plate_case(direction[0], float(exponent), (3e-3, 2e-3), 4)
    if kind == "soak":
        plate, d, exposure, times, law = soak_dry_case(float(exponent))
        return plate, d, exposure, times, law
    return plate_case(direction[0], float(exponent))


def nested(case: str, accuracy: str, *meshes: str) -> None:
    from fickcam.diffusion.nonfickian import corrected_product
    from fickcam.diffusion.planform.admissible import refine

    geometry, d, exposure, times, law = named_case(case)
    accuracy, _, base = accuracy.partition("@")
    start = time.process_time()
    run = corrected_product.corrected_levels(
        DiffusionProblem(geometry, d, exposure, times, float(accuracy), sorption=law), 1,
        plans=(float(base),) if base else None)
    print(f"{case} at {accuracy}: references {time.process_time() - start:.1f} CPU s, sheet "
          f"est. {run.sheet.error_estimate:.1e}, planform x{run.factor:g} est. "
          f"{run.planform_error:.1e}", flush=True)
    reference = corrected_product.CombinedMarch(run.sheet.mean, run.sheet.surface)
    results = {}
    for spec in meshes or ("00", "01", "10", "11", "02"):
        cells = run.meshes[0]
        tess, z = cells.tess, cells.z
        for _ in range(int(spec[0])):
            tess = refine(tess)
        for _ in range(int(spec[1])):
            z = np.repeat(0.5 * z, 2)
        start = time.process_time()
        level = corrected_product.three_d(run.setting, run.marched[0].plan, False, corrected_product.PrismCells(tess, z))
        results[spec] = corrected_product.corrected(level.plate, (level.slab, reference),
                                         (level.planform, run.planform),
                                         corrected_product.surface_of(run.setting), level.union)
        print(f"{spec}: {level.cells} cells ({tess.cells} x {z.size}), "
              f"{time.process_time() - start:.1f} CPU s", flush=True)
    print("| | " + " | ".join(results) + " |")
    for a in results:
        print(f"| {a} | " + " | ".join(f"{corrected_product.gap(results[a], results[b], run.scale):.2e}"
                                       for b in results) + " |")
    for path in (("00", "01", "02", "03"), ("00", "10", "20"), ("00", "11", "22")):
        path = [m for m in path if m in results]
        changes = [np.asarray(results[b]) - np.asarray(results[a])
                   for a, b in zip(path, path[1:])]
        for i in range(len(changes) - 1):
            with np.errstate(divide="ignore", invalid="ignore"):
                rho = changes[i] / changes[i + 1]
            print(f"{path[i]}-{path[i + 1]}-{path[i + 2]}: rho mean {np.round(rho[0], 2)}, "
                  f"layer {np.round(rho[1], 2)}; three_levels: "
                  f"{[three_levels_of(results, path[i:i + 3], q, run.scale) for q in (0, 1)]}")


def three_levels_of(results, path, quantity, scale):
    from fickcam.diffusion.accuracy.grid_convergence import three_levels
    from fickcam.diffusion.accuracy.budget import LAYER_TOLERANCE

    extrapolate, error = three_levels(*(np.asarray(results[m][quantity]) for m in path))
    return extrapolate, float(f"{error / scale / (LAYER_TOLERANCE if quantity else 1.0):.2e}")


def cross_run(case: str, accuracy: str) -> None:
    """The ``corrected_product.cross`` around the 2 x nested mesh (``CorrectedMeshes.finer`` with the diagonal's
    third mesh taken as past the cap) against that third mesh: distances (``corrected_product.gap``)
    and the estimates of two meshes, of the three diagonal ones and of the combination."""
    from dataclasses import replace

    from fickcam.diffusion.nonfickian import corrected_product

    geometry, d, exposure, times, law = named_case(case)
    start = time.process_time()
    run = corrected_product.corrected_levels(
        DiffusionProblem(geometry, d, exposure, times, float(accuracy), sorption=law), 3)
    middle = time.process_time()
    two = replace(run, results=run.results[:2], marched=run.marched[:2], meshes=run.meshes[:2])
    # the diagonal's third mesh taken as past the cap: the cross comes next
    caps = corrected_product.MeshCaps(nested=4 * run.meshes[1].cells, cross=2 * run.meshes[1].cells)
    crossed = two.finer(caps=caps)
    end, scale, r = time.process_time(), run.scale, dict(zip(crossed.keys, crossed.results))
    (two_v, two_e), (three_v, three_e), (cross_v, cross_e) = (
        corrected_product.unseparated(levels, 1.0) for levels in (two, run, crossed))
    raw = tuple(r[1, 1][i] + r[0, 2][i] - r[0, 1][i] + r[2, 0][i] - r[1, 0][i] for i in range(2))
    print(f"{case} at {accuracy}: diagonal {[m.cells for m in run.meshes]} cells "
          f"{middle - start:.1f} CPU s; cross {[m.cells for m in crossed.meshes]} "
          f"{end - middle:.1f} CPU s\nestimates: two meshes {two_e:.2e}, three {three_e:.2e}, "
          f"cross {cross_e:.2e}\n|combination - R22| {corrected_product.gap(raw, run.results[2], scale):.2e}"
          f", |R11 - R22| {corrected_product.gap(r[1, 1], run.results[2], scale):.2e}, |cross value - "
          f"three-mesh value| {corrected_product.gap(cross_v, three_v, scale):.2e}", flush=True)


def corrected_run(case: str, accuracy: str) -> None:
    """``corrected CASE A[@B]``: B forces the coarsest nested plan's accuracy (as is, even
    with one z width: ``corrected_product.base_level`` and ``MIN_Z_WIDTHS`` set for the run)."""
    from fickcam.diffusion.nonfickian import corrected_product
    from fickcam.diffusion.nonfickian.corrected_product import gap, solve_corrected

    geometry, d, exposure, times, law = named_case(case)
    accuracy, _, base = accuracy.partition("@")
    kept = corrected_product.base_level, corrected_product.MIN_Z_WIDTHS
    if base:
        corrected_product.base_level, corrected_product.MIN_Z_WIDTHS = (lambda a: float(base)), 1
    start = time.process_time()
    try:
        result = solve_corrected(DiffusionProblem(geometry, d, exposure, times, float(accuracy),
                                                  sorption=law))
    finally:
        corrected_product.base_level, corrected_product.MIN_Z_WIDTHS = kept
    line = (f"{case} at {accuracy}: {time.process_time() - start:.1f} CPU s, {result.cells} "
            f"cells, estimate {result.error_estimate:.2e} "
            f"({result.reason.split('measured: ')[-1]})")
    if case.startswith("plate"):
        k, direction = float(case.split("-")[1]), case.split("-")[2]
        stored = json.loads(reference_file(k).read_text())[direction]
        error = gap((result.mean, result.surface),
                    (np.asarray(stored["mean"]), np.asarray(stored["layer"])), MM)
        line += f"; to the stored 3-D run (est. {stored['estimate']:.1e}): {error:.2e}"
    print(line, flush=True)


if __name__ == "__main__":
    {"plate-reference": plate_reference, "plate": plate_record, "plate-order": plate_order,
     "skin-margin": skin_margins, "demo-cam": cam_table,
     "planform-sequence": planform_sequence,
     "fickian-reference": fickian_reference, "soak-dry": soak_dry,
     "march-cost": march_cost, "soak-dry-solid": soak_dry_solid, "nested": nested,
     "corrected": corrected_run, "cross": cross_run}[sys.argv[1]](*sys.argv[2:])
