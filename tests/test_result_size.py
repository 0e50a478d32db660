"""The result's size: estimated from the scene before any work, warned of above 1 GiB
with the settings that shrink it, refused before the run when the disk cannot hold it;
large results written in chunks, deflated, and read lazily."""
import re
from pathlib import Path

import h5py
import numpy as np
import pytest
import xarray as xr

import fickcam
from fickcam.results import store
from fickcam.cli.main import main
from fickcam.simulation.resultsize import WARN_ABOVE, estimate
from fickcam.scene.load import load_scene
from test_scene_errors import CAM_SCENE

ROOT = Path(__file__).resolve().parents[1]
#: ten years of hourly outputs: 87,601 ageing times (it ran 100 s and wrote 4.8 GB unasked)
HOURLY = CAM_SCENE.replace("duration: 60 d", "duration: 3650 d").replace(
    "ageing_times: [0 d, 1 d, 7 d, 30 d, 60 d]", "ageing_times: {every: 1 h}")


@pytest.mark.parametrize("config", ["singh2017_cam", "fourbar_r914_humid", "nylon_swinging_arm"])
def test_the_estimate_bounds_the_file_from_above_within_a_factor_of_two(config, tmp_path):
    """A cam, a four-bar and a swinging arm: the estimate (before any work) against the file
    the run writes. It counts every variable such a scene can compute: never below the file,
    at most 1.6 x it (measured 1.1 to 1.5 x)."""
    scene = load_scene(ROOT / "configs" / f"{config}.yaml")
    predicted = estimate(scene).bytes
    written = store.save(fickcam.run(scene), tmp_path / "r.h5").stat().st_size
    assert written <= predicted <= 1.6 * written


def test_check_prints_the_size_and_warns_above_a_gib_with_what_shrinks_it(tmp_path, capsys):
    scene = tmp_path / "hourly.yaml"
    scene.write_text(HOURLY)
    assert main(["check", str(scene)]) == 0
    out, err = capsys.readouterr()
    assert re.search(r"result: about 4\.\d+ GB \(87,601 ageing times x 360 cam angles\)", out)
    (warning,) = [line for line in err.splitlines() if "warning" in line]
    assert warning.startswith("fickcam: warning: the result will be about 4.")
    assert warning.endswith("to shrink it: fewer ageing times (outputs.ageing_times) or a "
                            "coarser outputs.angle_step")
    scene.write_text(HOURLY.replace("fields: false", "fields: true"))
    assert main(["check", str(scene)]) == 0
    assert "outputs.fields: false" in capsys.readouterr().err
    assert estimate(load_scene(scene)).bytes > WARN_ABOVE


def test_a_result_the_disk_cannot_hold_is_refused_before_the_run(tmp_path, capsys, monkeypatch):
    scene = tmp_path / "hourly.yaml"
    scene.write_text(HOURLY)
    output = tmp_path / "out.h5"

    def no_run(*args, **kwargs):
        raise AssertionError("the run started")

    monkeypatch.setattr("fickcam.simulation.simulate.run", no_run)
    monkeypatch.setattr("fickcam.simulation.resultsize.free_space", lambda folder: 10**9)  # 1 GB free
    assert main(["run", str(scene), "-o", str(output)]) == 1
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert re.fullmatch(rf"fickcam: error: {re.escape(str(output))}: the result will be about "
                        r"4\.\d+ GB \(87,601 ageing times x 360 cam angles\) and needs at least "
                        r"1\.\d+ GB on the disk, which has 1 GB free: nothing was run; to shrink "
                        r"it: .*", err), err
    assert not any(tmp_path.glob("*.h5*")) and not any(tmp_path.glob(".out*"))


def test_a_large_result_is_chunked_deflated_and_read_lazily(tmp_path, monkeypatch):
    """The bounds made small so that the demo's result counts as large: its big variables
    are stored in chunks of about CHUNK_BYTES along time, deflated; it opens lazily and a
    query gives what the in-memory result gives."""
    ds = fickcam.run(ROOT / "configs" / "singh2017_cam.yaml")
    small = store.save(ds, tmp_path / "small.h5")
    monkeypatch.setattr(store, "CHUNKED_ABOVE", 100_000)
    monkeypatch.setattr(store, "CHUNK_BYTES", 4_000)
    large = store.save(ds, tmp_path / "large.h5")
    with h5py.File(large) as f:
        lift = f["follower_displacement"]
        assert lift.chunks == (1, 360) and lift.compression == "gzip"
        assert f["moisture_content"].chunks is None  # smaller than a chunk: as it was
    with h5py.File(small) as f:
        assert f["follower_displacement"].chunks is None
    lazy = store.open_result(large)
    assert not lazy["follower_displacement"].variable._in_memory
    eager = store.open_result(small)
    from fickcam.results.query import select

    for time in ("45 d", "60 d"):
        np.testing.assert_array_equal(select(lazy, "follower_displacement", time=time).values,
                                      select(eager, "follower_displacement", time=time).values)
    xr.testing.assert_identical(lazy.load(), eager)
    lazy.close()


DAILY = CAM_SCENE.replace("duration: 60 d", "duration: 3650 d").replace(
    "ageing_times: [0 d, 1 d, 7 d, 30 d, 60 d]", "ageing_times: {every: 1 d}")


def test_a_sweep_is_estimated_warned_of_and_refused_before_its_first_case(tmp_path, capsys,
                                                                            monkeypatch):
    """A sweep combines its cases into one result: ten years of daily outputs are 0.2 GB
    a case, and 12 cases 2.4 GB, which no sweep estimated before its cases ran."""
    (tmp_path / "base.yaml").write_text(DAILY)
    sweep = tmp_path / "sweep.yaml"
    sweep.write_text("base: base.yaml\ngrid:\n  cam.speed: [" + ", ".join(
        f"{500 + 10 * k} rpm" for k in range(12)) + "]\n")
    output = tmp_path / "out.h5"

    def no_case(*args, **kwargs):
        raise AssertionError("a case started")

    monkeypatch.setattr("fickcam.sweep.runner.run_here", no_case)
    monkeypatch.setattr("fickcam.simulation.resultsize.free_space", lambda folder: 10**8)  # 100 MB free
    assert main(["sweep", str(sweep), "-o", str(output), "--workers", "1"]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    size = r"about 2\.\d+ GB \(12 cases x 3,651 ageing times x 360 cam angles\)"
    assert re.fullmatch(rf"fickcam: warning: the result will be {size}, written compressed; to "
                        r"shrink it: fewer cases, fewer ageing times \(outputs.ageing_times\) or "
                        r"a coarser outputs.angle_step", err[-2]), err
    assert re.fullmatch(rf"fickcam: error: {re.escape(str(output))}: the result will be {size} "
                        r"and needs at least .* on the disk, which has 100 MB free: nothing was "
                        r"run; .*", err[-1]), err
    assert not output.exists()
    one = estimate(load_scene(tmp_path / "base.yaml"))
    assert estimate(load_scene(tmp_path / "base.yaml"), cases=12).bytes == pytest.approx(
        12 * one.bytes, rel=0.01)
