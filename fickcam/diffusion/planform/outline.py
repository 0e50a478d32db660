"""The planform of a prismatic part as the meshers sample it: ``Outline``, which points
are inside, and samples along its edges and its contact edge. The shapes themselves (a
cam plate's profile, a link's bosses) are the geometries' own (``problem.geometry``)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Outline:
    """A planform: ``inside(x, y)``, boundary samples (all edges) and the contact edge.

    Parameters
    ----------
    part : CamPlate or LinkBar
        The part whose planform this is (lengths in [m]); any planform geometry.
    boundary : numpy.ndarray
        Points along every edge [m], shape (n, 2).
    contact : numpy.ndarray
        Points along the contact edge [m], shape (m, 2).
    """

    part: object
    boundary: np.ndarray   # (n, 2) points along every edge, spacing <= requested
    contact: np.ndarray    # (m, 2) points along the contact edge

    def inside(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        return self.part.inside(x, y)


def outline(part, spacing: float) -> Outline:
    """Boundary samples of a planform geometry (a CamPlate's contact: the profile; a
    LinkBar's: every edge), as the part gives them (``edge_samples``).

    Parameters
    ----------
    part : CamPlate or LinkBar
        The prismatic part, its lengths in [m]; any planform geometry.
    spacing : float
        The largest gap between samples [m].

    Returns
    -------
    Outline
        The planform with its boundary and contact samples [m].
    """
    boundary, contact = part.edge_samples(spacing)
    return Outline(part, boundary, contact)
