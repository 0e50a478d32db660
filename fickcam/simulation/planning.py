"""The run's plan: the climate its parts see, every refusal of `fickcam check`, and each
part's diffusion planned before any is solved.

:func:`climate_seen` asks the scene's climate history, once, for all a run reads of it at
its ageing times; :func:`planned_parts` refuses what cannot run (a mechanism whose dry
shape is none, a diffusion model that does not apply to a part's shape) and plans every
part's diffusion into the run's cache, which its solves then read.
"""
from __future__ import annotations

from ..climate.environment import ClimateSeen
from ..diffusion import plan_problem, refuse
from ..errors import InputError, SceneError
from ..mechanisms.part import Part
from ..scene.load import Scene
from .blas import on_one_blas_thread
from .options import RunOptions
from .times import ageing_times

#: the plan of a part whose moisture the environment's state gives (no diffusion)
STATE_GIVEN = "state"


def for_part(name: str, call, *args, **kwargs):
    """``call(*args, **kwargs)``, an InputError it raises (e.g. a model that does not apply)
    naming the part.

    Parameters
    ----------
    name : str
        The part's name.
    call : callable
        What to call, with the remaining arguments.

    Returns
    -------
    object
        What ``call`` returns.

    Raises
    ------
    fickcam.errors.InputError
        ``part NAME: ...``.
    """
    try:
        return call(*args, **kwargs)
    except InputError as exc:
        raise InputError(f"part {name}: {exc}") from None


def climate_seen(scene: Scene, times, parts: list[Part] | None = None, *,
                 summary: bool = True) -> ClimateSeen:
    """What the run reads of the scene's climate at ``times``, for ``parts`` (those that
    absorb; None: the scene's), asked of the history once.

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    times : array_like
        Ageing times [s].
    parts : list of Part, optional
        The parts aged; None: the scene's.
    summary : bool
        Also summarise the climate between the times (what a stored result keeps; a plan
        or compensation's part states do not).

    Returns
    -------
    fickcam.climate.environment.ClimateSeen
        T [K], RH [%], the parts' exposures and the climate between the times.
    """
    parts = scene.parts if parts is None else parts
    return scene.environment.seen_at(times, {part.name: part.material.saturation_moisture
                                             for part in parts if part.geometry is not None},
                                     summary=summary)


@on_one_blas_thread  # a two-phase plate's plan runs its planform refinement (as ``run``)
def plan_parts(scene: Scene, accuracy: float | None = None, *, parts: list[Part] | None = None,
               settings=None, cache=None):
    """What `fickcam check` shows: (environment, ageing times, diffusion options, [(part,
    diffusion Plan, None for a part that does not absorb, or STATE_GIVEN where the
    environment gives the moisture directly)]), planned as a run does.

    A run plans first too, with its own cache (its solves then read the plans): a
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
    options = RunOptions.for_scene(scene, accuracy, settings, cache)
    parts = scene.parts if parts is None else parts
    times = ageing_times(scene, scene.environment)
    plans = planned_parts(scene, climate_seen(scene, times, parts, summary=False), options,
                          parts)
    return scene.environment, times, options, plans


def planned_parts(scene: Scene, seen: ClimateSeen, options: RunOptions,
                  parts: list[Part]) -> list[tuple[Part, object]]:
    """Every refusal of `fickcam check`, then each part's diffusion planned into the run's
    cache, in the caller's BLAS threads.

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    seen : fickcam.climate.environment.ClimateSeen
        Its climate at the ageing times [K, %, s].
    options : RunOptions
        The run's diffusion options (its cache keeps the plans).
    parts : list of Part
        The parts to plan.

    Returns
    -------
    list of tuple
        (part, its diffusion Plan; None for a part that does not absorb, STATE_GIVEN where
        the environment gives the moisture directly).
    """
    refuse_shapes(scene)
    problems = []
    for part in parts:
        if part.geometry is None or seen.states_given:
            problems.append((part, None))
            continue
        problem = options.problem(part, seen.exposures[part.name], seen.times)
        for_part(part.name, refuse, problem)  # every part's before the first costly plan
        problems.append((part, problem))
    return [(part, (None if part.geometry is None else STATE_GIVEN) if problem is None else
             for_part(part.name, plan_problem, problem, options.settings, options.cache))
            for part, problem in problems]


def refuse_shapes(scene: Scene) -> None:
    """Refuse, at the scene's lines, a mechanism whose dry shape is none (a cam profile
    with a cusp): its parts cannot be meshed nor its follower run.

    Parameters
    ----------
    scene : Scene
        The loaded scene.

    Raises
    ------
    fickcam.errors.SceneError
        One line per problem, at its key.
    """
    problems = [scene.document.problem((mechanism.section_name, *path), reason)
                for mechanism in scene.mechanisms for path, reason in mechanism.shape_problems()]
    if problems:
        raise SceneError(problems)
