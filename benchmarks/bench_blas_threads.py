"""Cost of OpenBLAS's worker threads: each case run with the BLAS pool at its default size
and limited to one thread (``threadpoolctl.threadpool_limits(1, "blas")``), side by side
in this one process, taken alternately, every cache of fickcam emptied before each run
(a fresh run each time).

    python benchmarks/bench_blas_threads.py [--repeats 3] [--cases NAME ...]

Prints, per case, the median CPU seconds (``time.process_time``: every thread of this
process, the idle BLAS workers' spinning included) and the median wall seconds of each
arm, and their ratios (limited / default). The load average is printed: on a shared
machine the wall times move with other work, the ratios of runs taken side by side less.
"""
from __future__ import annotations

import argparse
import gc
import os
import runpy
import statistics
import sys
import tempfile
import time
from contextlib import contextmanager, nullcontext
from pathlib import Path

from threadpoolctl import threadpool_info, threadpool_limits

ROOT = Path(__file__).resolve().parents[1]
MONTE_CARLO_CASES = 4


def clear_caches() -> None:
    """Empty every functools cache of fickcam's modules (each run keeps its meshes, step
    responses and tables in a ``RunCache`` of its own; what is left are constant tables)."""
    for name, module in list(sys.modules.items()):
        if name.startswith("fickcam"):
            for value in vars(module).values():
                if callable(getattr(value, "cache_clear", None)):
                    value.cache_clear()
    gc.collect()


def _run_config(config: str, **options):
    from fickcam.simulation.simulate import run

    return lambda: run(ROOT / config, **options)


def _records_scene(case: str, constant: bool, folder: Path):
    """A bench --records scene: a year of Greensboro's record, or its mean climate."""
    from climate_records import CASES, MONTH_HOURS, record_csv, record_scene
    from fickcam.simulation.simulate import run

    path, celsius, humidity = record_csv(folder, 12)
    environment = ({"history": [{"duration": f"{12 * MONTH_HOURS} h",
                                 "temperature": f"{celsius:.2f} degC",
                                 "relative_humidity": f"{humidity:.2f} %"}]} if constant else
                   {"history_file": str(path)})
    scene = record_scene(ROOT / CASES[case], environment, 12)
    return lambda: run(scene)


def _solid_plate():
    """The bench's 3-D solid D(c) plate (``diffusion_tradeoff.py``, k = 2) at 3e-2."""
    from diffusion_tradeoff import D_REF, sorption_cases, sorption_law, uptake_times
    from fickcam.diffusion import Diffusivity, Exposure, solve

    name, plate, kind, _, accuracies = sorption_cases(False)[-1]
    times = uptake_times(plate)
    exposure = Exposure.piecewise([0.0, times[-1]], 300.0, [1.0], 0.0)
    law = sorption_law(kind, D_REF, plate.thickness)
    return lambda: solve(plate, Diffusivity((D_REF,) * 3, 0.0), exposure, times,
                         accuracy=accuracies[-1], model="solid", sorption=law)


def _monte_carlo(folder: Path):
    """A few cases of bench_montecarlo.py's draws, in this process (one worker)."""
    from fickcam.sweep import run_sweep

    montecarlo = runpy.run_path(str(ROOT / "benchmarks" / "bench_montecarlo.py"))
    sweep = folder / "montecarlo.yaml"
    sweep.write_text(montecarlo["SWEEP"].format(base=montecarlo["BASE"], cases=MONTE_CARLO_CASES))
    return lambda: run_sweep(sweep, folder / "montecarlo.h5", workers=1)


def cases(folder: Path) -> dict:
    return {
        "demo cam": _run_config("configs/singh2017_cam.yaml"),
        "nylon cam, constant year": _records_scene("nylon eccentric cam (exact disc)", True, folder),
        "four-bar, Greensboro year": _records_scene("four-bar (plane)", False, folder),
        "two-phase demo cam, accuracy 1e-3": _run_config(
            "configs/singh2017_cam_two_phase.yaml", accuracy=1e-3),
        "3-D solid D(c) plate, 3e-2": _solid_plate(),
        f"Monte Carlo, {MONTE_CARLO_CASES} cases (1 worker)": _monte_carlo(folder),
    }


@contextmanager
def default_threads():
    """BLAS at its default threads: ``simulate.run``'s own limit (fickcam.simulation.blas) lifted."""
    from fickcam.simulation import blas
    limit = blas.one_blas_thread
    blas.one_blas_thread = nullcontext
    try:
        yield
    finally:
        blas.one_blas_thread = limit


def timed(function, limited: bool) -> tuple[float, float]:
    """(CPU s, wall s) of one fresh call, with or without the one-thread BLAS limit."""
    clear_caches()
    with threadpool_limits(1, "blas") if limited else default_threads():
        cpu, wall = time.process_time(), time.perf_counter()
        function()
        return time.process_time() - cpu, time.perf_counter() - wall


def measure(function, repeats: int) -> dict:
    """Medians of ``repeats`` alternated runs of each arm (after one warm-up of each)."""
    timed(function, False), timed(function, True)
    runs = {False: [], True: []}
    for _ in range(repeats):
        for limited in (False, True):
            runs[limited].append(timed(function, limited))
    return {limited: tuple(statistics.median(column) for column in zip(*pairs))
            for limited, pairs in runs.items()}


def main(argv=None) -> None:
    import logging

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--cases", nargs="*", help="substrings of case names")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    import scipy.linalg  # noqa: F401  (numpy's and scipy's OpenBLAS loaded, to be listed)

    blas = [f"{p['internal_api']} {p['version']} ({p['num_threads']} threads)"
            for p in threadpool_info() if p["user_api"] == "blas"]
    print(f"{os.cpu_count()} cores, BLAS: {', '.join(blas)}; load {os.getloadavg()[0]:.2f}")
    print(f"{'case':40} {'CPU s default':>13} {'1 thread':>9} {'ratio':>6}   "
          f"{'wall s default':>14} {'1 thread':>9} {'ratio':>6}  {'load':>5}")
    with tempfile.TemporaryDirectory() as folder:
        for name, function in cases(Path(folder)).items():
            if args.cases and not any(part in name for part in args.cases):
                continue
            result = measure(function, args.repeats)
            (cpu0, wall0), (cpu1, wall1) = result[False], result[True]
            print(f"{name:40} {cpu0:13.3f} {cpu1:9.3f} {cpu1 / cpu0:6.2f}   {wall0:14.3f} "
                  f"{wall1:9.3f} {wall1 / wall0:6.2f}  {os.getloadavg()[0]:5.2f}", flush=True)


if __name__ == "__main__":
    main()
