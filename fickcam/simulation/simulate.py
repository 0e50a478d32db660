"""Run one scene: the only module that knows the order of the work.

scene → environment → parts (geometry, material) → diffusion per part →
material state per part → mechanisms at each ageing time → the same material
state and mechanisms for the design (dry, reference temperature) → Dataset.
"""
from __future__ import annotations

import logging
import time as _time
from dataclasses import replace

import numpy as np

from .._version import __version__
from ..climate.environment import Environment, summary_edges
from ..diffusion import plan_problem, refuse, solve_problem
from ..elastic.parts import sheet_profile, swelling_variables
from ..errors import InputError, SceneError, times_in, unit_of_length
from ..materials import material_state
from ..materials.state import wet_tg_error
from ..mechanisms.part import Part
from ..mechanisms.response import Response
from ..messages import log_notices, progress_bar, progress_summary
from ..quantities.parsing import parse_duration, split_number_unit
from ..results.dataset import build_dataset
from ..results.limits import Tolerance, first_crossings, limit_ratio
from ..scene.load import EveryStep, Scene, load_scene
from ..schema import VARIABLES, design_name
from .blas import on_one_blas_thread
from .options import RunOptions
from .parts import PartHistory, diffusion_attrs, field_values, part_values

log = logging.getLogger(__name__)


# ----------------------------------------------------------------- planning


def ageing_times(scene: Scene, environment: Environment) -> np.ndarray:
    """Ageing times: the environment's state times when it gives the moisture directly,
    else the scene's list, a regular ``every`` grid, or 11 points.

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    environment : Environment
        Its climate history (end time [s]).

    Returns
    -------
    numpy.ndarray
        The ageing times [s].
    """
    if environment.state_times is not None:
        return environment.state_times.copy()
    requested = scene.model.outputs.ageing_times
    end = environment.end
    if isinstance(requested, list):
        return np.asarray(requested, float)
    if isinstance(requested, EveryStep):
        return every_step_times(requested.every, end)
    return np.linspace(0.0, end, 11)


def every_step_times(step: float, end: float) -> np.ndarray:
    """0, step, 2 step, ... up to ``end`` (s), and ``end`` itself when the steps do not
    land on it: the history's last state is always reported (two years every 30 d:
    0, 30, ..., 720 d and 730.5 d). A step that lands within 1e-9 ``end`` of the end is
    moved onto it rather than followed by a sliver.

    Parameters
    ----------
    step : float
        The step [s].
    end : float
        The last ageing time [s].

    Returns
    -------
    numpy.ndarray
        The ageing times [s].
    """
    count = int(np.floor(end / step * (1 + 1e-12)))
    times = step * np.arange(count + 1)
    if count and end - times[-1] <= 1e-9 * end:
        times[-1] = end
        return times
    return np.append(times, end) if end > times[-1] else times


def written_time_unit(scene: Scene) -> str:
    """The unit the scene's ageing times were written in (else its history's durations),
    as the time unit its reports use (``errors.unit_of_length``: a month in days); "" where
    they are bare numbers or a climate record sets them (the reports then choose by span).

    Parameters
    ----------
    scene : Scene
        The loaded scene.

    Returns
    -------
    str
        ``"s"``, ``"min"``, ``"h"``, ``"d"``, ``"yr"`` or ``""``.
    """
    data = scene.document.data if scene.document is not None else {}
    requested = (data.get("outputs") or {}).get("ageing_times")
    texts = [requested.get("every")] if isinstance(requested, dict) else list(requested or [])
    history = (data.get("environment") or {}).get("history")
    if not texts and isinstance(history, list):
        texts = [segment.get("duration") for segment in history if isinstance(segment, dict)]
    for text in reversed(texts):
        try:
            unit = split_number_unit(text)[1] if isinstance(text, str) else ""
            if unit:
                return unit_of_length(parse_duration(f"1 {unit}"))[0]
        except ValueError:  # validated already; a spelling this does not read: by span
            continue
    return ""


def _for_part(name: str, call, *args, **kwargs):
    """``call`` with an InputError (e.g. a model that does not apply) naming the part."""
    try:
        return call(*args, **kwargs)
    except InputError as exc:
        raise InputError(f"part {name}: {exc}") from None


#: the plan of a part whose moisture the environment's state gives (no diffusion)
STATE_GIVEN = "state"


@on_one_blas_thread  # a two-phase plate's plan runs its planform refinement (as ``run``)
def plan_parts(scene: Scene, accuracy: float | None = None, *, parts: list[Part] | None = None,
               settings=None, cache=None):
    """What `fickcam check` shows: (environment, ageing times, diffusion options, [(part,
    diffusion Plan, None for a part that does not absorb, or STATE_GIVEN where the
    environment gives the moisture directly)]), planned as :func:`run` does.

    :func:`run` plans first too, with its own cache (its solves then read the plans): a
    diffusion model that does not apply to a part, or any other refusal of the planning,
    comes before any part is solved, as it does in `fickcam check`. The cheap refusals of
    every part (the model asked for against the part's shape) come before any plan.

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    accuracy : float, optional
        Relative accuracy of the diffusion [-]; None: the scene's.
    parts : list of Part, optional
        The parts to plan; None: the scene's.
    settings : SolverSettings, optional
        The solvers' tuned limits; None: the defaults.
    cache : RunCache, optional
        The run's cache, which its solves then read; None: a fresh one.

    Returns
    -------
    tuple
        (environment, ageing times [s], diffusion options, list of (part, plan)).

    Raises
    ------
    fickcam.errors.InputError
        Naming the part, when its diffusion cannot be planned (a model that does not
        apply to its shape, an outline that cannot be meshed).
    """
    return _planned_parts(scene, RunOptions.for_scene(scene, accuracy, settings, cache), parts)


def _planned_parts(scene: Scene, options: RunOptions, parts: list[Part] | None):
    """:func:`plan_parts` with the run's options, in the caller's BLAS threads (:func:`run`
    has limited them)."""
    _refuse_shapes(scene)
    environment = scene.environment
    times = ageing_times(scene, environment)
    problems = []
    for part in scene.parts if parts is None else parts:
        if part.geometry is None or environment.state_times is not None:
            problems.append((part, None))
            continue
        problem = options.problem(part, environment.exposure(part.material.saturation_moisture),
                                  times)
        _for_part(part.name, refuse, problem)  # every part's before the first costly plan
        problems.append((part, problem))
    plans = [(part, (None if part.geometry is None else STATE_GIVEN) if problem is None else
              _for_part(part.name, plan_problem, problem, options.settings, options.cache))
             for part, problem in problems]
    return environment, times, options, plans


def _refuse_shapes(scene: Scene) -> None:
    """Refuse, at the scene's lines, a mechanism whose dry shape is none (a cam profile
    with a cusp): its parts cannot be meshed nor its follower run."""
    problems = [scene.document.problem((mechanism.section_name, *path), reason)
                for mechanism in scene.mechanisms for path, reason in mechanism.shape_problems()]
    if problems:
        raise SceneError(problems)


# ---------------------------------------------------------------------- run


@on_one_blas_thread  # the caller's BLAS threads are restored on return (fickcam.simulation.blas)
def run(scene, *, accuracy: float | None = None, progress: bool = False, settings=None,
        diffusions: dict | None = None, cache=None):
    """Run one scene and return its xarray.Dataset; ``settings``: the
    diffusion solvers' tuned limits (``diffusion.SolverSettings``; None: the defaults);
    ``diffusions``: diffusion results already solved for this scene's ageing times, by
    (geometry, material name, fields kept) as :func:`age_part` keys them (parts that
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
        Diffusion results already solved, keyed as :func:`age_part` keys them.
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
        Diffusion results already solved, keyed as :func:`age_part` keys them.
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
    with progress_summary(f"run {scene.name}", progress), times_in(unit or None):
        environment = scene.environment
        times = ageing_times(scene, environment)
        parts = list(scene.parts)
        # every refusal of `fickcam check` before any solve; the solves read the plans cached
        _planned_parts(scene, options, parts)
        ds, histories = _age(scene, environment, times, options, progress, parts, diffusions)
        if scene.limits:
            limits, searched = _limits(ds, scene, environment, (times, histories), options)
            notices = [*ds.attrs["notices"], *searched]
            ds = ds.merge(limits, compat="override")
            ds.attrs["notices"] = notices
            ds.attrs["limits"] = {limit.variable: limit.as_attrs() for limit in scene.limits}
    ds.attrs["wall_time_s"] = _time.perf_counter() - started  # [s], named with its unit
    ds.attrs["time_unit"] = unit
    return ds


def _age(scene: Scene, environment: Environment, times: np.ndarray, options: RunOptions,
         progress: bool, parts: list[Part], diffusions: dict | None):
    """The Dataset of ``scene`` at ageing ``times`` (s) and the part histories;
    ``diffusions``: results already solved (:func:`run`)."""
    values, coords, notices, histories = _aged_values(scene, environment, times, options,
                                                      progress, parts, diffusions)
    as_designed = scene.as_designed()  # differs where the scene is made to compensate
    dry = [as_designed_part(part, environment) for part in as_designed.parts]
    values.update(_as_designed_values(as_designed, dry))
    if environment.state_times is None and times[-1] > 0:  # states given directly: no climate
        edges = summary_edges(times[-1])
        values.update(climate_values(environment, edges))
        coords["climate_time"] = 0.5 * (edges[:-1] + edges[1:])
    log_notices(log, notices)
    attrs = {
        "title": f"fickcam result: {scene.name}",
        "fickcam_version": __version__,
        "scene_name": scene.name,
        "scene_description": scene.model.description,
        "scene_file": scene.file,
        "scene_text": scene.text,
        "diffusion": {h.part.name: diffusion_attrs(h) for h in histories},
        "notices": notices,
        "Conventions": "CF-1.8",
    }
    return build_dataset(values, coords, attrs), histories


def climate_values(environment: Environment, edges: np.ndarray) -> dict[str, np.ndarray]:
    """The climate the parts saw, as result variables: the record itself, where the stored
    ageing times only sample it.

    Parameters
    ----------
    environment : Environment
        The scene's climate history.
    edges : numpy.ndarray
        Interval edges [s] (:func:`~fickcam.climate.environment.summary_edges`).

    Returns
    -------
    dict
        ``climate_temperature`` [K] and ``climate_relative_humidity`` [%] (the means over
        each interval) with their ``_min`` and ``_max``, one value per interval.
    """
    values = {}
    for name, (mean, low, high) in environment.interval_summary(edges).items():
        values.update({f"climate_{name}": mean, f"climate_{name}_min": low,
                       f"climate_{name}_max": high})
    return values


def _aged_values(scene: Scene, environment: Environment, times: np.ndarray,
                 options: RunOptions, progress: bool, parts: list[Part],
                 diffusions: dict | None = None):
    """(values, coords, notices, part histories) of ``scene`` at ageing ``times`` (s): every
    variable but the as-designed ones, as SI arrays keyed by schema name; ``diffusions``:
    results already solved, keyed as :func:`diffusion_key` keys them."""
    notices: list[str] = list(environment.notes)
    # diffusion then mechanisms, one bar each: a part's diffusion may cost a thousand times an
    # ageing time's mechanisms, and parts differ a hundredfold (a steel frame: nothing), so
    # the diffusion bar counts parts without a remaining time; the mechanisms' is honest
    bar = progress_bar(len(parts), enabled=progress, eta=False, desc=f"{scene.name}: diffusion",
                       unit="parts", leave=False)
    histories = age_parts(scene, environment, times, options, parts, notices, diffusions, bar)
    bar.close()
    return _values(scene, environment, times, histories, notices, scene.elastic_parts, progress)


def age_parts(scene: Scene, environment: Environment, times: np.ndarray, options: RunOptions,
              parts: list[Part], notices: list[str], diffusions: dict | None = None,
              bar=None) -> list[PartHistory]:
    """The diffusion and material state of ``parts`` of ``scene`` over ageing ``times``
    (:func:`age_part` each), no mechanisms: a part's moisture field is kept where the scene
    stores fields or its swelling stress needs it.

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    environment : Environment
        Its climate history (temperature [K], surface moisture).
    times : numpy.ndarray
        Ageing times [s].
    options : RunOptions
        The run's diffusion options.
    parts : list of Part
        The parts to age (the scene's, or some of them).
    notices : list of str
        Notices so far; the parts' are appended.
    diffusions : dict, optional
        Diffusion results already solved, keyed by :func:`diffusion_key`.
    bar : optional
        A progress bar (:func:`fickcam.messages.progress_bar`), updated per part.

    Returns
    -------
    list of PartHistory
        One per part, in order.
    """
    kept = scene.field_parts  # these need their moisture fields
    histories, solved = [], dict(diffusions or {})
    for part in parts:
        if bar is not None:
            bar.set_postfix_str(part.name)
        histories.append(age_part(part, environment, times, options, notices,
                                  store_fields=scene.model.outputs.fields or part.name in kept,
                                  solved=solved))
        if bar is not None:
            bar.update()
    return histories


def _searched_values(scene: Scene, environment: Environment, at: np.ndarray,
                     options: RunOptions, stored: tuple[np.ndarray, list[PartHistory]]):
    """:func:`_aged_values` at the limit search's ageing times ``at`` (s), given the stored
    run's (times, part histories): diffusion is taken at the stored times and ``at``
    together, so it has the stored run's plan and its material state the stored run's past
    (validity up to the wet Tg): extended from the stored solve where it can
    (``DiffusionResult.extend``: only the new times are summed), else re-solved at both;
    the part histories are then taken at ``at``."""
    notices: list[str] = list(environment.notes)
    elastic, kept = scene.elastic_parts, scene.field_parts
    stored_times, befores = stored
    both = np.union1d(stored_times, at)
    rows = np.searchsorted(both, at)
    solved: dict = {}
    histories = [age_part(before.part, environment, both, options, notices,
                          store_fields=scene.model.outputs.fields or before.part.name in kept,
                          before=before.diffusion, solved=solved).at_rows(rows)
                 for before in befores]
    return _values(scene, environment, at, histories, notices, elastic, False)


def _values(scene: Scene, environment: Environment, times: np.ndarray,
            histories: list[PartHistory], notices: list[str], elastic: frozenset[str],
            progress: bool):
    """(values, coords, notices, histories): the climate, the parts' states, the mechanisms,
    the swelling stress of the ``elastic`` parts and the moisture fields at ``times`` (s)
    from the parts' ``histories``; the mechanisms' notices join ``notices``."""
    bar = progress_bar(len(times), enabled=progress, desc=f"{scene.name}: mechanisms",
                       unit="ageing times", leave=False)
    values = {"temperature": environment.temperature(times),
              "relative_humidity": environment.relative_humidity(times)}
    coords: dict = {"time": times}
    if histories:
        coords["part"] = [h.part.name for h in histories]
        values.update(part_values(histories))
    valid_all = np.logical_and.reduce([h.valid for h in histories]) if histories else \
        np.ones_like(times, bool)
    histories = with_sheets(scene, environment, times, histories)
    mechanisms = mechanism_values(scene, histories, times, valid_all, bar.update)
    values.update(mechanisms.variables)
    coords.update(_mechanism_coords(scene))
    notices += mechanisms.notices
    if elastic:
        bar.set_postfix_str("swelling stress")
        swelling, points = swelling_variables(histories, elastic, environment, times,
                                              environment.temperature(times))
        values.update(swelling)
        coords.update(points)
    if scene.model.outputs.fields:
        fields, cells = field_values(histories, times)
        values.update(fields)
        coords.update(cells)
    bar.close()
    return values, coords, notices, histories


def with_sheets(scene: Scene, environment: Environment, times: np.ndarray,
                histories: list[PartHistory]) -> list[PartHistory]:
    """The histories, those of the parts whose moisture field a mechanism reads
    (``field_parts``) with the exact sheet of their thickness under their exposure
    (:func:`fickcam.elastic.parts.sheet_profile`), which carries their stored mid-plane field
    through the thickness.

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    environment : Environment
        Its climate history (temperature [K], surface moisture).
    times : numpy.ndarray
        Ageing times [s].
    histories : list of PartHistory
        The parts' ageing.

    Returns
    -------
    list of PartHistory
        The same, in order; a part without a stored field unchanged.
    """
    read = frozenset().union(*(m.field_parts for m in scene.mechanisms))
    return [replace(h, sheet=sheet_profile(h.part, environment, times))
            if h.part.name in read and getattr(h.diffusion, "fields", None) is not None else h
            for h in histories]


def _limits(ds, scene: Scene, environment: Environment,
            stored_run: tuple[np.ndarray, list[PartHistory]], options: RunOptions):
    """(limit_ratio (time, limit), time_out_of_spec (limit) and its error estimate of the
    scene's limits, each crossing located by re-running the model inside its bracketing
    interval to the crossing's own tolerance (``limits.Tolerance``, finer where the
    diffusion accuracy asked is); the search's notices, ``_search_notices``);
    ``stored_run``: the stored run's ageing times [s] and part histories."""
    missing = [limit for limit in scene.limits if limit.variable not in ds]
    if missing:
        raise SceneError([scene.document.problem(("limits", limit.variable),
                                                 f"this scene does not compute {limit.variable}")
                          for limit in missing])

    def ratios(data) -> np.ndarray:
        return np.stack([limit_ratio(data, limit) for limit in scene.limits], axis=1)

    names = {limit.variable for limit in scene.limits}
    designs = {design_name(n): ds[design_name(n)].variable for n in names
               if design_name(n) in ds}

    times, histories = stored_run
    searched: dict[str, float] = {}   # part -> largest diffusion estimate of the search

    def evaluate(at) -> np.ndarray:
        """The ratios at ageing times ``at`` (inside the stored span): diffusion at the
        stored times and ``at`` together (``_searched_values``), so its plan and cached step
        responses are the stored run's; the mechanisms evaluated at ``at`` only; only the
        limited variables go into the Dataset, beside the stored run's as-designed values."""
        at = np.asarray(at, float)
        values, coords, _, aged = _searched_values(scene, environment, at, options, stored_run)
        for history in aged:
            if history.diffusion is not None:
                searched[history.part.name] = max(searched.get(history.part.name, 0.0),
                                                  history.diffusion.error_estimate)
        kept = {name: value for name, value in values.items() if name in names}
        dims = {dim for name in kept for dim in VARIABLES[name].dims}
        return ratios(build_dataset(kept, {c: v for c, v in coords.items() if c in dims})
                      .assign(designs))

    stored = ratios(ds)
    search_times, search = times, stored
    if times[0] > 0 and (stored[0] > 1).any():  # out of spec at the first stored time: since?
        search_times, search = np.concatenate([[0.0], times]), np.vstack([evaluate([0.0]), stored])
    crossings, errors = first_crossings(search_times, search, evaluate,
                                        Tolerance.for_accuracy(options.accuracy),
                                        environment.change_times)
    return (build_dataset({"limit_ratio": stored, "time_out_of_spec": crossings,
                           "time_out_of_spec_error": errors},
                          {"time": times, "limit": [limit.variable for limit in scene.limits]}),
            search_notices(searched, {h.part.name: h.diffusion.error_estimate for h in histories
                                      if h.diffusion is not None}, options.accuracy))


def search_notices(searched: dict[str, float], stored: dict[str, float],
                   accuracy: float) -> list[str]:
    """Notices (also logged) for the parts whose diffusion at the limit search's times
    (read between the stored solve's steps, ``DiffusionResult.extend``: the stored estimate
    plus the interpolation's) is estimated above the requested accuracy while the stored
    run's was not (that one is already noticed).

    Parameters
    ----------
    searched : dict of str to float
        Part name -> largest diffusion error estimate over the search's solves [-]
        (relative to the moisture swing).
    stored : dict of str to float
        Part name -> error estimate of the stored run's solve [-].
    accuracy : float
        The requested accuracy [-].
    """
    notices = [f"{name}: estimated diffusion error {estimate:.1e} at the limit search's "
               f"times above the requested accuracy {accuracy:g} (the crossing times carry it)"
               for name, estimate in searched.items()
               if estimate > accuracy >= stored.get(name, 0.0)]
    log_notices(log, notices)
    return notices


def diffusion_key(part: Part, store_fields: bool) -> tuple:
    """What makes two parts' diffusion the same solve: their shape, material and whether
    the moisture field is kept (parts alike in all three absorb alike, e.g. a four-bar's
    coupler and rocker).

    Parameters
    ----------
    part : Part
        The part (its diffusion geometry [m] and material's name).
    store_fields : bool
        Whether its moisture field is kept.

    Returns
    -------
    tuple
        A hashable key.
    """
    return (part.geometry, part.material_name, store_fields)


def age_part(part: Part, environment: Environment, times, options: RunOptions,
             notices: list[str], *, store_fields: bool = False, before=None,
             solved: dict | None = None) -> PartHistory:
    """Diffusion, then the material state, of one part over the ageing times;
    ``before``: a DiffusionResult of this part at some of ``times``, extended to the others
    where it can be (``_extended``) instead of solving again; ``solved``: the diffusion
    results of the run's earlier parts by :func:`diffusion_key` (parts alike are solved once).

    Parameters
    ----------
    part : Part
        The part (geometry [m], material).
    environment : Environment
        The climate history (temperature [K], surface moisture).
    times : array_like
        Ageing times [s].
    options : RunOptions
        The run's diffusion options.
    notices : list of str
        Notices so far; this part's are appended.
    store_fields : bool
        Keep the moisture field (the scene stores fields, or the part's swelling stress
        needs it).
    before : DiffusionResult, optional
        A result of this part at some of ``times``, to extend.
    solved : dict, optional
        Diffusion results of earlier parts, added to in place.

    Returns
    -------
    PartHistory
        The part's diffusion result, material state and validity at each time.
    """
    temperature = environment.temperature(times)
    if part.geometry is None:
        result = None
        mean = surface = saturation = np.zeros_like(times)
    elif environment.state_times is not None:  # a state given directly: no diffusion
        result = None
        mean = surface = saturation = environment.uniform_moisture(
            part.material.saturation_moisture, times)
    else:
        exposure = environment.exposure(part.material.saturation_moisture)
        alike = diffusion_key(part, store_fields)
        result = (solved or {}).get(alike) or _extended(before, times)
        if result is None:
            result = _for_part(part.name, solve_problem,
                               options.problem(part, exposure, times, store_fields),
                               options.settings, options.cache)
        if solved is not None:
            solved[alike] = result
        mean, surface = result.mean, result.surface  # total (free + bound) moisture
        saturation = exposure.surface_moisture(times)
        if result.error_estimate > options.accuracy:  # e.g. capped at MAX_CELLS
            notices.append(f"{part.name}: estimated diffusion error "
                           f"{result.error_estimate:.1e} above the requested accuracy "
                           f"{options.accuracy:g} ({result.model})")
    state = _state(part, temperature, mean, surface, environment, times)
    state["equilibrium_moisture_content"] = saturation
    if result is not None and result.bound is not None:
        state["bound_moisture_content"] = result.bound
    valid = _valid_until_wet_tg(part, state, temperature, times, notices)
    return PartHistory(part, result, state, valid)


def _extended(before, times):
    """``before`` extended to ``times`` (``DiffusionResult.extend``) when it offers that and
    ``times`` lie inside its span, else None."""
    if before is None or before.extend is None:
        return None
    if np.min(times) < 0 or np.max(times) > np.max(before.times):
        return None
    return before.extend(times)


def as_designed_part(part: Part, environment: Environment) -> PartHistory:
    """The as-designed state of one part: dry (no moisture) at the reference temperature,
    by the same material-state model, as a history of one time.

    Parameters
    ----------
    part : Part
        The part.
    environment : Environment
        The climate history (its reference temperature [K]).

    Returns
    -------
    PartHistory
        The dry state at one time.
    """
    reference = np.array([environment.reference_temperature])
    dry = np.zeros(1)
    state = _state(part, reference, dry, dry, environment, np.zeros(1))
    valid = np.asarray(state.get("within_wet_tg", np.ones(1, bool)), bool)
    return PartHistory(part, None, state, valid)


def _state(part: Part, temperature, mean, surface, environment: Environment, times) -> dict:
    return material_state(part.material, temperature, mean, surface,
                          environment.reference_temperature, environment.initial_moisture,
                          part=part.name, times=times)


def _mechanism_coords(scene: Scene) -> dict:
    """The angle (and link, joint) coordinates of the mechanisms a scene models."""
    angles = _angle_grid(scene.model.outputs.angle_step)
    return {name: values for mechanism in scene.mechanisms
            for name, values in mechanism.coordinates(angles).items()}


def mechanism_values(scene: Scene, histories: list[PartHistory], times, valid,
                     on_step=lambda: None):
    """The scene's mechanisms, in turn, at every valid ageing time: a Response over time.

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    histories : list of PartHistory
        The parts' ageing.
    times : array_like
        Ageing times [s].
    valid : array_like of bool
        Which times every part is valid at (below its wet glass transition).
    on_step : callable
        Called once per mechanism evaluation (progress).

    Returns
    -------
    Response
        The mechanism variables over time and angle (SI) and the notices.
    """
    response = Response()
    angles = _angle_grid(scene.model.outputs.angle_step)
    by_name = {h.part.name: h for h in histories}
    for mechanism in scene.mechanisms:
        mech = mechanism.response(by_name, times, angles, valid, on_step=on_step)
        response.variables.update(mech.variables)
        response.notices += mech.notices
    return response


def _as_designed_values(scene: Scene, dry: list[PartHistory]) -> dict[str, np.ndarray]:
    """``<name>_design`` for every variable the schema marks: the material state and the
    mechanisms of the scene as designed, evaluated for its parts' dry state ``dry`` (one
    time, then the time axis dropped). These notices repeat those at t = 0 and are not
    reported."""
    if not dry:
        return {}
    values = part_values(dry)
    valid = np.logical_and.reduce([h.valid for h in dry])
    mechanisms = mechanism_values(scene, dry, np.zeros(1), valid)
    values.update(mechanisms.variables)
    return {design_name(name): np.asarray(value)[0] for name, value in values.items()
            if VARIABLES[name].has_design}


def _angle_grid(step: float) -> np.ndarray:
    count = max(int(round(2 * np.pi / step)), 4)
    return np.linspace(0.0, 2 * np.pi, count, endpoint=False)


def _valid_until_wet_tg(part: Part, state: dict, temperature, times, notices) -> np.ndarray:
    """False from the first ageing time at which T reaches the wet Tg of the
    bulk or of the surface layer (Chamis' degradation law no longer applies)."""
    within = np.asarray(state.get("within_wet_tg", np.ones(times.shape, bool)), bool)
    valid = np.logical_and.accumulate(within)
    if not valid.all():
        index = int(np.argmin(valid))
        notices.append(str(wet_tg_error(part.name, times, index, temperature, state)))
    return valid
