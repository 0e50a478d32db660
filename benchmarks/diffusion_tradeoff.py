"""The diffusion speed/accuracy trade, measured: the table `fickcam bench` prints.

    python benchmarks/diffusion_tradeoff.py [--quick] [--out benchmarks/results]

Writes ``bench.md`` (the table `fickcam bench` prints), ``bench.csv``, ``bench.json``
(the same rows with the commit, date, machine and load, for the benchmarks page) and
``error_vs_time.png`` (error against the exact solution vs CPU time, log-log,
one marker series per geometry and model) for the benchmarks page. A ``--quick`` run
only prints its table (it must not replace the committed full results) unless
``--out`` names a folder.

Fickian rows: for each geometry the full uptake curve of a unit surface step (c0 = 0,
g = 1 weight %, isothermal so tau = t) is solved by each model at a few accuracy
targets; the error is the largest |mean - exact| over 61 output times spanning Fourier
numbers (D t / h^2 of the thickness) 1e-2 .. 1.5 (relative to the step), against Crank's
series (``fickcam.diffusion.exact.separable.step_response``). Times are CPU seconds of
this process (``time.process_time``: the machine is shared, a wall time under load says
little), medians of ``repeats`` runs after one warm-up that pays the FiPy import. The row
``fipy-naive`` is FiPy solving every backward-Euler step itself (``eq.solve`` with
``LinearLUSolver(tolerance=1e-10)``) on the same step plan. Parts without an exact
solution (the link) are measured against the plane model at a third of the finest
accuracy asked (at most 1e-3); the link's ``solid`` row (3-D prisms marching the history,
the plane model's independent check) is timed in a single run.

Non-Fickian rows (``materials.NAME.sorption``; two-phase sheet and disc,
concentration-dependent sheet and plate, each against its own reference): unit surface
step (c0 = 0, Ms = 1 weight %, isothermal), the full uptake curve at the bench's 61
times, error = largest |mean - reference| (relative to the step):

- two-phase (Langmuir; gamma = beta = 0.1 pi^2 D/h^2): the sheet against Carter &
  Kibler's exact series (``diffusion.exact.two_phase.two_phase_sheet_uptake``), the
  disc's FiPy (r, z) block march against its exact modes at accuracy 1e-8, and a
  circular cam plate (a 160-gon, area short by 2.6e-4) on its planform quadrature
  (``nonfickian.planform_modes``) against the exact modes of that disc;
- concentration-dependent (D = D0 exp(2 c/Mm)): the FiPy slab against a 800-node method
  of lines (scipy BDF, tolerances 1e-10), an independent discretisation; a 4 x 3 x 2 mm
  plate (CamPlate, the 3-D prisms cut at the mid-plane, ``operators.symmetry_cuts``)
  against the same model run at ``PLANFORM_REFERENCE`` (a fine run: no independent 3-D
  solution exists), by the 3-D cells alone (``solid``) and by ``auto``'s corrected
  sheet x planform product (``nonfickian.corrected_product``), the two against the same
  fine 3-D run.
"""
from __future__ import annotations

import argparse
import csv
import logging
import os
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fickcam.simulation.blas import on_one_blas_thread

log = logging.getLogger("benchmarks.diffusion_tradeoff")
RESULTS = Path(__file__).resolve().parent / "results"

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


def bench_cases(quick: bool) -> list[Case]:
    from fickcam.diffusion import Bar, CamPlate, Disc, LinkBar, Sheet

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
    from fickcam.diffusion import Sheet

    return sum(sum(1 if model == "analytic" else len(case.accuracies) for model in case.models)
               + (len(NAIVE_ACCURACIES) if isinstance(case.geometry, Sheet) and not quick else 0)
               for case in bench_cases(quick)) + sorption_row_count(quick)


def uptake_times(geometry) -> np.ndarray:
    """0 and 60 times from Fourier 1e-2 to 1.5 of the thickness (the full uptake curve)."""
    scale = geometry.thickness ** 2 / D_REF
    return np.concatenate([[0.0], np.geomspace(1e-2, 1.5, 60) * scale])


def _reference(case: Case, times: np.ndarray) -> np.ndarray | None:
    if case.exact_as is None:
        return None
    from fickcam.diffusion.exact.separable import step_response

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


@on_one_blas_thread
def run_bench(quick: bool = False, repeats: int = 3, progress=lambda label: None) -> list[dict]:
    """Rows (geometry, model, accuracy, cells, steps, cpu_time s, error, error_estimate);
    ``progress(label)`` is called as each row starts. BLAS holds one thread, as in a run
    (``fickcam.simulation.blas``): on a loaded machine OpenBLAS's spinning workers otherwise count in
    the process's CPU time (the link's solid row: 16 CPU s on one thread, more than 300 s
    wall on two under a load of 4-7)."""
    from fickcam.diffusion import Diffusivity, Exposure, Sheet, solve

    diffusivity = Diffusivity((D_REF,) * 3, 0.0)
    rows: list[dict] = []
    for case in bench_cases(quick):
        times = uptake_times(case.geometry)
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
    return rows + sorption_rows(quick, uptake_times, diffusivity, D_REF,
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
    from fickcam.diffusion import plan
    from fickcam.diffusion.forcing.clock import scales as scales_of
    from fickcam.diffusion.models.finite_volume import step_plan

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


def result_table(rows: list[dict]) -> dict:
    """The rows as a table of a result file (the numbers formatted as ``format_table``)."""
    return {"columns": ["geometry", "model", "accuracy", "cells", "steps", "CPU s", "error",
                        "estimate", "reference"],
            "rows": [[r["geometry"], r["model"], f"{r['accuracy']:.0e}", r["cells"], r["steps"],
                      f"{r['cpu_time']:.4f}", f"{r['error']:.1e}", f"{r['error_estimate']:.1e}",
                      r["reference"]] for r in rows]}


# ------------------------------------------------ non-Fickian sorption rows
EXPONENT = 2.0
EXCHANGE = 0.1   # gamma = beta = EXCHANGE pi^2 D / h^2
PLANFORM_REFERENCE = 2e-2  # accuracy of the plate's fine reference run (15.6 k cells)


def sorption_cases(quick: bool) -> list[tuple]:
    """(name, geometry, law name, models, accuracies)."""
    from fickcam.diffusion import CamPlate, Disc, Sheet

    accuracies = (1e-2,) if quick else (1e-2, 1e-3)
    angle = np.linspace(0.0, 2.0 * np.pi, 160, endpoint=False)
    plate = CamPlate(5e-3 * np.cos(angle), 5e-3 * np.sin(angle), 2e-3)
    block = CamPlate(np.array([0, 4e-3, 4e-3, 0.0]), np.array([0, 0, 3e-3, 3e-3]), 2e-3)
    return [("sheet 2 mm, two-phase", Sheet(2e-3), "langmuir", ("analytic", "slab"), accuracies),
            ("disc r5 x 2 mm, two-phase", Disc(5e-3, 2e-3), "langmuir",
             ("analytic", "axisymmetric"), accuracies),
            ("cam plate circle r5 x 2 mm, two-phase", plate, "langmuir", ("plane",), accuracies),
            ("sheet 2 mm, D exp(2c/Mm)", Sheet(2e-3), "concentration_dependent", ("slab",),
             accuracies)] + ([] if quick else [  # the 3-D row: full bench only
            ("plate 4x3x2 mm, D exp(2c/Mm)", block, "concentration_dependent", ("solid",),
             (5e-2, 3e-2)),
            ("plate 4x3x2 mm, D exp(2c/Mm), corrected", block, "concentration_dependent",
             ("auto",), (3e-2, 1e-2))])


def sorption_row_count(quick: bool) -> int:
    return sum(len(models) * len(accuracies) for *_, models, accuracies in sorption_cases(quick))


def sorption_law(kind: str, d_ref: float, thickness: float):
    from fickcam.diffusion.problem.sorption import ConcentrationDependent, Langmuir, Rate

    if kind == "langmuir":
        rate = EXCHANGE * np.pi ** 2 * d_ref / thickness ** 2
        return Langmuir(Rate(rate), Rate(rate))
    return ConcentrationDependent(1.0, exponent=EXPONENT)


def _method_of_lines(times, d_ref: float, thickness: float, nodes: int = 800) -> np.ndarray:
    """Mean uptake of dc/dt = d/dz (D0 exp(k c) dc/dz), c = 1 on both faces, c0 = 0."""
    from scipy.integrate import solve_ivp
    from scipy.sparse import diags

    dz = 1.0 / nodes

    def rhs(_, c):
        full = np.concatenate([[1.0], c, [1.0]])
        return np.diff(np.exp(EXPONENT * 0.5 * (full[1:] + full[:-1])) * np.diff(full) / dz) / dz

    scale = d_ref / thickness ** 2
    pattern = diags([1.0, 1.0, 1.0], [-1, 0, 1], shape=(nodes - 1, nodes - 1))
    solution = solve_ivp(rhs, (0.0, times[-1] * scale), np.zeros(nodes - 1), t_eval=times * scale,
                         method="BDF", rtol=1e-10, atol=1e-12, jac_sparsity=pattern)
    full = np.vstack([np.ones(times.size), solution.y, np.ones(times.size)])
    return np.where(times > 0, np.trapezoid(full, dx=dz, axis=0), 0.0)  # t = 0: dry


def reference(name, geometry, kind, times, diffusivity, exposure, d_ref):
    """(values, label) of the reference uptake curve of a case."""
    from fickcam.diffusion import CamPlate, Disc, Sheet, solve
    from fickcam.diffusion.exact.two_phase import two_phase_sheet_uptake

    law = sorption_law(kind, d_ref, geometry.thickness)
    if kind != "langmuir" and not isinstance(geometry, Sheet):
        return solve(geometry, diffusivity, exposure, times, accuracy=PLANFORM_REFERENCE,
                     sorption=law).mean, f"fine run ({PLANFORM_REFERENCE:g})"
    if kind != "langmuir":
        return _method_of_lines(times, d_ref, geometry.thickness), "method of lines"
    if isinstance(geometry, Sheet):
        rate = law.binding.pre_exponential
        return two_phase_sheet_uptake(times, d_ref, geometry.thickness, rate, rate).total, "exact"
    if isinstance(geometry, CamPlate):  # the disc its outline approximates
        radius = float(np.max(np.hypot(geometry.profile_x, geometry.profile_y)))
        geometry = Disc(radius, geometry.thickness)
    return solve(geometry, diffusivity, exposure, times, accuracy=1e-8,
                 sorption=law).mean, "exact modes"


def sorption_rows(quick, times_of, diffusivity, d_ref, timed, make_row, progress) -> list[dict]:
    """The rows: each case, model and accuracy timed (``timed``) and compared."""
    from fickcam.diffusion import Exposure, solve

    rows, references = [], {}
    for name, geometry, kind, models, accuracies in sorption_cases(quick):
        times = times_of(geometry)
        exposure = Exposure.piecewise([0.0, times[-1]], 300.0, [1.0], 0.0)
        law = sorption_law(kind, d_ref, geometry.thickness)
        if (kind, geometry) not in references:  # the 3-D rows share their fine run
            references[kind, geometry] = reference(name, geometry, kind, times, diffusivity,
                                                   exposure, d_ref)
        values, label = references[kind, geometry]
        for model in models:
            for accuracy in accuracies:
                progress(f"{name}: {model} {accuracy:g}")
                result, wall = timed(lambda: solve(geometry, diffusivity, exposure, times,
                                                   accuracy=accuracy, model=model, sorption=law))
                rows.append(make_row(name, result.model, accuracy, result.cells, result.steps,
                                     wall, float(np.max(np.abs(result.mean - values))),
                                     result.error_estimate, label))
    return rows


# ------------------------------------------------ the script: table, CSV and figure


def write_figure(rows: list[dict], path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 5))
    series: dict[tuple[str, str], list[dict]] = {}
    for row in rows:
        if np.isfinite(row["cpu_time"]) and row["error"] > 0:
            series.setdefault((row["geometry"], row["model"]), []).append(row)
    markers = "os^Dv"  # with the 10 colours: 50 series told apart
    for k, ((geometry, model), points) in enumerate(series.items()):
        points.sort(key=lambda r: r["cpu_time"])
        ax.loglog([p["cpu_time"] for p in points], [p["error"] for p in points],
                  markers[k // 10 % len(markers)] + "-", label=f"{geometry}: {model}")
    ax.set_xlabel("CPU time per full uptake curve [s]")
    ax.set_ylabel("max error of the mean uptake (fraction of the step)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # beside, not over
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)
    return path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--out", type=Path, default=None,
                        help="folder for the results (default: benchmarks/results; "
                             "a --quick run writes nothing unless given)")
    args = parser.parse_args()
    logging.basicConfig(level=logging.WARNING, format="%(message)s")  # libraries: warnings only
    log.setLevel(logging.INFO)
    load = os.getloadavg()[0]
    rows = run_bench(quick=args.quick)
    if args.out is None and args.quick:
        log.info("%s", format_table(rows))
        log.info("--quick: results not written (give --out FOLDER to keep them)")
        return
    args.out = args.out or RESULTS
    args.out.mkdir(parents=True, exist_ok=True)
    from stamp import write_result

    write_result(args.out / "bench.json", "speed and accuracy of the diffusion engine",
                 "python benchmarks/diffusion_tradeoff.py", {"bench": result_table(rows)}, load)
    (args.out / "bench.md").write_text("```\n" + format_table(rows) + "\n```\n")
    with open(args.out / "bench.csv", "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    log.info("%s", format_table(rows))
    log.info("figure: %s", write_figure(rows, args.out / "error_vs_time.png"))


if __name__ == "__main__":
    main()
