"""Daily outputs over a weather year against 10 outputs of the same scene: the run of
each, side by side, and their ratio (the target: at most 3).

    python benchmarks/daily_outputs.py               # 3 runs of each scene
    python benchmarks/daily_outputs.py --repeats 5

Each scene below is aged through Greensboro NC's typical meteorological year (NREL TMY3,
hourly, shipped with pvlib: needs the weather extra) once with ``ageing_times: {every:
1 d}`` (366 outputs, day 0 to day 365) and once with 10 ageing times evenly spread over
the same year. Every run is one ``fickcam.run`` in a fresh Python process (its caches
empty, as a user's run starts), timed from after the imports to the returned dataset
("fresh"), then run again in that process ("warm": the first-use costs paid; a run keeps
its diffusion cache to itself, so the diffusion is solved again); the two
kinds alternate so that a change in the machine's load reaches both. Medians of the
repeats, the ratios of the medians, the machine (CPU model, cores, load average) and the
commit are printed and written to ``benchmarks/results/daily_outputs.json``.
"""
from __future__ import annotations

import argparse
import os
import tempfile
from pathlib import Path

import numpy as np
import yaml

from fickcam.cli.checkout import benchmark

ROOT = Path(__file__).resolve().parents[1]
RESULT = ROOT / "benchmarks" / "results" / "daily_outputs.json"
WEATHER = "pvlib:723170TYA.CSV"
#: (scene, what it is)
SCENES = (("eccentric_cam_greensboro.yaml", "nylon eccentric cam, roller follower"),
          ("fourbar_r914_humid.yaml", "R914 resin four-bar, steel frame"))
POINTS = benchmark("points_cam", ROOT)  # machine(), one_run(), write_record(), TIMED_RUNS
ONE_RUN = POINTS.TIMED_RUNS + """
print(json.dumps({"seconds": seconds, "again": again, "outputs": result.sizes["time"]}))
"""


def year_scene(name: str, folder: Path, ageing_times) -> Path:
    """A copy of configs/``name`` aged through the TMY3 year with ``ageing_times``."""
    scene = yaml.safe_load((ROOT / "configs" / name).read_text())
    environment = scene["environment"]
    for key in ("history", "initial_moisture"):
        environment.pop(key, None)
    environment["history_file"] = WEATHER
    scene["outputs"]["ageing_times"] = ageing_times
    scene["outputs"].pop("file", None)
    label = "daily" if isinstance(ageing_times, dict) else "ten"
    copy = folder / f"{Path(name).stem}_{label}.yaml"
    copy.write_text(yaml.safe_dump(scene))
    return copy


def compare(name: str, folder: Path, repeats: int) -> dict:
    """Median seconds of ``repeats`` runs of each kind and their ratio."""
    daily_yaml = year_scene(name, folder, {"every": "1 d"})
    ten_yaml = year_scene(name, folder, [f"{day:.4g} d" for day in np.linspace(0, 365, 10)])
    daily, ten = [], []
    for _ in range(repeats):
        ten.append(POINTS.one_run(ten_yaml, ONE_RUN))
        daily.append(POINTS.one_run(daily_yaml, ONE_RUN))
    return {"scene": f"configs/{name}", "weather": WEATHER, "runs": repeats,
            "outputs": {"daily": daily[-1]["outputs"], "ten": ten[-1]["outputs"]}} | \
        POINTS.medians(ten, daily, ("ten_outputs", "daily_outputs"))


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3, help="runs of each scene (median)")
    args = parser.parse_args(argv)
    about = POINTS.announced_machine()
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for name, kind in SCENES:
            row = compare(name, Path(folder), args.repeats) | {"what": kind}
            rows.append(row)
            for what in ("fresh", "warm"):
                timing = row[what]
                print(f"{name:30s} {what}: 10 outputs {timing['ten_outputs_s']:6.3f} s, "
                      f"{row['outputs']['daily']} daily {timing['daily_outputs_s']:6.3f} s, "
                      f"ratio {timing['ratio']:5.2f}")
    POINTS.write_record(RESULT, "daily outputs over a TMY3 year / 10 outputs, one run each",
                        3.0, about, rows)


if __name__ == "__main__":
    main()
