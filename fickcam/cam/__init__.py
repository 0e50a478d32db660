"""Cam and translating follower over ageing: motion laws, profile, curvature,
kinematics, dynamics, jump, Hertz contact stress, friction and wear.

Public API: :class:`CamSection` (scene section), :class:`CamDesign`,
:class:`CamState`, :func:`design_from_scene`, :func:`cam_response`,
:func:`working_profile`, and for :mod:`fickcam.simulate` :func:`scene_parts`,
:func:`scene_response`.
"""
from .spec import CamSection

__all__ = ["CamSection"]
