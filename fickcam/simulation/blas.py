"""One BLAS thread for the length of a run.

A run makes many small dense linear-algebra calls (the cams' Chebyshev fits, a least-squares
solve each; the four-bar's batched force solves, numpy.linalg.solve). OpenBLAS wakes its
pool of worker threads for them, which then spin idle between calls: on the project's 2-core
machine, limited to one thread, a demo-cam run took 0.68 x the CPU time, the four-bar
through a year 0.72 x and a 4-case Monte Carlo 0.85 x, while the large solves (the
two-phase demo cam's Lanczos on its 58 k-cell planform, a 3-D solid plate) kept their
wall time within 2 % (benchmarks/bench_blas_threads.py, benchmarks/results/blas_threads.json).
The limit is scoped (``threadpoolctl``): the caller's BLAS threads are restored on return.
"""
from __future__ import annotations

import functools
import scipy.linalg  # noqa: F401  (loads scipy's own OpenBLAS, so that it is limited too)
from threadpoolctl import threadpool_limits


def one_blas_thread():
    """A context manager limiting every loaded BLAS library (numpy's and scipy's OpenBLAS)
    to one thread, restoring the caller's limits on exit."""

    return threadpool_limits(1, "blas")


def on_one_blas_thread(function):
    """``function`` run inside :func:`one_blas_thread` (a decorator).

    Parameters
    ----------
    function : callable
        The function to limit.

    Returns
    -------
    callable
        A wrapper that calls ``function`` with every BLAS library on one thread.
    """
    @functools.wraps(function)
    def limited(*args, **kwargs):
        with one_blas_thread():
            return function(*args, **kwargs)
    return limited
