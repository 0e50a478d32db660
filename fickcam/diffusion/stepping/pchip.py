"""Shape-preserving piecewise cubic Hermite interpolation (PCHIP): the interpolant a step
response is read through between its nodes.

The slopes at the nodes are Fritsch and Butland's weighted harmonic mean of the two
neighbouring secants (zero where the data turn or stay flat), the end slopes Moler's
one-sided three-point formula kept to the data's shape; between two nodes the interpolant is
the cubic with those values and slopes. It is ``scipy.interpolate.PchipInterpolator``'s
interpolant, computed operation for operation as SciPy computes it (the slopes, the cubic's
power-basis coefficients and their evaluation), so that it reads the same values; it is
written out here because importing ``scipy.interpolate`` imports ``scipy.optimize`` and
``scipy.fft`` with it, 0.15-0.19 CPU s that were a tenth of a whole run of the demo scene,
whose only use of them was this interpolant.

References
----------
- Fritsch, F. N. & Butland, J. (1984). A method for constructing local monotone piecewise
  cubic interpolants. SIAM Journal on Scientific and Statistical Computing 5(2), 300-304.
  doi:10.1137/0905021
- Moler, C. (2004). Numerical Computing with MATLAB, sec. 3.6 (pchiptx). SIAM.
  doi:10.1137/1.9780898717952
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Pchip:
    """A PCHIP interpolant along the first axis of its values.

    Parameters
    ----------
    nodes : numpy.ndarray
        The abscissae [any unit], strictly increasing, shape (n,), n >= 2.
    coefficients : numpy.ndarray
        Each piece's cubic in the distance from its left node, highest power first, shape
        (4, n - 1, k): the k value columns flattened.
    shape : tuple of int
        The shape of one node's values (``()`` for a curve).
    """

    nodes: np.ndarray
    coefficients: np.ndarray
    shape: tuple

    @classmethod
    def through(cls, nodes, values) -> Pchip:
        """The interpolant through ``values`` at ``nodes``.

        Parameters
        ----------
        nodes : array_like
            The abscissae [any unit], strictly increasing, shape (n,), n >= 2.
        values : array_like
            The values [any unit], shape (n, ...).

        Returns
        -------
        Pchip
            The interpolant, extrapolated by its end pieces beyond the nodes.
        """
        x = np.asarray(nodes, float)
        y = np.asarray(values, float)
        columns = y.reshape(len(x), -1)
        h = np.diff(x)[:, None]
        slope = np.diff(columns, axis=0) / h
        dk = node_slopes(h, slope)
        t = (dk[:-1] + dk[1:] - 2 * slope) / h
        coefficients = np.stack((t / h, (slope - dk[:-1]) / h - t, dk[:-1], columns[:-1]))
        return cls(x, coefficients, y.shape[1:])

    def __call__(self, at) -> np.ndarray:
        """The interpolant at ``at`` [unit of the nodes], shape ``at.shape + shape``."""
        at = np.asarray(at, float)
        flat = at.ravel()
        piece = np.clip(np.searchsorted(self.nodes, flat, side="right") - 1, 0,
                        len(self.nodes) - 2)
        s = (flat - self.nodes[piece])[:, None]
        c = self.coefficients[:, piece]
        power = s * s  # the powers of s and the sum in SciPy's order (its PPoly evaluation)
        out = (0.0 + c[3]) + c[2] * s + c[1] * power + c[0] * (power * s)
        return out.reshape(at.shape + self.shape)


def node_slopes(h: np.ndarray, secant: np.ndarray) -> np.ndarray:
    """The slopes at the nodes: Fritsch and Butland's weighted harmonic mean inside, zero
    where the secants change sign or one is zero; Moler's one-sided ends.

    Parameters
    ----------
    h : numpy.ndarray
        The pieces' widths, shape (n - 1, 1).
    secant : numpy.ndarray
        The pieces' secant slopes, shape (n - 1, k).

    Returns
    -------
    numpy.ndarray
        The slope at each node, shape (n, k).
    """
    slopes = np.zeros((len(secant) + 1, secant.shape[1]))
    if len(secant) == 1:  # two nodes: the straight line
        slopes[:] = secant
        return slopes
    turn = ((np.sign(secant[1:]) != np.sign(secant[:-1])) | (secant[1:] == 0)
            | (secant[:-1] == 0))
    w1 = 2 * h[1:] + h[:-1]
    w2 = h[1:] + 2 * h[:-1]
    with np.errstate(divide="ignore", invalid="ignore"):  # the turns' division is not used
        mean = (w1 / secant[:-1] + w2 / secant[1:]) / (w1 + w2)
    slopes[1:-1][~turn] = 1.0 / mean[~turn]
    slopes[0] = end_slope(h[0], h[1], secant[0], secant[1])
    slopes[-1] = end_slope(h[-1], h[-2], secant[-1], secant[-2])
    return slopes


def end_slope(h0, h1, m0: np.ndarray, m1: np.ndarray) -> np.ndarray:
    """The slope at an end node from its two pieces (widths h0 then h1 inward, secants m0,
    m1): the three-point formula, zero where it has the other sign than m0, and 3 m0 where it
    exceeds that while the secants change sign (Moler 2004, pchiptx).

    Parameters
    ----------
    h0, h1 : numpy.ndarray
        The end piece's and its neighbour's widths, shape (1,).
    m0, m1 : numpy.ndarray
        Their secant slopes, shape (k,).

    Returns
    -------
    numpy.ndarray
        The end slope, shape (k,).
    """
    d = ((2 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
    wrong_sign = np.sign(d) != np.sign(m0)
    too_steep = (np.sign(m0) != np.sign(m1)) & (np.abs(d) > 3. * np.abs(m0))
    d[wrong_sign] = 0.
    d[~wrong_sign & too_steep] = 3. * m0[~wrong_sign & too_steep]
    return d
