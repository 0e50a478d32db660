"""A plain ``.plot()`` of every result variable, as a notebook user types it first: on a
result from ``fickcam.run``, from ``fickcam.open_result`` and from
``xarray.open_dataset``, it draws without an error or a warning, with ageing time in days."""
import warnings
from pathlib import Path

import matplotlib
import numpy as np
import pytest
import xarray as xr
import yaml

import fickcam

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

CONFIGS = Path(__file__).resolve().parents[1] / "configs"
DAYS = "ageing time [d]"


def short_scene(name: str, limits: bool) -> dict:
    """A config with three ageing times on a coarse angle grid, with or without its limits."""
    data = yaml.safe_load((CONFIGS / f"{name}.yaml").read_text())
    data["outputs"] = {"ageing_times": ["0 d", "30 d", "60 d"], "angle_step": "30 deg"}
    if not limits:
        data.pop("limits", None)
    return data


#: the cam with its limits holds every variable of the cam without them, and the limits'
SCENES = {"fourbar": ("fourbar_r914_humid", False), "cam_with_limits": ("singh2017_cam", True)}


@pytest.fixture(scope="module", params=list(SCENES))
def result_file(request, tmp_path_factory):
    name, limits = SCENES[request.param]
    ds = fickcam.run(fickcam.load_scene(short_scene(name, limits)))
    path = tmp_path_factory.mktemp(request.param) / "result.h5"
    fickcam.save(ds, path)
    return request.param, ds, path


def opened(source: str, ds, path):
    if source == "run":
        return ds
    if source == "open_result":
        return fickcam.open_result(path)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no decoding warning reaches the user
        return xr.open_dataset(path, engine="h5netcdf")


def time_axis(ax, array):
    """The axis that carries ageing time: x for a line, y for a pcolormesh (xarray puts
    the first dimension, ``time``, on y); None for a histogram (3 dimensions and more)."""
    return {1: ax.xaxis, 2: ax.yaxis}.get(array.ndim)


def drawn_variables(result, names) -> int:
    """Plot each of ``names`` as a notebook user would (``array.plot()``), failing on any
    warning, and check its ageing-time axis (days, spanning 0 to 60 d); the plots drawn."""
    drawn = 0
    for name in names:
        array = result[name]
        fig = plt.figure()
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("error")
                array.plot()
            axis = time_axis(fig.axes[0], array)
            if axis is None:  # xarray draws a histogram of the values, labelled with their unit
                assert fig.axes[0].get_xlabel().endswith(f"[{array.attrs['units']}]"), name
            elif "time" in array.dims:
                assert axis.get_label_text() == DAYS, name
                low, high = axis.get_view_interval()
                assert low <= 0.0 and high >= 60.0, name
            drawn += 1
        finally:
            plt.close(fig)
    return drawn


def plotted(result) -> list[str]:
    """The variables a plain ``.plot()`` applies to: all but the as-designed single numbers."""
    names = [name for name, array in result.data_vars.items() if array.ndim]
    assert all(name.endswith("_design") for name in result.data_vars if name not in names)
    return names


def test_plain_plot_of_every_variable_draws_with_time_in_days(result_file):
    scene, ds, _ = result_file
    assert ds["time"].dtype.kind == "f" and ds["time"].attrs["units"] == "d"
    if scene == "cam_with_limits":
        assert "limit_ratio" in ds and "time_out_of_spec" in ds
    assert drawn_variables(ds, plotted(ds)) > 40


@pytest.mark.parametrize("source", ["open_result", "open_dataset"])
def test_a_saved_result_plots_as_the_run_does(result_file, source):
    """Each variable read back is identical to the run's (values, coordinates, attributes:
    all that ``.plot()`` reads), so it draws as the run's does; any that is not is drawn
    and checked here (plotting all of them again from each source tripled the test)."""
    import xarray.testing

    _, ds, path = result_file
    result = opened(source, ds, path)
    assert result["time"].dtype.kind == "f" and result["time"].attrs["units"] == "d"
    assert plotted(result) == plotted(ds)
    different = []
    for name in plotted(result):
        try:
            xarray.testing.assert_identical(result[name], ds[name])
        except AssertionError:
            different.append(name)
    assert drawn_variables(result, different) == len(different)


def test_selection_interpolation_and_days_agree_across_the_three_sources(result_file):
    _, ds, path = result_file
    sources = [opened(source, ds, path) for source in ("run", "open_result", "open_dataset")]
    for result in sources:
        assert result["time"].values.tolist() == [0.0, 30.0, 60.0]
        np.testing.assert_array_equal(result.moisture_content.sel(time=30).values,
                                      ds.moisture_content.isel(time=1).values)
        expected = 0.5 * (ds.moisture_content.isel(time=1) + ds.moisture_content.isel(time=2))
        np.testing.assert_allclose(result.moisture_content.interp(time=45).values, expected.values,
                                   rtol=1e-12)
