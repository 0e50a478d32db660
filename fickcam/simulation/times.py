"""The ageing times a scene asks for, and the unit it wrote them in.

A run stores its results at these times: the environment's state times where it gives
the moisture directly, else the scene's list, a regular ``every`` grid, or 11 points over
the history. Its reports read times in the unit the scene wrote them in.
"""
from __future__ import annotations

import numpy as np

from ..climate.environment import Environment
from ..errors import unit_of_length
from ..quantities.parsing import parse_duration, split_number_unit
from ..scene.load import EveryStep, Scene


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
