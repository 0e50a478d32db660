"""The demo cam's skin against its bulk through Greensboro NC's TMY3 year.

    python benchmarks/greensboro_skin_bulk.py [--out docs/images/greensboro_skin_bulk.png]

Ages the demo cam (configs/singh2017_cam.yaml, carbon/epoxy) through the hourly rows of
Greensboro's typical meteorological year (``pvlib:723170TYA.CSV``, needs the weather
extra) and draws the moisture of its 0.5 mm contact layer (the skin) and of its whole
volume (the bulk) with the equilibrium value of the air: daily over the year, and hourly
over a week of July. Diffusion only (``fickcam.diffusion.solve``, the plane model, the
record superposed by the tabulated sum), so hundreds of output times cost seconds.
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
import yaml

ROOT = Path(__file__).resolve().parents[1]
HOUR, DAY = 3600.0, 86400.0
JULY_WEEK = (182.0, 189.0)  # days from 1 January


def skin_and_bulk(times: np.ndarray):
    """(mean, skin, equilibrium) moisture in weight % of the demo cam at ``times`` (s)."""
    from fickcam.diffusion import solve
    from fickcam.scene.load import load_scene

    data = yaml.safe_load((ROOT / "configs" / "singh2017_cam.yaml").read_text())
    data["environment"] = {"reference_temperature": "23 degC",
                           "history_file": "pvlib:723170TYA.CSV"}
    data["outputs"] = {"ageing_times": [f"{times[-1] / DAY:g} d"]}
    scene = load_scene(data)
    environment = scene.environment
    cam = next(part for part in scene.parts if part.name == "cam")
    exposure = environment.exposure(cam.material.saturation_moisture)
    result = solve(cam.geometry, cam.material.diffusivity_for(cam.geometry), exposure, times,
                   accuracy=scene.model.diffusion.accuracy, part="cam")
    return result, exposure.surface_moisture(times)


def draw(times, result, equilibrium, out: Path) -> Path:
    from fickcam.plotting.common import figure, save_figure

    plt = figure()
    days = times / DAY
    fig, (year, week) = plt.subplots(2, 1, figsize=(8, 6.5), layout="constrained")
    daily = np.isclose(days % 1.0, 0.0) | np.isclose(days % 1.0, 1.0)
    for ax, chosen, step in ((year, daily, "daily"),
                             (week, (days >= JULY_WEEK[0]) & (days <= JULY_WEEK[1]), "hourly")):
        ax.plot(days[chosen], equilibrium[chosen], color="0.75", lw=0.8,
                label="equilibrium with the air")
        ax.plot(days[chosen], result.surface[chosen], "C3-", lw=1.2, label="skin (0.5 mm layer)")
        ax.plot(days[chosen], result.mean[chosen], "C0-", lw=1.6, label="bulk (volume mean)")
        ax.set_ylabel("moisture [wt %]")
        ax.grid(alpha=0.3)
        ax.set_title(f"demo cam, Greensboro NC TMY3 ({step} values)", fontsize=10)
    year.set_xlabel("day of the year")
    week.set_xlabel("day of the year (a week of July)")
    year.legend(fontsize=8, loc="upper left")
    return save_figure(fig, out)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "docs/images/greensboro_skin_bulk.png")
    args = parser.parse_args()
    times = np.unique(np.concatenate([np.arange(0.0, 365.0) * DAY,
                                      np.arange(JULY_WEEK[0] * 24, JULY_WEEK[1] * 24 + 1) * HOUR]))
    start = time.process_time()
    result, equilibrium = skin_and_bulk(times)
    cost = time.process_time() - start
    print(f"{times.size} output times, {result.model} model, estimate {result.error_estimate:.1e}, "
          f"{cost:.1f} CPU s")
    print(f"wrote {draw(times, result, equilibrium, args.out)}")


if __name__ == "__main__":
    main()
