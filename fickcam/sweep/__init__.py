"""Sweeps and Monte Carlo over many scenes on dask.distributed.

``run_sweep(sweep_path, output, workers=None, scheduler=None, progress=False)``
is what ``fickcam sweep`` calls. dask is imported only when a sweep runs, so
``import fickcam`` stays light.
"""
from __future__ import annotations

from .runner import compute_cases, dask_client, run_sweep
from .spec import Case, Distribution, Parameter, Sweep, load_sweep
from .workdir import WorkFolder

__all__ = ["run_sweep", "load_sweep", "compute_cases", "dask_client", "Sweep", "Case",
           "Parameter", "Distribution", "WorkFolder"]
