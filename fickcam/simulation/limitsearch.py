"""The limit search: when a stored run's limited variables first leave their spec.

The limits' ratios are read at the stored ageing times; each first crossing is then
located by evaluating the model inside its bracketing interval only, the diffusion taken
at the stored times and the search's together (so the search has the stored run's plan
and past), until the crossing's own tolerance is met
(:func:`fickcam.results.limits.first_crossings`).
"""
from __future__ import annotations

import logging

import numpy as np

from ..climate.environment import ClimateSeen
from ..errors import SceneError
from ..messages import log_notices
from ..results.dataset import build_dataset, stored_unit
from ..results.limits import Tolerance, first_crossings, limit_ratio, values_ratio
from ..scene.load import Scene
from ..schema import VARIABLES, design_name
from .ageing import values_at_times
from .options import RunOptions
from .parts import PartHistory

log = logging.getLogger(__name__)


def limits_dataset(ds, scene: Scene, seen: ClimateSeen, histories: list[PartHistory],
                   options: RunOptions):
    """The scene's limits over the stored run: each limit's ratio at the stored times, and
    the first time out of spec with its error estimate, each crossing located by re-running
    the model inside its bracketing interval to the crossing's own tolerance
    (:class:`~fickcam.results.limits.Tolerance`, finer where the diffusion accuracy asked
    is).

    Parameters
    ----------
    ds : xarray.Dataset
        The stored run's result.
    scene : Scene
        The loaded scene, with its ``limits``.
    seen : fickcam.climate.environment.ClimateSeen
        Its climate at the stored ageing times [s, K, %].
    histories : list of PartHistory
        The stored run's parts' histories.
    options : RunOptions
        The run's diffusion options.

    Returns
    -------
    tuple
        (Dataset of limit_ratio (time, limit) [-], time_out_of_spec (limit) [s] and its
        error [s]; the search's notices, :func:`search_notices`).

    Raises
    ------
    fickcam.errors.SceneError
        A limit on a variable this scene does not compute, at its key.
    """
    missing = [limit for limit in scene.limits if limit.variable not in ds]
    if missing:
        raise SceneError([scene.document.problem(("limits", limit.variable),
                                                 f"this scene does not compute {limit.variable}")
                          for limit in missing])

    def ratios(data) -> np.ndarray:
        return np.stack([limit_ratio(data, limit) for limit in scene.limits], axis=1)

    designs = {limit.variable: ds[design_name(limit.variable)].values for limit in scene.limits
               if design_name(limit.variable) in ds}

    times = seen.times
    searched: dict[str, float] = {}   # part -> largest diffusion estimate of the search
    values_at = values_at_times(scene, seen, options, histories)

    def evaluate(at) -> np.ndarray:
        """The ratios at ageing times ``at`` (inside the stored span): diffusion at the
        stored times and ``at`` together (``values_at``), so its plan and cached step
        responses are the stored run's; the mechanisms evaluated at ``at`` only; the
        limited variables' ratios read from their values in the stored unit and the stored
        run's as-designed values, no Dataset built."""
        at = np.asarray(at, float)
        values, _, _, aged = values_at(at)
        for history in aged:
            if history.diffusion is not None:
                searched[history.part.name] = max(searched.get(history.part.name, 0.0),
                                                  history.diffusion.error_estimate)
        return np.stack([values_ratio(stored_unit(limit.variable, values[limit.variable]),
                                      designs.get(limit.variable), limit,
                                      VARIABLES[limit.variable].units == "degree")
                         for limit in scene.limits], axis=1)

    stored = ratios(ds)
    search_times, search = times, stored
    if times[0] > 0 and (stored[0] > 1).any():  # out of spec at the first stored time: since?
        search_times, search = np.concatenate([[0.0], times]), np.vstack([evaluate([0.0]), stored])
    crossings, errors = first_crossings(search_times, search, evaluate,
                                        Tolerance.for_accuracy(options.accuracy),
                                        seen.environment.change_times)
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