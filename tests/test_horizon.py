"""The requested horizon is honoured or refused, never cut without a word: ``every`` ends
at the end of the history, ageing times past the history are refused (or, for a climate
record, held with a notice), query times outside the stored ones are refused, and a
sweep's cases with different ageing times are each read at their own."""
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from hypothesis import given
from hypothesis import strategies as st

from fickcam.cli.main import main
from fickcam.results.query import select
from fickcam.scene.load import load_scene
from fickcam.simulation.times import ageing_times, every_step_times

CONFIGS = Path(__file__).resolve().parents[1] / "configs"
DAY = 86400.0
TWO_YEARS = 730.5 * DAY  # pint's year is the Julian year, 365.25 d


def steel_cam(folder: Path, ageing_times, **environment) -> Path:
    """The steel cam of configs/yadav2017_cam.yaml (no moisture: a run takes a second)
    with the given ageing times and environment history."""
    scene = yaml.safe_load((CONFIGS / "yadav2017_cam.yaml").read_text())
    scene["environment"] = {"reference_temperature": "23 degC", **environment}
    scene["outputs"] = {"ageing_times": ageing_times, "angle_step": "10 deg"}
    path = folder / "cam.yaml"
    path.write_text(yaml.safe_dump(scene, sort_keys=False))
    return path


TWO_YEAR_HISTORY = [{"duration": "2 years", "temperature": "90 degC", "relative_humidity": "50 %"}]


# ------------------------------------------------------------------------ every


def test_every_ends_at_the_end_of_the_history():
    times = every_step_times(30 * DAY, TWO_YEARS)
    assert times[-2] == 720 * DAY and times[-1] == TWO_YEARS and times.size == 26
    assert np.array_equal(every_step_times(30 * DAY, 60 * DAY), [0, 30 * DAY, 60 * DAY])


@given(step=st.floats(1.0, 1e8), steps=st.floats(1.0, 1e3) | st.sampled_from([1.0, 2.0, 24.35,
                                                                             1 + 1e-10, 3 - 1e-10]))
def test_every_grid_starts_at_zero_steps_evenly_and_ends_on_the_history(step, steps):
    end = step * steps
    times = every_step_times(step, end)
    gaps = np.diff(times)
    assert times[0] == 0 and times[-1] == end and np.all(gaps > 0)
    assert np.allclose(gaps[:-1], step, rtol=1e-12) and gaps[-1] <= step + 1e-9 * end


@pytest.mark.slow
def test_a_two_year_history_every_30_d_is_reported_to_two_years(tmp_path, capsys):
    path = steel_cam(tmp_path, {"every": "30 d"}, history=TWO_YEAR_HISTORY)
    scene = load_scene(path)
    times = ageing_times(scene, scene.environment)
    assert times[-1] == TWO_YEARS and times[-2] == 720 * DAY
    result = tmp_path / "out.h5"
    assert main(["run", str(path), "-o", str(result), "--quiet"]) == 0
    capsys.readouterr()
    assert main(["query", str(result), "lift", "--time", "2 years"]) == 0
    assert "lift at time = 730.5 d (stored)" in capsys.readouterr().out
    assert main(["query", str(result), "lift", "--time", "25 months"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == ("fickcam: error: time 25 months is outside the stored ageing times "
                   "(0 to 730.5 d)")


def test_a_chamber_log_ends_the_every_grid_at_its_last_row(tmp_path):
    (tmp_path / "log.csv").write_text("time [d],temperature [degC],relative_humidity [%]\n"
                                      "0,90,50\n45,90,50\n")
    scene = load_scene(steel_cam(tmp_path, {"every": "30 d"}, history_file="log.csv"))
    assert np.array_equal(ageing_times(scene, scene.environment) / DAY, [0, 30, 45])


# ------------------------------------------------------------- beyond the history


@pytest.mark.parametrize("ageing, reason, key", [
    (["0 d", "1 year", "3 years"], "ageing time beyond the end of the environment history (730.5 d)",
     "outputs.ageing_times.2"),
    ({"every": "3 years"}, "step longer than the environment history", "outputs.ageing_times.every"),
])
def test_ageing_times_past_a_history_are_refused_at_their_key(tmp_path, capsys, ageing, reason, key):
    path = steel_cam(tmp_path, ageing, history=TWO_YEAR_HISTORY)
    assert main(["check", str(path)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert line.startswith(f"{path}:") and f" {key}: {reason}" in line


def test_a_chamber_log_shorter_than_the_ageing_times_is_held_with_a_notice(tmp_path):
    import fickcam

    (tmp_path / "log.csv").write_text("time [d],temperature [degC],relative_humidity [%]\n"
                                      "0,90,50\n45,90,50\n")
    path = steel_cam(tmp_path, ["0 d", "30 d", "90 d"], history_file="log.csv")
    ds = fickcam.run(path)
    assert ds.time.values[-1] == 90.0  # days
    assert any("ends at 45 d" in n and "is held to 90 d" in n for n in ds.attrs["notices"])


# ---------------------------------------------------------------------- queries


def two_cases() -> xr.Dataset:
    """A sweep over the history's duration, every 30 d: case 0 to 45 d, case 1 to 100 d
    (their ageing times joined: each case is NaN at the other's)."""
    days = np.array([0, 30, 45, 60, 90, 100])
    lift = np.array([[0.0, 3.0, 4.5, np.nan, np.nan, np.nan],
                     [0.0, 3.0, np.nan, 6.0, 9.0, 10.0]])  # lift = t / 10 d
    return xr.Dataset({"lift": (("case", "time"), lift, {"units": "m"})},
                      coords={"case": [0, 1], "time": days.astype(float)})


@pytest.mark.parametrize("days, expected", [
    (30, [3.0, 3.0]),       # stored for both
    (45, [4.5, 4.5]),       # stored for case 0; case 1 between its 30 d and 60 d
    (50, [np.nan, 5.0]),    # past case 0's last ageing time: not extrapolated
    (100, [np.nan, 10.0]),  # stored for case 1 only
    (15, [1.5, 1.5]),
])
def test_each_case_of_a_sweep_is_read_at_its_own_ageing_times(days, expected):
    values = select(two_cases(), "lift", time=f"{days} d").values
    np.testing.assert_allclose(values, expected, rtol=1e-12)


def test_a_stored_time_next_to_a_missing_value_is_read_as_stored():
    """A run whose part left the model's domain stores NaN from then on: the last value
    before is read as stored, not lost to its NaN neighbour."""
    ds = two_cases().isel(case=0)
    assert float(select(ds, "lift", time="45 d")) == 4.5
    assert np.isnan(float(select(ds, "lift", time="46 d")))


def test_a_limit_is_said_to_hold_only_as_far_as_the_model_computed_it(tmp_path):
    """The R914 four-bar leaves the model's domain (wet Tg) between 2 h 20 min and 2 h
    30 min of its 3 h history: its limit holds to 2 h (the last ageing time with values),
    not to 3 h, said in the minutes the ageing times were written in."""
    import fickcam
    from fickcam.cli.reporting import limit_line

    scene = yaml.safe_load((CONFIGS / "singh2016_fourbar.yaml").read_text())
    scene["limits"] = {"rocker_angle": {"deviation": "5 deg"}}
    scene["outputs"] = {"ageing_times": {"every": "30 min"}, "angle_step": "10 deg"}
    path = tmp_path / "fourbar.yaml"
    path.write_text(yaml.safe_dump(scene, sort_keys=False))
    ds = fickcam.run(path)
    assert ds.time.values[-1] == pytest.approx(3 / 24)  # days
    line = limit_line(ds, "rocker_angle")
    assert "holds to 120 min (" in line and "no value after 120 min, see the notices" in line, \
        line


def test_a_sweep_whose_cases_end_at_different_times_says_which_end_early():
    from fickcam.sweep.combine import case_ends, early_ends

    ds = two_cases().assign_coords(case_status=("case", np.array(["ok", "ok"], dtype=object)))
    np.testing.assert_array_equal(case_ends(ds) / DAY, [45, 100])
    assert early_ends(ds) == (
        "1 case(s) end before 100 d (case 0 at 45 d): empty there in the table and plots")
    assert early_ends(ds.isel(case=[1])) is None
    failed = ds.assign_coords(case_status=("case", np.array(["failed", "ok"], dtype=object)))
    assert early_ends(failed) is None  # a failed case has no values at all: said elsewhere
