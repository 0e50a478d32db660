"""Environment history and moisture uptake per part."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .common import days, figure, legend_outside, save_figure


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
    absorbing = [p for p in ds["part"].values if _absorbs(ds, p)]
    for part in absorbing:
        line, = moist_ax.plot(t, ds["moisture_content"].sel(part=part).values, "-o", ms=3,
                              label=str(part))
        if "surface_moisture_content" in ds:
            moist_ax.plot(t, ds["surface_moisture_content"].sel(part=part).values, ":",
                          color=line.get_color())
    if "surface_moisture_content" in ds and absorbing:  # one key for the two line styles
        moist_ax.plot([], [], "k-o", ms=3, label="volume mean")
        moist_ax.plot([], [], "k:", label="surface layer")
    skipped = [str(p) for p in ds["part"].values if p not in absorbing]
    if skipped:
        moist_ax.set_title(f"no moisture uptake: {', '.join(skipped)}", fontsize=9)
    moist_ax.set_xlabel("ageing time [d]")
    moist_ax.set_ylabel("moisture content [wt %]")
    legend_outside(moist_ax)
    moist_ax.grid(alpha=0.3)
    return [save_figure(fig, Path(outdir) / "uptake.png")]


def _absorbs(ds, part) -> bool:
    """A part that takes up moisture (steel and other metals do not: no line for them)."""
    info = ds.attrs.get("diffusion", {})
    if isinstance(info, dict) and info.get(str(part), {}).get("model") == "none":
        return False
    return bool(np.nanmax(np.abs(ds["moisture_content"].sel(part=part).values), initial=0.0) > 0)
