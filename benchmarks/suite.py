"""The test suite against demo runs, side by side: the README's test command (its pytest
part, in this environment) and the slow tier, each as a ratio to one demo run (the
target: the README's command within 150 demo runs).

    python benchmarks/suite.py                  # 3 demo runs before and after each tier
    python benchmarks/suite.py --tiers quick --demos 5

Absolute seconds differ several-fold between machines and with their load, so the figure
is the ratio to ``fickcam run configs/singh2017_cam.yaml`` run as a whole process just
before and just after each tier (the median of those runs). The install step of the
README's command is left out (it depends on the network, not on the code). Each tier runs
as a whole process (wall, and the CPU seconds of it and its workers); its last line
(passed, skipped, deselected) is kept. The medians, ratios, machine and commit are written
to ``benchmarks/results/suite.json``.
"""
from __future__ import annotations

import argparse
import os
import re
import shlex
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from points_cam import announced_machine
from stamp import write_result
from startup import demo_command, timed

ROOT = Path(__file__).resolve().parents[1]
RESULT = ROOT / "benchmarks" / "results" / "suite.json"
TARGET_DEMO_RUNS = 150


def readme_pytest() -> list[str]:
    """The pytest arguments of the README's test command (its fifth line, after the last
    ``&&``), the command CI runs."""
    line = (ROOT / "README.md").read_text().splitlines()[4]
    command = shlex.split(line.split("&&")[-1])
    if command[0] != "pytest":
        raise SystemExit(f"README line 5 does not end in a pytest command: {line}")
    return command[1:]


def tiers() -> dict[str, list[str]]:
    """Tier name -> pytest arguments: the README's command, and the slow tier CI adds."""
    quick = readme_pytest()
    slow = [*quick, "-m", "slow"] if "-m" not in quick else [
        "slow" if before == "-m" else a for before, a in zip(["", *quick], quick)]
    return {"quick": quick, "slow": slow}


def run_tier(arguments: list[str]) -> tuple[float, float, str]:
    """(wall s, CPU s of pytest and its workers, pytest's last line and the tests that
    failed, named) of one tier."""
    command = [sys.executable, "-m", "pytest", *arguments, "-p", "no:cacheprovider", "-rfE"]
    print("+ " + " ".join(command[2:]), flush=True)
    with tempfile.TemporaryFile("w+") as out:
        wall, cpu = timed(command, stdout=out, check=False)
        out.seek(0)
        lines = [line.strip() for line in out if line.strip()]
    counted = [line for line in lines if re.search(r"\d+ (passed|failed|error|deselected)", line)]
    failed = [line.split()[1] for line in lines if line.startswith(("FAILED ", "ERROR "))]
    outcome = (counted or lines or ["no output"])[-1].strip("= ")
    return wall, cpu, outcome + (f"; failed: {', '.join(failed)}" if failed else "")


def demo_runs(output: Path, count: int) -> list[tuple[float, float]]:
    return [timed(demo_command(output)) for _ in range(count)]


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--demos", type=int, default=3,
                        help="demo runs before and after each tier (median of all)")
    parser.add_argument("--tiers", nargs="+", choices=("quick", "slow"),
                        default=["quick", "slow"])
    args = parser.parse_args(argv)
    announced_machine()
    load_at_start = os.getloadavg()[0]
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        output = Path(folder) / "cam.h5"
        timed(demo_command(output))  # the OS's file cache warm
        for name in args.tiers:
            arguments = tiers()[name]
            before = demo_runs(output, args.demos)
            wall, cpu, outcome = run_tier(arguments)
            demos = before + demo_runs(output, args.demos)
            demo_wall = statistics.median(w for w, _ in demos)
            demo_cpu = statistics.median(c for _, c in demos)
            print(f"{name}: {wall:.0f} s wall, {cpu:.0f} CPU s; demo run {demo_wall:.2f} s "
                  f"wall, {demo_cpu:.2f} CPU s; {wall / demo_wall:.0f} demo runs ({outcome})")
            rows.append([f"`pytest {shlex.join(arguments)}`", f"{wall:.0f}", f"{cpu:.0f}",
                         f"{demo_wall:.2f}", f"{wall / demo_wall:.0f}",
                         f"{cpu / demo_cpu:.0f}", outcome])
    columns = ["tier", "wall s", "CPU s (all workers)", "demo run wall s (median)",
               "wall / demo run", "CPU / demo run CPU", "outcome"]
    note = (f"Target: the README's command (the first row) within {TARGET_DEMO_RUNS} demo "
            f"runs; {2 * args.demos} demo runs around each tier.")
    write_result(RESULT, "the test suite's tiers against demo runs, side by side",
                 "python benchmarks/suite.py",
                 {"suite": {"columns": columns, "rows": rows, "note": note}}, load_at_start)


if __name__ == "__main__":
    main()
