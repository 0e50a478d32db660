"""Helpers every plot module shares: the figure factory, ageing times in days, labels,
the plan-view finisher and the atomic save."""
from __future__ import annotations

from pathlib import Path


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
