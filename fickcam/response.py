"""What a mechanism model returns at one ageing time."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class Response:
    """Arrays named after schema variables (SI, angles in rad) and user notices.

    ``variables`` maps a schema name (see :mod:`fickcam.schema`) to a scalar or
    an array over the mechanism angle; ``notices`` are one-line warnings the run
    reports (e.g. "follower jumps at 312 deg"), without the ageing time, which
    the orchestrator adds.
    """

    variables: dict[str, np.ndarray] = field(default_factory=dict)
    notices: list[str] = field(default_factory=list)
