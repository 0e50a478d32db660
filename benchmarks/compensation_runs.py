"""The cost of `fickcam compensate` as a number of runs of the same scene (the targets:
``--at`` at most 3 runs, ``--over`` two years at most 10).

    python benchmarks/compensation_runs.py               # 5 repeats
    python benchmarks/compensation_runs.py --repeats 3

Two scenes, each made to age for two years: configs/eccentric_cam.yaml (a nylon
eccentric cam, given a limit on the follower displacement of 0.1 mm) and
configs/fourbar_r914_humid.yaml (an R914 four-bar with its own limits). For each, one
``fickcam.run`` of the scene, ``fickcam.compensate(scene, at="6 months")``,
``compensate(scene, over=("0 d", "2 years"))`` and the same with ``plot=True`` (what
``--plot`` adds to the runs; the PNG itself is not drawn) are each timed in a fresh
Python process (caches empty, as a user's command starts), from after the imports to the
returned result ("fresh"), and in another process after a run of a copy 10 % thicker
("warm": the imports and first-use costs paid, the solvers' caches holding nothing of this
scene's shapes: a designer's next compensation in a session or a notebook); they alternate
within a repeat so that a change in the machine's load reaches all. The diffusion solves of each are counted from the solver's debug records.
Medians of the repeats, the ratios to the run's median, the machine (CPU model, cores,
load average) and the commit are printed and written to
``benchmarks/results/compensation_runs.json``.
"""
from __future__ import annotations

import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import yaml

from points_cam import announced_machine, commit  # the sibling benchmark's machine stamp

ROOT = Path(__file__).resolve().parents[1]
RESULT = ROOT / "benchmarks" / "results" / "compensation_runs.json"
#: (scene, limits added to it)
SCENES = (("eccentric_cam.yaml", {"follower_displacement": {"deviation": "0.1 mm"}}),
          ("fourbar_r914_humid.yaml", None))
HISTORY = "2 years"
#: what each fresh process times: keyword arguments of compensate, or None for a run
WORK = {"run": None, "at": {"at": "6 months"}, "over": {"over": ("0 d", HISTORY)},
        "over_plot": {"over": ("0 d", HISTORY), "plot": True}}
ONE = """
import json, logging, sys, time
import fickcam
from fickcam.compensation import compensate

solves = []
handler = logging.Handler(logging.DEBUG)
handler.emit = solves.append
logger = logging.getLogger("fickcam.diffusion.dispatch")
logger.setLevel(logging.DEBUG)
logger.addHandler(handler)
scene = fickcam.load_scene(sys.argv[1])
work = json.loads(sys.argv[2])
if len(sys.argv) > 3:  # warm: imports and first uses paid on another shape
    fickcam.run(sys.argv[3])
    solves.clear()
started = time.perf_counter()
fickcam.run(scene) if work is None else compensate(scene, **work)
print(json.dumps({"seconds": time.perf_counter() - started, "solves": len(solves)}))
"""


def two_year_scene(name: str, limits: dict | None, folder: Path,
                   thicker: bool = False) -> Path:
    """A copy of configs/``name`` whose climate lasts two years (its first step held; a
    list of ageing times gains the end), with ``limits`` added, no output file;
    ``thicker``: its cam or links 10 % thicker (the warm-up of a warm measurement)."""
    scene = yaml.safe_load((ROOT / "configs" / name).read_text())
    step = scene["environment"]["history"][0]
    scene["environment"]["history"] = [dict(step, duration=HISTORY)]
    scene["outputs"].pop("file", None)
    if isinstance(scene["outputs"]["ageing_times"], list):
        scene["outputs"]["ageing_times"].append(HISTORY)
    if limits:
        scene["limits"] = limits
    if thicker:
        body = scene["cam"] if "cam" in scene else scene["linkage"]["section"]
        millimetres = float(body["thickness"].removesuffix("mm"))
        body["thickness"] = f"{millimetres * 1.1:g} mm"
    path = folder / (("thicker_" if thicker else "") + name)
    path.write_text(yaml.safe_dump(scene, sort_keys=False))
    return path


def timed(scene: Path, work, warm_up: Path | None = None) -> dict:
    """Seconds and diffusion solves of ``work`` (WORK) on ``scene`` in a fresh process,
    after a run of ``warm_up`` when given."""
    extra = [str(warm_up)] if warm_up else []
    done = subprocess.run([sys.executable, "-c", ONE, str(scene), json.dumps(work), *extra],
                          capture_output=True, text=True, check=True, cwd=scene.parent)
    return json.loads(done.stdout.splitlines()[-1])


def measure(scene: Path, warm_up: Path, repeats: int) -> dict:
    """Median seconds (fresh and warm) of each WORK over ``repeats``, the ratios to the
    run's, the diffusion solves."""
    found = {kind: {what: [] for what in WORK} for kind in ("fresh", "warm")}
    for _ in range(repeats):
        for what, work in WORK.items():
            found["fresh"][what].append(timed(scene, work))
            found["warm"][what].append(timed(scene, work, warm_up))
    row = {}
    for kind, runs in found.items():
        medians = {what: statistics.median(r["seconds"] for r in rows) for what, rows in runs.items()}
        row[kind] = {what: {"median_s": medians[what], "runs_worth": medians[what] / medians["run"],
                            "seconds": [r["seconds"] for r in rows],
                            "diffusion_solves": rows[-1]["solves"]}
                     for what, rows in runs.items()}
    return row


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5, help="repeats of each (median)")
    args = parser.parse_args(argv)
    load = os.getloadavg()
    about = announced_machine()
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for name, limits in SCENES:
            row = {"scene": f"configs/{name}", "history": HISTORY, "limits_added": limits,
                   "repeats": args.repeats} | measure(
                two_year_scene(name, limits, Path(folder)),
                two_year_scene(name, limits, Path(folder), thicker=True), args.repeats)
            rows.append(row)
            for kind in ("fresh", "warm"):
                timing = row[kind]
                print(f"{name} {kind}: run {timing['run']['median_s']:.3f} s; " + ", ".join(
                    f"{what} {timing[what]['median_s']:.3f} s = {timing[what]['runs_worth']:.2f}"
                    f" runs ({timing[what]['diffusion_solves']} solves)" for what in WORK
                    if what != "run"))
    record = {"benchmark": "fickcam compensate --at / --over two years, in runs of the scene",
              "target_runs": {"at": 3, "over": 10}, "commit": commit(),
              "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
              "machine": about, "load_average": {"start": load[0], "end": os.getloadavg()[0]},
              "scenes": rows}
    RESULT.write_text(json.dumps(record, indent=1) + "\n")
    print(f"wrote {RESULT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
