"""Three meshes, each refined by 2: how far the finest is from the converged value, and
whether its second-order Richardson extrapolation may be taken (Roache 1998,
Verification and Validation in Computational Science and Engineering, ch. 5; Celik et
al. 2008, J. Fluids Eng. 130:078001). Used on the D(c) planform of ``corrected_product`` and on its
nested 3-D meshes.

References
----------
- Roache, P. J. (1998). Verification and Validation in Computational Science and Engineering.
  Albuquerque: Hermosa Publishers.
- Celik, I. B., Ghia, U., Roache, P. J., Freitas, C. J., Coleman, H. & Raad, P. E. (2008).
  Procedure for estimation and reporting of uncertainty due to discretization in CFD
  applications. Journal of Fluids Engineering 130(7):078001. doi:10.1115/1.2960953
"""
from __future__ import annotations

import numpy as np

from .budget import CONVERGENCE_INDEX_SAFETY


def taken(extrapolate: bool, middle, fine):
    """What ``three_levels`` chose: the 2x Richardson extrapolation, or the finest mesh.

    Parameters
    ----------
    extrapolate : bool
        ``three_levels``'s choice: True takes fine + (fine - middle) / 3.
    middle, fine : numpy.ndarray
        The quantity on the middle and the finest mesh, in its own unit (weight % for
        moisture).

    Returns
    -------
    numpy.ndarray
        The extrapolated or the finest values, in the quantity's unit.
    """
    return fine + (fine - middle) / 3.0 if extrapolate else fine


CONTRACTION = 3.0  # |change ratio| between two 2x refinements read as converging (order >= 1.6)
OVERSHOOT = 7.0    # largest rho at which the order-2 extrapolation is taken


def three_levels(coarse, middle, fine) -> tuple[bool, float]:
    """(extrapolate, error) of one quantity (an array over the outputs) on the finest of
    three meshes each refined 2x: the three-grid check of Roache (1998, Verification and
    Validation in Computational Science and Engineering, ch. 5; Celik et al. 2008, J. Fluids
    Eng. 130:078001, eqs. 1-5). The ratio of the changes, rho = (middle - coarse) /
    (fine - middle), is read where the finer change is at least a tenth of its largest:

    - ``CONTRACTION`` <= rho throughout (monotone, at least order log2 3 = 1.6): the
      error of ``fine`` is its grid convergence index 1.25 |fine - middle| / (rho - 1)
      with the smallest rho seen (for an error a h^p, |fine - middle| / (rho - 1) is the
      error); where also rho <= ``OVERSHOOT`` the second-order extrapolation
      fine + (fine - middle) / 3 is taken: its error |4 - rho| / 3 that of ``fine``, no
      larger (an order-2 extrapolation of a sequence of order above log2 7 = 2.8
      overshoots by more than the fine mesh's own error);
    - |rho| >= ``CONTRACTION`` throughout (converging, but oscillating or changing sign):
      ``fine``, its error at most half its change (the rest of a series contracting by 3
      or more, alternating or not, is at most |fine - middle| / 2);
    - else ``fine``, its error at most the whole change (an upper bound from order 1 on).

    On the demo cam's D(c) planform (k = 2, accuracy 1e-3) the contact layer at 1 d flips
    sign between the meshes (rho = -14): there the extrapolation erred 1.8e-4 of the swing
    (layer / 4; against the 8x mesh, 108 000 cells), the 4x mesh itself 2e-5.

    Parameters
    ----------
    coarse, middle, fine : numpy.ndarray
        The quantity over the outputs on meshes each refined 2x from the last, in its own
        unit (weight % for moisture).

    Returns
    -------
    extrapolate : bool
        Whether the order-2 extrapolation (``taken``) may be used.
    error : float
        The error bound of what ``taken`` returns, in the quantity's unit.

    References
    ----------
    Roache (1998), ch. 5; Celik et al. (2008), eqs. 1-5 (see the module docstring).
    """
    changes = (middle - coarse, fine - middle)
    largest = float(np.max(np.abs(changes[1])))
    if largest == 0.0:
        return False, 0.0
    significant = np.abs(changes[1]) >= 0.1 * largest
    rho = changes[0][significant] / changes[1][significant]
    if np.all(rho >= CONTRACTION):
        return (bool(np.all(rho <= OVERSHOOT)),
                CONVERGENCE_INDEX_SAFETY * largest / (float(np.min(rho)) - 1.0))
    if np.all(np.abs(rho) >= CONTRACTION):
        return False, 0.5 * largest
    return False, largest
