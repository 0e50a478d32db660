"""Throughput of a Monte Carlo of the demo cam (configs/singh2017_cam.yaml) on 1 and 2
LocalCluster workers, and what one case costs against one run in a warm process.

    python benchmarks/bench_montecarlo.py            # 1000 cases (issue 17's target)
    python benchmarks/bench_montecarlo.py --quick    # 100 cases
    python benchmarks/bench_montecarlo.py --cases 8 --workers 2

The sweep draws the fibre volume fraction, the service temperature and the cam
thickness (so no two cases share a geometry or a climate). Each worker count
runs the whole sweep from a fresh folder (cluster start-up and the final write
included: that is what a user waits for). Printed per worker count: wall time,
cases per second per worker, the cost of a case (wall x workers / cases) as a
ratio to one warm single run, and the 1 -> 2 worker scaling measured in this
same run. Then up to ``--check`` cases of the 2-worker result are compared
with single runs of the same scene (numpy.testing.assert_allclose, rtol 1e-9:
a case must be its single run). The load average is printed because other
work on the machine skews every figure.
"""
from __future__ import annotations

import argparse
import logging
import os
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

from fickcam.simulate import run
from fickcam.store import open_result
from fickcam.sweep import run_sweep
from fickcam.sweep.case import CaseTask, case_scene
from fickcam.sweep.spec import load_sweep

ROOT = Path(__file__).resolve().parents[1]
BASE = ROOT / "configs" / "singh2017_cam.yaml"
SWEEP = """base: {base}
samples: {cases}
seed: 17
random:
  materials.cfrp.fiber_volume_fraction: {{uniform: [0.57, 0.63]}}
  environment.history.0.temperature: {{normal: [113 degC, 2 degC]}}
  cam.thickness: {{normal: [12, 0.05], unit: mm}}
"""


def single_run_time(repeats: int = 3) -> float:
    """Median wall time (s) of one run of the base scene in a warm process."""
    run(BASE)
    times = []
    for _ in range(repeats):
        started = time.perf_counter()
        run(BASE)
        times.append(time.perf_counter() - started)
    return statistics.median(times)


def time_sweep(sweep_file: Path, output: Path, workers: int) -> float:
    started = time.perf_counter()
    run_sweep(sweep_file, output, workers=workers)
    return time.perf_counter() - started


def check_cases(sweep_file: Path, output: Path, count: int) -> int:
    """Compare ``count`` cases of ``output`` with single runs of their scenes; return count."""
    sweep = load_sweep(sweep_file)
    result = open_result(output)
    picks = np.unique(np.linspace(0, len(sweep.cases) - 1, count).round().astype(int))
    for index in picks:
        case = sweep.cases[index]
        task = CaseTask(index=int(index), scene=sweep.scene_dict(case), values=case.values,
                        label=f"case {index}", base_dir=str(sweep.base_dir), result_path="",
                        record_path="")
        alone = run(case_scene(task))
        for name, variable in alone.data_vars.items():
            if variable.dtype.kind == "f" and name in result:
                np.testing.assert_allclose(result[name].sel(case=index).values, variable.values,
                                           rtol=1e-9, equal_nan=True, err_msg=f"case {index} {name}")
    return len(picks)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=1000)
    parser.add_argument("--quick", action="store_true", help="100 cases")
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--check", type=int, default=20, help="cases compared with single runs")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    cases = 100 if args.quick else args.cases
    single = single_run_time()
    print(f"Monte Carlo of {BASE.name}: {cases} cases, {os.cpu_count()} cores, "
          f"load {os.getloadavg()[0]:.1f}; one warm single run {single:.3f} s")
    print(f"{'workers':>8} {'wall s':>8} {'cases/s/worker':>15} {'case/single':>12} {'load':>6}")
    walls = {}
    with tempfile.TemporaryDirectory() as folder:
        sweep_file = Path(folder) / "montecarlo.yaml"
        sweep_file.write_text(SWEEP.format(base=BASE, cases=cases))
        for workers in args.workers:
            load = os.getloadavg()[0]
            output = Path(folder) / f"mc-{workers}.h5"
            walls[workers] = wall = time_sweep(sweep_file, output, workers)
            print(f"{workers:>8} {wall:>8.1f} {cases / wall / workers:>15.2f} "
                  f"{wall * workers / cases / single:>12.2f} {load:>6.1f}", flush=True)
        if 1 in walls and 2 in walls:
            print(f"scaling 1 -> 2 workers: {walls[1] / walls[2]:.2f} x")
        checked = check_cases(sweep_file, output, min(args.check, cases))
        print(f"{checked} cases of the {args.workers[-1]}-worker result equal their single runs")


if __name__ == "__main__":
    main()
