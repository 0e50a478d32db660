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
    (Crank 1975 section 5.3), with D along the length and width = D x ``in_plane``."""
    t = specimen.time if times is None else np.asarray(times, float)
    deficit = 1.0 - sheet_uptake(diffusivity * t / specimen.thickness ** 2)
    if specimen.width is not None:
        for side, ratio in zip((specimen.length, specimen.width), in_plane):
            deficit = deficit * (1.0 - sheet_uptake(ratio * diffusivity * t / side ** 2))
    return 1.0 - deficit


def edge_factor(specimen: Specimen, in_plane=(1.0, 1.0)) -> float:
    """Shen & Springer (1976, J. Compos. Mater. 10:2, eq. 17; ASTM D5229 eq. 5) edge
    correction: apparent D = D (1 + h/l sqrt(Dl/D) + h/w sqrt(Dw/D))^2. 1 when sealed."""
    if specimen.width is None:
        return 1.0
    h = specimen.thickness
    return (1.0 + h / specimen.length * np.sqrt(in_plane[0]) + h / specimen.width * np.sqrt(in_plane[1])) ** 2


def two_phase_fraction(specimen: Specimen, diffusivity: float, gamma: float, beta: float,
                       in_plane=(1.0, 1.0), times=None) -> np.ndarray:
    """Total M/Mm of a coupon under the Carter & Kibler (1978) two-phase model. Exact for
    a sheet with sealed edges; with exposed edges the sheet solution is taken with the
    Shen & Springer apparent diffusivity D x ``edge_factor`` (an approximation: the
    exact box solution of the two-phase model does not factor into sheets)."""
    t = specimen.time if times is None else np.asarray(times, float)
    apparent = diffusivity * edge_factor(specimen, in_plane)
    return two_phase_sheet_uptake(t, apparent, specimen.thickness, gamma, beta, SERIES_TOLERANCE).total
