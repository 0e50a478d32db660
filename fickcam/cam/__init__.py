"""Cam and translating follower over ageing: motion laws, profile, curvature,
kinematics, dynamics, jump, Hertz contact stress, friction and wear.

Public API: :class:`~fickcam.cam.spec.CamSection` (scene section), :class:`~fickcam.cam.design.CamDesign`,
:class:`~fickcam.cam.design.CamState`, :func:`~fickcam.cam.design.cam_design`, :func:`~fickcam.cam.model.cam_response`,
:func:`~fickcam.cam.kinematics.working_profile`; the scene's cam as a mechanism is
:class:`~fickcam.cam.mechanism.CamMechanism` (imported from its module: it imports the
mechanisms' package, which the scene's validation loads).

References
----------
Chen, F. Y. (1982). Mechanics and Design of Cam Mechanisms. New York: Pergamon Press.
de Boor, C. (2001). A Practical Guide to Splines, revised ed. New York: Springer.
Norton, R. L. (2012). Design of Machinery: An Introduction to the Synthesis and Analysis
    of Mechanisms and Machines, 5th ed. New York: McGraw-Hill.
Al-Shamma, F. & Yousuf, L. S. (2011). Predictive model of orthotropic un-symmetric
    box cam based on deflection and countered by segments of circular-arc contact
    profiles. Global Journal of Researches in Engineering (A) 11(7).
Madhukar, S., Manu, G., Shyam Venkat, P., Jaswanth Kumar, B. & Sai Kumar, M. (2023).
    Experimental investigation on contact force analysis of eccentric cam with roller
    follower. B.Tech project report, Anil Neerukonda Institute of Technology & Sciences,
    Visakhapatnam.
Singh, S. & Sanyal, S. (2017). Kinematic and dynamic variations in cam and follower
    made of composite material under hygrothermal environment. International Journal of
    Innovative Research in Science, Engineering and Technology (IJIRSET) 6(3).
Yadav, S., Karmarkar, V., Surti, J., Mistry, S. & Vardhe, G. (2017). To study wear
    and friction at contact surface of cam and follower of I.C. engine. International
    Research Journal of Engineering and Technology (IRJET) 4(4).
"""
from .design import CamDesign, CamState, cam_design
from .kinematics import working_profile
from .model import cam_response
from .profile import write_profile_csv
from .spec import CamSection

__all__ = ["CamDesign", "CamSection", "CamState", "cam_design", "cam_response",
           "working_profile", "write_profile_csv"]
