"""Run a sweep's cases and write one combined result.

With one worker (``--workers 1``, or a single case) the cases run one after the
other in this process, without dask. Otherwise a :class:`distributed.LocalCluster`
of single-threaded worker processes is started for the sweep and closed after it,
or with ``scheduler`` the cases go to any running dask scheduler (a real cluster,
whose workers need fickcam and the base scene's ``history_file``). Each worker
returns its case's record and result; the client appends them to the sweep's
journal as they arrive (:mod:`fickcam.sweep.journal`) and writes the result file
once at the end. dask is imported here, inside functions only, and only when it
is used: a plain install needs it only for ``--workers N`` > 1 or ``--scheduler``
(``pip install "fickcam[sweep]"``).
"""
from __future__ import annotations

import collections

import logging
import os
import time
import uuid
from collections.abc import Mapping
from contextlib import contextmanager
from pathlib import Path

from ..errors import FickcamError, InputError
from ..extras import installed, require
from ..messages import quieter, warn
from .case import CaseTask, run_case, run_cases
from .combine import combine, early_ends
from .journal import decode_arrays
from .scheduler import probe
from .spec import Sweep, load_sweep
from .workdir import WorkFolder
from ..diffusion import run_cache
from ..scene.load import load_scene
from ..simulation.planning import plan_parts
from ..simulation.times import written_time_unit
from ..results.store import save
from ..simulation.resultsize import result_fits
from ..messages import progress_bar

log = logging.getLogger(__name__)


def case_task(sweep: Sweep, index: int) -> CaseTask:
    """The worker task of case ``index``.

    Parameters
    ----------
    sweep : fickcam.sweep.spec.Sweep
        The sweep.
    index : int
        The case's index.

    Returns
    -------
    fickcam.sweep.case.CaseTask
        Its scene, values, label and base folder.
    """
    case = sweep.cases[index]
    return CaseTask(index=index, scene=sweep.scene_dict(case), values=case.values,
                    label=f"{Path(sweep.file).name} case {index}", base_dir=str(sweep.base_dir))


def default_workers(n_cases: int) -> int:
    """One worker process per core, but no more than there are cases.

    Parameters
    ----------
    n_cases : int
        The cases to run [1].

    Returns
    -------
    int
        The number of workers [1], at least 1.
    """
    return max(1, min(os.cpu_count() or 1, n_cases))


def require_distributed() -> None:
    """Import dask.distributed, or say how to install it (exit status 2)."""
    require("sweep", advice="or run with --workers 1")


@contextmanager
def dask_client(workers: int | None, scheduler: str | None, n_cases: int):
    """A distributed.Client to ``scheduler`` if given, else to a new LocalCluster.

    The cluster is closed again on exit; dask's INFO chatter is kept off fickcam's stderr, and
    a local cluster's worker processes report only what stops them.

    Parameters
    ----------
    workers : int, optional
        Local worker processes [1]; None: :func:`default_workers`.
    scheduler : str, optional
        The address of a running dask scheduler.
    n_cases : int
        The cases to run [1].

    Yields
    ------
    distributed.Client
        The client.

    Raises
    ------
    fickcam.extras.MissingExtra
        When dask.distributed is not installed.
    fickcam.errors.FickcamError
        When the scheduler cannot be reached.
    fickcam.errors.InputError
        When fewer than one worker is asked for.
    """
    require_distributed()  # importing it sets its loggers' levels: do that first
    with quieter("distributed", logging.WARNING), _connect(workers, scheduler, n_cases) as client:
        yield client


#: dask settings of the sweep's own processes (client, local scheduler and workers): dask's
#: defaults wake every process's event loop every 20 ms to check its health, a worker's
#: statistical profiler samples the running case's stack every 10 ms, and its system and
#: memory monitors poll every 0.5 s and 0.1 s. Idle, those cost a LocalCluster of two
#: workers about 12 % of one core (the client 5 %, each worker 3.4 %), CPU a sweep's
#: cases share the cores with; here 1.5 %. None of them changes what a case computes.
QUIET_CLUSTER = {
    "distributed.admin.tick.interval": "1s",
    "distributed.worker.profile.enabled": False,
    "distributed.admin.system-monitor.interval": "5s",
    "distributed.worker.memory.monitor-interval": "1s",
}


@contextmanager
def _connect(workers: int | None, scheduler: str | None, n_cases: int):
    # deferred: keeps dask off the start-up path
    import dask

    with dask.config.set(QUIET_CLUSTER):  # the workers a LocalCluster starts inherit it
        with _connected(workers, scheduler, n_cases) as client:
            yield client


@contextmanager
def _connected(workers: int | None, scheduler: str | None, n_cases: int):
    # deferred: keeps distributed off the start-up path
    from distributed import Client, LocalCluster

    if scheduler:
        probe(scheduler)
        try:
            client = Client(scheduler, timeout="20s")
        except (OSError, TimeoutError) as exc:
            raise FickcamError(f"cannot reach the dask scheduler at {scheduler}: {exc}") from None
        with client:
            yield client
        return
    n_workers = workers if workers is not None else default_workers(n_cases)
    if n_workers < 1:
        raise InputError("--workers must be at least 1")
    # the worker processes log only what stops them: a case's failure is its record's, a lost
    # worker the client's error; a worker's heartbeat that no longer reached the scheduler
    # while the cluster closed printed a traceback (seen under load)
    with LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True,
                      dashboard_address=":0", silence_logs=logging.CRITICAL) as cluster, \
            Client(cluster) as client:
        log.info("local dask cluster: %d worker process(es)", n_workers)
        yield client


class _Collector:
    """Appends each finished case to the journal, keeps its record, shows progress."""

    def __init__(self, sweep: Sweep, folder: WorkFolder, progress: bool, done: int):
        self.journal = folder.journal
        self.records: dict[int, dict] = {}
        self.failed = 0
        self.bar = progress_bar(len(sweep.cases), initial=done, enabled=progress, unit="cases",
                                desc="sweep", leave=True)

    def add(self, record: dict, payload: bytes | None, label: str) -> None:
        if payload is not None:
            self.journal.append(payload)
        if record["status"] != "ok":
            warn("%s failed: %s", label, record["message"])
            self.failed += 1
            self.bar.set_postfix(failed=self.failed, refresh=False)
        self.records[record["index"]] = record
        self.bar.update()


def run_here(sweep: Sweep, folder: WorkFolder, indices, *, progress: bool = False,
             done: int = 0, cache=None) -> dict[int, dict]:
    """Run the cases ``indices`` one after the other in this process (no dask).

    One ``diffusion.RunCache`` serves every case: meshes, step responses and tables carry
    over from case to case.

    Parameters
    ----------
    sweep : fickcam.sweep.spec.Sweep
        The sweep.
    folder : fickcam.sweep.workdir.WorkFolder
        Its work folder (each finished case is appended to the journal there).
    indices : iterable of int
        The cases to run.
    progress : bool
        Show a progress bar over the cases.
    done : int
        Cases already finished, where the bar starts [1].
    cache : fickcam.diffusion.RunCache, optional
        The cache the cases share (the base scene's plans already in it); None: a fresh one.

    Returns
    -------
    dict of int to dict
        Case index -> its record (:func:`fickcam.sweep.case.run_case`).
    """

    cache = run_cache(cache)
    collector = _Collector(sweep, folder, progress, done)
    try:
        for index in indices:
            task = case_task(sweep, index)
            record, payload = run_case(task, cache)
            collector.add(record, payload, task.label)
    finally:
        collector.bar.close()
    return collector.records


#: batches per worker thread at least (the last ones end together, within one batch)
BATCHES_PER_THREAD = 8
#: cases per batch at most (a lost worker costs little, the progress bar moves)
MAX_BATCH = 10


def batches(indices, threads: int) -> list[list[int]]:
    """The cases ``indices`` as consecutive batches, each one worker task: a task costs the
    scheduler, the client and the worker a few milliseconds whatever it holds, a case about
    a tenth of a second. Consecutive cases of a grid differ in its last parameter only, so
    a batch mostly holds cases whose parts share their geometry and material, and its worker
    solves what they share once (:func:`~.case.run_cases`).

    Parameters
    ----------
    indices : iterable of int
        The cases to run, in order.
    threads : int
        Worker threads of the cluster [1].

    Returns
    -------
    list of list of int
        The batches, consecutive, of at most ``MAX_BATCH`` cases each.
    """
    indices = list(indices)
    size = max(1, min(MAX_BATCH, len(indices) // (BATCHES_PER_THREAD * max(threads, 1))))
    return [indices[start:start + size] for start in range(0, len(indices), size)]


def compute_cases(sweep: Sweep, folder: WorkFolder, indices, client, *, progress: bool = False,
                  done: int = 0) -> dict[int, dict]:
    """Run the cases ``indices`` on ``client`` in batches (:func:`batches`); return their
    records, each batch's appended to the journal as it finishes.

    At most a few batches per worker thread are in flight at once, so neither the
    client nor the scheduler holds the scenes of a large sweep all together. The cases
    of a batch whose task itself broke (e.g. its worker died) are returned as failed and
    marked ``retry``, so a resumed sweep runs them again.

    Parameters
    ----------
    sweep, folder, indices
        The sweep, its work folder and the cases to run, as for :func:`run_here`.
    client : distributed.Client
        Where the cases run (:func:`dask_client`).
    progress, done
        The progress bar, and the count of cases already finished [1] it starts from.

    Returns
    -------
    dict of int to dict
        The records of the cases, by index, as :func:`run_here` gives them.
    """
    # deferred: keeps distributed off the start-up path
    from distributed import as_completed

    run_id = uuid.uuid4().hex[:12]  # keys unique per run: never reuse another run's result
    threads = sum(client.nthreads().values())
    waiting = iter(batches(indices, threads))
    in_flight: dict = {}
    finished = as_completed()

    def submit_next() -> None:
        batch = next(waiting, None)
        if batch is not None:
            tasks = [case_task(sweep, index) for index in batch]
            future = client.submit(run_cases, tasks, key=f"fickcam-cases-{run_id}-{batch[0]}",
                                   pure=False)
            in_flight[future] = tasks
            finished.add(future)

    for _ in range(max(4, 3 * threads)):
        submit_next()
    collector = _Collector(sweep, folder, progress, done)
    try:
        for future in finished:
            tasks = in_flight.pop(future)
            try:
                results = future.result()
            except Exception as exc:  # noqa: BLE001 - the worker, not the cases, failed
                results = [(unfinished(task, exc), None) for task in tasks]
            future.release()
            submit_next()
            for task, (record, payload) in zip(tasks, results):
                collector.add(record, payload, task.label)
    finally:
        collector.bar.close()
        if in_flight:
            client.cancel(list(in_flight))
    return collector.records


def unfinished(task: CaseTask, exc: BaseException) -> dict:
    """The record of a case whose worker task broke: failed, to be run again on resume.

    Parameters
    ----------
    task : CaseTask
        The case.
    exc : BaseException
        What broke its task.

    Returns
    -------
    dict
        The case's record, with ``status`` "failed" and ``retry`` set.
    """
    return {"index": task.index, "status": "failed", "values": task.values,
            "message": f"did not finish: {type(exc).__name__}: {exc}", "retry": True}


def in_process(workers: int | None, scheduler: str | None, n_cases: int) -> bool:
    """Whether the cases run in this process.

    They do when one worker is asked for (or there is one case), or no worker count is given
    and dask.distributed is not installed; never with a scheduler.

    Parameters
    ----------
    workers : int, optional
        The worker processes asked for [1].
    scheduler : str, optional
        The address of a dask scheduler.
    n_cases : int
        The cases to run [1].

    Returns
    -------
    bool
        True to run here.
    """
    if scheduler:
        return False
    if workers is None and not installed("sweep"):
        log.info("dask.distributed is not installed: running the cases in this process "
                 "(pip install \"fickcam[sweep]\" for one worker process per core)")
        return True
    return (workers if workers is not None else default_workers(n_cases)) == 1


def checked_base(sweep: Sweep, output: Path, cache):
    """The sweep's base scene as `fickcam check` takes it (its parts planned, into
    ``cache``) and its combined result's size judged, before any case; a case's own
    refusals come before its solves (``fickcam.run`` plans first). A temporary file a
    killed write of ``output`` left is removed when the result is saved.

    Parameters
    ----------
    sweep : fickcam.sweep.spec.Sweep
        The sweep.
    output : pathlib.Path
        Its result file.
    cache : RunCache
        The run's cache of diffusion plans.

    Returns
    -------
    fickcam.scene.load.Scene
        The base scene.
    """
    base = load_scene(sweep.base_file)
    plan_parts(base, cache=cache)
    result_fits(base, output, cases=len(sweep.cases))
    return base


def run_sweep(sweep_path, output, workers: int | None = None, scheduler: str | None = None,
              progress: bool = False) -> Path:
    """Run every case of the sweep file ``sweep_path`` and write one result to ``output``.

    Finished cases of an interrupted run of the same sweep (same sweep file,
    base scene and fickcam version) are reused, not recomputed, even after a
    ``kill -9``. The work folder ``OUTPUT.parts`` is removed once the result is
    written.

    Parameters
    ----------
    sweep_path : str or pathlib.Path
        The sweep file (YAML: a ``base`` scene and a ``grid`` or ``random`` section).
    output : str or pathlib.Path
        The result file to write (netCDF-4, compressed, written atomically).
    workers : int, optional
        Local worker processes (dask.distributed); None or 1: in this process.
    scheduler : str, optional
        The address of a running dask scheduler (a cluster), instead of local workers.
    progress : bool
        Show a progress bar over the cases.

    Returns
    -------
    pathlib.Path
        The result file, one ``case`` dimension over every case (failed cases hold NaN
        and say why in ``case_status`` and ``case_message``).

    Raises
    ------
    fickcam.errors.SceneError
        When the sweep file or its base scene does not validate.
    fickcam.extras.MissingExtra
        When workers or a scheduler are asked for without dask.distributed installed.
    """

    started = time.perf_counter()
    if scheduler or (workers or 1) > 1:
        require_distributed()  # before the sweep file is read
    sweep = load_sweep(sweep_path)
    here = in_process(workers, scheduler, len(sweep.cases))
    cache = run_cache(None)
    output = Path(output)
    base = checked_base(sweep, output, cache)
    folder = WorkFolder.next_to(output)
    records = folder.open_for(sweep.identity, len(sweep.cases))
    todo = [c.index for c in sweep.cases if c.index not in records]
    if records:
        log.info("resuming: %d of %d case(s) already finished", len(records), len(sweep.cases))
    if todo and (here or in_process(workers, scheduler, len(todo))):
        records.update(run_here(sweep, folder, todo, progress=progress, done=len(records),
                                cache=cache))
    elif todo:
        with dask_client(workers, scheduler, len(todo)) as client:
            records.update(compute_cases(sweep, folder, todo, client, progress=progress,
                                         done=len(records)))
    failed = sorted(i for i, r in records.items() if r["status"] != "ok")
    if failed:
        shown = ", ".join(str(i) for i in failed[:20]) + (" ..." if len(failed) > 20 else "")
        warn("%d of %d case(s) failed (case_status, case_message in the result): %s",
             len(failed), len(sweep.cases), shown)
    report_case_warnings(records, len(sweep.cases))
    result = combine(sweep, records, finished_cases(folder, sweep, records), started=started)
    result.attrs["time_unit"] = written_time_unit(base)  # the reports' unit, as a run's
    short = early_ends(result)
    if short:
        warn(short)
    save(result, output, compress=True)
    if not any(r.get("retry") for r in records.values()):
        folder.remove_own_files()
    else:
        warn("kept %s: rerun the same command to retry the cases that did not finish",
             folder.path)
    return output


#: distinct warnings of the cases a sweep shows at its end at most (the others counted)
SHOWN_WARNINGS = 5


def report_case_warnings(records: dict[int, dict], cases: int) -> None:
    """Report each distinct warning the cases made once, with the number of cases that made
    it, the most frequent first: at most ``SHOWN_WARNINGS``, then how many others there are
    (every case's own are in its ``case_message``).

    Parameters
    ----------
    records : dict of int to dict
        Case index -> its record (:func:`fickcam.sweep.case.run_case`; a record journaled
        before records kept their warnings has none).
    cases : int
        The sweep's number of cases [1].
    """
    counts = collections.Counter(text for record in records.values()
                                 for text in record.get("warnings", ()))
    for text, count in counts.most_common(SHOWN_WARNINGS):
        warn("%d of %d case(s): %s", count, cases, text)
    if len(counts) > SHOWN_WARNINGS:
        warn("%d other warning(s) of the cases (case_message in the result)",
             len(counts) - SHOWN_WARNINGS)


class JournalCases(Mapping):
    """The results of a sweep's ok cases, each decoded from the journal when asked for.

    Building the result thus holds one case at a time besides the stacked arrays.

    Parameters
    ----------
    folder : fickcam.sweep.workdir.WorkFolder
        The work folder holding the journal.
    entries : dict of int to fickcam.sweep.journal.Entry
        Case index -> where its payload lies.
    """

    def __init__(self, folder: WorkFolder, entries: dict):
        self.folder, self.entries = folder, entries

    def __getitem__(self, index: int):
        return decode_arrays(self.folder.journal.payload(self.entries[index]))

    def __contains__(self, index) -> bool:  # without decoding (Mapping's would)
        return index in self.entries

    def __iter__(self):
        return iter(self.entries)

    def __len__(self) -> int:
        return len(self.entries)


def finished_cases(folder: WorkFolder, sweep: Sweep, records: dict[int, dict]) -> JournalCases:
    """The ok cases among ``records``, as they are in the journal.

    Parameters
    ----------
    folder : fickcam.sweep.workdir.WorkFolder
        The work folder.
    sweep : fickcam.sweep.spec.Sweep
        The sweep.
    records : dict of int to dict
        Case index -> its record.

    Returns
    -------
    JournalCases
        Index -> the case's arrays, decoded on demand.
    """
    entries = folder.finished(sweep.identity, len(sweep.cases))
    return JournalCases(folder, {index: entries[index] for index, record in records.items()
                                 if record["status"] == "ok" and index in entries})
