"""The two-phase demo cam under a constant climate and a daily chamber record.

    python benchmarks/two_phase_cam_records.py [--reference] [--log]

- ``--log`` writes ``configs/chamber_daily_113C.csv``: a SYNTHETIC daily chamber log,
  181 rows (0 to 180 d), temperature uniform in 113 +- 4 degC and relative humidity in
  80 +- 12 %, drawn once (numpy default_rng seed 13); rows are joined linearly.
- ``--reference`` computes the fine references of the cam's diffusion (the plane
  two-phase path on fixed planform meshes 8 and 16 times finer in w0, 4 and 8 times in
  growth than the scene's first mesh, march at 1e-5, Richardson-extrapolated: the cells
  go as 1/(w0 g), second order) and writes ``tests/data/two_phase_cam_reference.json``
  (mean, bound, contact layer in weight %, with the two fine meshes' difference as the
  reference's own uncertainty bound).
- Default: the validation table (accuracy asked, the run's estimate, the true error
  against the reference: the largest of mean, bound and layer / 4 relative to the swing,
  planform cells, CPU seconds of the whole scene run in this process), for
  ``configs/singh2017_cam_two_phase.yaml`` and ``configs/singh2017_cam_two_phase_daily.yaml``,
  and a circular plate (r 50 mm, 12 mm, the cam's transverse D) against the exact disc
  over the same record.

The fine references are what ``tests/test_sorption_planform_records.py`` checks the
cam's runs against (``cam_problem``, ``true_error``).
"""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from fickcam.simulation.blas import one_blas_thread
from fickcam.diffusion import CamPlate, Diffusivity, Disc, solve
from fickcam.diffusion.accuracy.budget import LAYER_TOLERANCE
from fickcam.diffusion.problem.exposure import swing as history_swing
from fickcam.scene.load import load_scene
from fickcam.simulation.simulate import run
from fickcam.simulation.times import ageing_times

ROOT = Path(__file__).resolve().parents[1]
CONFIGS = {"constant": ROOT / "configs/singh2017_cam_two_phase.yaml",
           "daily record": ROOT / "configs/singh2017_cam_two_phase_daily.yaml"}
LOG = ROOT / "configs/chamber_daily_113C.csv"
REFERENCE = ROOT / "tests/data/two_phase_cam_reference.json"
FINE = ((8.0, 4.0), (16.0, 8.0))   # (w0, growth) divisors of the first mesh


def write_log(path: Path = LOG, days: int = 181, seed: int = 13) -> None:
    rng = np.random.default_rng(seed)
    day = np.arange(days)
    temperature = 113 + 4 * rng.uniform(-1, 1, days)
    humidity = 80 + 12 * rng.uniform(-1, 1, days)
    path.write_text("time [d],temperature [degC],relative_humidity [%]\n" + "".join(
        f"{d},{t:.2f},{h:.2f}\n" for d, t, h in zip(day, temperature, humidity)))


def cam_problem(config: Path):
    """(geometry, diffusivity, exposure, ageing times, sorption law, layer depth) of the
    scene's cam, as ``simulate`` builds them."""
    scene = load_scene(config)
    environment = scene.environment
    times = ageing_times(scene, environment)
    cam = next(part for part in scene.parts if part.name == "cam")
    return (cam.geometry, cam.material.diffusivity_for(cam.geometry),
            environment.exposure(cam.material.saturation_moisture), times,
            cam.material.sorption_law(), scene.model.diffusion.surface_layer_depth)


def fine_history(problem, divisors):
    """The cam's (mean, bound, layer) on a fixed planform mesh ``divisors`` finer than
    the first (the refinement's own ``_level``, march at 1e-5)."""
    from fickcam.diffusion.nonfickian import planform_modes
    from fickcam.diffusion.forcing.clock import RescaledTime
    from fickcam.diffusion.nonfickian.two_phase_planform import read_ages
    from fickcam.diffusion.nonfickian.two_phase_modes import langmuir_history

    geometry, diffusivity, exposure, times, law, depth = problem
    start = _first_mesh(problem)
    ages = read_ages(RescaledTime(diffusivity, exposure), exposure, times)
    operator = planform_modes.planform_operator(geometry, diffusivity.pre_exponential, depth,
                                           start[0] / divisors[0], start[1] / divisors[1])
    steps, _ = planform_modes.lanczos_count(operator, ages[ages > 0], 1e-5)
    source = planform_modes.planform_source(geometry, diffusivity.pre_exponential,
                                       planform_modes.lanczos_spectrum(operator, steps))
    history, _ = langmuir_history(geometry, diffusivity, law, exposure, times, 1e-5, depth, source)
    return np.stack([history["mean"], history["bound"], history["surface"]]), operator.cells


def _first_mesh(problem):
    from fickcam.diffusion.forcing.clock import scales as scales_of
    from fickcam.diffusion.nonfickian.planform_modes import first_planform_mesh
    from fickcam.diffusion.stepping.step_plans import earliest_output

    geometry, diffusivity, exposure, times, _, _ = problem
    scales = scales_of(geometry, diffusivity, exposure)
    t_lo = earliest_output(scales.tau_star(exposure.change_times), scales.tau_star(times))
    design = first_planform_mesh(geometry, diffusivity.pre_exponential, 1e-3, t_lo)
    return design.finest, design.growth


def write_reference() -> None:
    found = {}
    for name, config in CONFIGS.items():
        problem = cam_problem(config)
        start = time.process_time()
        (coarse, cells_c), (fine, cells_f) = (fine_history(problem, d) for d in FINE)
        ratio2 = (FINE[1][0] / FINE[0][0]) * (FINE[1][1] / FINE[0][1])  # cells ratio = r^2
        extrapolated = fine + (fine - coarse) / (ratio2 - 1.0)
        found[name] = {"times_s": problem[3].tolist(), "swing": history_swing(problem[2]),
                       "mean": extrapolated[0].tolist(), "bound": extrapolated[1].tolist(),
                       "surface": extrapolated[2].tolist(),
                       "uncertainty": float(np.max(np.abs(fine - coarse) / (ratio2 - 1.0)
                                                   / history_swing(problem[2]))),
                       "cells": [cells_c, cells_f], "cpu_s": time.process_time() - start}
        print(f"{name}: reference on {cells_c} and {cells_f} cells, uncertainty "
              f"{found[name]['uncertainty']:.1e} of the swing, {found[name]['cpu_s']:.0f} CPU s")
    REFERENCE.write_text(json.dumps(found, indent=1) + "\n")


def true_error(result, reference: dict) -> float:
    """max(|mean|, |bound|, |layer| / LAYER_TOLERANCE) against the reference, / swing."""
    errors = [np.max(np.abs(np.asarray(getattr(result, key)) - reference[key]))
              for key in ("mean", "bound", "surface")]
    return max(errors[0], errors[1], errors[2] / LAYER_TOLERANCE) / reference["swing"]


def cam_rows(accuracies=(1e-3, 1e-4)) -> list[dict]:
    """Each scene at each accuracy: the cam's solve (estimate, cells, error against the
    reference) and the CPU seconds of the whole scene run."""
    reference = json.loads(REFERENCE.read_text())
    rows = []
    for name, config in CONFIGS.items():
        geometry, diffusivity, exposure, times, law, depth = cam_problem(config)
        for accuracy in accuracies:
            start = time.process_time()
            run(load_scene(config), accuracy=accuracy)
            cost = time.process_time() - start
            result = solve(geometry, diffusivity, exposure, times, accuracy=accuracy,
                           sorption=law, surface_layer_depth=depth)   # cached: no new solve
            rows.append({"climate": name, "accuracy": accuracy,
                         "estimate": result.error_estimate,
                         "error": true_error(result, reference[name]), "cells": result.cells,
                         "cpu": cost, "capped": "capped" in result.reason})
    return rows


def circle_rows(accuracies=(1e-3, 1e-4)) -> list[dict]:
    """A circular plate (720-gon, r 50 mm, 12 mm, the cam's transverse D in-plane) against
    the exact two-phase disc of its area over the daily record (mean, bound, layer)."""
    _, diffusivity, exposure, times, law, depth = cam_problem(CONFIGS["daily record"])
    times = np.unique(np.concatenate([times, np.array([1.5, 3.5, 10.5, 45.5]) * 86400.0]))
    d = Diffusivity((diffusivity.pre_exponential[1],) * 2 + (diffusivity.pre_exponential[2],),
                    diffusivity.activation_energy)
    angle = np.linspace(0.0, 2 * np.pi, 720, endpoint=False)
    plate = CamPlate(0.05 * np.cos(angle), 0.05 * np.sin(angle), 0.012)
    area = 0.5 * np.sum(plate.profile_x * np.roll(plate.profile_y, -1)
                        - np.roll(plate.profile_x, -1) * plate.profile_y)
    exact = solve(Disc(float(np.sqrt(area / np.pi)), 0.012), d, exposure, times, accuracy=1e-7,
                  sorption=law, surface_layer_depth=depth)
    reference = {"mean": exact.mean, "bound": exact.bound, "surface": exact.surface,
                 "swing": history_swing(exposure)}
    rows = []
    for accuracy in accuracies:
        start = time.process_time()
        with one_blas_thread():   # as a run
            result = solve(plate, d, exposure, times, accuracy=accuracy, sorption=law,
                           surface_layer_depth=depth)
        rows.append({"climate": "circle r50 daily record vs exact disc", "accuracy": accuracy,
                     "estimate": result.error_estimate, "error": true_error(result, reference),
                     "cells": result.cells, "cpu": time.process_time() - start,
                     "capped": "capped" in result.reason})
    return rows


def format_rows(rows) -> str:
    lines = ["| case | accuracy | estimate | true error | planform cells | CPU s |",
             "|---|---|---|---|---|---|"]
    for row in rows:
        flag = " (capped)" if row["capped"] else ""
        lines.append(f"| {row['climate']} | {row['accuracy']:g} | {row['estimate']:.1e}{flag} | "
                     f"{row['error']:.1e} | {row['cells']} | {row['cpu']:.1f} |")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--log", action="store_true", help="write the daily chamber log")
    parser.add_argument("--reference", action="store_true", help="write the fine references")
    args = parser.parse_args()
    if args.log:
        write_log()
    if args.reference:
        write_reference()
    if not (args.log or args.reference):
        print(format_rows(cam_rows() + circle_rows()))


if __name__ == "__main__":
    main()
