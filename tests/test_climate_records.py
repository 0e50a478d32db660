"""Climate records (chamber logs, TMY3 and EPW weather years) and standard
damp-heat test climates: what they read, what they refuse, how they repeat."""
import numpy as np
import pytest

import fickcam
from fickcam.climate.damp_heat import STANDARD_TESTS, standard_climate
from fickcam.climate.environment import Environment
from fickcam.climate.records import read_record, resolve_record_path
from fickcam.scene.load import SceneError

HOUR, DAY = 3600.0, 86400.0
pvlib = pytest.importorskip("pvlib")  # the optional extra fickcam[weather]


def greensboro():
    return read_record(resolve_record_path("pvlib:723170TYA.CSV", None))


def test_tmy3_year_reads_hourly_dry_bulb_and_humidity_with_its_winter_frost():
    record = greensboro()
    assert record.time.size == 8760 and np.all(np.diff(record.time) == HOUR)
    assert record.period == 8760 * HOUR
    # the file's own extremes (NREL TMY3, Greensboro NC): -16.7 to 35.6 degC, RH 11 to 100 %
    assert record.temperature.min() - 273.15 == pytest.approx(-16.7)
    assert record.temperature.max() - 273.15 == pytest.approx(35.6)
    assert record.relative_humidity.min() == 11 and record.relative_humidity.max() == 100
    assert "GREENSBORO" in record.source
    assert record.site == "Greensboro Piedmont Triad Int, NC"  # the file's Name and State


def test_weather_year_repeats_for_multi_year_ageing():
    record = greensboro()
    env = Environment.from_samples(*_samples(record.covering(2.5 * 365 * DAY)), 296.15)
    t = np.linspace(0, record.end, 997)
    assert env.end >= 2.5 * 365 * DAY
    for years in (1, 2):
        shifted = t + years * record.period
        # equal up to the round-off of the interpolation fraction: eps * t / (1 h) ~ 1e-11
        np.testing.assert_allclose(env.temperature(shifted), env.temperature(t), rtol=0, atol=1e-9)
        np.testing.assert_allclose(env.relative_humidity(shifted), env.relative_humidity(t),
                                   rtol=0, atol=1e-9)
    # the year closes on itself: from the last row to the repeated first row is one hour
    last = record.end
    assert env.temperature(last + HOUR) == pytest.approx(record.temperature[0])


def _samples(record):
    return record.time, record.temperature, record.relative_humidity


def _write_epw(path, temperatures, humidities):
    """An EPW year (8760 hourly rows, as the format has): ``temperatures`` and ``humidities``
    repeated over it."""
    import pandas as pd

    header = ["LOCATION,Testville,ST,USA,TMY3,999999,36.1,-79.9,-5.0,273.0"] + [
        f"HEADER{k},..." for k in range(6)] + ["DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31"]
    rows = []
    hours = pd.date_range("1999-01-01", periods=8760, freq="h")
    for when, temp, rh in zip(hours, np.resize(temperatures, 8760), np.resize(humidities, 8760)):
        fields = ["1999", str(when.month), str(when.day), str(when.hour + 1), "0", "?",
                  f"{temp}", "0.0", f"{rh}"]
        fields += ["101300"] + ["0"] * 25
        rows.append(",".join(fields))
    path.write_text("\n".join(header + rows) + "\n")


def test_epw_file_reads_through_pvlib(tmp_path):
    path = tmp_path / "site.epw"
    temps = np.round(10 + 5 * np.sin(np.arange(48) / 24 * 2 * np.pi), 1)
    _write_epw(path, temps, np.full(48, 80))
    record = read_record(path)
    assert np.allclose(record.temperature - 273.15, np.resize(temps, 8760))
    assert np.all(record.relative_humidity == 80) and record.period == 8760 * HOUR
    assert record.site == "Testville, ST"  # the LOCATION line's city and state-prov


def test_epw_missing_value_is_refused_at_its_line(tmp_path):
    path = tmp_path / "site.epw"
    rh = np.full(48, 70.0)
    rh[5] = 999  # EPW's code for a missing relative humidity
    _write_epw(path, np.full(48, 20.0), rh)
    with pytest.raises(ValueError, match=r"site.epw:14 relative_humidity: missing value"):
        read_record(path)


@pytest.mark.parametrize("body, message", [
    ("0,20,50\n1,21,\n", "log.csv:3 relative_humidity: missing value"),
    ("0,20,50\n2,21,50\n1,22,50\n", r"log.csv:4 time: time goes back \(line 3 is later\)"),
    ("0,20,50\n1,21,50\n1,22,50\n", r"log.csv:4 time: repeated timestamp \(also on line 3\)"),
    ("0,20,50\n1,nan,50\n", "log.csv:3 temperature: missing value"),
])
def test_rough_chamber_logs_are_refused_naming_file_line_and_column(tmp_path, body, message):
    path = tmp_path / "log.csv"
    path.write_text("time [h],temperature [degC],relative_humidity [%]\n" + body)
    with pytest.raises(ValueError, match=message):
        read_record(path)


def test_cyclic_damp_heat_has_the_standard_24_h_shape():
    test = standard_climate("cyclic_damp_heat", cycles=3)
    env = Environment(test.change_times, test.temperature_end, test.humidity_end, test.ramp,
                      test.temperature_start, test.humidity_start, 296.15, 0.0)
    assert env.end == 3 * DAY
    hours = np.array([0, 1.5, 3, 7, 12, 13.5, 15, 20]) * HOUR
    expected_t = [25, 40, 55, 55, 55, 40, 25, 25]
    for cycle in range(3):
        assert np.allclose(env.temperature(hours + cycle * DAY) - 273.15, expected_t)
    assert np.allclose(env.relative_humidity(np.array([7, 20]) * HOUR), [93, 95])
    lower = standard_climate("cyclic_damp_heat", cycles=1, upper_temperature=313.15)
    assert lower.temperature_end.max() == pytest.approx(313.15)
    with pytest.raises(ValueError, match="40 degC or 55 degC"):
        standard_climate("cyclic_damp_heat", upper_temperature=323.15)


@pytest.mark.parametrize("name, temperature, humidity", [
    ("steady_damp_heat", 40, 93), ("damp_heat_85_85", 85, 85)])
def test_steady_damp_heat_tests_hold_their_standard_values(name, temperature, humidity):
    test = standard_climate(name, duration=10 * DAY)
    assert test.temperature_end[0] - 273.15 == pytest.approx(temperature)
    assert test.humidity_end[0] == humidity and test.change_times[-1] == 10 * DAY
    assert STANDARD_TESTS[name].source


def _scene(environment, times="[0 d, 2 d, 4 d]"):
    return f"""
name: record
environment:
{environment}
materials:
  nylon: {{plastic: nylon}}
cam:
  material: nylon
  eccentric: {{eccentricity: 4 mm, radius: 23 mm}}
  thickness: 10 mm
  bore_radius: 0 mm
  speed: 300 rpm
  follower: {{kind: roller, roller_radius: 10 mm, mass: 0.7 kg, spring_rate: 660 N/m, spring_preload: 20 N}}
outputs: {{ageing_times: {times}, angle_step: 10 deg}}
"""


def test_short_record_holds_its_last_state_and_says_so(tmp_path):
    log = tmp_path / "chamber.csv"
    log.write_text("time [d],temperature [degC],relative_humidity [%]\n0,40,90\n2,40,90\n")
    scene = tmp_path / "scene.yaml"
    scene.write_text(_scene("  history_file: chamber.csv"))
    ds = fickcam.run(fickcam.load_scene(scene))
    assert any("ends at 2 d" in n and "held to 4 d" in n for n in ds.attrs["notices"])
    assert np.allclose(ds.temperature.values, 313.15)
    uptake = ds.moisture_content.sel(part="cam").values
    assert np.all(np.diff(uptake) > 0)  # the held humid state keeps the cam absorbing


def test_frost_and_days_at_full_humidity_stay_bounded(tmp_path):
    hours = np.arange(0, 4 * 24 + 1, 6)
    temps = np.where(hours < 48, -17.0, 5.0)   # Greensboro's winter low, then a thaw
    log = tmp_path / "winter.csv"
    log.write_text("time [h],temperature [degC],relative_humidity [%]\n" + "".join(
        f"{h},{t},100\n" for h, t in zip(hours, temps)))
    scene = tmp_path / "scene.yaml"
    scene.write_text(_scene("  history_file: winter.csv", "[0 d, 1 d, 2 d, 4 d]"))
    ds = fickcam.run(fickcam.load_scene(scene))
    moisture = ds.moisture_content.values
    assert np.all(np.isfinite(moisture)) and np.all(moisture >= -1e-12 * moisture.max())
    surface = ds.surface_moisture_content.sel(part="cam").values
    assert np.all(moisture[:, 0] <= surface.max() + 1e-12)


def test_standard_test_runs_as_a_scene_and_bad_keys_name_their_line(tmp_path):
    scene = tmp_path / "scene.yaml"
    scene.write_text(_scene("  test: cyclic_damp_heat\n  cycles: 4"))
    ds = fickcam.run(fickcam.load_scene(scene))
    assert ds.temperature.sel(time=2).item() == pytest.approx(298.15)
    scene.write_text(_scene("  test: steady_damp_heat\n  cycles: 4"))
    with pytest.raises(SceneError, match=r"scene.yaml:\d+ environment.*steady test"):
        fickcam.load_scene(scene)
    scene.write_text(_scene("  test: cyclic_damp_heat\n  cycles: 1"))
    with pytest.raises(SceneError, match="beyond the end"):
        fickcam.load_scene(scene)
