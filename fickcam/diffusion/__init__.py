"""Fickian moisture diffusion in the parts of a mechanism.

``solve`` and ``plan`` are the entry points (``dispatch``); FiPy is imported only
inside the functions that assemble a mesh operator, so importing this package stays
light. Import direction (each module imports only modules to its left):
docs/architecture.md.
"""
from .dispatch import MODELS, plan, solve
from .problem.exposure import GAS_CONSTANT, Diffusivity, Exposure
from .problem.geometry import Bar, CamPlate, Disc, Geometry, LinkBar, Sheet
from .problem.results import DiffusionResult, Plan

__all__ = ["GAS_CONSTANT", "Diffusivity", "Exposure", "Bar", "CamPlate", "Disc",
           "Geometry", "LinkBar", "Sheet", "MODELS", "DiffusionResult", "Plan", "plan", "solve"]
