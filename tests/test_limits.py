"""Limits: ratios, the first time out of spec, and refused limits."""
import math

import numpy as np
import pytest
import xarray as xr
import yaml

import fickcam
from fickcam.cli.main import main
from fickcam.results.limits import (FLOOR, POINTS, RELATIVE, Tolerance, first_crossings, limit_ratio,
                                    polynomial_crossing)
from fickcam.scene.limits import Limit, LimitSpec, parse_limit
from fickcam.schema import VARIABLES
from fickcam.simulation.limitsearch import search_notices

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


def _search(shape, times, tolerance=Tolerance()):
    """(crossings, errors, evaluations per round) of the ratios ``shape(t)`` (time, limit)."""
    calls = []

    def evaluate(ts):
        calls.append(len(ts))
        return shape(np.asarray(ts, float))
    found, errors = first_crossings(times, shape(np.asarray(times, float)), evaluate, tolerance)
    return found, errors, calls


def _two_limits(t):
    """Two limits crossed at 37.3 d (as the square root of the time) and at 12.25 d (an
    exponential e-folding in a day); a third never fails."""
    t = np.asarray(t, float)[:, None]
    return np.hstack([0.2 + (t / (37.3 * DAY)) ** 0.5 * 0.8, np.exp((t - 12.25 * DAY) / DAY),
                      0.5 + 0 * t])


def test_crossings_are_within_their_error_estimate_and_it_within_their_tolerance():
    times = np.array([0.0, 10.0, 30.0, 60.0, 90.0]) * DAY
    found, errors, calls = _search(_two_limits, times)
    for value, error, exact in zip(found[:2], errors[:2], (37.3 * DAY, 12.25 * DAY)):
        assert abs(value - exact) <= error <= Tolerance().at(exact)
    assert math.isnan(found[2]) and math.isnan(errors[2])
    # one model run per round for both brackets: POINTS equally spaced in sqrt(t) (none
    # where the stored times about the crossing agree on it), then pairs straddling the
    # guess; the exponential, e-folding in a day between stored times 20 d apart, takes
    # two sampling rounds and four of pairs (measured: [6, 2, 2, 2, 4, 4])
    assert calls[0] <= 2 * POINTS and len(calls) <= 6, calls


@pytest.mark.parametrize("stored", [
    [0.0, 30.0, 60.0, 90.0, 730.5],           # monthly-like
    [0.0, 17.0, 17.7, 18.5, 730.5],           # dense just before the crossing, then a gap
    [0.0, 730.5],                             # the ends only
    np.arange(0.0, 730.6, 1.0),               # daily
])
@pytest.mark.parametrize("crossing", [3 / 24, 21.9, 400.0])
def test_the_stored_times_do_not_move_the_crossing_beyond_its_error(stored, crossing):
    """A ratio growing as the square root of the time (moisture uptake) from 0.8, crossing
    1 within hours, in weeks or in a year: wherever the stored times fall, the crossing is
    found within its error estimate, which is within 0.1 % of it or 1 h."""
    exact = crossing * DAY

    def shape(t):
        return (0.8 + 0.2 * np.sqrt(np.asarray(t, float) / exact))[:, None]
    found, errors, calls = _search(shape, np.asarray(stored, float) * DAY)
    assert abs(found[0] - exact) <= errors[0] <= max(RELATIVE * exact, FLOOR)
    assert len(calls) <= 4


def test_a_finer_diffusion_accuracy_tightens_the_tolerance():
    assert Tolerance.for_accuracy(1e-3) == Tolerance() == Tolerance.for_accuracy(1e-2)
    fine = Tolerance.for_accuracy(1e-4)
    assert fine.at(100 * DAY) == pytest.approx(1e-4 * 100 * DAY)
    assert fine.at(0.0) == pytest.approx(360.0)
    times = np.array([0.0, 10.0, 30.0, 60.0, 90.0]) * DAY
    found, errors, _ = _search(_two_limits, times, fine)
    for value, error, exact in zip(found[:2], errors[:2], (37.3 * DAY, 12.25 * DAY)):
        assert abs(value - exact) <= error <= fine.at(exact)


def test_out_of_spec_at_the_start_and_short_brackets():
    times = np.array([0.0, 1.0, 2.0, 3.0]) * DAY
    column = np.array([[1.2], [0.9], [1.7], [2.0]])
    found, errors = first_crossings(times, column, None)
    assert (found[0], errors[0]) == (0.0, 0.0)
    # a bracket shorter than the 1 h floor is not refined: linear in sqrt(t) inside it,
    # its error the larger distance to the bracket's ends
    found, errors = first_crossings(np.array([0.0, 1800.0]), np.array([[0.0], [2.0]]), None)
    assert found[0] == pytest.approx(450.0) and errors[0] == pytest.approx(1350.0)


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
    linear between them, whose own error is about 1e-4 of the time): within 1 % of the
    time (measured: 3e-5)."""
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


@pytest.mark.parametrize("root", [0.0, 1e-9, 0.3, 0.999, 1.0])
@pytest.mark.parametrize("degree", [1, 2, 3])
def test_the_crossing_is_the_root_of_the_line_quadratic_or_cubic(degree, root):
    # r - 1 = (x - root)(x + 2)^(degree - 1): the one root in [0, 1], a sign change there
    x = np.linspace(-0.5, 1.5, degree + 1)
    r = 1.0 + (x - root) * (x + 2.0) ** (degree - 1)
    found = polynomial_crossing(10.0 + 5.0 * x, r, 10.0, 15.0)
    assert found == pytest.approx(10.0 + 5.0 * root, abs=64 * np.finfo(float).eps * 15.0)


def test_the_crossing_is_the_first_of_three_roots():
    # r - 1 = (x - 0.2)(x - 0.5)(x - 0.8): three crossings in [0, 1], the first is taken
    x = np.array([-0.1, 0.35, 0.65, 1.1])
    r = 1.0 + (x - 0.2) * (x - 0.5) * (x - 0.8)
    assert polynomial_crossing(x, r, 0.0, 1.0) == pytest.approx(0.2, abs=1e-14)
