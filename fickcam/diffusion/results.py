"""What a diffusion solve plans (``Plan``) and returns (``DiffusionResult``)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

@dataclass(frozen=True)
class Plan:
    """What ``solve`` will do for one part (printed by ``fickcam check``)."""

    model: str
    cells: int
    steps: int
    reason: str
    error_estimate: float
    cells_per_axis: tuple[int, ...] = ()
    steps_per_doubling: int = 0
    expansion_tolerance: float = 0.0  # plane: the short-time expansion's error allowance
    finest: float = 0.0      # graded meshes: finest spacing at the exposed faces/outline
    #                          (scaled units, thickness = 1); 0 for a uniform grid
    growth: float = 0.0      # graded meshes: growth per cell/row away from them


@dataclass
class DiffusionResult:
    """Moisture of one part at the requested times (weight %)."""

    times: np.ndarray
    mean: np.ndarray
    surface: np.ndarray
    model: str
    cells: int
    steps: int
    error_estimate: float
    reason: str
    fields: np.ndarray | None = None
    bound: np.ndarray | None = None  # two-phase (Langmuir) sorption: bound-water mean, weight %
    cell_coordinates: dict[str, np.ndarray] = field(default_factory=dict)

