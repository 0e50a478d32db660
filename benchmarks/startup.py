"""Start-up: the demo run as a whole process against the import floor, side by side, and
their ratio (the target: at most 1.5 x the floor).

    python benchmarks/startup.py               # 7 runs of each
    python benchmarks/startup.py --repeats 3

The demo run is ``fickcam run configs/singh2017_cam.yaml`` (its result written to a
temporary folder), the floor a process that only imports what any run needs: numpy,
scipy.sparse, scipy.special, xarray, h5netcdf, pint, pydantic and yaml. The two alternate,
so that a change in the machine's load reaches both; each is timed as a whole process
(wall, and the CPU seconds of the child, which other work on the machine skews less). The
package's bytecode is compiled first, as an install has it (``PYTHONDONTWRITEBYTECODE``
would otherwise make every run compile fickcam's sources). Then one more demo run under
``python -X importtime`` gives the import seconds of the packages the demo imports beyond
the floor. Medians, the ratios of the medians, the machine and the commit are printed and
written to ``benchmarks/results/startup.json``.
"""
from __future__ import annotations

import argparse
import collections
import compileall
import datetime
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from points_cam import announced_machine, commit  # the sibling benchmark's machine stamp

ROOT = Path(__file__).resolve().parents[1]
RESULT = ROOT / "benchmarks" / "results" / "startup.json"
DEMO = ROOT / "configs" / "singh2017_cam.yaml"
FLOOR_IMPORTS = "numpy, scipy.sparse, scipy.special, xarray, h5netcdf, pint, pydantic, yaml"
#: the demo run at most this many times the floor (CPU and wall, medians)
TARGET_RATIO = 1.5
#: one ``-X importtime`` line: self and cumulative microseconds, the indented module name
IMPORT_LINE = re.compile(r"import time:\s+(\d+) \|\s+(\d+) \|( *)(\S+)")


def demo_command(output: Path) -> list[str]:
    """The demo run as the ``fickcam`` command runs it."""
    return [sys.executable, "-m", "fickcam.cli.main", "run", str(DEMO), "-o", str(output)]


def floor_command() -> list[str]:
    return [sys.executable, "-c", f"import {FLOOR_IMPORTS}"]


def timed(command: list[str], stdout=subprocess.DEVNULL, check: bool = True) -> tuple[float, float]:
    """(wall s, CPU s of it and the processes it waited for) of ``command`` as a whole
    process; its output to ``stdout`` (a file) or nowhere."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    started = time.perf_counter()
    subprocess.run(command, check=check, stdout=stdout, stderr=subprocess.STDOUT
                   if stdout is not subprocess.DEVNULL else subprocess.DEVNULL, cwd=ROOT)
    wall = time.perf_counter() - started
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)


def imports_beyond_floor(output: Path, shown: int = 12) -> dict[str, float]:
    """Seconds of import (``-X importtime`` self times, summed per top-level package, its
    own overhead included) of the modules the demo run imports and the floor does not."""
    def self_times(command):
        done = subprocess.run([command[0], "-X", "importtime", *command[1:]], check=True,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                              cwd=ROOT)
        return {m.group(4): int(m.group(1)) * 1e-6
                for m in map(IMPORT_LINE.match, done.stderr.splitlines()) if m}

    floor = self_times(floor_command())
    packages = collections.Counter()
    for module, seconds in self_times(demo_command(output)).items():
        if module not in floor:
            top = module.split(".")[0]
            packages[".".join(module.split(".")[:2]) if top == "fickcam" else top] += seconds
    return dict(packages.most_common(shown))


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7, help="runs of each (median)")
    args = parser.parse_args(argv)
    compileall.compile_dir(ROOT / "fickcam", quiet=1)
    about = announced_machine()
    runs: dict[str, list[tuple[float, float]]] = {"floor": [], "demo": []}
    with tempfile.TemporaryDirectory() as folder:
        output = Path(folder) / "cam.h5"
        timed(demo_command(output))  # the OS's file cache warm for both
        for _ in range(args.repeats):
            runs["floor"].append(timed(floor_command()))
            runs["demo"].append(timed(demo_command(output)))
        imports = imports_beyond_floor(output)
    row = {kind: {"wall_s": statistics.median(w for w, _ in timings),
                  "cpu_s": statistics.median(c for _, c in timings),
                  "wall_runs_s": [w for w, _ in timings], "cpu_runs_s": [c for _, c in timings]}
           for kind, timings in runs.items()}
    row["ratio_wall"] = row["demo"]["wall_s"] / row["floor"]["wall_s"]
    row["ratio_cpu"] = row["demo"]["cpu_s"] / row["floor"]["cpu_s"]
    row["imports_beyond_floor_s"] = imports
    for kind, what in (("floor", f"import {FLOOR_IMPORTS}"), ("demo", "fickcam run (demo)")):
        print(f"{what:80s} wall {row[kind]['wall_s']:.3f} s  CPU {row[kind]['cpu_s']:.3f} s")
    print(f"demo / floor: wall {row['ratio_wall']:.2f}, CPU {row['ratio_cpu']:.2f}; "
          f"target: at most {TARGET_RATIO} x the floor")
    print("imports beyond the floor (-X importtime, s): "
          + ", ".join(f"{name} {seconds:.3f}" for name, seconds in imports.items()))
    record = {"benchmark": "demo run as a whole process / importing what any run needs",
              "target_ratio": TARGET_RATIO, "commit": commit(),
              "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
              "machine": about, "load_average": os.getloadavg()[0], "runs": args.repeats,
              "command": f"fickcam run {DEMO.relative_to(ROOT)}", "floor": f"import {FLOOR_IMPORTS}",
              **row}
    RESULT.write_text(json.dumps(record, indent=1) + "\n")
    print(f"wrote {RESULT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
