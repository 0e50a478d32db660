"""Fickian moisture diffusion in the parts of a mechanism."""
from .exposure import GAS_CONSTANT, Diffusivity, Exposure
from .geometry import Bar, CamPlate, Disc, Geometry, LinkBar, Sheet

__all__ = ["GAS_CONSTANT", "Diffusivity", "Exposure", "Bar", "CamPlate", "Disc",
           "Geometry", "LinkBar", "Sheet"]
