"""The example climate grid (configs/sweep_singh2017_climate.yaml, 9 cases) against
single runs of its base scene, each as a whole `fickcam` process, as a user runs them.

    python benchmarks/bench_sweep.py [--workers 1 2] [--singles 3]

Prints, per worker count, the wall time and the CPU time (the process and every
process it started: rusage of the children, so other work on a shared machine
does not count) of `fickcam sweep --workers N`, and the same for one
`fickcam run` of the base scene (median of ``--singles`` runs); then the sweep's
cost in single runs. The target: the 9 cases on 1 worker cost less than
3 single runs. The load average is printed because other work skews wall times.
"""
from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SWEEP = ROOT / "configs" / "sweep_singh2017_climate.yaml"
BASE = ROOT / "configs" / "singh2017_cam.yaml"


def children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed(args: list[str]) -> tuple[float, float]:
    """(wall s, CPU s) of `python -m fickcam.cli.main ARGS` and everything it started."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    cpu, started = children_cpu(), time.perf_counter()
    subprocess.run([sys.executable, "-m", "fickcam.cli.main", *args], env=env, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - started, children_cpu() - cpu


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workers", type=int, nargs="+", default=[1])
    parser.add_argument("--singles", type=int, default=3)
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as folder:
        singles = [timed(["run", str(BASE), "-o", f"{folder}/single.h5", "--quiet"])
                   for _ in range(args.singles)]
        wall1 = statistics.median(w for w, _ in singles)
        cpu1 = statistics.median(c for _, c in singles)
        print(f"{SWEEP.name} (9 cases) against `fickcam run {BASE.name}`, {os.cpu_count()} cores, "
              f"load {os.getloadavg()[0]:.1f}")
        print(f"one single run: wall {wall1:.2f} s, CPU {cpu1:.2f} s (median of {args.singles})")
        print(f"{'workers':>8} {'wall s':>8} {'CPU s':>8} {'wall/single':>12} {'CPU/single':>11} "
              f"{'load':>6}")
        for workers in args.workers:
            load = os.getloadavg()[0]
            wall, cpu = timed(["sweep", str(SWEEP), "--workers", str(workers), "-o",
                               f"{folder}/sweep-{workers}.h5", "--quiet"])
            print(f"{workers:>8} {wall:>8.2f} {cpu:>8.2f} {wall / wall1:>12.2f} {cpu / cpu1:>11.2f} "
                  f"{load:>6.1f}", flush=True)


if __name__ == "__main__":
    main()
