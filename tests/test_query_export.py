"""Queries interpolate linearly between stored ageing times; exports round-trip."""
import csv
import json
import math

import numpy as np
import pytest
import xarray as xr

from fickcam.results.dataset import build_dataset
from fickcam.errors import InputError
from fickcam.results.export import export
from fickcam.results.query import format_result, select
from fickcam.results.store import open_result, save

DAY = 86400.0


@pytest.fixture()
def stored(tmp_path):
    rng = np.random.default_rng(3)
    times = np.array([0, 1, 7, 30, 60]) * DAY
    angles = np.radians(np.arange(0, 360, 30))
    ds = build_dataset(
        {"temperature": 300 + rng.random(5),
         "moisture_content": rng.random((5, 2)),
         "follower_displacement": rng.random((5, angles.size)),
         "pressure_angle": rng.random((5, angles.size)),
         "lift": rng.random(5)},
        {"time": times, "part": ["cam", "follower"], "cam_angle": angles},
        {"scene_name": "synthetic", "notices": []})
    path = tmp_path / "r.h5"
    save(ds, path)
    return open_result(path)


def test_time_selection_in_days_matches_stored_values(stored):
    assert float(stored.lift.sel(time=30)) == float(stored.lift.values[3])
    assert float(stored.lift.sel(time=29.6, method="nearest")) == float(stored.lift.values[3])


@pytest.mark.parametrize("when, seconds", [("10 d", 10 * DAY), ("6 weeks", 42 * DAY), (45 * DAY, 45 * DAY)])
def test_query_interpolates_linearly_between_stored_times(stored, when, seconds):
    t = stored.time.values * DAY
    for part in ("cam", "follower"):
        expected = np.interp(seconds, t, stored.moisture_content.sel(part=part).values)
        got = select(stored, "moisture_content", time=when, part=part)
        assert float(got) == pytest.approx(expected, rel=1e-12)


def test_query_interpolates_in_cam_angle_periodically(stored):
    values = stored.follower_displacement.isel(time=2).values
    got = select(stored, "follower_displacement", time="7 d", cam_angle=345.0)
    assert float(got) == pytest.approx(0.5 * (values[-1] + values[0]))


@pytest.mark.parametrize("kwargs, fragment", [
    ({"time": "90 d"}, "outside"), ({"time": "3 parsec"}, "--time"), ({"part": "crank"}, "no part"),
    ({"crank_angle": 10.0}, "no crank_angle"),
])
def test_bad_queries_are_refused_with_reason(stored, kwargs, fragment):
    with pytest.raises(InputError, match=fragment):
        select(stored, "moisture_content", **kwargs)


def test_a_bare_query_time_is_refused_naming_the_units(stored):
    """`--time 45` would be 45 s (SI), a slip in a history of days: judged as a scene's
    ageing time, it is refused with the likely unit."""
    with pytest.raises(InputError, match=r"^--time 45: 45 s is an implausible ageing time "
                                         r"\(the history lasts .*\): did you mean '45 d'\?"):
        select(stored, "lift", time="45")


@pytest.mark.parametrize("kwargs, said", [
    ({"time": "45 d"}, "lift at time = 45 d (interpolated between 30 d and 60 d)"),
    ({"time": "30 d"}, "lift at time = 30 d (stored)"),
])
def test_a_query_answer_states_the_time_it_answers(stored, kwargs, said):
    text = format_result(select(stored, "lift", **kwargs), "lift", "table")
    assert text.splitlines()[0] == said


def test_a_query_answer_states_the_angle_it_answers(stored):
    array = select(stored, "follower_displacement", time="7 d", cam_angle=345.0)
    table = format_result(array, "follower_displacement", "table")
    assert table.splitlines()[0] == ("follower_displacement at cam_angle = 345 deg (interpolated "
                                     "between 330 deg and 0 deg), time = 7 d (stored)")
    assert json.loads(format_result(array, "follower_displacement", "json"))["selection"] == \
        table.splitlines()[0].split(" at ", 1)[1]
    rows = list(csv.DictReader(format_result(array, "follower_displacement", "csv").splitlines()))
    assert float(rows[0]["cam_angle [degree]"]) == 345.0 and float(rows[0]["time [d]"]) == 7.0


def test_time_is_float_days_and_ageing_time_the_same_days_beside_it(stored):
    for name in ("time", "ageing_time"):
        assert stored[name].dims == ("time",) and stored[name].attrs["units"] == "d"
        assert stored[name].values.tolist() == [0.0, 1.0, 7.0, 30.0, 60.0]


def test_days_coordinate_plots_and_interpolates(stored):
    """The days of `time` go on an axis as they are, and `interp` takes days."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    mesh = stored.follower_displacement.plot()
    assert mesh.axes.get_ylabel() == "ageing time [d]"
    assert mesh.axes.get_ylim()[1] >= 60.0
    lines = stored.moisture_content.plot.line(x="time")
    assert lines[0].get_xdata().tolist() == [0.0, 1.0, 7.0, 30.0, 60.0]
    plt.close("all")
    expected = np.interp(45.0, stored.time.values, stored.lift.values)
    assert float(stored.lift.interp(time=45.0)) == pytest.approx(expected, rel=1e-12)


def test_a_result_with_a_timedelta_time_opens_in_days(stored, tmp_path):
    """Files written when fickcam stored `time` as a timedelta read into the same days."""
    legacy = stored.drop_vars("ageing_time").assign_coords(
        time=(stored.time.values * DAY * 1e9).astype("timedelta64[ns]"))
    legacy.to_netcdf(tmp_path / "old.h5", engine="h5netcdf")
    reopened = open_result(tmp_path / "old.h5")
    assert reopened.time.dtype.kind == "f" and reopened.time.attrs["units"] == "d"
    xr.testing.assert_identical(reopened.time, stored.time)
    assert reopened.ageing_time.values.tolist() == stored.ageing_time.values.tolist()


def test_unknown_variable_lists_known_ones(stored):
    with pytest.raises(InputError, match="moisture_content"):
        select(stored, "moisture", time="1 d")


@pytest.mark.parametrize("fmt", ["table", "csv", "json"])
def test_formats_carry_the_interpolated_values(stored, fmt):
    array = select(stored, "moisture_content", time="10 d")
    text = format_result(array, "moisture_content", fmt)
    if fmt == "json":
        rows = json.loads(text)["rows"]
        assert [r[-1] for r in rows] == pytest.approx(array.values.tolist())
    else:
        assert f"{array.values[0]:.6g}"[:5] in text


def test_csv_export_round_trips(stored, tmp_path):
    path = export(stored, tmp_path / "out.csv", "csv")
    with open(path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    for name in stored.data_vars:
        array = stored[name]
        mine = [r for r in rows if r["variable"] == name]
        assert len(mine) == array.size
        for r in mine:
            index = {}
            for dim in array.dims:
                key = "time_d" if dim == "time" else dim
                value = r[key]
                coord = array[dim].values
                if dim == "time":
                    index[dim] = int(np.argmin(np.abs(coord - float(value))))
                elif coord.dtype.kind in "US":
                    index[dim] = list(coord).index(value)
                else:
                    index[dim] = int(np.argmin(np.abs(coord - float(value))))
            assert float(r["value"]) == array.isel(index).item()
        assert all(r["units"] == array.attrs["units"] for r in mine)


def test_json_and_netcdf_exports_hold_the_same_numbers(stored, tmp_path):
    doc = json.loads(export(stored, tmp_path / "o.json", "json").read_text())
    assert np.allclose(doc["variables"]["lift"]["data"], stored.lift.values)
    back = xr.open_dataset(export(stored, tmp_path / "o.nc", "netcdf", ["lift"]), engine="h5netcdf")
    assert list(back.data_vars) == ["lift"]
    assert np.array_equal(back.lift.values, stored.lift.values)


def test_result_file_has_units_and_long_names_everywhere(stored):
    for name in stored.data_vars:
        assert stored[name].attrs["units"] and stored[name].attrs["long_name"]
    assert stored.cam_angle.attrs["units"] == "degree"
    assert math.isclose(stored.cam_angle.values[1], 30.0)
