"""Mechanisms over ageing: map each part's material state onto the cam and
four-bar models at every ageing time, and collect their responses.

The physics lives in :mod:`fickcam.cam` and :mod:`fickcam.linkage` (pure
functions of one geometry and state); this module only says which state
variable of which part feeds which input, and gathers the arrays over time.
"""
from __future__ import annotations

import re
from typing import Callable

import numpy as np

from ..errors import format_duration
from ..messages import DesignNotice, restated
from .response import Response


def over_ageing(times: np.ndarray, valid: np.ndarray, evaluate: Callable[[int], Response],
                on_step: Callable[[], object] = lambda: None) -> Response:
    """Evaluate ``evaluate(k)`` at every valid ageing time k and stack the results.

    Scalars become arrays over time, arrays over angle become (time, angle); invalid times
    stay NaN (or '' for text). A notice that recurs at several times, alike but for its
    numbers, is reported once with the range of those times and of each number that differs
    (:func:`merged_notices`).

    Parameters
    ----------
    times : numpy.ndarray
        The ageing times [s].
    valid : numpy.ndarray of bool
        Where the mechanism is evaluated (its parts are in their model's domain).
    evaluate : callable
        ``evaluate(k) -> Response`` at ageing index k.
    on_step : callable
        Called after each ageing time (a progress bar's update).

    Returns
    -------
    Response
        The stacked variables [their SI units] and the notices, each with its ageing time.
    """
    stacked: dict[str, np.ndarray] = {}
    seen: list[tuple[float, str]] = []
    for k, t in enumerate(times):
        if valid[k]:
            response = evaluate(k)
            for name, value in response.variables.items():
                value = np.asarray(value)
                if name not in stacked:
                    if value.dtype.kind in "US":
                        stacked[name] = np.full((len(times),) + value.shape, "", dtype=object)
                    else:
                        stacked[name] = np.full((len(times),) + value.shape, np.nan)
                stacked[name][k] = value
            seen += [(float(t), message) for message in response.notices]
        on_step()
    notices = merged_notices(seen, float(np.max(times)) if len(times) else None)
    variables = {name: (value.astype(str) if value.dtype == object else value)
                 for name, value in stacked.items()}
    return Response(variables, notices)


#: a number in a notice (``104``, ``-2.5``, ``1.2e+03``)
NUMBER = re.compile(r"[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def merged_notices(seen, span: float | None) -> list[str]:
    """Notices said at several ageing times, each told once: ``at t = 0 d to 60 d (4 ageing
    times): MESSAGE``, where a number that differs between the times shows its range
    (``near 104–106 deg``). Notices alike at one time (two joints of a motion) stay apart;
    a :class:`~fickcam.messages.DesignNotice` is told once, without times.

    Parameters
    ----------
    seen : sequence of tuple of (float, str)
        (ageing time [s], notice), in time order.
    span : float or None
        The run's last ageing time [s], so that every time shares one unit.

    Returns
    -------
    list of str
        One notice per group of notices alike but for their numbers, in the order the
        groups first occur; each keeps its level (:func:`~fickcam.messages.restated`).
    """
    groups: dict[tuple, list[tuple[float, str]]] = {}
    counts: dict[tuple, int] = {}
    for t, message in seen:
        shape = (t, NUMBER.sub("#", message))
        counts[shape] = counts.get(shape, 0) + 1  # the n-th alike at this time joins the n-th group
        groups.setdefault((shape[1], counts[shape]), []).append((t, message))
    notices = []
    for said in groups.values():
        if isinstance(said[0][1], DesignNotice):
            notices.append(said[0][1])
            continue
        when = sorted({t for t, _ in said})
        at = format_duration(when[0], span)
        if len(when) > 1:
            at = f"{at} to {format_duration(when[-1], span)} ({len(when)} ageing times)"
        notices.append(restated(said[0][1], f"at t = {at}: {_ranged([m for _, m in said])}"))
    return notices


def _ranged(messages: list[str]) -> str:
    """The first message, with each number that differs among ``messages`` as ``low–high``."""
    pieces = [NUMBER.split(m) for m in messages]
    numbers = [NUMBER.findall(m) for m in messages]
    text = pieces[0][0]
    for k, tail in enumerate(pieces[0][1:]):
        said = sorted({found[k] for found in numbers}, key=float)
        text += said[0] if len(said) == 1 else f"{said[0]}–{said[-1]}"
        text += tail
    return text


def first_change(values: np.ndarray, times: np.ndarray, what: str) -> list[str]:
    """Notices where a per-time label (e.g. the Grashof class) changes.

    Parameters
    ----------
    values : numpy.ndarray of str
        The label at each ageing time ("" where unknown: no change is told across it).
    times : numpy.ndarray
        The ageing times [s].
    what : str
        What the label is, for the notice.

    Returns
    -------
    list of str
        ``at t = ...: WHAT changed from A to B``, one per change.
    """
    notices = []
    span = float(np.max(times)) if len(times) else None
    for k in range(1, len(values)):
        if values[k] and values[k - 1] and values[k] != values[k - 1]:
            notices.append(f"at t = {format_duration(times[k], span)}: {what} changed from "
                           f"{values[k - 1]} to {values[k]}")
    return notices
