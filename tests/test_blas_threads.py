"""A run limits BLAS to one thread only while it runs (fickcam.simulation.blas): the caller's BLAS
threads are the same before and after, also when the run fails, and the limit leaves
every result of the demo scene bit-identical."""
from __future__ import annotations

import logging
from pathlib import Path

import numpy as np
import pytest
from threadpoolctl import threadpool_info, threadpool_limits

from fickcam.errors import SceneError
from fickcam.scene.load import load_scene
from fickcam.simulation.options import RunOptions
from fickcam.simulation.simulate import run, run_with

DEMO = Path(__file__).resolve().parents[1] / "configs" / "singh2017_cam.yaml"
CALLER_THREADS = 2  # what the caller asks for; the run must give it back


def blas_threads() -> dict[str, int]:
    """Threads of every loaded BLAS library, by file."""
    return {p["filepath"]: p["num_threads"] for p in threadpool_info() if p["user_api"] == "blas"}


class ThreadsSeen(logging.Handler):
    """Each loaded BLAS library's threads whenever fickcam logs (a run logs each diffusion
    solve at DEBUG): the threads inside the run, seen through the logging API."""

    def __init__(self):
        super().__init__(logging.DEBUG)
        self.seen: list[dict[str, int]] = []

    def emit(self, record):
        self.seen.append(blas_threads())


@pytest.fixture(scope="module")
def demo_runs():
    """The demo run with the limit, then without it (``run_with.__wrapped__``: the function
    the limit wraps, which ``run`` calls once it has loaded the scene), the caller having set its own limit first: (threads seen inside the
    limited run, the caller's threads after it, its result, the result without the limit,
    threads seen inside that run)."""
    spy, logger = ThreadsSeen(), logging.getLogger("fickcam")
    level = logger.level
    logger.addHandler(spy)
    logger.setLevel(logging.DEBUG)
    try:
        with threadpool_limits(CALLER_THREADS, "blas"):
            limited = run(DEMO)
            inside, after = list(spy.seen), blas_threads()
            scene = load_scene(DEMO)
            default = run_with.__wrapped__(scene, RunOptions.for_scene(scene))
            unlimited = spy.seen[len(inside):]
    finally:
        logger.removeHandler(spy)
        logger.setLevel(level)
    return inside, after, limited, default, unlimited


@pytest.mark.slow
def test_run_uses_one_blas_thread_in_every_blas_library(demo_runs):
    seen = demo_runs[0]
    assert seen and len(seen[0]) >= 1  # numpy's OpenBLAS at least (scipy's too when loaded)
    assert all(threads == 1 for during in seen for threads in during.values())


def test_without_the_limit_the_run_would_use_the_callers_threads(demo_runs):
    unlimited = demo_runs[4]  # the comparison below compares two thread counts
    # the run's planning is limited by itself (fickcam.simulation.planning.plan_parts, as `check`);
    # its solves, unwrapped, run on the caller's threads
    assert unlimited and any(all(threads == CALLER_THREADS for threads in during.values())
                             for during in unlimited)


def test_caller_blas_threads_are_restored_after_run(demo_runs):
    after = demo_runs[1]
    assert after and all(threads == CALLER_THREADS for threads in after.values())


def test_caller_blas_threads_are_restored_when_run_fails():
    with threadpool_limits(CALLER_THREADS, "blas"):
        before = blas_threads()
        with pytest.raises(SceneError):
            run({"name": "broken"})  # no environment: refused inside the limited run
        assert blas_threads() == before


def test_one_blas_thread_leaves_the_demo_results_bit_identical(demo_runs):
    limited, default = demo_runs[2], demo_runs[3]
    assert set(limited.data_vars) == set(default.data_vars)
    for name, variable in limited.data_vars.items():
        assert np.array_equal(variable.values, default[name].values,
                              equal_nan=variable.dtype.kind == "f"), name
