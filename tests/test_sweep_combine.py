"""Per-case bookkeeping (the sweep's journal) and combining along ``case``, with small
synthetic results (built through fickcam.results.dataset like a real run), so no physics is
needed."""
import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import fickcam
from fickcam.results.dataset import build_dataset
from fickcam.errors import InputError
from fickcam.sweep import WorkFolder, load_sweep
from fickcam.sweep.combine import combine, missing_like, stack_cases
from fickcam.sweep.journal import HEAD, decode_dataset, encode_case
from fickcam.sweep.runner import finished_cases

CONFIGS = Path(__file__).resolve().parents[1] / "configs"
DAY = 86400.0


def synthetic_result(rh: float):
    times = np.array([0.0, 10.0, 30.0]) * DAY
    moisture = np.outer(1 - np.exp(-times / (20 * DAY)), [1.0, 0.5]) * rh / 50
    values = {"temperature": np.full(3, 360.0), "relative_humidity": np.full(3, rh),
              "moisture_content": moisture, "lift": 0.0381 * (1 + 1e-4 * moisture[:, 0])}
    return build_dataset(values, {"time": times, "part": ["cam", "follower"]},
                         {"scene_name": "synthetic", "notices": [], "wall_time": 0.1})


@pytest.fixture
def sweep(tmp_path):
    (tmp_path / "base.yaml").write_text((CONFIGS / "singh2016_fourbar.yaml").read_text())
    path = tmp_path / "sweep.yaml"
    path.write_text("base: base.yaml\ngrid:\n"
                    "  environment.history.0.relative_humidity: [50 %, 150 %, 80 %]\n")
    return load_sweep(path)


def finish(folder: WorkFolder, index: int, message: str = "", rh: float | None = None,
           retry: bool = False) -> dict:
    """What the client journals for a finished case: its record and (ok cases) its result."""
    record = {"index": index, "status": "ok" if rh is not None else "failed", "message": message,
              "values": {}, "wall_time": 0.5}
    if retry:
        record["retry"] = True
    folder.journal.append(encode_case(record, None if rh is None else synthetic_result(rh)))
    return record


def combined_file(sweep, folder, records, path):
    fickcam.save(combine(sweep, records, finished_cases(folder, sweep, records)), path)
    return fickcam.open_result(path)


def test_combined_result_has_a_case_dimension_with_each_varied_value_as_coordinate(sweep, tmp_path):
    folder = WorkFolder.next_to(tmp_path / "out.h5")
    folder.open_for(sweep.identity, 3)
    records = {0: finish(folder, 0, rh=50.0), 1: finish(folder, 1, "too wet"), 2: finish(folder, 2, rh=80.0)}
    ds = combined_file(sweep, folder, records, tmp_path / "out.h5")
    rh = ds["environment__history__0__relative_humidity"]
    assert rh.dims == ("case",) and rh.attrs["units"] == "%"
    assert rh.attrs["dotted_path"] == "environment.history.0.relative_humidity"
    np.testing.assert_allclose(rh.values, [50, 150, 80])
    assert ds["moisture_content"].dims == ("case", "time", "part")
    for index, value in ((0, 50.0), (2, 80.0)):
        xr.testing.assert_allclose(ds.isel(case=index, drop=True).reset_coords(drop=True),
                                   synthetic_result(value).drop_attrs().reset_coords(drop=True),
                                   check_dim_order=False)
    assert ds["moisture_content"].attrs["units"] == "%"
    assert ds.attrs["sweep_kind"] == "grid" and ds.attrs["cases"] == 3
    assert "relative_humidity: [50 %, 150 %, 80 %]" in ds.attrs["sweep_text"]


def test_a_failed_case_has_nan_data_and_its_message_and_the_result_says_so(sweep, tmp_path):
    folder = WorkFolder.next_to(tmp_path / "out.h5")
    folder.open_for(sweep.identity, 3)
    records = {0: finish(folder, 0, rh=50.0), 1: finish(folder, 1, "relative_humidity: too wet"),
               2: finish(folder, 2, rh=80.0)}
    ds = combined_file(sweep, folder, records, tmp_path / "out.h5")
    assert ds["case_status"].values.tolist() == ["ok", "failed", "ok"]
    assert ds["case_message"].values[1] == "relative_humidity: too wet"
    assert np.isnan(ds["moisture_content"].isel(case=1).values).all()
    assert np.isfinite(ds["moisture_content"].isel(case=[0, 2]).values).all()
    assert ds.attrs["failed_cases"] == 1


def test_a_case_comes_back_from_the_journal_exactly():
    original = synthetic_result(65.0)
    record = {"index": 3, "status": "ok", "message": "", "values": {"a": "65 %"}, "wall_time": 1.0}
    xr.testing.assert_identical(decode_dataset(encode_case(record, original)),
                                original.drop_attrs(deep=False))


def test_stacking_case_by_case_equals_xarray_concat():
    parts = [synthetic_result(50.0), missing_like(synthetic_result(51.0)), synthetic_result(52.0)]
    flags = [np.array([True, False, True]), np.full(3, np.nan), np.array([False, False, True])]
    parts = [p.assign(flag=("time", f)) for p, f in zip(parts, flags)]  # bool among NaN: float
    fast = stack_cases(lambda i: parts[i], 3)
    assert fast["flag"].dtype == float
    xr.testing.assert_identical(fast.drop_attrs(deep=False), xr.concat(
        parts, dim="case", data_vars="all", coords="minimal", compat="override", join="outer",
        combine_attrs="override").drop_attrs(deep=False))


def test_a_work_folder_of_the_same_sweep_gives_back_its_finished_cases(sweep, tmp_path):
    folder = WorkFolder.next_to(tmp_path / "out.h5")
    assert folder.path == tmp_path / "out.h5.parts"
    assert folder.open_for(sweep.identity, 3) == {}
    done = {0: finish(folder, 0, rh=50.0), 1: finish(folder, 1, "failed for good")}
    assert folder.open_for(sweep.identity, 3) == done


def test_a_torn_last_entry_is_cut_off_and_the_whole_ones_kept(sweep, tmp_path):
    folder = WorkFolder.next_to(tmp_path / "out.h5")
    folder.open_for(sweep.identity, 3)
    finish(folder, 0, rh=50.0)
    whole = folder.journal.path.stat().st_size
    finish(folder, 2, rh=80.0)
    with open(folder.journal.path, "r+b") as handle:  # a kill -9 in the middle of the append
        handle.truncate(whole + HEAD.size + 100)
    assert set(folder.open_for(sweep.identity, 3)) == {0}
    assert folder.journal.path.stat().st_size == whole
    finish(folder, 2, rh=80.0)  # appends after the cut: both cases read back
    assert set(folder.open_for(sweep.identity, 3)) == {0, 2}


def test_a_work_folder_of_another_sweep_is_cleared_not_reused(sweep, tmp_path):
    folder = WorkFolder.next_to(tmp_path / "out.h5")
    folder.open_for("another sweep", 3)
    finish(folder, 0, rh=50.0)
    assert folder.open_for(sweep.identity, 3) == {}
    assert not folder.journal.path.exists()
    assert json.loads((folder.path / "manifest.json").read_text())["identity"] == sweep.identity


def test_a_foreign_folder_in_the_way_is_refused_not_deleted(sweep, tmp_path):
    folder = WorkFolder.next_to(tmp_path / "out.h5")
    folder.path.mkdir()
    (folder.path / "notes.txt").write_text("mine")
    with pytest.raises(InputError, match="not a fickcam sweep work folder"):
        folder.open_for(sweep.identity, 3)
    assert (folder.path / "notes.txt").read_text() == "mine"


def synthetic_sweep(kind: str, n: int = 6, failed=(1,)):
    """A combined result as a sweep writes it, without running physics."""
    cases = [synthetic_result(50.0 + 5 * i) for i in range(n)]
    for i in failed:
        cases[i] = cases[i].map(lambda v: v * np.nan)
    ds = xr.concat(cases, dim="case", data_vars="all", coords="minimal", compat="override",
                   join="outer", combine_attrs="override")
    rh = np.array([50.0 + 5 * i for i in range(n)])
    return ds.assign_coords(
        case=np.arange(n),
        environment__history__0__relative_humidity=("case", rh, {"units": "%", "dotted_path":
                                                                 "environment.history.0.relative_humidity"}),
        case_status=("case", np.array(["failed" if i in failed else "ok" for i in range(n)], object)),
        case_message=("case", np.array(["" for _ in range(n)], object)),
    ).assign_attrs(sweep_kind=kind, scene_name="synthetic")


def test_lift_change_is_measured_from_the_first_ageing_time_in_mm():
    from fickcam.plotting.sweep import outputs

    ds = synthetic_sweep("grid")
    label, change = outputs(ds)["lift_change"]
    expected = (ds["lift"] - ds["lift"].isel(time=0)) * 1e3
    xr.testing.assert_allclose(change, expected)
    assert label == "lift change since age 0 [mm]" and float(change.isel(case=0, time=0)) == 0.0
    assert (change.isel(case=0, time=-1) > 0).all(), "the synthetic cam swells: its lift grows"
    assert np.isnan(change.isel(case=1)).all()


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["grid", "monte_carlo"])
def test_sweep_plots_one_figure_per_output_through_fickcam_plot(kind, tmp_path):
    from fickcam.plotting import plot

    written = plot(synthetic_sweep(kind), tmp_path, "sweep").paths
    assert sorted(p.name for p in written) == ["sweep_cam_moisture.png", "sweep_lift_change.png"]
    assert all(p.stat().st_size > 1000 for p in written)


def test_a_case_that_failed_for_a_reason_other_than_its_scene_runs_again(sweep, tmp_path):
    folder = WorkFolder.next_to(tmp_path / "out.h5")
    folder.open_for(sweep.identity, 3)
    finish(folder, 0, rh=50.0)
    finish(folder, 1, "internal error: RuntimeError: pool closed", retry=True)
    assert set(folder.open_for(sweep.identity, 3)) == {0}


def test_a_single_text_value_per_case_is_stacked_as_text_and_saved(tmp_path):
    """A four-bar's as-designed Grashof class is one text value per case; the journal gives
    it back as a 0-d object array, whose item (not the array) goes into the stack, so the
    sweep's result saves."""
    from fickcam.sweep.journal import decode_arrays

    record = {"index": 0, "status": "ok", "message": "", "values": {"a": "65 %"}, "wall_time": 1.0}
    cases = [synthetic_result(50.0 + i).assign(grashof_class_design=((), "crank-rocker"))
             for i in range(2)]
    journal = [decode_arrays(encode_case(record, case)) for case in cases]
    stacked = stack_cases(lambda i: journal[i], 2)
    assert stacked["grashof_class_design"].values.tolist() == ["crank-rocker"] * 2
    fickcam.save(stacked, tmp_path / "text.h5")
    assert fickcam.open_result(tmp_path / "text.h5")["grashof_class_design"].values.tolist() == \
        ["crank-rocker"] * 2
