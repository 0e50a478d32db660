"""Moisture diffusion in the parts of a mechanism: ``solve`` and ``plan`` (``dispatch``).

The sub-packages are the stages of the data flow, each importing only the ones listed
before it (tests/test_architecture.py holds the order):

- ``problem``: what is solved (geometries, exposure, diffusivity, sorption laws, the frozen
  ``DiffusionProblem`` that carries them, results) and the run's cache (``RunCache``: what
  plans and solves build once, read-only);
- ``accuracy``: the error model every plan sizes its cells and steps with;
- ``forcing``: the climate as the solvers see it (the rescaled clock, long records);
- ``exact``: closed-form series (the exact path);
- ``planform``: the outline of cam plates and links, its meshes and expansion;
- ``superposition``: Duhamel's theorem over the exposure history;
- ``operators``: the discrete operators, FiPy's (``operators.fipy_backend``, the one
  module that imports FiPy) and the plane model's P1;
- ``stepping``: step plans, the marcher, dense output;
- ``models``: the Fickian models ``solve`` chooses between;
- ``nonfickian``: two-phase (Langmuir-type) and concentration-dependent moisture.

FiPy is imported inside the backend's functions only, so importing this package stays
light.
"""
from .accuracy.error_model import CellCaps
from .dispatch import MODELS, SolverSettings, plan, plan_problem, refuse, solve, solve_problem
from .problem.cache import RunCache, run_cache
from .problem.definition import DiffusionProblem
from .problem.exposure import GAS_CONSTANT, Diffusivity, Exposure
from .problem.geometry import Bar, CamPlate, Disc, Geometry, LinkBar, Sheet
from .problem.results import DiffusionResult, Plan

__all__ = ["GAS_CONSTANT", "Diffusivity", "Exposure", "Bar", "CamPlate", "Disc",
           "Geometry", "LinkBar", "Sheet", "MODELS", "DiffusionResult", "Plan", "SolverSettings",
           "CellCaps", "RunCache", "run_cache", "DiffusionProblem", "plan", "plan_problem", "refuse",
           "solve", "solve_problem"]
