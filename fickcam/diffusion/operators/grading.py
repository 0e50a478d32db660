"""Cell widths graded towards exposed faces.

After a change of the surface value the solution varies over a boundary layer
of depth ~ sqrt(tau) (Crank 1975 eq. 2.45): cells must be fine at the faces
and early, but the interior only sees the smoother later profile. A cell
width that grows in geometric progression away from a face, w_k = w_0 (1 + g)^k,
keeps the local ratio w / sqrt(tau) bounded for every tau >= tau_lo; a smoothly
graded cell-centred grid keeps second-order global accuracy in w_0 at fixed g
(supraconvergence: Manteuffel & White 1986, Math. Comp. 47, 511-535), and the
growth adds an error of its own, measured on the sheet against Crank's series
(eq. 4.18, mean uptake over tau* >= 1e-3 and >= 1e-2, g = 0.03-0.24):
about ``GROWTH_ERROR`` g^2 (0.040-0.063 g^2).

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
- Manteuffel, T. A. & White, A. B. (1986). The numerical solution of second-order boundary
  value problems on nonuniform meshes. Mathematics of Computation 47(176):511-535.
  doi:10.1090/S0025-5718-1986-0856700-3
"""
from __future__ import annotations

import math

import numpy as np

from ..accuracy.error_model import GROWTH_ERROR

MAX_GROWTH = 0.25  # at most 25 % wider than the neighbour


def growth_rate(tolerance: float) -> float:
    """The growth g whose own error GROWTH_ERROR g^2 is ``tolerance``, at most ``MAX_GROWTH``.

    Parameters
    ----------
    tolerance : float
        The relative error [-] the grading may add.

    Returns
    -------
    float
        g, the relative growth of a cell's width over its neighbour's [-].
    """
    return min(MAX_GROWTH, math.sqrt(max(tolerance, 0.0) / GROWTH_ERROR))


def graded_widths(length: float, finest: float, growth: float, ends: str = "both") -> np.ndarray:
    """Widths of cells across ``length``, ``finest`` at the exposed end(s)
    (``ends``: ``both``, ``low`` or ``high``), each at most (1 + ``growth``) times
    its neighbour; uniform when ``growth`` is 0. The widths sum to ``length`` and
    none exceeds ``finest`` at the exposed faces (they are scaled down to fit).

    Parameters
    ----------
    length : float
        The span to cover [m] (or scaled [-]; the widths take its unit).
    finest : float
        The width at the exposed end(s), in ``length``'s unit [m].
    growth : float
        g, the relative growth from a cell to the next [-]; 0: uniform.
    ends : str
        The exposed end(s): ``both``, ``low`` or ``high``.

    Returns
    -------
    numpy.ndarray
        The widths from the low end, summing to ``length`` [m].

    Raises
    ------
    ValueError
        When ``ends`` is none of the three, or ``length`` or ``finest`` is not positive.

    References
    ----------
    Manteuffel & White (1986), see the module docstring.
    """
    if ends not in ("both", "low", "high"):
        raise ValueError(f"ends {ends!r}: both, low or high")
    if not (length > 0 and finest > 0):
        raise ValueError("length and finest must be positive")
    span = 0.5 * length if ends == "both" else length
    if growth <= 0 or finest >= span:
        count = max(1, math.ceil(span / finest))
        half = np.full(count, span / count)
    else:
        ratio = 1.0 + growth
        # fewest cells whose geometric widths cover the span
        count = max(1, math.ceil(math.log1p(span * growth / finest) / math.log(ratio)))
        half = finest * ratio ** np.arange(count)
        half *= span / half.sum()
    if ends == "both":
        return np.concatenate([half, half[::-1]])
    return half if ends == "low" else half[::-1]
