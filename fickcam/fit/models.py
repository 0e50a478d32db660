"""Uptake models of a weighed coupon. The one place where the fit package takes
the diffusion solutions (Crank's sheet series and the two-phase modes) from
``fickcam.diffusion``: keep those imports here."""
from __future__ import annotations

import numpy as np

from ..diffusion.exact.series import sheet_uptake
from ..diffusion.exact.two_phase import two_phase_sheet_uptake
from .data import Specimen

SERIES_TOLERANCE = 1e-7   # two-phase series truncation (fraction of Mm): far below any weighing scatter


def fickian_fraction(specimen: Specimen, diffusivity: float, in_plane=(1.0, 1.0), times=None):
    """F = M/Mm of the coupon at ``times`` (default: its weighing times), through-thickness
    diffusivity D (m^2/s). Sealed edges: Crank's sheet series (Crank 1975 eqs. 4.18/4.20).
    Exposed edges: the box is the product of three sheets, 1 - F = prod (1 - F_i)
    (Crank 1975 section 5.3), with D along the length and width = D x ``in_plane``.

    Parameters
    ----------
    specimen : Specimen
        The coupon: thickness, and length and width unless its edges are sealed [m];
        weighing times [s].
    diffusivity : float
        Through-thickness diffusivity D [m^2/s].
    in_plane : tuple of float
        Diffusivity along the length and the width over D [-].
    times : array_like, optional
        Times since the start of exposure [s]; default the weighing times.

    Returns
    -------
    numpy.ndarray
        The uptake fraction M/Mm [-].

    References
    ----------
    Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
    """
    t = specimen.time if times is None else np.asarray(times, float)
    deficit = 1.0 - sheet_uptake(diffusivity * t / specimen.thickness ** 2)
    if specimen.width is not None:
        for side, ratio in zip((specimen.length, specimen.width), in_plane):
            deficit = deficit * (1.0 - sheet_uptake(ratio * diffusivity * t / side ** 2))
    return 1.0 - deficit


def edge_factor(specimen: Specimen, in_plane=(1.0, 1.0)) -> float:
    """Shen & Springer (1976, J. Compos. Mater. 10:2, eq. 17; ASTM D5229 eq. 5) edge
    correction: apparent D = D (1 + h/l sqrt(Dl/D) + h/w sqrt(Dw/D))^2. 1 when sealed.

    Parameters
    ----------
    specimen : Specimen
        The coupon: thickness h, length l and width w [m] (width None: sealed edges).
    in_plane : tuple of float
        Dl/D and Dw/D, the in-plane over the through-thickness diffusivity [-].

    Returns
    -------
    float
        The factor apparent D / D [-].

    References
    ----------
    Shen, C.-H. & Springer, G. S. (1976). Moisture absorption and desorption of composite
    materials. Journal of Composite Materials 10(1), 2-20.
    ASTM D5229/D5229M, Standard Test Method for Moisture Absorption Properties and
    Equilibrium Conditioning of Polymer Matrix Composite Materials.
    """
    if specimen.width is None:
        return 1.0
    h = specimen.thickness
    return (1.0 + h / specimen.length * np.sqrt(in_plane[0]) + h / specimen.width * np.sqrt(in_plane[1])) ** 2


def two_phase_fraction(specimen: Specimen, diffusivity: float, gamma: float, beta: float,
                       in_plane=(1.0, 1.0), times=None) -> np.ndarray:
    """Total M/Mm of a coupon under the Carter & Kibler (1978) two-phase model. Exact for
    a sheet with sealed edges; with exposed edges the sheet solution is taken with the
    Shen & Springer apparent diffusivity D x ``edge_factor`` (an approximation: the
    exact box solution of the two-phase model does not factor into sheets).

    Parameters
    ----------
    specimen : Specimen
        The coupon: dimensions [m], weighing times [s].
    diffusivity : float
        Through-thickness diffusivity D of the mobile phase [m^2/s].
    gamma : float
        Rate at which mobile molecules become bound [1/s].
    beta : float
        Rate at which bound molecules become mobile [1/s].
    in_plane : tuple of float
        In-plane over through-thickness diffusivity along length and width [-].
    times : array_like, optional
        Times since the start of exposure [s]; default the weighing times.

    Returns
    -------
    numpy.ndarray
        The total (mobile + bound) uptake fraction M/Mm [-].

    References
    ----------
    Carter, H. G. & Kibler, K. G. (1978). Langmuir-type model for anomalous moisture
    diffusion in composite resins. Journal of Composite Materials 12(2), 118-131.
    """
    t = specimen.time if times is None else np.asarray(times, float)
    apparent = diffusivity * edge_factor(specimen, in_plane)
    return two_phase_sheet_uptake(t, apparent, specimen.thickness, gamma, beta, SERIES_TOLERANCE).total
