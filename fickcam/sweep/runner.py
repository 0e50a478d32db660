"""Run a sweep's cases on dask.distributed and write one combined result.

By default a :class:`distributed.LocalCluster` of single-threaded worker
processes is started for the sweep and closed after it; with ``scheduler``
the cases go to any running dask scheduler (a real cluster, whose workers
must have fickcam installed and see the output folder). Workers write each
case to the work folder as it finishes; the client keeps only the small
per-case records. dask is imported here, inside functions only.
"""
from __future__ import annotations

import logging
import os
import time
import uuid
from contextlib import ExitStack, contextmanager
from pathlib import Path

from ..errors import FickcamError, InputError
from .case import CaseTask, quieter, run_case
from .combine import combine
from .scheduler import probe
from .spec import Sweep, load_sweep
from .workdir import WorkFolder

log = logging.getLogger(__name__)


def case_task(sweep: Sweep, folder: WorkFolder, index: int) -> CaseTask:
    """The worker task of case ``index``."""
    case = sweep.cases[index]
    return CaseTask(index=index, scene=sweep.scene_dict(case), values=case.values,
                    label=f"{Path(sweep.file).name} case {index}", base_dir=str(sweep.base_dir),
                    result_path=str(folder.result(index)), record_path=str(folder.record(index)))


def default_workers(n_cases: int) -> int:
    """One worker process per core, but no more than there are cases."""
    return max(1, min(os.cpu_count() or 1, n_cases))


@contextmanager
def dask_client(workers: int | None, scheduler: str | None, n_cases: int):
    """A distributed.Client: to ``scheduler`` if given, else to a new LocalCluster
    (closed again on exit); dask's INFO chatter is kept off fickcam's stderr."""
    import distributed  # noqa: F401 - importing it sets its loggers' levels: do that first

    with quieter("distributed", logging.WARNING), _connect(workers, scheduler, n_cases) as client:
        yield client


@contextmanager
def _connect(workers: int | None, scheduler: str | None, n_cases: int):
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
    with LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True,
                      dashboard_address=":0", silence_logs=logging.WARNING) as cluster, \
            Client(cluster) as client:
        log.info("local dask cluster: %d worker process(es)", n_workers)
        yield client


def compute_cases(sweep: Sweep, folder: WorkFolder, indices, client, *, progress: bool = False,
                  done: int = 0) -> dict[int, dict]:
    """Run the cases ``indices`` on ``client``; return their records as they finish.

    At most a few cases per worker thread are in flight at once, so neither the
    client nor the scheduler holds the scenes of a large sweep all together. A
    case whose task itself broke (e.g. its worker died) is returned as failed and
    marked ``retry``, so a resumed sweep runs it again.
    """
    from distributed import as_completed
    from tqdm.auto import tqdm

    run_id = uuid.uuid4().hex[:12]  # keys unique per run: never reuse another run's result
    waiting = iter(indices)
    in_flight: dict = {}
    finished = as_completed()

    def submit_next() -> None:
        index = next(waiting, None)
        if index is not None:
            task = case_task(sweep, folder, index)
            future = client.submit(run_case, task, key=f"fickcam-case-{run_id}-{index}", pure=False)
            in_flight[future] = (index, task.label, task.values)
            finished.add(future)

    for _ in range(max(16, 4 * sum(client.nthreads().values()))):
        submit_next()
    records: dict[int, dict] = {}
    failed = 0
    bar = tqdm(total=len(sweep.cases), initial=done, disable=not progress, unit="case",
               desc="sweep", leave=True)
    try:
        for future in finished:
            index, label, values = in_flight.pop(future)
            try:
                record = future.result()
            except Exception as exc:  # noqa: BLE001 - the worker, not the case, failed
                record = {"index": index, "status": "failed", "values": values,
                          "message": f"did not finish: {type(exc).__name__}: {exc}", "retry": True}
            submit_next()
            if record["status"] != "ok":
                log.warning("%s failed: %s", label, record["message"])
                failed += 1
                bar.set_postfix(failed=failed, refresh=False)
            records[index] = record
            bar.update()
    finally:
        bar.close()
        if in_flight:
            client.cancel(list(in_flight))
    return records


def run_sweep(sweep_path, output, workers: int | None = None, scheduler: str | None = None,
              progress: bool = False) -> Path:
    """Run every case of the sweep file ``sweep_path`` and write one result to ``output``.

    Finished cases of an interrupted run of the same sweep (same sweep file,
    base scene and fickcam version) are reused, not recomputed. The per-case
    work folder ``OUTPUT.parts`` is removed once the result is written.
    """
    import dask

    from ..store import save

    started = time.perf_counter()
    sweep = load_sweep(sweep_path)
    output = Path(output)
    folder = WorkFolder.next_to(output)
    records = folder.open_for(sweep.identity, len(sweep.cases))
    todo = [c.index for c in sweep.cases if c.index not in records]
    if records:
        log.info("resuming: %d of %d case(s) already finished", len(records), len(sweep.cases))
    if todo:
        with dask_client(workers, scheduler, len(todo)) as client:
            records.update(compute_cases(sweep, folder, todo, client, progress=progress,
                                         done=len(records)))
    failed = sorted(i for i, r in records.items() if r["status"] != "ok")
    if failed:
        shown = ", ".join(str(i) for i in failed[:20]) + (" ..." if len(failed) > 20 else "")
        log.warning("%d of %d case(s) failed (case_status, case_message in the result): %s",
                    len(failed), len(sweep.cases), shown)
    with ExitStack() as stack, dask.config.set(scheduler="synchronous"):
        save(combine(sweep, folder, records, stack, started=started), output)
    if not any(r.get("retry") for r in records.values()):
        folder.remove_own_files()
    else:
        log.warning("kept %s: rerun the same command to retry the cases that did not finish",
                    folder.path)
    return output
