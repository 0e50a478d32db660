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
