"""A cam given by points against the same cam given in closed form: the run of each,
side by side, and their ratio (the target: at most 2).

    python benchmarks/points_cam.py               # 5 runs of each scene
    python benchmarks/points_cam.py --repeats 3

For each scene below, ``fickcam profile`` writes the cam's dry working profile as points
(3,600 by default, as ``fickcam compensate --points`` writes them) and a copy of the
scene reads them through ``cam.profile_file``. Every run is one ``fickcam.run`` in a
fresh Python process (its own caches empty, as a user's run starts), timed from after
the imports to the returned dataset ("fresh"), then run again in that process ("warm":
the first-use costs paid; a run keeps its diffusion cache to itself, so the diffusion is
solved again); the two kinds alternate so that a change in the machine's load reaches
both. Medians of the repeats, the ratios of the medians, the
machine (CPU model, cores, load average) and the commit are printed and written to
``benchmarks/results/points_cam.json``. The results of the two kinds are also compared
(the largest difference of the follower displacement, or arm angle, over its lift,
and of the jump speeds).
"""
from __future__ import annotations

import argparse
import contextlib
import datetime
import io
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
RESULT = ROOT / "benchmarks" / "results" / "points_cam.json"
#: (scene, what its cam is given by)
SCENES = (("eccentric_cam.yaml", "eccentric disc"),
          ("nylon_swinging_arm.yaml", "motion program, swinging arm"),
          ("singh2017_cam.yaml", "motion program, CFRP"))
LAWS = ("eccentric", "motion", "base_circle_radius")
#: a fresh process's run of the scene named by its argument: ``result``, ``seconds`` (the
#: first run, after the imports) and ``again`` (the same run warm)
TIMED_RUNS = """
import json, sys, time
import numpy as np
import scipy.interpolate, scipy.optimize
import fickcam, fickcam.simulation.simulate
scene = fickcam.load_scene(sys.argv[1])
started = time.perf_counter()
result = fickcam.run(scene)
seconds = time.perf_counter() - started
started = time.perf_counter()
fickcam.run(scene)
again = time.perf_counter() - started
"""
ONE_RUN = TIMED_RUNS + """
motion = result["follower_displacement" if "follower_displacement" in result
                else "follower_arm_angle"].values
print(json.dumps({"seconds": seconds, "again": again, "motion": motion.tolist(),
                  "lift": float(np.max(np.ptp(motion, axis=-1))),
                  "jump_speed": result["jump_speed"].values.tolist()}))
"""


def machine() -> dict:
    """CPU model, logical cores, Python and platform of this machine."""
    model = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as handle:
            model = next(line.split(":", 1)[1].strip() for line in handle
                         if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return {"cpu": model, "cores": os.cpu_count(), "python": platform.python_version(),
            "platform": platform.platform()}


def announced_machine() -> dict:
    """:func:`machine`, printed with the load average (other work skews wall times)."""
    about = machine()
    print(f"machine: {about['cpu']}, {about['cores']} logical cores, Python {about['python']}; "
          f"load average {os.getloadavg()[0]:.2f} (other work skews wall times)")
    return about


def commit() -> str:
    """The checked-out commit, with '+changes' if the work tree differs from it."""
    def git(*args):
        return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True).stdout

    head = git("rev-parse", "--short", "HEAD").strip() or "unknown"
    return head + ("+changes" if git("status", "--porcelain", "--untracked-files=no").strip()
                   else "")


def points_scene(name: str, folder: Path) -> Path:
    """A copy of configs/``name`` whose cam is its own dry profile written by
    ``fickcam profile`` (default points)."""
    from fickcam.cli.main import main

    source = ROOT / "configs" / name
    points = folder / (source.stem + "_points.csv")
    with contextlib.redirect_stdout(io.StringIO()):  # its 'wrote ...' line
        main(["profile", "-q", str(source), "-o", str(points)])
    scene = yaml.safe_load(source.read_text())
    for key in LAWS:
        scene["cam"].pop(key, None)
    scene["cam"]["profile_file"] = str(points)
    copy = folder / (source.stem + "_points.yaml")
    copy.write_text(yaml.safe_dump(scene))
    return copy


def one_run(scene: Path, program: str = ONE_RUN) -> dict:
    """Seconds of one run in a fresh process, and what it found (the last line that
    ``program``, given the scene's path, prints: JSON)."""
    done = subprocess.run([sys.executable, "-c", program, str(scene)], capture_output=True,
                          text=True, check=True, cwd=scene.parent)
    return json.loads(done.stdout.splitlines()[-1])


def compare(name: str, points_yaml: Path, repeats: int) -> dict:
    """Median seconds of ``repeats`` runs of each kind, their ratio and the differences."""
    closed_yaml = ROOT / "configs" / name
    closed, points = [], []
    for _ in range(repeats):
        closed.append(one_run(closed_yaml))
        points.append(one_run(points_yaml))
    a, b = closed[-1], points[-1]
    gap = max(abs(x - y) for row_a, row_b in zip(a["motion"], b["motion"])
              for x, y in zip(row_a, row_b))
    jump = max(abs(x / y - 1) for x, y in zip(b["jump_speed"], a["jump_speed"]))
    row = {"scene": f"configs/{name}", "runs": repeats} | medians(closed, points)
    return row | {"motion_difference_over_lift": gap / a["lift"],
                  "jump_speed_relative_difference": jump}


def medians(reference: list, other: list, names=("closed_form", "points")) -> dict:
    """Per kind of timing ("fresh": the first run, "warm": again): the median seconds of
    the ``reference`` and ``other`` runs, their ratio other / reference, every run's."""
    row = {}
    for run, what in (("seconds", "fresh"), ("again", "warm")):
        low, high = (statistics.median(r[run] for r in runs) for runs in (reference, other))
        row[what] = {f"{names[0]}_s": low, f"{names[1]}_s": high, "ratio": high / low,
                     f"{names[0]}_runs_s": [r[run] for r in reference],
                     f"{names[1]}_runs_s": [r[run] for r in other]}
    return row


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5, help="runs of each scene (median)")
    args = parser.parse_args(argv)
    about = announced_machine()
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for name, kind in SCENES:
            row = compare(name, points_scene(name, Path(folder)), args.repeats) | {"cam": kind}
            rows.append(row)
            for what in ("fresh", "warm"):
                timing = row[what]
                print(f"{name:24s} {what}: closed form {timing['closed_form_s']:6.3f} s, points "
                      f"{timing['points_s']:6.3f} s, ratio {timing['ratio']:5.2f}")
            print(f"{'':24s} ({kind}; points - closed form: motion "
                  f"{row['motion_difference_over_lift']:.1e} of the lift, jump speed "
                  f"{row['jump_speed_relative_difference']:.1e} relative)")
    write_record(RESULT, "cam given by points / the same cam in closed form, one run each",
                 2.0, about, rows)


def write_record(path: Path, what: str, target: float, about: dict, rows: list) -> None:
    """Write the benchmark's rows as JSON with the commit, date, machine and load."""
    record = {"benchmark": what, "target_ratio": target, "commit": commit(),
              "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
              "machine": about, "load_average": os.getloadavg()[0], "scenes": rows}
    path.write_text(json.dumps(record, indent=1) + "\n")
    print(f"wrote {path.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
