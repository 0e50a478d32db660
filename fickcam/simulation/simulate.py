"""Run one scene: the only module that knows the order of the work.

scene → ageing times and the climate the parts see (:mod:`~fickcam.simulation.times`,
:mod:`~fickcam.simulation.planning`) → every refusal and diffusion plan before any solve →
diffusion, material state and mechanisms per part at each ageing time, and the same for the
design (dry, reference temperature) (:mod:`~fickcam.simulation.ageing`) → the limits'
crossings (:mod:`~fickcam.simulation.limitsearch`) → Dataset.
"""
from __future__ import annotations

import time as _time

from ..errors import times_in
from ..messages import progress_summary
from ..scene.load import Scene, load_scene
from .ageing import aged_dataset
from .blas import on_one_blas_thread
from .limitsearch import limits_dataset
from .options import RunOptions
from .planning import climate_seen, planned_parts
from .times import ageing_times, written_time_unit

def run(scene, *, accuracy: float | None = None, progress: bool = False, settings=None,
        diffusions: dict | None = None, cache=None):
    """Run one scene and return its xarray.Dataset; ``settings``: the
    diffusion solvers' tuned limits (``diffusion.SolverSettings``; None: the defaults);
    ``diffusions``: diffusion results already solved for this scene's ageing times, by
    (geometry, material name, fields kept) as :func:`~fickcam.simulation.ageing.diffusion_key` keys them (parts that
    match take them instead of solving again); ``cache``: what the diffusion solves share.

    Parameters
    ----------
    scene : str, pathlib.Path, dict or Scene
        The scene, as :func:`fickcam.load_scene` takes it.
    accuracy : float, optional
        Relative accuracy of the diffusion [-] (a fraction of the moisture swing); None:
        the scene's.
    progress : bool
        Show progress: a bar over the parts' diffusion, then one over the ageing times'
        mechanisms, and at the end a line saying what ran and how long it took
        (:func:`fickcam.messages.progress_summary`).
    settings : SolverSettings, optional
        The diffusion solvers' tuned limits; None: the defaults.
    diffusions : dict, optional
        Diffusion results already solved, keyed as :func:`~fickcam.simulation.ageing.diffusion_key` keys them.
    cache : RunCache, optional
        What the diffusion solves build once and share: the run's plans, solves and limit
        search share it; None: a fresh one for this run (a sweep worker passes its own to
        every case).

    Returns
    -------
    xarray.Dataset
        The result (time in days, angles in degrees, moisture in weight %, else SI).

    Raises
    ------
    fickcam.errors.SceneError
        When the scene does not validate.
    fickcam.errors.SolverError
        When a diffusion solve fails.
    """
    started = _time.perf_counter()
    scene = load_scene(scene)
    # run_with holds BLAS to one thread (not limited twice: each limit costs 2 ms)
    return run_with(scene, RunOptions.for_scene(scene, accuracy, settings, cache),
                    progress=progress, diffusions=diffusions, started=started)


@on_one_blas_thread  # the caller's BLAS threads are restored on return (fickcam.simulation.blas)
def run_with(scene: Scene, options: RunOptions, *, progress: bool = False,
             diffusions: dict | None = None, started: float | None = None):
    """:func:`run` of a loaded scene with its options built: what compensation calls,
    passing the one :class:`~fickcam.simulation.options.RunOptions` of all its runs.

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    options : RunOptions
        The diffusion's accuracy, models, solver settings and cache [-, SI].
    progress : bool
        Show progress (as :func:`run`).
    diffusions : dict, optional
        Diffusion results already solved, keyed as :func:`~fickcam.simulation.ageing.diffusion_key` keys them.
    started : float, optional
        When the caller started, by ``time.perf_counter`` [s] (the result's wall time
        counts from it); None: now.

    Returns
    -------
    xarray.Dataset
        The result (as :func:`run`).
    """
    started = _time.perf_counter() if started is None else started
    unit = written_time_unit(scene)  # the unit the scene wrote its times in: reports use it
    parts = list(scene.parts)
    seen = climate_seen(scene, ageing_times(scene, scene.environment), parts)
    with progress_summary(f"run {scene.name}", progress), times_in(unit or None):
        # every refusal of `fickcam check` before any solve; the solves read the plans cached
        planned_parts(scene, seen, options, parts)
        ds, histories = aged_dataset(scene, seen, options, progress, parts, diffusions)
        if scene.limits:
            limits, searched = limits_dataset(ds, scene, seen, histories, options)
            notices = [*ds.attrs["notices"], *searched]
            ds = ds.merge(limits, compat="override")
            ds.attrs["notices"] = notices
            ds.attrs["limits"] = {limit.variable: limit.as_attrs() for limit in scene.limits}
    ds.attrs["wall_time_s"] = _time.perf_counter() - started  # [s], named with its unit
    ds.attrs["time_unit"] = unit
    return ds
