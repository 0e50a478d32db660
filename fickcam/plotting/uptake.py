"""Environment history and moisture uptake per part."""
from __future__ import annotations

from pathlib import Path

from .common import days, figure, save_figure


def plot(ds, outdir) -> list[Path]:
    """Two panels: T and RH over ageing; mean and surface moisture per part."""
    plt = figure()
    t = days(ds)
    fig, (env_ax, moist_ax) = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
    env_ax.plot(t, ds["temperature"].values - 273.15, "r-", label="temperature")
    env_ax.set_ylabel("temperature [degC]", color="r")
    rh_ax = env_ax.twinx()
    rh_ax.plot(t, ds["relative_humidity"].values, "b--", label="relative humidity")
    rh_ax.set_ylabel("relative humidity [%]", color="b")
    env_ax.set_title(f"{ds.attrs.get('scene_name', '')}: environment")
    for part in ds["part"].values:
        line, = moist_ax.plot(t, ds["moisture_content"].sel(part=part).values, "-o", ms=3,
                              label=f"{part} mean")
        if "surface_moisture_content" in ds:
            moist_ax.plot(t, ds["surface_moisture_content"].sel(part=part).values, ":",
                          color=line.get_color(), label=f"{part} surface layer")
    moist_ax.set_xlabel("ageing time [d]")
    moist_ax.set_ylabel("moisture content [wt %]")
    moist_ax.legend(fontsize=8)
    moist_ax.grid(alpha=0.3)
    return [save_figure(fig, Path(outdir) / "uptake.png")]
