"""Moisture fields: stored per cell with coordinates, drawn by ``plot --kind fields``."""
from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from fickcam.diffusion import Bar, Diffusivity, Exposure, LinkBar, Sheet, solve
from fickcam.plotting import fields

DAY = 86400.0


def fields_dataset(results: dict) -> xr.Dataset:
    """The layout the lead's dataset uses: moisture (time, part, cell), cell_x/y/z (part, cell)."""
    n_cells = max(r.fields.shape[1] for r in results.values())
    times = next(iter(results.values())).times
    moisture = np.full((times.size, len(results), n_cells), np.nan)
    cells = {a: np.full((len(results), n_cells), np.nan) for a in "xyz"}
    for index, result in enumerate(results.values()):
        n = result.fields.shape[1]
        moisture[:, index, :n] = result.fields
        for axis, values in result.cell_coordinates.items():
            cells[axis][index, :n] = values
    data = {"moisture": (("time", "part", "cell"), moisture)}
    data.update({f"cell_{a}": (("part", "cell"), v) for a, v in cells.items()})
    return xr.Dataset(data, coords={"time": times / 86400.0,
                                    "part": list(results)})


@pytest.fixture(scope="module")
def results():
    exposure = Exposure.piecewise([0.0, 20 * DAY, 40 * DAY], 330.0, [1.0, 0.2], 0.0)
    times = np.linspace(0, 40 * DAY, 5)
    iso = Diffusivity((1e-12,) * 3, 0.0)
    kw = dict(accuracy=5e-2, store_fields=True)
    return {"sheet": solve(Sheet(2e-3), iso, exposure, times, model="slab", **kw),
            "crank": solve(LinkBar(0.03, 0.01, 0.004, 0.007, 0.003), iso, exposure, times, **kw),
            "block": solve(Bar(6e-3, 4e-3, 2e-3), iso, exposure, times, model="solid", **kw)}


def test_stored_fields_integrate_to_the_mean(results):
    sheet = results["sheet"]
    assert np.allclose(sheet.fields.mean(axis=1), sheet.mean, atol=1e-12)


@pytest.mark.slow
def test_fields_plot_writes_one_png_per_part(results, tmp_path):
    written = fields.plot(fields_dataset(results), tmp_path).paths
    assert sorted(p.name for p in written) == ["fields_block.png", "fields_crank.png",
                                               "fields_sheet.png"]
    assert all(p.stat().st_size > 1000 for p in written)


def test_chosen_ages_include_first_and_last():
    from fickcam.plotting.common import ages

    assert ages(xr.Dataset(coords={"time": np.arange(11)}), 4) == [0, 3, 7, 10]
    assert ages(xr.Dataset(coords={"time": np.arange(2)}), 4) == [0, 1]
