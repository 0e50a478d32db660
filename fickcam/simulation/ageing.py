"""The run's ageing: each part's diffusion and material state over the ageing times, its
mechanisms at every time, the same for the scene as designed, gathered into the Dataset.

:func:`age_part` solves one part (or takes a solve already made: parts alike absorb
alike); :func:`aged_values` reads the parts' histories into the result's variables
through the scene's mechanisms; :func:`aged_dataset` is the whole of it, as a run stores
it.
"""
from __future__ import annotations

import logging
from dataclasses import replace

import numpy as np

from .._version import __version__
from ..climate.environment import ClimateSeen, Environment
from ..diffusion import solve_problem
from ..elastic.parts import SWELLING, sheet_profile, swelling_variables
from ..materials import material_state
from ..materials.state import wet_tg_error
from ..mechanisms.part import Part
from ..mechanisms.response import Response
from ..messages import log_notices, progress_bar
from ..results.dataset import build_dataset
from ..scene.load import Scene
from ..schema import VARIABLES, design_name
from .options import RunOptions
from .parts import PartHistory, diffusion_attrs, field_values, part_values
from .planning import for_part

log = logging.getLogger(__name__)


def aged_dataset(scene: Scene, seen: ClimateSeen, options: RunOptions, progress: bool,
                 parts: list[Part], diffusions: dict | None = None):
    """The Dataset of ``scene`` at its ageing times and the parts' histories: every part's
    diffusion and material state, its mechanisms at each time, the same for the scene as
    designed, and the climate the parts saw.

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    seen : fickcam.climate.environment.ClimateSeen
        Its climate at the ageing times [s, K, %].
    options : RunOptions
        The run's diffusion options.
    progress : bool
        Show a bar over the parts' diffusion, then one over the ageing times.
    parts : list of Part
        The parts to age (the scene's).
    diffusions : dict, optional
        Diffusion results already solved, keyed by :func:`diffusion_key`.

    Returns
    -------
    tuple
        (xarray.Dataset, list of PartHistory).
    """
    values, coords, notices, histories = _aged_values(scene, seen, options, progress, parts,
                                                      diffusions)
    as_designed = scene.as_designed()  # differs where the scene is made to compensate
    dry = [as_designed_part(part, seen.environment) for part in as_designed.parts]
    values.update(_as_designed_values(as_designed, dry))
    if seen.summary:  # the record itself, where the stored ageing times only sample it
        for name, (mean, low, high) in seen.summary.items():
            values.update({f"climate_{name}": mean, f"climate_{name}_min": low,
                           f"climate_{name}_max": high})
        coords["climate_time"] = seen.summary_times
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


def _aged_values(scene: Scene, seen: ClimateSeen, options: RunOptions, progress: bool,
                 parts: list[Part], diffusions: dict | None = None):
    """(values, coords, notices, part histories) of ``scene`` at the ageing times: every
    variable but the as-designed ones, as SI arrays keyed by schema name; ``diffusions``:
    results already solved, keyed as :func:`diffusion_key` keys them."""
    notices: list[str] = list(seen.environment.notes)
    # diffusion then mechanisms, one bar each: a part's diffusion may cost a thousand times an
    # ageing time's mechanisms, and parts differ a hundredfold (a steel frame: nothing), so
    # the diffusion bar counts parts without a remaining time; the mechanisms' is honest
    bar = progress_bar(len(parts), enabled=progress, eta=False, desc=f"{scene.name}: diffusion",
                       unit="parts", leave=False)
    histories = age_parts(scene, seen, options, parts, notices, diffusions, bar)
    bar.close()
    return aged_values(scene, seen, histories, notices, scene.elastic_parts, progress)


def age_parts(scene: Scene, seen: ClimateSeen, options: RunOptions, parts: list[Part],
              notices: list[str], diffusions: dict | None = None,
              bar=None) -> list[PartHistory]:
    """The diffusion and material state of ``parts`` of ``scene`` over its ageing times
    (:func:`age_part` each), no mechanisms: a part's moisture field is kept where the scene
    stores fields or its swelling stress needs it.

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    seen : fickcam.climate.environment.ClimateSeen
        Its climate at the ageing times [s, K, %] (the parts' exposures).
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
        histories.append(age_part(part, seen, options, notices,
                                  store_fields=scene.model.outputs.fields or part.name in kept,
                                  solved=solved))
        if bar is not None:
            bar.update()
    return histories


def aged_values(scene: Scene, seen: ClimateSeen, histories: list[PartHistory],
                notices: list[str], elastic: frozenset[str], progress: bool = False,
                wanted: frozenset | None = None):
    """The climate, the parts' states, the mechanisms, the swelling stress of the
    ``elastic`` parts and the moisture fields at the ageing times, from the parts' histories.

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    seen : fickcam.climate.environment.ClimateSeen
        Its climate at the ageing times [s, K, %].
    histories : list of PartHistory
        The parts' diffusion and material state at those times.
    notices : list of str
        Notices so far; the mechanisms' are appended.
    elastic : frozenset of str
        The parts whose swelling stress is asked for.
    progress : bool
        Show a bar over the ageing times.
    wanted : frozenset of str, optional
        The only variables the caller reads (the limit search's limited ones): the parts'
        other states are left out, and the swelling stress and the moisture fields where
        none of them is one; the mechanisms are told (``Mechanism.response``). None: every
        variable.

    Returns
    -------
    tuple
        (values by schema name [SI], coords, notices, histories with their sheets).
    """
    times = seen.times
    bar = progress_bar(len(times), enabled=progress, desc=f"{scene.name}: mechanisms",
                       unit="ageing times", leave=False)
    values = {"temperature": seen.temperature, "relative_humidity": seen.relative_humidity}
    coords: dict = {"time": times}
    if histories:
        coords["part"] = [h.part.name for h in histories]
        values.update(part_values(histories, wanted))
    valid_all = np.logical_and.reduce([h.valid for h in histories]) if histories else \
        np.ones_like(times, bool)
    histories = with_sheets(scene, seen, histories)
    mechanisms = mechanism_values(scene, histories, times, valid_all, bar.update, wanted)
    values.update(mechanisms.variables)
    coords.update(_mechanism_coords(scene))
    notices += mechanisms.notices
    if elastic and (wanted is None or not wanted.isdisjoint(SWELLING)):
        bar.set_postfix_str("swelling stress")
        swelling, points = swelling_variables(histories, elastic, seen)
        values.update(swelling)
        coords.update(points)
    if scene.model.outputs.fields and (wanted is None or "moisture" in wanted):
        fields, cells = field_values(histories, times)
        values.update(fields)
        coords.update(cells)
    bar.close()
    return values, coords, notices, histories


def values_at_times(scene: Scene, seen: ClimateSeen, options: RunOptions,
                    befores: list[PartHistory], wanted: frozenset | None = None):
    """The stored run's model as a function of ageing time, for the limit search:
    :func:`aged_values` at other times, given the stored run's climate and part histories.

    Diffusion is taken at the stored times and the asked ones together, so it has the
    stored run's plan and its material state the stored run's past (validity up to the wet
    Tg): extended from the stored solve where it can (``DiffusionResult.extend``: only the
    new times are summed), else re-solved at both; the part histories are then taken at the
    asked times.

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    seen : fickcam.climate.environment.ClimateSeen
        Its climate at the stored ageing times [s, K, %].
    options : RunOptions
        The run's diffusion options (its cache holds the stored run's plans).
    befores : list of PartHistory
        The stored run's parts' histories.
    wanted : frozenset of str, optional
        The only variables read (:func:`aged_values`); None: every variable.

    Returns
    -------
    callable
        ``values_at(at)``: ageing times ``at`` [s] inside the stored span -> (values,
        coords, notices, histories) as :func:`aged_values` gives them.
    """
    elastic, kept = scene.elastic_parts, scene.field_parts
    fields = scene.model.outputs.fields

    def values_at(at):
        notices: list[str] = list(seen.environment.notes)
        both = seen.at(np.union1d(seen.times, at))
        rows = np.searchsorted(both.times, at)
        solved: dict = {}
        histories = [age_part(before.part, both, options, notices,
                              store_fields=fields or before.part.name in kept,
                              before=before.diffusion, solved=solved).at_rows(rows)
                     for before in befores]
        return aged_values(scene, both.at_rows(rows), histories, notices, elastic,
                           wanted=wanted)

    return values_at


def with_sheets(scene: Scene, seen: ClimateSeen,
                histories: list[PartHistory]) -> list[PartHistory]:
    """The histories, those of the parts whose moisture field a mechanism reads
    (``field_parts``) with the exact sheet of their thickness under their exposure
    (:func:`fickcam.elastic.parts.sheet_profile`), which carries their stored mid-plane field
    through the thickness.

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    seen : fickcam.climate.environment.ClimateSeen
        Its climate at the ageing times [s, K, %] (the parts' exposures).
    histories : list of PartHistory
        The parts' ageing.

    Returns
    -------
    list of PartHistory
        The same, in order; a part without a stored field unchanged.
    """
    read = frozenset().union(*(m.field_parts for m in scene.mechanisms))
    return [replace(h, sheet=sheet_profile(h.part, seen.exposures[h.part.name], seen.times))
            if h.part.name in read and getattr(h.diffusion, "fields", None) is not None else h
            for h in histories]


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


def age_part(part: Part, seen: ClimateSeen, options: RunOptions, notices: list[str], *,
             store_fields: bool = False, before=None, solved: dict | None = None) -> PartHistory:
    """Diffusion, then the material state, of one part over the ageing times;
    ``before``: a DiffusionResult of this part at some of ``times``, extended to the others
    where it can be (``_extended``) instead of solving again; ``solved``: the diffusion
    results of the run's earlier parts by :func:`diffusion_key` (parts alike are solved once).

    Parameters
    ----------
    part : Part
        The part (geometry [m], material).
    seen : fickcam.climate.environment.ClimateSeen
        The climate at the ageing times [s, K, %] (this part's exposure).
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
    times, temperature = seen.times, seen.temperature
    if part.geometry is None:
        result = None
        mean = surface = saturation = np.zeros_like(times)
    elif seen.states_given:  # a state given directly: no diffusion
        result = None
        mean = surface = saturation = seen.state_moisture[part.name]
    else:
        exposure = seen.exposures[part.name]
        alike = diffusion_key(part, store_fields)
        result = (solved or {}).get(alike) or _extended(before, times)
        if result is None:
            result = for_part(part.name, solve_problem,
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
    state = _state(part, temperature, mean, surface, seen.environment, times)
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
                     on_step=lambda: None, wanted: frozenset | None = None):
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
    wanted : frozenset of str, optional
        The only variables read (``Mechanism.response``); None: every variable.

    Returns
    -------
    Response
        The mechanism variables over time and angle (SI) and the notices.
    """
    response = Response()
    angles = _angle_grid(scene.model.outputs.angle_step)
    by_name = {h.part.name: h for h in histories}
    for mechanism in scene.mechanisms:
        mech = mechanism.response(by_name, times, angles, valid, on_step=on_step, wanted=wanted)
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