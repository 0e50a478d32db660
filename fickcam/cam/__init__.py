"""Cam and translating follower over ageing: motion laws, profile, curvature,
kinematics, dynamics, jump, Hertz contact stress, friction and wear.

Public API: :class:`CamSection` (scene section), :class:`CamDesign`,
:class:`CamState`, :func:`design_from_scene`, :func:`cam_response`,
:func:`working_profile`, and for :mod:`fickcam.simulate` :func:`scene_parts`,
:func:`scene_response`.
"""
from .ageing import cam_state, scene_parts, scene_response
from .design import CamDesign, CamState, design_from_scene
from .kinematics import working_profile, write_profile_csv
from .model import cam_response
from .spec import CamSection

__all__ = ["CamDesign", "CamSection", "CamState", "cam_response", "cam_state", "design_from_scene",
           "scene_parts", "scene_response", "working_profile", "write_profile_csv"]
