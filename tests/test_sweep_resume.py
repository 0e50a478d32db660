"""A sweep killed with SIGKILL at a random moment and run again gives exactly the result of
an uninterrupted run (what was done stays done; a torn journal entry runs again)."""
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
import xarray as xr
import yaml

import fickcam
from fickcam.sweep import WorkFolder, run_sweep
from test_sweep_run import small_base

ROOT = Path(__file__).resolve().parents[1]
GRID = """\
base: base.yaml
grid:
  environment.history.0.relative_humidity: [55 %, 70 %, 85 %, 95 %, 150 %]
"""


def write_sweep(folder: Path) -> Path:
    """GRID over test_sweep_run's small base without its limits (cheaper cases)."""
    base = yaml.safe_load(small_base())
    base.pop("limits")
    (folder / "base.yaml").write_text(yaml.safe_dump(base, sort_keys=False))
    (folder / "sweep.yaml").write_text(GRID)
    return folder / "sweep.yaml"


def without_timings(ds):
    """The result but for what measures time (case_wall_time, the sweep's wall_time)."""
    ds = ds.drop_vars("case_wall_time")
    ds.attrs.pop("wall_time_s")
    return ds


CASES = 5


def kill_while_running(sweep_file: Path, output: Path, delay: float) -> dict | None:
    """Start `fickcam sweep --workers 1` in a process and kill -9 it ``delay`` seconds after
    its first bytes are journaled; the journal's whole cases at the kill, or None when the sweep
    had already finished (the kill came too late to test anything)."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    process = subprocess.Popen([sys.executable, "-m", "fickcam.cli.main", "sweep", str(sweep_file),
                                "--workers", "1", "-o", str(output), "--quiet"], env=env,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    journal = WorkFolder.next_to(output).journal
    deadline = time.monotonic() + 120
    while not (journal.path.is_file() and journal.path.stat().st_size) and \
            time.monotonic() < deadline and process.poll() is None:
        time.sleep(0.01)
    time.sleep(delay)
    process.send_signal(signal.SIGKILL)
    process.wait()
    if process.returncode != -signal.SIGKILL or not journal.path.is_file():
        return None
    done = journal.read()
    return done if len(done) < CASES else None


@pytest.mark.slow
def test_a_sweep_killed_at_a_random_moment_resumes_to_the_uninterrupted_result(tmp_path):
    seed = random.randrange(1 << 16)
    path = write_sweep(tmp_path)
    run_sweep(path, tmp_path / "whole.h5", workers=1)
    whole = fickcam.open_result(tmp_path / "whole.h5")

    # a random moment within the sweep: how long its cases take depends on the machine, so
    # a kill that comes after the last case is tried again sooner (never a pass by default)
    delay = random.Random(seed).uniform(0.0, 0.4)
    for attempt in range(5):
        resumed_path = tmp_path / f"resumed{attempt}.h5"
        done = kill_while_running(path, resumed_path, delay)
        if done is not None:
            break
        delay /= 4
    else:
        raise AssertionError(f"seed {seed}: every kill came after the sweep had finished")
    run_sweep(path, resumed_path, workers=1)
    resumed = fickcam.open_result(resumed_path)
    xr.testing.assert_identical(without_timings(resumed), without_timings(whole))
    for index, entry in done.items():  # finished before the kill: not run again
        assert resumed["case_wall_time"].values[index] == entry.record["wall_time"], f"seed {seed}"
    assert not WorkFolder.next_to(resumed_path).path.exists()
