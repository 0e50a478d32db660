"""Limits: ratios, the first time out of spec, and refused limits."""
import math

import numpy as np
import pytest
import xarray as xr
import yaml

import fickcam
from fickcam.cli import main
from fickcam.limits import (FLOOR, POINTS, TOLERANCE, Limit, LimitSpec, first_crossings,
                            limit_ratio, parse_limit)
from fickcam.schema import VARIABLES
from fickcam.simulate import search_notices

from test_scene_errors import LINKAGE_SCENE

DAY = 86400.0


def fast_fourbar(times, limits=None) -> dict:
    """Singh & Sanyal 2016's R914 four-bar at 60 degC / 85 % RH for 40 days."""
    scene = yaml.safe_load(LINKAGE_SCENE)
    scene["environment"]["history"] = [{"duration": "40 d", "temperature": "60 degC",
                                        "relative_humidity": "85 %"}]
    scene["outputs"] = {"ageing_times": times, "angle_step": "4 deg"}
    if limits:
        scene["limits"] = limits
    return scene


# ------------------------------------------------------------------ parsing


@pytest.mark.parametrize("name, spec, stored", [
    ("rocker_angle", {"deviation": "0.25 deg"}, {"deviation": 0.25}),
    ("rocker_angle", {"deviation": 0.01}, {"deviation": math.degrees(0.01)}),  # bare: SI (rad)
    ("peak_contact_stress", {"max": "60 MPa"}, {"max": 60e6}),
    ("jump_speed", {"min": "12 revolution/s"}, {"min": 720.0}),
    ("temperature", {"max": "120 degC"}, {"max": 393.15}),
    ("glass_transition_temperature", {"deviation": "5 degC"}, {"deviation": 5.0}),  # a step
    ("moisture_content", {"max": "1.5 %"}, {"max": 1.5}),
    ("hygrothermal_strain", {"max": "0.5 %"}, {"max": 0.005}),
    ("link_length", {"min": "99.9 mm", "max": "100.4 mm"}, {"min": 0.0999, "max": 0.1004}),
])
def test_limits_are_stored_in_the_variables_stored_unit(name, spec, stored):
    limit = parse_limit(name, LimitSpec(**spec), {"cam", "linkage"})
    for key, value in stored.items():
        assert getattr(limit, key) == pytest.approx(value)
    assert limit.units == VARIABLES[name].units


@pytest.mark.parametrize("entry, reason", [
    ("rocker_angel: {deviation: 0.25 deg}", "no result variable 'rocker_angel'"),
    ("rocker_angle: {deviation: 0.25 mm}", "deviation: '0.25 mm' has the wrong dimension"),
    ("rocker_angle: {max: 3 %}", "max: '3 %' has the wrong dimension"),
    ("transmission_angle: {min: 50 deg, max: 40 deg}", "min (50 deg) is above max (40 deg)"),
    ("jump_speed: {min: 720 rpm}", "jump_speed needs a cam section"),
    ("rocker_angle: {deviation: -1 deg}", "deviation must be positive"),
    ("rocker_angle: {}", "give deviation, max or min"),
    ("rocker_angle: {dev: 1 deg}", "unknown key"),
    ("grashof_class: {max: 1}", "no result variable 'grashof_class'"),
    ("temperature: {deviation: 2 K}", "temperature has no as-designed value"),
])
def test_bad_limits_name_their_line_and_exit_2(tmp_path, capsys, entry, reason):
    path = tmp_path / "scene.yaml"
    path.write_text(LINKAGE_SCENE + "limits:\n  " + entry + "\n")
    line = len(LINKAGE_SCENE.splitlines()) + 2
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"{path}:{line} limits.{entry.split(':')[0]}"), err
    assert reason in err and "\n" not in err


# ------------------------------------------------------------------- ratios


def _dataset(values, design=None):
    """A result with one (time, cam_angle) variable, optionally its design state."""
    data = {"follower_displacement": (("time", "cam_angle"), np.asarray(values, float))}
    if design is not None:
        data["follower_displacement_design"] = ("cam_angle", np.asarray(design, float))
    return xr.Dataset(data, coords={"time": np.arange(len(values)), "cam_angle": [0.0, 90.0, 180.0]})


def test_ratio_is_one_at_each_kind_of_limit_and_grows_out_of_spec():
    ds = _dataset([[0.0, 1.0, 2.0], [0.0, 1.1, 2.5], [-1.0, 1.0, 2.0]], design=[0.0, 1.0, 2.0])
    units = "m"
    # max 2.5: worst values 2, 2.5, 2 -> 0.8, 1, 0.8
    np.testing.assert_allclose(limit_ratio(ds, Limit("follower_displacement", units, max=2.5)),
                               [0.8, 1.0, 0.8])
    # min -0.5: smallest values 0, 0, -1 -> 1 + (-0.5 - x)/0.5
    np.testing.assert_allclose(limit_ratio(ds, Limit("follower_displacement", units, min=-0.5)),
                               [0.0, 0.0, 2.0])
    # deviation 0.5 around the design: largest |x - design| 0, 0.5, 1 over the cycle
    np.testing.assert_allclose(limit_ratio(ds, Limit("follower_displacement", units, deviation=0.5)),
                               [0.0, 1.0, 2.0])
    # several entries: the largest ratio
    both = Limit("follower_displacement", units, deviation=0.5, max=2.5)
    np.testing.assert_allclose(limit_ratio(ds, both), [0.8, 1.0, 2.0])


def test_a_zero_bound_is_scaled_by_the_design_value():
    ds = _dataset([[4.0, 5.0, 6.0], [-1.0, 5.0, 6.0]], design=[4.0, 5.0, 6.0])
    ratio = limit_ratio(ds, Limit("follower_displacement", "m", min=0.0))
    np.testing.assert_allclose(ratio, [1 - 4 / 6, 1 + 1 / 6])


def test_times_where_the_physics_stopped_give_nan_ratios():
    ds = _dataset([[0.0, 1.0, 2.0], [np.nan] * 3])
    assert np.isnan(limit_ratio(ds, Limit("follower_displacement", "m", max=3.0))[1])


# ----------------------------------------------------------------- crossing


def test_crossings_are_located_to_the_tolerance_with_one_model_run_per_round():
    calls = []

    def ratio(t):  # two limits: crossing 1 at 37.3 d and at 12.25 d; a third never fails
        t = np.asarray(t, float)[:, None]
        return np.hstack([0.2 + (t / (37.3 * DAY)) ** 0.5 * 0.8, np.exp((t - 12.25 * DAY) / DAY),
                          0.5 + 0 * t])

    def evaluate(ts):
        calls.append(len(ts))
        return ratio(ts)

    times = np.array([0.0, 10.0, 30.0, 60.0, 90.0]) * DAY
    found = first_crossings(times, ratio(times), evaluate)
    for value, exact, bracket in zip(found[:2], (37.3, 12.25), (30.0, 20.0)):
        assert abs(value - exact * DAY) <= max(TOLERANCE * bracket * DAY, FLOOR)
        assert value not in times
    assert math.isnan(found[2])
    # 4 equally spaced points, then Illinois-secant pairs: the sqrt-shaped crossing closes
    # after the first round (the cubic through its samples and the quadratics agree on it
    # within half the tolerance), the exponential one (e-folding in a day, samples 4 d
    # apart) in the fourth (19 % of the 9-point search's model evaluations, 36)
    assert calls == [2 * POINTS, 2, 2, 2]
    smooth = []
    first_crossings(times, ratio(times)[:, :1], lambda ts: smooth.append(len(ts)) or ratio(ts)[:, :1])
    assert smooth == [POINTS]


def test_a_crossing_read_off_the_first_rounds_samples_is_within_the_tolerance():
    """Closed by the samples' interpolants after one round, the crossing of smooth ratios
    (power laws, a saturating exponential, as moisture uptake drives them) lies within the
    tolerance of the exact one, and well within it (the interpolants' own estimate)."""
    times = np.array([0.0, 1.0, 7.0, 30.0, 60.0]) * DAY
    shapes = [lambda t, c: 0.3 + 0.7 * (t / c) ** 0.5, lambda t, c: (t / c) ** 0.25,
              lambda t, c: 0.2 + 0.8 * (1 - np.exp(-t / (40 * DAY))) / (1 - np.exp(-c / (40 * DAY)))]
    for shape in shapes:
        for crossing in np.array([31.0, 36.0, 44.5, 59.0]) * DAY:
            calls = []

            def evaluate(ts):
                calls.append(len(ts))
                return shape(np.asarray(ts, float), crossing)[:, None]
            found = first_crossings(times, shape(times, crossing)[:, None], evaluate)[0]
            assert len(calls) == 1
            assert abs(found - crossing) <= 0.1 * TOLERANCE * 30 * DAY


def test_out_of_spec_at_the_start_and_short_brackets():
    times = np.array([0.0, 1.0, 2.0, 3.0]) * DAY
    column = np.array([[1.2], [0.9], [1.7], [2.0]])
    assert first_crossings(times, column, None)[0] == 0.0
    # a bracket shorter than the 1 h floor is not refined: linear inside it
    short = np.array([0.0, 1800.0])
    assert first_crossings(short, np.array([[0.0], [2.0]]), None)[0] == pytest.approx(900.0)


@pytest.fixture(scope="module")
def dense():
    """The four-bar at 81 ageing times, 0.5 d apart."""
    times = np.arange(0.0, 40.01, 0.5) * DAY
    return times, fickcam.run(fast_fourbar([f"{t / DAY} d" for t in times]))


def brute_force(dense, name, spec) -> float:
    """The first crossing on the dense grid, linear between its two times (s)."""
    times, ds = dense
    ratio = limit_ratio(ds, parse_limit(name, LimitSpec(**spec), {"linkage"}))
    k = int(np.flatnonzero(ratio > 1)[0])
    return float(np.interp(1.0, ratio[k - 1:k + 1], times[k - 1:k + 1]))


def test_time_out_of_spec_agrees_with_a_brute_force_search_on_a_dense_grid(dense):
    """The crossing found from 4 stored times (re-running the model in the bracket)
    against the first crossing on a dense grid of 81 ageing times (0.5 d apart,
    linear between them): within 1 % of the time (measured: 3e-5)."""
    limits = {"minimum_transmission_angle": {"min": "35.5 deg"},
              "peak_input_torque": {"max": "0.215 N m"}}
    sparse = fickcam.run(fast_fourbar(["0 d", "7 d", "30 d", "40 d"], limits))
    for name, spec in limits.items():
        found = float(sparse["time_out_of_spec"].sel(limit=name)) * DAY
        brute = brute_force(dense, name, spec)
        assert 7 * DAY < brute < 30 * DAY, name
        assert found == pytest.approx(brute, rel=0.01), name
    assert sparse["limit_ratio"].dims == ("time", "limit")
    assert sparse["time_out_of_spec"].attrs["units"] == "d"


def test_out_of_spec_at_a_first_stored_time_after_0_is_located_from_age_0(dense):
    """Stored times from 7 d: a limit already failed there is searched from age 0."""
    spec = {"min": "35.9 deg"}
    late = fickcam.run(fast_fourbar(["7 d", "40 d"], {"minimum_transmission_angle": spec}))
    found = float(late["time_out_of_spec"].sel(limit="minimum_transmission_angle")) * DAY
    brute = brute_force(dense, "minimum_transmission_angle", spec)
    assert 0 < brute < 7 * DAY
    assert found == pytest.approx(brute, rel=0.01)


def test_a_limit_the_scene_does_not_compute_is_refused_at_its_line(tmp_path, capsys):
    scene = fast_fourbar(["0 d", "40 d"], {"wear_depth": {"max": "1 mm"}})
    path = tmp_path / "scene.yaml"
    path.write_text(yaml.safe_dump(scene, sort_keys=False))
    assert main(["run", str(path), "-o", str(tmp_path / "r.h5"), "--quiet"]) == 2
    assert "limits.wear_depth: wear_depth needs a cam section" in capsys.readouterr().err


@pytest.mark.slow
def test_summary_query_and_plot_show_the_limit(tmp_path, capsys):
    scene = fast_fourbar(["0 d", "7 d", "40 d"], {"minimum_transmission_angle": {"min": "35.5 deg"},
                                                  "rocker_swing": {"max": "80 deg"}})
    path = tmp_path / "scene.yaml"
    path.write_text(yaml.safe_dump(scene, sort_keys=False))
    result = tmp_path / "r.h5"
    assert main(["run", str(path), "-o", str(result)]) == 0
    out = capsys.readouterr().out
    assert "first limit to fail: minimum_transmission_angle (min 35.5 deg) at 21.3" in out, out
    assert "rocker_swing (max 80 deg): holds to 40 d" in out
    assert main(["query", str(result), "minimum_transmission_angle"]) == 0
    assert capsys.readouterr().out.strip().splitlines()[-1].startswith(
        "limit: minimum_transmission_angle (min 35.5 deg): out of spec from 21.3")
    assert main(["plot", str(result), "--kind", "limits", "-o", str(tmp_path)]) == 0
    assert (tmp_path / "limits.png").stat().st_size > 10_000


def test_a_limit_search_of_honest_estimates_adds_no_notice():
    """The four-bar's limit search reads diffusion at the stored and new times together;
    its estimates stay within the requested accuracy and no search notice appears."""
    limits = {"minimum_transmission_angle": {"min": "35.5 deg"}}
    honest = fickcam.run(fast_fourbar(["0 d", "7 d", "30 d", "40 d"], limits), accuracy=1e-3)
    assert not [n for n in honest.attrs["notices"] if "limit search" in n]


def test_a_search_estimate_above_the_accuracy_is_noticed_only_where_the_stored_was_within():
    """Diffusion at the search's times estimated above the requested accuracy (as a D(c)
    result read between its steps can be: the stored estimate plus the interpolation's)
    while the stored run's is within it: one notice naming the part and both figures. A
    part whose stored estimate already exceeds the accuracy is noticed by the run itself,
    and a search estimate within the accuracy says nothing."""
    searched = {"coupler": 2e-3, "rocker": 3e-3, "crank": 5e-4}
    stored = {"coupler": 8e-4, "rocker": 2e-3, "crank": 4e-4}
    notices = search_notices(searched, stored, 1e-3)
    assert len(notices) == 1 and notices[0].startswith("coupler: estimated diffusion error "
                                                       "2.0e-03 at the limit search's times")
    assert "accuracy 0.001" in notices[0]
