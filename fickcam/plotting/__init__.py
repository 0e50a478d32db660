"""Figures (PNG) from a result Dataset; one module per kind of plot.

Each module exposes functions ``(ds, outdir) -> list[Path]``; matplotlib is
imported inside them (Agg backend), so ``import fickcam.plotting`` stays light.
"""
from __future__ import annotations

import importlib
from pathlib import Path

from ..errors import InputError

# kind -> (module, function, variables the kind needs)
KINDS = {
    "uptake": ("uptake", "plot", ("moisture_content",)),
    "kinematics": ("cam", "plot_kinematics", ("follower_displacement",)),
    "dynamics": ("cam", "plot_dynamics", ("contact_force",)),
    "vibration": ("train", "plot", ("dynamic_contact_force",)),
    "linkage": ("linkage", "plot", ("rocker_angle",)),
    "fields": ("fields", "plot", ("moisture",)),
    "limits": ("limits", "plot", ("limit_ratio",)),
    "sweep": ("sweep", "plot", ("case",)),
}


def available_kinds(ds) -> list[str]:
    """The plot kinds this result has data for."""
    if "case" in ds.dims:  # a sweep result: one figure set over its varied parameters
        return ["sweep"]
    names = set(ds.variables)
    return [k for k, (_, _, needs) in KINDS.items() if k != "sweep" and all(n in names for n in needs)]


def plot(ds, outdir, kind: str = "all") -> list[Path]:
    """Write the figures of ``kind`` (or every kind the result supports) to ``outdir``."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    kinds = available_kinds(ds) if kind == "all" else [kind]
    if kind != "all":
        if kind not in KINDS:
            raise InputError(f"unknown plot kind {kind!r} (one of: {', '.join(KINDS)}, all)")
        if kind not in available_kinds(ds):
            raise InputError(f"this result has no data for --kind {kind} "
                             f"(available: {', '.join(available_kinds(ds)) or 'none'})")
    written: list[Path] = []
    for name in kinds:
        module_name, function, _ = KINDS[name]
        module = importlib.import_module(f".{module_name}", __name__)
        written += getattr(module, function)(ds, outdir)
    return written


def figure():
    """A new (figure, pyplot) pair on the Agg backend (no display needed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def days(ds):
    """Ageing times of ``ds`` in days (float array)."""
    import numpy as np

    return ds["time"].values / np.timedelta64(1, "D")


def ages(ds, most: int = 4) -> list[int]:
    """Indices of up to ``most`` ageing times spread from the first to the last."""
    import numpy as np

    n = ds.sizes["time"]
    return sorted(set(np.linspace(0, n - 1, min(n, most)).round().astype(int).tolist()))


def age_label(t_days: float) -> str:
    """Legend text of an ageing time in days."""
    return f"t = {t_days:g} d"


def finish_plan_view(ax, title: str) -> None:
    """Equal-aspect x-y axes in mm with title, legend and grid (profiles, coupler curves)."""
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(title)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)


def save_figure(fig, path: Path) -> Path:
    fig.savefig(path, dpi=120, bbox_inches="tight")
    import matplotlib.pyplot as plt

    plt.close(fig)
    return path
