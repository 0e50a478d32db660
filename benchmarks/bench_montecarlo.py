"""Throughput of a Monte Carlo of the demo cam (configs/singh2017_cam.yaml) on 2
LocalCluster workers, as a multiple of one demo run (``fickcam run`` of the demo as a whole
process), and what one case costs against one run in a warm process.

    python benchmarks/bench_montecarlo.py            # 1000 cases, 3 sweeps (target: 25 demo runs)
    python benchmarks/bench_montecarlo.py --quick    # 100 cases
    python benchmarks/bench_montecarlo.py --repeats 1 --scaling-cases 100
    python benchmarks/bench_montecarlo.py --against ../other-checkout   # side by side

The sweep draws the fibre volume fraction, the service temperature and the cam
thickness (so no two cases share a geometry or a climate: nothing is reused
across cases). Every sweep is a whole process (``--one-sweep``: imports, cluster start-up
and the final write included, what a user waits for), from a fresh folder, and so is every
demo run; each sweep follows a demo run of the same checkout, so that both see the same
load. With ``--against DIR`` the checkout in DIR runs the same sweeps and demo runs
alternately with this one (its package first on the path), side by side. First the
1 -> 2 worker scaling, when asked for, measured in this same run on the first
``--scaling-cases`` draws (1 worker runs in the process, 2 on a LocalCluster); then the
whole sweep, ``--repeats`` times, on ``--workers`` workers: wall time, cases per second per
worker, the whole sweep as a multiple of one demo run and of one warm single run, the cost
of a case (wall x workers / cases) as a ratio to one warm single run, and the CPU seconds
per case of the sweep's process and its workers (rusage: comparable on a loaded machine);
medians over the repeats. Then ``--check`` cases of the result are compared with single
runs of the same scene (numpy.testing.assert_allclose, rtol 1e-9: a case must be its single
run). The medians, every sweep's figures, the machine, its load average (other work on
the machine skews wall times) and the commit go to
``benchmarks/results/montecarlo.json``.
"""
from __future__ import annotations

import argparse
import datetime
import json
import logging
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from fickcam.simulation.simulate import run
from fickcam.results.store import open_result
from fickcam.sweep import run_sweep
from fickcam.sweep.case import CaseTask, case_scene
from fickcam.sweep.spec import load_sweep
from points_cam import commit, machine  # the sibling benchmark's machine stamp

ROOT = Path(__file__).resolve().parents[1]
RESULT = ROOT / "benchmarks" / "results" / "montecarlo.json"
TARGET_DEMO_RUNS = 25.0  # 1000 cases on 2 workers, in demo runs (whole processes)
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
    """Median wall time (s) of one run of the base scene in a warm process, with a cache of
    its own (a fresh ``RunCache``: no mesh or step response kept): what a case of this sweep
    costs, none of whose geometries repeats."""
    run(BASE)
    times = []
    for _ in range(repeats):
        started = time.perf_counter()
        run(BASE)
        times.append(time.perf_counter() - started)
    return statistics.median(times)


def cpu_seconds() -> float:
    """CPU time of this process and of its finished child processes (the workers)."""
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + children.ru_utime + children.ru_stime


def time_sweep(sweep_file: Path, output: Path, workers: int) -> tuple[float, float]:
    """(wall s, CPU s) of one sweep from a fresh folder, in this process."""
    cpu, started = cpu_seconds(), time.perf_counter()
    run_sweep(sweep_file, output, workers=workers)
    return time.perf_counter() - started, cpu_seconds() - cpu


def timed_process(command: list[str], checkout: Path) -> tuple[float, float]:
    """(wall s, CPU s of it and the processes it waited for) of ``command`` as a whole
    process, with ``checkout``'s package first on the path."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    started = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, cwd=checkout,
                   env={**os.environ, "PYTHONPATH": str(checkout)})
    wall = time.perf_counter() - started
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)


def demo_run(checkout: Path, folder: Path) -> float:
    """Wall seconds of ``fickcam run`` of the demo as a whole process."""
    return timed_process([sys.executable, "-m", "fickcam.cli.main", "run", str(BASE), "-o",
                          str(folder / "demo.h5")], checkout)[0]


def sweep_process(checkout: Path, sweep_file: Path, output: Path,
                  workers: int) -> tuple[float, float]:
    """(wall s, CPU s) of one sweep as a whole process (``--one-sweep``)."""
    return timed_process([sys.executable, str(Path(__file__).resolve()), "--one-sweep",
                          str(sweep_file), str(output), "--workers", str(workers)], checkout)


def sweep_row(checkout: Path, folder: Path, sweep_file: Path, output: Path, workers: int,
              cases: int, single: float) -> dict:
    """One demo run, then one sweep, of ``checkout``: the sweep's figures."""
    load = os.getloadavg()[0]
    demo = demo_run(checkout, folder)
    wall, cpu = sweep_process(checkout, sweep_file, output, workers)
    return {"wall_s": wall, "cpu_s_per_case": cpu / cases, "load_average": load,
            "demo_run_s": demo, "sweep_over_demo_run": wall / demo,
            "sweep_over_single": wall / single, "case_over_single": wall * workers / cases / single}


def printed(name: str, row: dict, cases: int, workers: int) -> None:
    print(f"{name:>10} {row['wall_s']:>8.1f} {cases / row['wall_s'] / workers:>15.2f} "
          f"{row['demo_run_s']:>7.2f} {row['sweep_over_demo_run']:>7.1f} "
          f"{row['sweep_over_single']:>9.0f} {row['cpu_s_per_case']:>11.3f} "
          f"{row['load_average']:>6.1f}", flush=True)


def check_cases(sweep_file: Path, output: Path, count: int) -> int:
    """Compare ``count`` cases of ``output`` with single runs of their scenes; return count."""
    sweep = load_sweep(sweep_file)
    result = open_result(output)
    picks = np.unique(np.linspace(0, len(sweep.cases) - 1, count).round().astype(int))
    for index in picks:
        case = sweep.cases[index]
        task = CaseTask(index=int(index), scene=sweep.scene_dict(case), values=case.values,
                        label=f"case {index}", base_dir=str(sweep.base_dir))
        alone = run(case_scene(task))
        for name, variable in alone.data_vars.items():
            if variable.dtype.kind == "f" and name in result:
                np.testing.assert_allclose(result[name].sel(case=index).values, variable.values,
                                           rtol=1e-9, equal_nan=True, err_msg=f"case {index} {name}")
    return len(picks)


def scaling(folder: Path, cases: int) -> dict:
    """Wall seconds of the first ``cases`` draws on 1 and on 2 workers."""
    sweep_file = folder / "scaling.yaml"
    sweep_file.write_text(SWEEP.format(base=BASE, cases=cases))
    walls = {w: time_sweep(sweep_file, folder / f"scaling-{w}.h5", w)[0] for w in (1, 2)}
    print(f"scaling 1 -> 2 workers on {cases} cases: {walls[1]:.1f} s -> {walls[2]:.1f} s, "
          f"{walls[1] / walls[2]:.2f} x (load {os.getloadavg()[0]:.1f})")
    return {"cases": cases, "one_worker_s": walls[1], "two_workers_s": walls[2]}


def sweeps(folder: Path, cases: int, workers: int, repeats: int, single: float,
           against: Path | None) -> tuple:
    """``repeats`` sweeps of ``cases`` draws from fresh folders, each after a demo run, and as
    many of the checkout ``against`` alternately: (this checkout's rows, the other's, the
    sweep file, this checkout's last result file)."""
    sweep_file = folder / "montecarlo.yaml"
    sweep_file.write_text(SWEEP.format(base=BASE, cases=cases))
    print(f"{'checkout':>10} {'wall s':>8} {'cases/s/worker':>15} {'demo s':>7} {'x demo':>7} "
          f"{'x single':>9} {'CPU s/case':>11} {'load':>6}")
    rows, other = [], []
    for repeat in range(repeats):
        output = folder / f"montecarlo-{repeat}.h5"
        rows.append(sweep_row(ROOT, folder, sweep_file, output, workers, cases, single))
        printed("this", rows[-1], cases, workers)
        if against is not None:
            other.append(sweep_row(against, folder, sweep_file, folder / f"against-{repeat}.h5",
                                   workers, cases, single))
            printed("against", other[-1], cases, workers)
    return rows, other, sweep_file, output


def medians_of(rows: list[dict]) -> dict:
    return {key: statistics.median(row[key] for row in rows) for key in rows[0]}


def checkout_commit(checkout: Path) -> str:
    """The commit checked out in ``checkout``, with '+changes' where its tree differs."""
    def git(*args):
        return subprocess.run(["git", *args], cwd=checkout, capture_output=True,
                              text=True).stdout

    head = git("rev-parse", "--short", "HEAD").strip() or "unknown"
    return head + ("+changes" if git("status", "--porcelain", "--untracked-files=no").strip()
                   else "")


def one_sweep(sweep_file: str, output: str, workers: int) -> None:
    """The ``--one-sweep`` process: one sweep, nothing else."""
    logging.basicConfig(level=logging.ERROR)
    run_sweep(Path(sweep_file), Path(output), workers=workers)


def summary(rows: list[dict], other: list[dict], cases: int, workers: int) -> dict:
    """The medians, printed; with the other checkout's medians and the ratio of the walls."""
    medians = medians_of(rows)
    print(f"median of {len(rows)}: {medians['wall_s']:.1f} s for {cases} cases on {workers} "
          f"workers, {medians['sweep_over_demo_run']:.1f} demo runs of "
          f"{medians['demo_run_s']:.2f} s (target {TARGET_DEMO_RUNS:g} for 1000 on 2), "
          f"{medians['sweep_over_single']:.0f} warm single runs")
    if other:
        theirs = medians_of(other)
        print(f"against: {theirs['wall_s']:.1f} s, {theirs['sweep_over_demo_run']:.1f} demo runs; "
              f"this checkout {theirs['wall_s'] / medians['wall_s']:.2f} x faster")
    return medians


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=1000)
    parser.add_argument("--quick", action="store_true", help="100 cases")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--repeats", type=int, default=3, help="sweeps (median)")
    parser.add_argument("--scaling-cases", type=int, default=0,
                        help="draws run on 1 and on 2 workers for the scaling (0: none)")
    parser.add_argument("--check", type=int, default=20, help="cases compared with single runs")
    parser.add_argument("--against", type=Path, help="another checkout, run side by side")
    parser.add_argument("--one-sweep", nargs=2, metavar=("SWEEP", "OUTPUT"),
                        help=argparse.SUPPRESS)  # one sweep as a whole process (the children)
    args = parser.parse_args(argv)
    if args.one_sweep:
        return one_sweep(*args.one_sweep, args.workers)
    logging.basicConfig(level=logging.ERROR)
    cases = 100 if args.quick else args.cases
    against = args.against.resolve() if args.against else None
    single = single_run_time()
    about = machine()
    print(f"Monte Carlo of {BASE.name}: {cases} cases, {about['cpu']}, {about['cores']} cores, "
          f"load {os.getloadavg()[0]:.1f}; one warm single run {single:.3f} s")
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        scaled = scaling(folder, min(args.scaling_cases, cases)) if args.scaling_cases else None
        rows, other, sweep_file, output = sweeps(folder, cases, args.workers, args.repeats,
                                                 single, against)
        size = output.stat().st_size
        print(f"result file: {size / 1e6:.1f} MB ({size / cases / 1e3:.0f} kB per case); "
              f"this process's peak "
              f"memory {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e3:.0f} MB")
        checked = check_cases(sweep_file, output, min(args.check, cases))
        print(f"{checked} cases of the {args.workers}-worker result equal their single runs")
    medians = summary(rows, other, cases, args.workers)
    record = {"benchmark": f"Monte Carlo of {BASE.name} on {args.workers} workers / one demo "
                           f"run (whole processes)", "target_demo_runs": TARGET_DEMO_RUNS,
              "commit": commit(),
              "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
              "machine": about, "load_average": os.getloadavg()[0], "cases": cases,
              "workers": args.workers, "single_run_s": single, "median": medians,
              "sweeps": rows, "scaling": scaled, "cases_checked_equal_to_single_runs": checked,
              "result_file_mb": size / 1e6}
    if other:
        record["against"] = {"commit": checkout_commit(against), "median": medians_of(other),
                             "sweeps": other}
    RESULT.write_text(json.dumps(record, indent=1) + "\n")
    print(f"wrote {RESULT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
