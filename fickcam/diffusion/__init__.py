"""Fickian moisture diffusion in the parts of a mechanism.

``solve`` and ``plan`` are the entry points (``solve.py``); FiPy is imported
only inside the finite-volume functions, so importing this package stays light.
"""
from .exposure import GAS_CONSTANT, Diffusivity, Exposure
from .geometry import Bar, CamPlate, Disc, Geometry, LinkBar, Sheet
from .solve import MODELS, DiffusionResult, Plan, plan, solve

__all__ = ["GAS_CONSTANT", "Diffusivity", "Exposure", "Bar", "CamPlate", "Disc",
           "Geometry", "LinkBar", "Sheet", "MODELS", "DiffusionResult", "Plan", "plan", "solve"]
