"""``DiffusionProblem``: what one solve is asked, frozen, passed whole from ``solve`` and
``plan`` to the models instead of the same ten arguments at every layer."""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from .exposure import Diffusivity, Exposure
from .geometry import LAYER_DEPTH

#: The models a problem may ask for (``diffusion.model``): ``auto`` (the dispatcher
#: chooses) and the Fickian models of the dispatcher's registry, in its order. The names
#: live here, apart from the models, so that the scene checks them without loading the
#: engine; ``tests/test_diffusion_registry.py`` holds them equal to the registry's.
MODELS = ("auto", "analytic", "slab", "axisymmetric", "plane", "solid")


@dataclass(frozen=True, eq=False)
class DiffusionProblem:
    """One part's moisture problem: the part, its diffusivity, its surface history, the
    times asked for and how (accuracy, model, contact layer, fields, sorption).

    Parameters
    ----------
    geometry : Sheet, Disc, Bar, CamPlate or LinkBar
        The part, dry dimensions [m].
    diffusivity : Diffusivity
        D(T) along the part axes [m^2/s].
    exposure : Exposure
        The surface history: temperature [K] and surface moisture [weight %] over time.
    times : numpy.ndarray
        The times at which the moisture is wanted [s] (kept read-only).
    accuracy : float
        The relative accuracy [-] asked for, a fraction of the moisture swing, in (0, 0.1].
    model : str
        One of ``MODELS``; "auto" chooses.
    surface_layer_depth : float or None
        The depth of the contact layer whose mean is reported as ``surface`` [m]; None
        (a plan alone): not given, the contact layer is not read.
    store_fields : bool
        Keep the moisture field of every cell at every time.
    part : str
        The part's name, for messages.
    sorption : optional
        A sorption law of ``problem.sorption``; None: Fick's law.
    """

    geometry: object
    diffusivity: Diffusivity
    exposure: Exposure
    times: np.ndarray = field(repr=False)
    accuracy: float = 1e-3
    model: str = "auto"
    surface_layer_depth: float | None = LAYER_DEPTH
    store_fields: bool = False
    part: str = ""
    sorption: object = None

    def __post_init__(self):
        times = np.array(self.times, float)
        times.setflags(write=False)
        object.__setattr__(self, "times", times)

    def at(self, times) -> "DiffusionProblem":
        """The same problem at other ``times`` [s] (the limit search's)."""
        return replace(self, times=times)

    def with_diffusivity(self, diffusivity: Diffusivity) -> "DiffusionProblem":
        """The same problem with another D(T) (Fick with D f where f is one number)."""
        return replace(self, diffusivity=diffusivity)

    @property
    def name(self) -> str:
        """The part's name, else its shape's (for messages)."""
        return self.part or type(self.geometry).__name__
