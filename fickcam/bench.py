"""``fickcam bench``: the diffusion speed/accuracy trade, measured.

For each geometry the full uptake curve of a unit surface step (c0 = 0,
g = 1 weight %, isothermal so tau = t) is solved by each model at a few
accuracy targets; the error is the largest |mean - exact| over 61 output
times spanning Fourier numbers (D t / h^2 of the thickness) 1e-2 .. 1.5 (relative to the step), against
Crank's series (``fickcam.diffusion.exact.separable.step_response``). Times are CPU seconds of
this process (``time.process_time``: the machine is shared, a wall time under load
says little), medians of ``repeats`` runs after one warm-up that pays the FiPy import.
The row ``fipy-naive`` is FiPy solving every backward-Euler step itself
(``eq.solve`` with ``LinearLUSolver(tolerance=1e-10)``) on the same step plan.
Non-Fickian rows (``bench_sorption``): two-phase sheet and disc, concentration-dependent
sheet, each against its own reference. Parts without an exact solution (the link) are measured against the plane model
at a third of the finest accuracy asked (at most 1e-3); the link's ``solid`` row
(3-D prisms marching the history, the plane model's independent check) is timed
in a single run.
"""
from __future__ import annotations

import logging
import time
from dataclasses import dataclass

import numpy as np

log = logging.getLogger(__name__)

D_REF = 1e-12  # m^2/s
NAIVE_ACCURACIES = (1e-3, 1e-4)  # the fipy-naive rows (full bench only)


@dataclass(frozen=True)
class Case:
    name: str
    geometry: object
    exact_as: object      # the geometry whose exact solution is the reference (or None)
    models: tuple[str, ...]
    accuracies: tuple[float, ...]
    runs: int = 0          # > 0: time this many runs without a warm-up (slow models)


def _cases(quick: bool) -> list[Case]:
    from .diffusion import Bar, CamPlate, Disc, LinkBar, Sheet

    plate = CamPlate(np.array([0.0, 12e-3, 12e-3, 0.0]), np.array([0.0, 0.0, 8e-3, 8e-3]), 3e-3)
    fine = (1e-2, 1e-3, 1e-4)
    cases = [Case("sheet 2 mm", Sheet(2e-3), Sheet(2e-3), ("analytic", "slab"), fine),
             Case("disc r5 x 2 mm", Disc(5e-3, 2e-3), Disc(5e-3, 2e-3),
                  ("analytic", "axisymmetric"), (1e-2, 3e-3, 1e-3)),
             Case("bar 8x6x3 mm", Bar(8e-3, 6e-3, 3e-3), Bar(8e-3, 6e-3, 3e-3),
                  ("analytic", "solid"), (5e-2, 3e-2)),
             Case("cam plate 12x8x3 mm (rectangle)", plate, Bar(12e-3, 8e-3, 3e-3), ("plane",),
                  (3e-2, 1e-2)),
             Case("link bar 40 mm, bosses r8/r3", LinkBar(0.04, 0.01, 0.004, 0.008, 0.003), None,
                  ("plane",), (3e-2, 1e-2)),
             Case("link bar 40 mm: plane vs solid", LinkBar(0.04, 0.01, 0.004, 0.008, 0.003),
                  None, ("plane", "solid"), (1e-1,), runs=1)]
    if quick:  # seconds: each geometry at its coarsest target, without the 3-D solid model
        cases = [Case(c.name, c.geometry, c.exact_as, tuple(m for m in c.models if m != "solid"),
                      c.accuracies[:1 + (i == 0)])
                 for i, c in enumerate(cases) if c.models != ("plane", "solid")]
    return cases


def row_count(quick: bool = False) -> int:
    """How many rows :func:`run_bench` measures (for a progress bar)."""
    from .diffusion import Sheet

    from .bench_sorption import sorption_row_count

    return sum(sum(1 if model == "analytic" else len(case.accuracies) for model in case.models)
               + (len(NAIVE_ACCURACIES) if isinstance(case.geometry, Sheet) and not quick else 0)
               for case in _cases(quick)) + sorption_row_count(quick)


def _uptake_times(geometry) -> np.ndarray:
    """0 and 60 times from Fourier 1e-2 to 1.5 of the thickness (the full uptake curve)."""
    scale = geometry.thickness ** 2 / D_REF
    return np.concatenate([[0.0], np.geomspace(1e-2, 1.5, 60) * scale])


def _reference(case: Case, times: np.ndarray) -> np.ndarray | None:
    if case.exact_as is None:
        return None
    from .diffusion.exact.separable import step_response

    return step_response(case.exact_as, (D_REF,) * 3, times)[0]


def _timed(function, repeats: int, warm_up: bool = True):
    if warm_up:
        function()  # imports, caches
    seconds = []
    result = None
    for _ in range(repeats):
        started = time.process_time()
        result = function()
        seconds.append(time.process_time() - started)
    return result, float(np.median(seconds))


def run_bench(quick: bool = False, repeats: int = 3, progress=lambda label: None) -> list[dict]:
    """Rows (geometry, model, accuracy, cells, steps, cpu_time s, error, error_estimate);
    ``progress(label)`` is called as each row starts."""
    from .diffusion import Diffusivity, Exposure, Sheet, solve

    diffusivity = Diffusivity((D_REF,) * 3, 0.0)
    rows: list[dict] = []
    for case in _cases(quick):
        times = _uptake_times(case.geometry)
        exposure = Exposure.piecewise([0.0, times[-1]], 300.0, [1.0], 0.0)
        reference = _reference(case, times)
        if reference is None:
            reference = solve(case.geometry, diffusivity, exposure, times,
                              accuracy=min(min(case.accuracies) / 3, 1e-3),
                              model=case.models[0]).mean
            label = "finer plane"
        else:
            label = "exact"
        for model in case.models:
            for accuracy in (case.accuracies if model != "analytic" else case.accuracies[:1]):
                progress(f"{case.name}: {model} {accuracy:g}")
                try:
                    result, cpu = _timed(lambda: solve(case.geometry, diffusivity, exposure,
                                                        times, accuracy=accuracy, model=model),
                                          1 if quick else case.runs or repeats,
                                          warm_up=not case.runs)
                except ImportError as exc:  # exact.py without exact_history yet
                    log.warning("%s %s skipped: %s", case.name, model, exc)
                    continue
                except Exception as exc:  # noqa: BLE001 - a bench row reports, never hides
                    log.warning("%s %s failed: %s", case.name, model, exc)
                    rows.append(_row(case, model, accuracy, 0, 0, np.nan, np.nan, np.nan, label))
                    continue
                error = float(np.max(np.abs(result.mean - reference)))
                rows.append(_row(case, result.model, accuracy, result.cells, result.steps, cpu,
                                 error, result.error_estimate, label))
        if isinstance(case.geometry, Sheet) and not quick:
            rows += _naive_fipy_rows(case, diffusivity, exposure, times, reference, progress)
    from .bench_sorption import sorption_rows

    return rows + sorption_rows(quick, _uptake_times, diffusivity, D_REF,
                                lambda run: _timed(run, 1 if quick else repeats), _named_row,
                                progress)


def _row(case, model, accuracy, cells, steps, cpu, error, estimate, reference) -> dict:
    return {"geometry": case.name, "model": model, "accuracy": accuracy, "cells": int(cells),
            "steps": int(steps), "cpu_time": cpu, "error": error,
            "error_estimate": estimate, "reference": reference}


def _named_row(name, model, accuracy, cells, steps, wall, error, estimate, reference) -> dict:
    return _row(Case(name, None, None, (), ()), model, accuracy, cells, steps, wall, error,
                estimate, reference)


def _naive_fipy_rows(case, diffusivity, exposure, times, reference, progress) -> list[dict]:
    """FiPy assembling and solving every step itself, same plan (coarse + bisected, Richardson)."""
    from .diffusion import plan
    from .diffusion.forcing.clock import scales as scales_of
    from .diffusion.models.finite_volume import step_plan

    rows = []
    for accuracy in NAIVE_ACCURACIES:
        progress(f"{case.name}: fipy-naive {accuracy:g}")
        chosen = plan(case.geometry, diffusivity, exposure, times, accuracy, "slab")
        scales = scales_of(case.geometry, diffusivity, exposure)
        plans = [step_plan(exposure, times, scales, chosen.steps_per_doubling, b)
                 for b in (False, True)]

        def run():
            coarse, fine = (_fipy_march(chosen.cells_per_axis[0], p.nodes, p.outputs)
                            for p in plans)
            return 2 * fine - coarse
        mean, cpu = _timed(run, 1)
        steps = sum(p.nodes.size - 1 for p in plans)
        rows.append(_row(case, "fipy-naive", accuracy, chosen.cells_per_axis[0], steps, cpu,
                         float(np.max(np.abs(mean - reference))), np.nan, "exact"))
    return rows


def _fipy_march(cells: int, nodes: np.ndarray, outputs: np.ndarray) -> np.ndarray:
    from fipy import CellVariable, DiffusionTerm, Grid1D, LinearLUSolver, TransientTerm

    mesh = Grid1D(nx=cells, dx=1.0 / cells)
    var = CellVariable(mesh=mesh, value=0.0)
    var.constrain(1.0, mesh.exteriorFaces)
    equation = TransientTerm() == DiffusionTerm(coeff=1.0)
    means = np.zeros(nodes.size)
    for k, dt in enumerate(np.diff(nodes), start=1):
        equation.solve(var=var, dt=dt, solver=LinearLUSolver(tolerance=1e-10))
        means[k] = float(np.mean(var.value))
    return means[outputs]


def format_table(rows: list[dict]) -> str:
    """A fixed-width table, one line per (geometry, model, accuracy)."""
    header = (f"{'geometry':<32} {'model':<13} {'accuracy':>8} {'cells':>8} {'steps':>6} "
              f"{'CPU [s]':>9} {'error':>9} {'estimate':>9}  reference")
    lines = [header, "-" * len(header)]
    for r in rows:
        lines.append(f"{r['geometry']:<32} {r['model']:<13} {r['accuracy']:>8.0e} "
                     f"{r['cells']:>8d} {r['steps']:>6d} {r['cpu_time']:>9.4f} "
                     f"{r['error']:>9.1e} {r['error_estimate']:>9.1e}  {r['reference']}")
    return "\n".join(lines)
