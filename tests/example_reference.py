"""Compact references of the example scenes' results: every variable of each result at a
fixed subsample of its coordinates, so that a test can compare a run of today's code with
the results an earlier commit gave.

A dimension longer than ``KEPT`` points (cam or crank angle, stress points) is kept at
every ``stride``-th index from 0, ``stride = ceil(n / KEPT)``; ageing times, parts, links,
joints and limits are short and kept whole. Ageing time is stored in days. One
compressed NumPy archive holds every scene's variables (``scene/variable``) and a JSON
file their dimensions, the full sizes and the diffusion's error estimates.

Made with the commit's own environment (its checkout and virtual environment), from the
result files of ``fickcam run`` of each example scene::

    python tests/example_reference.py tests/data/examples_5559169 RESULT.nc ...

(``RESULT.nc`` named as the scene, e.g. ``singh2017_cam.nc``).
"""
from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np
import xarray as xr

KEPT = 12  # points kept along a long dimension
DAY = 86400.0  # s


def kept_indices(size: int) -> np.ndarray:
    """The indices kept along a dimension of ``size`` points."""
    return np.arange(0, size, max(1, math.ceil(size / KEPT)))


def in_days(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with its ageing time in float days (a result stores it either as float days
    or, before, as a timedelta)."""
    if "time" in ds.coords and ds["time"].dtype.kind == "m":
        days = ds["time"].values / np.timedelta64(1, "s") / DAY
        ds = ds.assign_coords(time=("time", days, {**ds["time"].attrs, "units": "d"}))
    return ds


def subsample(ds: xr.Dataset) -> xr.Dataset:
    """The variables of a result at the kept indices of its long dimensions."""
    ds = in_days(ds)
    return ds.isel({dim: kept_indices(size) for dim, size in ds.sizes.items()
                    if dim != "time" and size > KEPT})


def record(ds: xr.Dataset) -> tuple[dict[str, np.ndarray], dict]:
    """The subsampled arrays of a result by variable name, and its description: each
    variable's dimensions, the full sizes and the diffusion's summary."""
    kept = subsample(ds)
    arrays = {name: np.asarray(kept[name].values) for name in kept.variables}
    return arrays, {"dims": {name: list(kept[name].dims) for name in kept.variables},
                    "full_sizes": {dim: int(size) for dim, size in ds.sizes.items()},
                    "diffusion": json.loads(ds.attrs.get("diffusion", "{}"))}


def write(results: dict[str, xr.Dataset], folder: Path) -> None:
    """``values.npz`` and ``scenes.json`` in ``folder`` for the results by scene name."""
    arrays, scenes = {}, {}
    for scene, ds in results.items():
        values, scenes[scene] = record(ds)
        arrays.update({f"{scene}/{name}": value for name, value in values.items()})
    folder.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(folder / "values.npz", **arrays)
    (folder / "scenes.json").write_text(json.dumps(scenes, indent=1, sort_keys=True) + "\n")


def read(folder: Path) -> tuple[dict[str, dict[str, np.ndarray]], dict]:
    """The arrays by scene and variable, and the scenes' descriptions, of :func:`write`."""
    scenes = json.loads((folder / "scenes.json").read_text())
    with np.load(folder / "values.npz") as archive:
        arrays = {scene: {} for scene in scenes}
        for key in archive.files:
            scene, name = key.split("/", 1)
            arrays[scene][name] = archive[key]
    return arrays, scenes


if __name__ == "__main__":
    write({Path(result).stem: xr.open_dataset(result).load() for result in sys.argv[2:]},
          Path(sys.argv[1]))
