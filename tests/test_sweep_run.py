"""Sweeps on dask.distributed: one LocalCluster with 2 worker processes shared by the
module; each case checked against its single run, a failing case reported while the
others complete, a resumed sweep recomputing no finished case."""
import logging
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

import fickcam
from fickcam.cli.main import main
from fickcam.sweep import WorkFolder, compute_cases, load_sweep, run_sweep

CONFIGS = Path(__file__).resolve().parents[1] / "configs"


def small_base() -> str:
    """Singh & Sanyal 2017's cam with three ageing times, a coarse angle step and a loose
    diffusion accuracy (fast cases: the sweep machinery is under test, not the physics)."""
    scene = yaml.safe_load((CONFIGS / "singh2017_cam.yaml").read_text())
    scene["outputs"].update(ageing_times=["0 d", "30 d", "60 d"], angle_step="10 deg")
    scene["diffusion"]["accuracy"] = 5e-2
    scene["outputs"].pop("file", None)
    return yaml.safe_dump(scene, sort_keys=False)


def write_sweep(folder: Path, text: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "base.yaml").write_text(small_base())
    (folder / "sweep.yaml").write_text(text)
    return folder / "sweep.yaml"


GRID = """\
base: base.yaml
grid:
  environment.history.0.relative_humidity: [60 %, 150 %, 90 %]
  environment.history.0.temperature: [113 degC]
"""
INVALID = """\
base: base.yaml
grid:
  environment.history.0.relative_humidity: [120 %, 150 %]
"""
RH_FAILED = {1}  # the 150 % case of GRID


@pytest.fixture(scope="module")
def scheduler():
    """One LocalCluster (2 single-threaded worker processes) for the whole module."""
    from distributed import LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=":0", silence_logs=logging.WARNING) as cluster:
        yield cluster.scheduler_address


@pytest.fixture(scope="module")
def interrupted_then_resumed(scheduler, tmp_path_factory):
    """GRID run as a sweep that stopped after cases 0 and 1, then was resumed (case 2)."""
    from distributed import Client

    path = write_sweep(tmp_path_factory.mktemp("grid"), GRID)
    output = path.parent / "out.h5"
    sweep = load_sweep(path)
    folder = WorkFolder.next_to(output)
    folder.open_for(sweep.identity, len(sweep.cases))
    with Client(scheduler) as client:
        first = compute_cases(sweep, folder, [0, 1], client)
    run_sweep(path, output, scheduler=scheduler)
    return sweep, first, fickcam.open_result(output), output


@pytest.mark.slow
def test_every_case_equals_running_its_scene_alone(interrupted_then_resumed):
    sweep, _, result, _ = interrupted_then_resumed
    assert result.sizes["case"] == len(sweep.cases) == 3
    for case in sweep.cases:
        if case.index in RH_FAILED:
            continue
        alone = fickcam.run(fickcam.load_scene(sweep.scene_dict(case)))
        per_case = [name for name in result.data_vars if "case" in result[name].dims]
        in_sweep = result[per_case].isel(case=case.index, drop=True).reset_coords(drop=True)
        assert set(in_sweep.data_vars) == set(alone.data_vars)
        xr.testing.assert_allclose(in_sweep, alone.drop_attrs().reset_coords(drop=True), rtol=1e-12,
                                   atol=0)


def test_failing_cases_are_reported_and_the_others_complete(interrupted_then_resumed):
    _, _, result, _ = interrupted_then_resumed
    status = result["case_status"].values.tolist()
    assert [i for i, s in enumerate(status) if s == "failed"] == sorted(RH_FAILED)
    for index in RH_FAILED:
        message = result["case_message"].values[index]
        assert "environment.history.0.relative_humidity" in message and "100" in message
        assert np.isnan(result["moisture_content"].isel(case=index).values).all()
    ok = [i for i in range(3) if i not in RH_FAILED]
    assert np.isfinite(result["lift"].isel(case=ok).values).all()
    assert result.attrs["failed_cases"] == 1
    np.testing.assert_allclose(result["environment__history__0__relative_humidity"].values,
                               [60, 150, 90])
    np.testing.assert_allclose(result["environment__history__0__temperature"].values, [386.15] * 3)


def test_a_resumed_sweep_recomputes_no_finished_case(interrupted_then_resumed):
    _, first, result, output = interrupted_then_resumed
    for index, record in first.items():
        assert result["case_wall_time"].values[index] == record["wall_time"], \
            f"case {index} was computed again"
    assert not WorkFolder.next_to(output).path.exists(), "the work folder is removed when done"


def test_a_sweep_whose_cases_all_finished_needs_no_workers(scheduler, tmp_path):
    from distributed import Client

    path = write_sweep(tmp_path, INVALID)
    sweep = load_sweep(path)
    folder = WorkFolder.next_to(tmp_path / "out.h5")
    folder.open_for(sweep.identity, len(sweep.cases))
    with Client(scheduler) as client:
        compute_cases(sweep, folder, [0, 1], client)
    # nothing left to run: no scheduler is contacted (this address has none)
    run_sweep(path, tmp_path / "out.h5", scheduler="tcp://127.0.0.1:9")
    assert fickcam.open_result(tmp_path / "out.h5")["case_status"].values.tolist() == ["failed"] * 2


def test_invalid_values_become_failed_cases_with_the_reason(scheduler, tmp_path):
    path = write_sweep(tmp_path, INVALID)
    assert main(["sweep", str(path), "--scheduler", scheduler, "-o", str(tmp_path / "out.h5"),
                 "--quiet"]) == 0
    result = fickcam.open_result(tmp_path / "out.h5")
    assert result["case_status"].values.tolist() == ["failed", "failed"]
    assert all("relative_humidity: must not exceed 100" in m for m in result["case_message"].values)


def test_one_worker_runs_the_cases_in_this_process_without_bars_in_a_log(tmp_path, capsys):
    path = write_sweep(tmp_path, INVALID)
    run_sweep(path, tmp_path / "out.h5", workers=1, progress=True)
    assert "\r" not in capsys.readouterr().err  # stderr is no terminal: no progress frames
    assert fickcam.open_result(tmp_path / "out.h5").sizes["case"] == 2


def test_monte_carlo_draws_run_as_cases_with_their_values_as_coordinates(scheduler, tmp_path):
    # draws above 100 % RH: every case fails validation on a worker, cheaply
    path = write_sweep(tmp_path, "base: base.yaml\nsamples: 3\nseed: 4\nrandom:\n"
                                 "  environment.history.0.relative_humidity: {uniform: [101 %, 140 %]}\n")
    run_sweep(path, tmp_path / "mc.h5", scheduler=scheduler)
    result = fickcam.open_result(tmp_path / "mc.h5")
    assert result.attrs["sweep_kind"] == "monte_carlo" and result.attrs["seed"] == 4
    drawn = result["environment__history__0__relative_humidity"].values
    expected = [float(c.values["environment.history.0.relative_humidity"].split()[0])
                for c in load_sweep(path).cases]
    np.testing.assert_allclose(drawn, expected)
    assert ((drawn > 101) & (drawn < 140)).all() and len(set(drawn)) == 3
    assert (result["case_status"] == "failed").all()
    assert all("must not exceed 100" in m for m in result["case_message"].values)


def test_grid_plots_show_each_output_against_the_varied_values(interrupted_then_resumed, tmp_path):
    from fickcam.plotting.sweep import outputs, plot

    _, _, result, _ = interrupted_then_resumed
    written = plot(result, tmp_path).paths
    assert {p.name for p in written} >= {"sweep_lift_change.png", "sweep_jump_speed.png",
                                         "sweep_peak_cam_torque.png"}
    change = outputs(result)["lift_change"][1]
    assert change.dims == ("case", "time") and np.isnan(change.isel(case=sorted(RH_FAILED))).all()


@pytest.mark.slow
def test_more_cases_than_are_kept_in_flight_all_complete_once(scheduler, tmp_path):
    values = ", ".join(f"{101 + k} %" for k in range(40))  # 40 cheap (invalid) cases
    path = write_sweep(tmp_path, f"base: base.yaml\ngrid:\n  environment.history.0.relative_humidity: [{values}]\n")
    sweep = load_sweep(path)
    folder = WorkFolder.next_to(tmp_path / "out.h5")
    folder.open_for(sweep.identity, len(sweep.cases))
    from distributed import Client

    with Client(scheduler) as client:
        records = compute_cases(sweep, folder, range(40), client)
    assert sorted(records) == list(range(40))
    assert sorted(folder.journal.read()) == list(range(40))


@pytest.mark.parametrize("cases, threads", [(1, 2), (3, 2), (17, 1), (1000, 2), (1000, 64)])
def test_batches_hold_every_case_once_in_order_and_keep_every_thread_busy(cases, threads):
    from fickcam.sweep.runner import BATCHES_PER_THREAD, MAX_BATCH, batches

    indices = list(range(5, 5 + cases))
    split = batches(indices, threads)
    assert [i for batch in split for i in batch] == indices
    assert all(1 <= len(batch) <= MAX_BATCH for batch in split)
    assert len(split) >= min(cases, BATCHES_PER_THREAD * threads)


OK_GRID = """\
base: base.yaml
grid:
  environment.history.0.relative_humidity: [60 %, 90 %]
"""


def test_a_case_keeps_its_warnings_in_its_record_and_lets_none_escape(tmp_path):
    """A worker has no terminal: a case's warnings (here the demo motion's infinite jerk)
    go into its record and its message, none reaches Python's warnings machinery."""
    import warnings

    from fickcam.sweep.case import run_case
    from fickcam.sweep.runner import case_task

    sweep = load_sweep(write_sweep(tmp_path, OK_GRID))
    with warnings.catch_warnings(record=True) as escaped:
        warnings.simplefilter("always")
        record, _ = run_case(case_task(sweep, 0))
    assert record["status"] == "ok"
    assert [w.message for w in escaped if issubclass(w.category, fickcam.FickcamWarning)] == []
    assert len(record["warnings"]) == 1 and "infinite jerk" in record["warnings"][0]
    assert record["warnings"][0] in record["message"]


def test_a_sweep_reports_each_warning_of_its_cases_once_with_their_count(tmp_path, capsys):
    path = write_sweep(tmp_path, OK_GRID)
    assert main(["sweep", str(path), "--workers", "1", "-o", str(tmp_path / "out.h5")]) == 0
    warned = [line for line in capsys.readouterr().err.splitlines() if "warning" in line]
    assert len(warned) == 1, warned
    assert warned[0].startswith("fickcam: warning: 2 of 2 case(s): motion as designed:")


def test_at_most_a_few_distinct_warnings_are_listed_and_the_rest_counted():
    from fickcam.sweep.runner import SHOWN_WARNINGS, report_case_warnings

    records = {i: {"status": "ok", "warnings": [f"case {i} is odd", "shared"]}
               for i in range(SHOWN_WARNINGS + 3)}
    records[99] = {"status": "ok"}  # journaled before records kept their warnings
    with pytest.warns(fickcam.FickcamWarning) as caught:
        report_case_warnings(records, len(records))
    texts = [str(w.message) for w in caught]
    assert texts[0] == f"{SHOWN_WARNINGS + 3} of {SHOWN_WARNINGS + 4} case(s): shared"
    assert len(texts) == SHOWN_WARNINGS + 1
    assert texts[-1].startswith("4 other warning(s) of the cases")
