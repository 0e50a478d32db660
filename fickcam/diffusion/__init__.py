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

Importing this package loads none of it: the public names below are looked up in their
modules on first use (PEP 562), so a module that needs one light part (the model names,
the accuracy check) does not load the engine with it.
"""
from __future__ import annotations

import importlib

#: public name -> the module (relative to this package) that defines it
_PUBLIC = {
    "CellCaps": ".accuracy.error_model",
    "MODELS": ".problem.definition",
    "SolverSettings": ".dispatch", "plan": ".dispatch", "plan_problem": ".dispatch",
    "refuse": ".dispatch", "solve": ".dispatch", "solve_problem": ".dispatch",
    "RunCache": ".problem.cache", "run_cache": ".problem.cache",
    "DiffusionProblem": ".problem.definition",
    "GAS_CONSTANT": ".problem.exposure", "Diffusivity": ".problem.exposure",
    "Exposure": ".problem.exposure",
    "Bar": ".problem.geometry", "CamPlate": ".problem.geometry", "Disc": ".problem.geometry",
    "Geometry": ".problem.geometry", "LinkBar": ".problem.geometry", "Sheet": ".problem.geometry",
    "DiffusionResult": ".problem.results", "Plan": ".problem.results",
}

__all__ = sorted(_PUBLIC)


def __getattr__(name: str):
    """A public name, imported from its module on first use (PEP 562)."""
    if name not in _PUBLIC:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(_PUBLIC[name], __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_PUBLIC))
