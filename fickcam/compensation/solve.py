"""The fixed point of compensation: compute each part's strain at the ageing times
compensated for with the current made dimensions, make the dimensions anew
(:mod:`fickcam.compensation.core`), until they stop moving.

Two runs of the whole scene are made, both at the *check times*: the scene's ageing times
inside the life asked about, its ends, the times compensated for (and, when asked, the
scene's ageing times over the whole history for a plot, or the grid of the wider window of
``keep_limits``), with the scene's own angle step and limits. The run of the design is both
the fixed point's start and the uncompensated part of the report; the run of the made
scene, once the dimensions have settled, is the compensated part. In between, each
iteration computes only the parts whose dimensions are made (their diffusion at the made
size and their material state): no mechanisms, no limit search. The made scene's run takes
its diffusion from the last iteration, solved for those very dimensions.

The moisture a part takes up depends on its dry dimensions only through its size (a
disc's radius, a link's outline), weakly: a 1 % smaller nylon disc (23 mm radius, 10 mm
thick) or R914 link (100 to 160 mm long) changes the mean moisture by at most 1.7e-3 or
8e-4 of itself over the history. So the first iteration (from the design's diffusion)
lands within a few 1e-3 of the compensation (0.15 µm of the disc's 418 µm at 6 months),
the next move is predicted from that contraction, and when it lies within the fixed
point's tolerances the dimensions are made without solving their diffusion again: a
part's diffusion is then solved twice in all, for the design and its first made size,
and the made scene's run takes the second.
"""
from __future__ import annotations

import copy
import dataclasses
import logging
import tempfile
from pathlib import Path

import numpy as np

from ..cam.profile import write_profile_csv
from ..diffusion import RunCache
from ..errors import FickcamError, InputError, format_duration
from ..quantities.options import ageing_time
from ..results.dataset import build_dataset
from ..scene.load import as_designed_data, load_scene
from ..simulation.ageing import age_parts, diffusion_key, with_sheets
from ..simulation.options import RunOptions
from ..simulation.parts import part_values
from ..simulation.planning import climate_seen
from ..simulation.simulate import run_with
from ..simulation.times import ageing_times
from . import cam, linkage
from .core import (MAX_ITERATIONS, Compensation, converged, made_value, quiet_runs, residual,
                   scene_from, target_shifts, target_strains, window_times)

log = logging.getLogger(__name__)


def length_text(value: float, digits: int = 6) -> str:
    """A length for the written scene in mm, to the nanometre (``digits`` decimals of mm).

    Parameters
    ----------
    value : float
        The length [m].
    digits : int
        Decimals of the millimetres.

    Returns
    -------
    str
        E.g. ``"12.345678 mm"``.
    """
    return f"{value * 1e3:.{digits}f} mm"


#: what compensation does to each mechanism, by its scene section: the dimensions it
#: compensates (``targets``), how the made values are written into the scene (``write``)
#: and the ``design:`` entry that keeps the design's (``design_entry``)
COMPENSATED = {"cam": cam, "linkage": linkage}


def _targets(scene, points: bool) -> list:
    """The dimensions compensated, mechanism by mechanism, each marked with its section."""
    return [dataclasses.replace(target, mechanism=mechanism.section_name)
            for mechanism in scene.mechanisms
            for target in COMPENSATED[mechanism.section_name].targets(
                mechanism.section, points, mechanism=mechanism)]


def with_design(data: dict, design: dict, targets: list) -> dict:
    """The made scene mapping with its ``design:`` section (``design`` is the design's
    mapping): what its as-designed values, drift and limits are measured against; placed
    after the mechanism sections.

    Parameters
    ----------
    data : dict
        The made scene mapping.
    design : dict
        The design scene mapping.
    targets : list of Target
        The dimensions compensated.

    Returns
    -------
    dict
        A new mapping with the ``design:`` section.
    """
    sections = [name for name in data if name in COMPENSATED]
    entry = {name: COMPENSATED[name].design_entry(
        design[name], [t for t in targets if t.mechanism == name]) for name in sections}
    out = {}
    for key, value in data.items():
        if key != "design":
            out[key] = value
        if key == sections[-1]:
            out["design"] = entry
    return out


def write_made(data: dict, scene, targets: list, made: list, stem: Path):
    """(a copy of the scene mapping ``data`` (as designed) with the made dimensions and a
    ``design:`` section, the made cam's points or None, the made drawings): a cam given by
    points names its points file, a drawn cam or link its made drawing, all named from
    ``stem``, where the caller writes them (a drawn cam's points are its made outline's,
    which its drawing or the scene holds).

    Parameters
    ----------
    data : dict
        The scene mapping as designed (not changed).
    scene : Scene
        The design scene.
    targets : list of Target
        The dimensions.
    made : list
        Their made values [m].
    stem : pathlib.Path
        The made scene's path without its suffix: the points go to
        :func:`fickcam.compensation.cam.profile_path` of it, a drawn cam's drawing to
        :func:`fickcam.compensation.cam.drawing_path` of it, a drawn link's to
        :func:`fickcam.compensation.linkage.drawing_path` of it.

    Returns
    -------
    tuple
        (the made scene mapping, the made points (n, 2) [m] or None, the made drawings as
        path -> writer of a temporary path).
    """
    design, data = data, copy.deepcopy(data)
    points = None
    for name, compensated in COMPENSATED.items():
        own = [(t, m) for t, m in zip(targets, made) if t.mechanism == name]
        if own:
            written = compensated.write(data, scene.mechanism(name).section, *zip(*own), stem,
                                        length_text)
            points = points if written is None else written
    drawings = {**cam.made_drawings(scene, targets, made, stem),
                **linkage.made_drawings(scene, targets, made, stem)}
    return with_design(data, design, targets), points, drawings


def write_points(path, points: np.ndarray) -> Path:
    """A made cam's points as the profile CSV a scene reads (mm, units in the header).

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file.
    points : numpy.ndarray
        The points, shape (n, 2) [m].

    Returns
    -------
    pathlib.Path
        The path written.
    """
    return write_profile_csv(path, points[:, 0], points[:, 1])


def _scene_at(data: dict, base_dir: Path, times: np.ndarray):
    """The scene mapping validated with ageing ``times`` (s) only, fields off, no file."""
    data = copy.deepcopy(data)
    outputs = dict(data.get("outputs") or {})
    # with their unit: a time the user gave with one is not judged again as a bare number
    outputs.update(ageing_times=[f"{float(t)!r} s" for t in times], fields=False)
    outputs.pop("file", None)
    data["outputs"] = outputs
    return scene_from(data, base_dir, "<compensation>")


def _run_at(data: dict, base_dir: Path, times: np.ndarray, options: RunOptions,
            diffusions=None):
    """The scene mapping run at ageing ``times`` (s) only, fields off, no file;
    ``diffusions``: diffusion results already solved at ``times`` (:func:`part_states`);
    ``options``: the compensation's, one for all its runs (they share its cache)."""
    ds = run_with(_scene_at(data, base_dir, times), options, diffusions=diffusions)
    if ds.sizes["time"] != len(times):
        raise FickcamError("compensation: a run did not keep the ageing times it was given")
    return ds


def part_states(data: dict, base_dir: Path, times: np.ndarray, options: RunOptions,
                names: set, grown: dict | None = None, outline: bool = False):
    """What a run of the scene computes for the parts ``names``, without its limits and
    other parts: their diffusion and material state, and the mechanisms' variables
    ``grown`` asks for (a drawn link's aged length: :func:`grown_values`).

    Parameters
    ----------
    data : dict
        The scene mapping (as YAML gives it), relative paths from ``base_dir``.
    base_dir : pathlib.Path
        The folder the scene's relative paths start from.
    times : numpy.ndarray
        Ageing times [s].
    options : fickcam.simulation.options.RunOptions
        The compensation's diffusion options [-, SI], one for all its runs (they share its
        cache).
    names : set of str
        The parts to compute.
    grown : dict, optional
        Mechanism section -> the names of its result variables to compute; None: none.
    outline : bool
        Also the displacement of a drawn cam's outline by its moisture field's unevenness
        (:func:`fickcam.compensation.cam.outline_shift_values`).

    Returns
    -------
    tuple
        (xarray.Dataset of the parts' state variables over (time, part), the variables
        ``grown`` names and the outline's; dict of part name -> its ``DiffusionResult`` at
        ``times``, None for a part that does not absorb).
    """
    scene = _scene_at(data, base_dir, times)
    parts = [part for part in scene.parts if part.name in names]
    seen = climate_seen(scene, times, parts, summary=False)  # part states: no record kept
    histories = age_parts(scene, seen, options, parts, [])
    values = part_values(histories)
    coords = {"time": times, "part": [h.part.name for h in histories]}
    for section, variables in (grown or {}).items():
        more, more_coords = grown_values(scene, seen, scene.mechanism(section), histories,
                                         variables)
        values.update(more)
        coords.update(more_coords)
    ds = build_dataset(values, coords)
    if outline:
        ds = ds.assign(cam.outline_shift_values(scene, with_sheets(scene, seen, histories)))
    return ds, {h.part.name: h.diffusion for h in histories}


#: crank angles of a mechanism evaluated for its aged dimensions alone
GROWN_ANGLES = np.linspace(0.0, 2.0 * np.pi, 4, endpoint=False)


def grown_values(scene, seen, mechanism, histories: list, variables) -> tuple:
    """A mechanism's result variables ``variables`` at the ageing times from its parts' histories
    (a drawn link's aged length: its moisture field carried through the thickness with the
    exact sheet, as a run does), at a few crank angles.

    Parameters
    ----------
    scene : Scene
        The scene [SI].
    seen : fickcam.climate.environment.ClimateSeen
        Its climate at the ageing times [s, K, %] (the parts' exposures).
    mechanism : Mechanism
        One of its mechanisms, whose parts ``histories`` holds.
    histories : list of PartHistory
        The parts' ageing.
    variables : collection of str
        The result variables to keep.

    Returns
    -------
    tuple of dict
        (values [SI] by name, the mechanism's coordinates).
    """
    by_name = {h.part.name: h for h in with_sheets(scene, seen, histories)}
    valid = np.logical_and.reduce([h.valid for h in histories])
    response = mechanism.response(by_name, seen.times, GROWN_ANGLES, valid)
    return ({name: response.variables[name] for name in variables},
            mechanism.coordinates(GROWN_ANGLES))


def diffusions_for(data: dict, base_dir: Path, times: np.ndarray, by_name: dict) -> dict:
    """The diffusion results ``by_name`` keyed for a run of the scene mapping at ``times``
    (``simulate.run(diffusions=...)``), by :func:`fickcam.simulation.ageing.diffusion_key`: the
    part's shape (of this scene mapping), material and whether its field is kept.

    Parameters
    ----------
    data : dict
        The scene mapping to be run.
    base_dir : pathlib.Path
        The folder the scene's relative paths start from.
    times : numpy.ndarray
        Ageing times of the run [s], those of the results.
    by_name : dict
        Part name -> ``DiffusionResult`` (:func:`part_states`).
    """
    scene = _scene_at(data, base_dir, times)
    kept = scene.field_parts  # its runs keep no fields but these (``_scene_at``)
    return {diffusion_key(part, part.name in kept): by_name[part.name]
            for part in scene.parts if by_name.get(part.name) is not None}


def _compensation_times(scene, at, over) -> tuple[np.ndarray, tuple[float, float]]:
    """([T] for ``at`` or the window grid for ``over``, the life asked about: the window,
    or delivery to the end of the history for ``at``), s; refuses times outside the
    history."""
    environment = scene.environment
    if (at is None) == (over is None):
        raise InputError("give exactly one of --at TIME or --over T1 T2")
    given = [("--at", at)] if at is not None else [("--over", value) for value in over]
    seconds = [ageing_time(option, value, environment.end) for option, value in given]
    for (option, value), s in zip(given, seconds):
        if not s <= environment.end * (1 + 1e-12):
            raise InputError(f"{option} {value}: {format_duration(s)} is outside the scene's "
                             f"history (0 to {format_duration(environment.end)})")
    if at is not None:
        return np.array(seconds), (0.0, float(environment.end))
    if seconds[1] <= seconds[0]:
        raise InputError("--over T1 T2 needs T1 < T2")
    return (window_times(seconds[0], seconds[1], ageing_times(scene, environment)),
            (seconds[0], seconds[1]))


def _check_times(scene, times: np.ndarray, life: tuple[float, float], *, plot: bool = False,
                wide: bool = False) -> np.ndarray:
    """The ageing times (s) of every run (module docstring): the scene's ageing times
    inside ``life``, its ends and ``times``; ``plot``: the scene's ageing times over the
    whole history too (the plot shows the part before and after a window, from the runs
    the compensation makes anyway); ``wide``: the grid of a window over the whole life."""
    environment = scene.environment
    stored = ageing_times(scene, environment)
    inside = stored[(stored >= life[0]) & (stored <= life[1])]
    extra = [stored] if plot else []
    if wide:
        extra.append(window_times(*life, stored))
    return np.unique(np.concatenate([inside, np.array(life), times, *extra]))


def settles_next(previous: list, made: list, new: list, targets: list) -> bool:
    """True when the move after ``made`` -> ``new`` is predicted within the fixed point's
    tolerances: the iteration contracts by q = |new - made| / |made - previous| per
    step (linear convergence), so the next move is about q |new - made|.

    Parameters
    ----------
    previous, made, new : list
        Three successive iterates of every target [m] (floats or arrays).
    targets : list of Target
        The targets, whose design values [m] scale the relative tolerance.
    """
    predicted = []
    for before, now, after in zip(previous, made, new):
        step, last = np.abs(np.asarray(after) - now), np.abs(np.asarray(now) - before)
        q = float(np.max(step) / np.max(last)) if np.max(last) > 0 else 0.0
        predicted.append(np.asarray(after) + q * step)
    return converged(new, predicted, targets)


def _fixed_point(scene, data: dict, targets: list, times: np.ndarray, check: np.ndarray,
                 start, options: RunOptions):
    """(made values, the run of the made scene at ``check``, iterations, the largest
    deviation left on each target over ``times`` [m]) from ``start``, the run of the design
    at ``check``.

    Each iteration computes only the targets' parts (:func:`part_states`: their diffusion
    at the made size and their material state). The moisture depends on the made size
    weakly (module docstring), so once the next move is predicted within the tolerances
    (:func:`settles_next`), the last dimensions are made without solving their diffusion
    again: their strains differ from the last iteration's by less than the tolerances'
    share of the compensation. The made scene is run once, at the end, with the diffusion
    of the last iteration. ``options``: the compensation's, one for all its runs. A
    dimension that grows otherwise than by its part's mean strain (``Target.grown``: a
    drawn link's displaced pins) takes its strain from its mechanism's aged value of it
    (:func:`grown_values`) in every iteration; a drawn cam's outline (``Target.shifted``)
    the displacement of its moisture field's unevenness on the made plate, from the first
    made plate on (the design's run holds none: its first move is the mean strain's)."""
    at = np.searchsorted(check, times)
    names = {t.part for t in targets}
    grown: dict = {}
    for target in targets:
        if target.grown:
            grown.setdefault(target.mechanism, set()).add(target.grown[0])
    outline = any(t.shifted >= 0 for t in targets)
    made = previous = [t.design for t in targets]
    ds, solved, trial = start, {}, data
    with tempfile.TemporaryDirectory(prefix="fickcam-compensate-") as folder, quiet_runs():
        for iteration in range(MAX_ITERATIONS + 1):
            strains = [s[at] for s in target_strains(ds, targets, made)]
            shifts = [None if s is None else s[at] for s in target_shifts(ds, targets, made)]
            new = [made_value(t.design, s, d) for t, s, d in zip(targets, strains, shifts)]
            log.debug("compensation iteration %d: largest moves %s m", iteration,
                      [float(np.max(np.abs(np.asarray(n) - m))) for n, m in zip(new, made)])
            settled = iteration if iteration and converged(made, new, targets) else 0
            if not settled and iteration and settles_next(previous, made, new, targets):
                made, settled = new, iteration + 1
                trial = _made_trial(data, scene, targets, made, Path(folder))
            if settled:
                after = _run_at(trial, scene.base_dir, check, options,
                               diffusions_for(trial, scene.base_dir, check, solved))
                return made, after, settled, [residual(t.design, m, s, d) for t, m, s, d
                                              in zip(targets, made, strains, shifts)]
            previous, made = made, new
            trial = _made_trial(data, scene, targets, made, Path(folder))
            ds, solved = part_states(trial, scene.base_dir, check, options, names, grown,
                                     outline)
    raise FickcamError(f"compensation did not settle in {MAX_ITERATIONS} iterations")


def _made_trial(data: dict, scene, targets: list, made: list, folder: Path) -> dict:
    """The scene mapping with the ``made`` dimensions (a cam given by points: its points,
    a drawn link: its made drawing, written in ``folder``)."""
    stem = folder / "trial"
    trial, points, drawings = write_made(data, scene, targets, made, stem)
    if points is not None and not cam.drawn(scene.model.cam):
        write_points(cam.profile_path(folder, stem.name), points)
    for path, write in drawings.items():
        write(path)
    return trial


def compensate(scene, at=None, over=None, *, accuracy: float | None = None,
               plot: bool = False, keep_limits: bool = False, points: bool = False) -> Compensation:
    """The dry dimensions to make so that the mechanism has its design geometry at ageing
    time ``at`` (a duration, e.g. "60 d", or seconds), or stays closest to it over the
    window ``over`` = (T1, T2) (minimax). ``keep_limits`` (with ``at``): when that leaves
    one of the scene's limits failing between delivery and the end of the history, make
    the dimensions for that whole life instead (minimax over it). ``points``: make a cam
    given by its parameters as points (x and y compensated apart). Returns a
    :class:`~fickcam.compensation.core.Compensation` with the design's and the made scene's runs; its scene is
    written by :func:`fickcam.compensation.report.write_scene`.

    Parameters
    ----------
    scene : str, pathlib.Path, dict or Scene
        The design, as :func:`fickcam.load_scene` takes it.
    at : str or float, optional
        The ageing time [s] at which the mechanism must have its design geometry (a
        duration with units, or seconds: a bare number is judged as a scene's ageing time
        is, so ``45`` is refused with '45 d' suggested).
    over : tuple of (str or float), optional
        The window (T1, T2) [s] over which the largest deviation is made smallest;
        exactly one of ``at`` and ``over``.
    accuracy : float, optional
        The diffusion's relative accuracy [-]; None: the scene's.
    plot : bool
        Also run the check runs on a regular grid over the whole history (the
        compensation figure shows the part before and after a window too).
    keep_limits : bool
        With ``at``: compensate over the whole life when a limit fails.
    points : bool
        Make a parametric cam as a cam given by points.

    Returns
    -------
    Compensation
        The made dimensions (SI), the iterations, the residual and the runs before and
        after.

    Raises
    ------
    fickcam.errors.InputError
        When ``at`` and ``over`` are both given or both missing, a time is outside the
        scene's history, or ``keep_limits`` is given without ``at``.
    """
    scene = load_scene(scene)
    # one set of options for every run of this compensation: they share its cache
    options = RunOptions.for_scene(scene, accuracy, cache=RunCache())
    times, life = _compensation_times(scene, at, over)
    if keep_limits and at is None:
        raise InputError("--keep-limits goes with --at (a window is already its own life)")
    wide = keep_limits and bool(scene.limits)
    check = _check_times(scene, times, life, plot=plot, wide=wide)
    design = scene.as_designed()  # a compensated scene is compensated anew
    targets = _targets(design, points)
    data = as_designed_data(copy.deepcopy(scene.document.data))
    with quiet_runs():
        before = _run_at(data, scene.base_dir, check, options)
    made, after, iterations, left = _fixed_point(design, data, targets, times, check, before,
                                                 options)
    comp = Compensation(targets, made, times, iterations, data, scene=scene, life=life,
                        check=check, before=before, after=after, residual=left)
    if wide and comp.fails():
        window = window_times(*life, check)
        made, after, iterations, left = _fixed_point(design, data, targets, window, check,
                                                     before, options)
        comp = comp.widened(window, made, after, iterations, left)
    return comp

