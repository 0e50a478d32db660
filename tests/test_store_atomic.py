"""A failed or killed run never damages an earlier result file."""
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from fickcam.results import ncwrite
from fickcam.results.dataset import build_dataset
from fickcam.results.store import open_result, save

CONFIGS = Path(__file__).resolve().parents[1] / "configs"


def _dataset(value):
    return build_dataset({"temperature": np.full(3, value)}, {"time": [0.0, 1.0, 2.0]}, {})


@pytest.mark.parametrize("writer", ["h5py", "xarray"])
def test_failure_while_writing_keeps_the_old_file_and_leaves_no_temporary(tmp_path, monkeypatch,
                                                                          writer):
    path = tmp_path / "r.h5"
    save(_dataset(300.0), path)

    def broken(*args, **kwargs):  # the temporary file is open and half written
        raise OSError("disk full")

    if writer == "h5py":
        monkeypatch.setattr(ncwrite, "set_attributes", broken)
    else:  # the datasets fickcam.results.ncwrite does not take
        monkeypatch.setattr(ncwrite, "writable", lambda ds: False)
        monkeypatch.setattr(xr.Dataset, "dump_to_store", broken)
    with pytest.raises(OSError):
        save(_dataset(400.0), path)
    monkeypatch.undo()
    assert float(open_result(path).temperature[0]) == 300.0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.h5"]


def test_saved_file_reads_back_identical_to_what_to_netcdf_writes(tmp_path):
    ds = build_dataset({"temperature": np.array([300.0, 310.0, 320.0])},
                       {"time": [0.0, 3600.0, 86400.0]}, {"notices": ["a", "b"], "flag": True})
    save(ds, tmp_path / "ours.h5")
    reference = ds.copy()
    reference.attrs = {"notices": '["a", "b"]', "flag": 1}
    reference.time.encoding.update({"units": "seconds", "dtype": "float64"})
    reference.to_netcdf(tmp_path / "xarray.h5", engine="h5netcdf")
    ours, theirs = open_result(tmp_path / "ours.h5"), open_result(tmp_path / "xarray.h5")
    xr.testing.assert_identical(ours, theirs)


def test_dask_backed_data_is_written_not_skipped(tmp_path):
    pytest.importorskip("dask.array")
    ds = build_dataset({"temperature": np.array([300.0, 310.0, 320.0])}, {"time": [0.0, 1.0, 2.0]})
    save(ds.chunk({"time": 2}), tmp_path / "lazy.h5")
    np.testing.assert_array_equal(open_result(tmp_path / "lazy.h5").temperature, ds.temperature)


@pytest.mark.slow
def test_saving_a_result_does_not_import_dask_distributed(tmp_path):
    code = ("import sys, numpy as np\n"
            "from fickcam.results.dataset import build_dataset\n"
            "from fickcam.results.store import save\n"
            "save(build_dataset({'temperature': np.ones(2)}, {'time': [0.0, 1.0]}, {}), sys.argv[1])\n"
            "assert 'distributed' not in sys.modules, 'save imported dask.distributed'\n")
    subprocess.run([sys.executable, "-c", code, str(tmp_path / "r.h5")], check=True,
                   env={**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[1])})


@pytest.mark.slow
def test_kill_9_at_random_moments_never_leaves_an_unreadable_result(tmp_path):
    scene = CONFIGS / "yadav2017_cam.yaml"  # no diffusion: each run is mostly start-up and writing
    target = tmp_path / "existing.h5"
    command = [sys.executable, "-m", "fickcam.cli.main", "run", str(scene), "-o", str(target), "--quiet"]
    started = time.perf_counter()
    subprocess.run(command, check=True, capture_output=True, cwd=tmp_path)
    duration = time.perf_counter() - started
    reference = open_result(target)
    rng = random.Random(20261121)
    outcomes = []
    for _ in range(6):
        process = subprocess.Popen(command, cwd=tmp_path, stdout=subprocess.DEVNULL,
                                   stderr=subprocess.DEVNULL)
        time.sleep(rng.uniform(0.3, 1.1) * duration)
        os.kill(process.pid, signal.SIGKILL)
        process.wait()
        result = open_result(target)  # raises if damaged
        assert result.sizes == reference.sizes
        xr.testing.assert_allclose(result.drop_attrs(), reference.drop_attrs())
        outcomes.append(process.returncode)
    assert any(code == -signal.SIGKILL for code in outcomes), "no run was actually killed"


SLOW_WRITE = """
import signal, sys, time
from pathlib import Path
import fickcam.results.store
from fickcam.cli.main import process_main

READY = Path(sys.argv[1])
# Ctrl-C as in a terminal's foreground, whatever this process inherited: a shell starts a
# background job (a CI script run with &) with SIGINT ignored, which Python then leaves
# ignored, and a blocked signal stays blocked across exec; either way the signal did
# nothing and the test timed out
signal.signal(signal.SIGINT, signal.default_int_handler)
signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT, signal.SIGTERM})


def stalled(ds, target):  # the temporary file is open and half written when the signal comes
    target.write(b"half a result")
    READY.write_text("writing")
    time.sleep(60)

fickcam.results.store._write_netcdf = stalled
sys.argv = ["fickcam", "run", sys.argv[2], "-o", sys.argv[3], "-qq"]
sys.exit(process_main())
"""


@pytest.mark.parametrize("stop, status, said", [(signal.SIGTERM, 143, "terminated"),
                                                (signal.SIGINT, 130, "interrupted")])
def test_a_run_stopped_while_it_writes_leaves_no_temporary(tmp_path, stop, status, said):
    """SIGTERM ended the process on the spot and left the hidden ``.out.h5.XXXXXXXX.tmp``
    beside the result; it is now raised where the process is, as Ctrl-C is."""
    target, ready = tmp_path / "out.h5", tmp_path / "ready"
    save(_dataset(300.0), target)
    process = subprocess.Popen([sys.executable, "-c", SLOW_WRITE, str(ready),
                                str(CONFIGS / "yadav2017_cam.yaml"), str(target)],
                               cwd=tmp_path, stderr=subprocess.PIPE, text=True,
                               env=dict(os.environ, PYTHONPATH=str(CONFIGS.parent)))
    deadline = time.monotonic() + 120
    while not ready.exists() and process.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    process.send_signal(stop)
    _, err = process.communicate(timeout=60)
    assert (process.returncode, err) == (status, f"fickcam: error: {said}\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.h5", "ready"]
    assert float(open_result(target).temperature[0]) == 300.0


HOLDER = """
import sys, time
from pathlib import Path
from fickcam.files import temporary_beside

with temporary_beside(Path(sys.argv[1])) as tmp:
    print(tmp, flush=True)
    time.sleep(60)
"""


def test_a_later_write_removes_a_dead_writers_temporary_and_keeps_a_live_ones(tmp_path):
    """A writer killed by SIGKILL (nothing runs) leaves its temporary file: the next save
    of the same result removes it, but never the file a live writer holds."""
    target = tmp_path / "out.h5"
    dead = tmp_path / ".out.h5.k3j_9x2q.tmp"  # what a killed write leaves, held by nobody
    dead.write_bytes(b"half a result")
    other = tmp_path / ".other.h5.k3j_9x2q.tmp"  # another result's
    other.write_bytes(b"another file's")
    holder = subprocess.Popen([sys.executable, "-c", HOLDER, str(target)], stdout=subprocess.PIPE,
                              text=True, env=dict(os.environ, PYTHONPATH=str(CONFIGS.parent)))
    try:
        live = Path(holder.stdout.readline().strip())
        save(_dataset(300.0), target)
        assert not dead.exists() and other.exists() and live.exists()
    finally:
        holder.kill()
        holder.wait()
    save(_dataset(400.0), target)  # its writer is gone now
    assert sorted(p.name for p in tmp_path.iterdir()) == [".other.h5.k3j_9x2q.tmp", "out.h5"]
