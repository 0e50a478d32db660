"""Wall time of the example sweep (configs/sweep_singh2017_climate.yaml, 9 cases)
on a LocalCluster of 1 and of 2 worker processes.

    python benchmarks/bench_sweep.py [--workers 1 2] [--sweep PATH]

Each run starts its own cluster (start-up included: that is what a user waits
for) and writes to a fresh temporary folder, so nothing is resumed. Prints one
line per worker count: the wall time, the speed-up relative to the first count,
the sum of the cases' own wall times ("cases s"; its ratio to the wall time is
the parallelism reached) and the load average when the run started (other work
on the machine skews the ratio).
"""
from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

from fickcam.store import open_result
from fickcam.sweep import run_sweep

ROOT = Path(__file__).resolve().parents[1]


def time_sweep(sweep: Path, workers: int) -> tuple[float, int, int, float]:
    """(wall time in s, cases, failed cases, summed case wall times in s) of one sweep."""
    with tempfile.TemporaryDirectory() as folder:
        output = Path(folder) / "sweep.h5"
        started = time.perf_counter()
        run_sweep(sweep, output, workers=workers)
        wall = time.perf_counter() - started
        result = open_result(output)
        return (wall, result.sizes["case"], int((result["case_status"] != "ok").sum()),
                float(result["case_wall_time"].sum()))


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--sweep", type=Path, default=ROOT / "configs" / "sweep_singh2017_climate.yaml")
    args = parser.parse_args(argv)
    timings = {}
    print(f"sweep {args.sweep.name}, {os.cpu_count()} cores")
    print(f"{'workers':>8} {'cases':>6} {'failed':>7} {'wall s':>8} {'speed-up':>9} "
          f"{'cases s':>8} {'load':>6}")
    for workers in args.workers:
        load = os.getloadavg()[0]
        wall, cases, failed, case_sum = time_sweep(args.sweep, workers)
        timings[workers] = wall
        speedup = timings[args.workers[0]] / wall
        print(f"{workers:>8} {cases:>6} {failed:>7} {wall:>8.2f} {speedup:>9.2f} "
              f"{case_sum:>8.2f} {load:>6.1f}", flush=True)


if __name__ == "__main__":
    main()
