"""Four-bar linkage over ageing: positions (Freudenstein), Grashof class,
transmission angle, coupler curve, velocities, accelerations and kinetostatics.

Public API: :class:`~fickcam.linkage.spec.LinkageSection` (scene section), :class:`~fickcam.linkage.model.FourBarDesign`,
:class:`~fickcam.linkage.model.FourBarState`, :func:`~fickcam.linkage.model.fourbar_response`, :func:`~fickcam.linkage.classify.class_changes`,
:func:`~fickcam.linkage.classify.grashof_class`, ``JOINTS`` (coordinate values); the scene's
four-bar as a mechanism is :class:`~fickcam.linkage.mechanism.LinkageMechanism` (with
``LINKS``), imported from its module.

References
----------
Freudenstein, F. (1955). Approximate synthesis of four-bar linkages. Transactions of the
    ASME 77, 853-861.
Norton, R. L. (2012). Design of Machinery: An Introduction to the Synthesis and Analysis
    of Mechanisms and Machines, 5th ed. New York: McGraw-Hill.
Singh, S. & Sanyal, S. (2016). Variations in geometry, volume, mass and moment of
    inertia of link of a four bar mechanism made of neat resin under hygrothermal
    environment. International Journal of Innovative Research in Science, Engineering and
    Technology (IJIRSET) 5(12).
"""
from .classify import class_changes, grashof_class
from .dynamics import JOINT_MEANING, JOINTS
from .model import FourBarDesign, FourBarState, fourbar_response
from .spec import LinkageSection

__all__ = ["JOINTS", "JOINT_MEANING", "FourBarDesign", "FourBarState", "LinkageSection",
           "class_changes", "fourbar_response", "grashof_class"]
