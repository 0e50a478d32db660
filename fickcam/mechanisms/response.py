"""What a mechanism model returns at one ageing time."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class Response:
    """What a mechanism model returns at one ageing time: schema-named arrays and user notices.

    Parameters
    ----------
    variables : dict of str to numpy.ndarray
        Schema name (:mod:`fickcam.schema`) -> a scalar or an array over the mechanism angle
        [SI units, angles in rad].
    notices : list of str
        One-line warnings the run reports (e.g. "follower jumps at 312 deg"), without the
        ageing time, which the orchestrator adds.
    """

    variables: dict[str, np.ndarray] = field(default_factory=dict)
    notices: list[str] = field(default_factory=list)


def peak(values: np.ndarray, axis: int = -1) -> np.ndarray:
    """The largest finite value along ``axis``; NaN where there is none (an ageing time past
    a part's wet glass transition), told by the array, not by a numpy warning.

    Parameters
    ----------
    values : numpy.ndarray
        E.g. a force over (time, cam angle) [any unit].
    axis : int
        The axis reduced.

    Returns
    -------
    numpy.ndarray
        The peaks [``values``' unit], NaN where ``values`` holds nothing finite.
    """
    values = np.asarray(values, float)
    finite = np.isfinite(values)
    largest = np.max(np.where(finite, values, -np.inf), axis=axis)
    return np.where(finite.any(axis=axis), largest, np.nan)
