"""One case of a sweep, as a worker process runs it: scene dict → validated
scene → :func:`fickcam.simulation.simulate.run` → its record and journal payload (the client
appends that to the sweep's journal; the worker writes no file).

Whatever goes wrong in a case (an invalid value, physics out of its domain, a
solver failure, even a bug) becomes a ``failed`` record with its message; it
never stops the other cases. Failures that are not the scene's fault (anything
but a :class:`~fickcam.errors.FickcamError`) are marked ``retry``: a resumed
sweep runs those cases again.

A worker runs its cases with one ``diffusion.RunCache`` (``worker_cache``: one per worker
process), so cases that share a part, its material and its climate reuse its solves.
"""
from __future__ import annotations

import logging
import time
from dataclasses import dataclass
from pathlib import Path

from ..errors import FickcamError, SceneError
from ..messages import collected_warnings, quieter
import yaml
from ..scene.load import parse_yaml, validate_document
from ..diffusion import RunCache
from ..simulation.simulate import run
from .journal import encode_case

log = logging.getLogger(__name__)

CACHE_ATTRIBUTE = "fickcam_run_cache"  # where a dask worker keeps its cases' cache


@dataclass(frozen=True)
class CaseTask:
    """Everything a worker needs for one case (small and picklable).

    Parameters
    ----------
    index : int
        The case's index.
    scene : dict
        The case's scene as plain YAML data.
    values : dict
        The raw values this case sets, by dotted path.
    label : str
        Names the scene in messages (``"sweep.yaml case 7"``).
    base_dir : str
        The folder that relative paths in the scene refer to.
    """

    index: int
    scene: dict          # the case's scene as plain YAML data
    values: dict         # the raw values this case sets, by dotted path
    label: str           # e.g. "sweep.yaml case 7", names the scene in messages
    base_dir: str        # folder that relative paths in the scene refer to


def case_scene(task: CaseTask):
    """Validate the case's scene exactly as ``fickcam run`` would validate its file.

    Parameters
    ----------
    task : CaseTask
        The case, its scene as YAML data.

    Returns
    -------
    fickcam.scene.load.Scene
        The validated scene.

    Raises
    ------
    fickcam.errors.SceneError
        When a value of the case is invalid.
    """


    text = yaml.dump(task.scene, Dumper=getattr(yaml, "CSafeDumper", yaml.SafeDumper),
                     sort_keys=False, allow_unicode=True)
    return validate_document(parse_yaml(text, file=task.label), base_dir=Path(task.base_dir))


def failure_message(exc: BaseException) -> str:
    """One line saying why a case failed.

    Scene problems are given by key path, without line numbers: the case's scene is not a
    file the user wrote.

    Parameters
    ----------
    exc : BaseException
        What the case raised.

    Returns
    -------
    str
        The reason; an exception other than a :class:`~fickcam.errors.FickcamError` is
        ``internal error: TYPE: message``.
    """
    if isinstance(exc, SceneError):
        return "; ".join(f"{p.key}: {p.reason}" if p.key else p.reason for p in exc.problems)
    if isinstance(exc, FickcamError):
        return str(exc)
    return f"internal error: {type(exc).__name__}: {exc}"


def worker_cache():
    """The ``diffusion.RunCache`` of this dask worker process, shared by its cases.

    Made by the worker's first case and kept on the worker; outside a dask worker a fresh
    one.

    Returns
    -------
    fickcam.diffusion.RunCache
        The cache.
    """

    try:
        # deferred: dask.distributed only on a cluster
        from distributed import get_worker

        worker = get_worker()
    except (ImportError, ValueError):   # not installed, or not on a worker
        return RunCache()
    cache = getattr(worker, CACHE_ATTRIBUTE, None)
    if cache is None:
        cache = RunCache()
        setattr(worker, CACHE_ATTRIBUTE, cache)
    return cache


def run_case(task: CaseTask, cache=None) -> tuple[dict, bytes]:
    """Run one case; return its record and its journal payload (record and result).

    Whatever goes wrong becomes a ``failed`` record with its message, never an exception; a
    failure that is not the scene's fault is marked ``retry``.

    Parameters
    ----------
    task : CaseTask
        The case.
    cache : fickcam.diffusion.RunCache, optional
        The worker's cache, shared by its cases; None: the dask worker's
        (:func:`worker_cache`).

    Returns
    -------
    record : dict
        ``index``, ``status`` ("ok" or "failed"), ``message``, ``values``, ``wall_time`` [s],
        ``warnings`` (the distinct warnings the case made, in order; also in ``message``) and,
        when rerun on resume, ``retry``.
    payload : bytes
        The journal entry (:func:`fickcam.sweep.journal.encode_case`).
    """

    started = time.perf_counter()
    retry = False
    dataset = None
    caught: list[str] = []
    try:
        # its notices and warnings go into the record (the sweep reports each warning once)
        with quieter("fickcam.simulation", logging.ERROR), collected_warnings() as caught:
            dataset = run(case_scene(task), cache=worker_cache() if cache is None else cache)
        notices = [str(n) for n in dataset.attrs.get("notices") or []]
        notices += [text for text in dict.fromkeys(caught) if text not in notices]
        status, message = "ok", "; ".join(notices)
    except Exception as exc:  # noqa: BLE001 - a case's failure is data, not a crash
        if not isinstance(exc, FickcamError):
            log.exception("%s: internal error", task.label)
            retry = True  # not the scene's fault (a bug, or the cluster went away): rerun on resume
        status, message = "failed", failure_message(exc)
    record = {"index": task.index, "status": status, "message": message,
              "values": task.values, "wall_time": time.perf_counter() - started,
              "warnings": list(dict.fromkeys(caught))}
    if retry:
        record["retry"] = True
    return record, encode_case(record, dataset if status == "ok" else None)


def run_cases(tasks: list[CaseTask]) -> list[tuple[dict, bytes]]:
    """Run a batch of cases one after the other (one worker task); their records and journal
    payloads, in order. The worker's caches of meshes and step responses carry over from
    case to case, so cases alike in their parts' geometry and material solve those once.

    Parameters
    ----------
    tasks : list of CaseTask
        The batch's cases, in order.

    Returns
    -------
    list of tuple of (dict, bytes)
        Each case's record and journal payload, as :func:`run_case` gives them.
    """
    cache = worker_cache()
    return [run_case(task, cache) for task in tasks]
