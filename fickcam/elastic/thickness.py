r"""Moisture through the thickness of a plate from its in-plane field and the exact sheet.

The diffusion engine gives a plate's moisture on one level of its thickness (the
mid-plane of a cam plate or link, the level nearest it of a disc's (r, z) cells); the
exact series of an infinite sheet of the same thickness under the same exposure gives
the variation through the thickness. For a part whose faces, edge and bore all hold
one surface value Ms after a uniform initial moisture M0, the field is the product of
the unaccomplished fractions of its directions (Crank, The Mathematics of Diffusion,
2nd ed., Oxford 1975, §5.3, the finite cylinder as the infinite cylinder's solution
times the plane sheet's; Carslaw & Jaeger, Conduction of Heat in Solids, 2nd ed.,
Oxford 1959, §1.16):

.. math::

    M_s - M(x, y, z) = (M_s - M_0)\, U_p(x, y)\, U_s(z),

U_p of the planform, U_s of the sheet. With the sheet's field S(z) = Ms - (Ms - M0) U_s(z)
this reads

.. math::

    M(x, y, z) = (1 - w)\, S(z) + w M_s, \qquad w = 1 - U_p,

the sheet's field where the planform has not been reached (w = 0, the core) and the
surface value where it is saturated (w = 1, the edge and the bore), and w follows from
the engine's in-plane field M_p at its level z_p: w = (M_p - S(z_p)) / (Ms - S(z_p)).
This is exact for any uniform initial moisture, absorption or desorption.

Under a varying surface value (steps, records) the exact field is Duhamel's sum of the
product over the surface history, which needs U_p at every past age; only its current
in-plane level is known here, so w is read the same way relative to the current surface
value (one effective planform fraction for the whole history) and clipped to [0, 1].
The field is then a convex combination of the exact sheet field and the current surface
value, so it stays within the initial and surface values the part has seen (the
maximum principle of the exact field; Protter & Weinberger, Maximum Principles in
Differential Equations, Springer 1984, ch. 3), it is still exact in the core (w = 0) and
on the exposed edge (w = 1), and it reproduces the engine's in-plane value wherever
w lies in [0, 1]. Measured on an annulus (radii 8 and 25 mm, 6 mm thick, D = 1e-12 m^2/s)
against the engine's own (r, z) field, largest difference over the part relative to the
surface swing: 0.2-2 % under a constant climate (the sheet's depth sampling), up to 32 %
close to the rim within a day or two of a step of the surface value (2 -> 0.5 -> 3 %, or
daily steps), 0.2 % once the steps are a few weeks old; the sum of the in-plane field and
the sheet's deviation from its mid-plane differed by 61-96 % in the same cases.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class SheetProfile:
    """The exact moisture of an infinite sheet of the part's thickness under its exposure.

    Parameters
    ----------
    depths : numpy.ndarray
        Depths below a face [m], shape (n,), increasing from 0 (the face) to half the
        thickness (the mid-plane).
    moisture : numpy.ndarray
        Moisture at those depths [weight %], shape (times, n); column 0 is the face (the
        surface value).
    mean : numpy.ndarray
        Thickness mean of the sheet's moisture [weight %], shape (times,).
    """

    depths: np.ndarray
    moisture: np.ndarray
    mean: np.ndarray

    @property
    def surface(self) -> np.ndarray:
        """The face value [weight %], shape (times,)."""
        return self.moisture[:, 0]

    def at(self, depth: float) -> np.ndarray:
        """Moisture at ``depth`` [m] below a face (linear between the stored depths),
        shape (times,) [weight %]."""
        return np.array([np.interp(depth, self.depths, row) for row in self.moisture])


def planform_accomplished_fraction(in_plane, sheet_level, surface) -> np.ndarray:
    """The planform's accomplished fraction w = 1 - U_p read from the in-plane field.

    Parameters
    ----------
    in_plane : array_like
        The engine's moisture at one level of the thickness [weight %], any shape.
    sheet_level : float or array_like
        The sheet's moisture at that level [weight %] (broadcasts with ``in_plane``).
    surface : float or array_like
        The current surface value Ms [weight %] (broadcasts with ``in_plane``).

    Returns
    -------
    numpy.ndarray
        w = (M_p - S(z_p)) / (Ms - S(z_p)) clipped to [0, 1] [-]; 0 where the sheet's
        level already holds the surface value (the sheet's field alone then).
    """
    gap = np.asarray(surface, float) - np.asarray(sheet_level, float)
    change = np.asarray(in_plane, float) - np.asarray(sheet_level, float)
    gap, change = np.broadcast_arrays(gap, change)
    fraction = np.divide(change, gap, out=np.zeros(change.shape), where=gap != 0.0)
    return np.clip(fraction, 0.0, 1.0)


def product_moisture(accomplished, sheet, surface) -> np.ndarray:
    """M = (1 - w) S + w Ms: the product of the planform's and the sheet's unaccomplished
    fractions written with the sheet's field.

    Parameters
    ----------
    accomplished : array_like
        The planform's accomplished fraction w in [0, 1] [-].
    sheet : array_like
        The sheet's moisture S at the depth wanted [weight %] (broadcasts with w).
    surface : float or array_like
        The current surface value Ms [weight %] (broadcasts with w).

    Returns
    -------
    numpy.ndarray
        The plate's moisture [weight %], between S and Ms.
    """
    w = np.asarray(accomplished, float)
    return (1.0 - w) * np.asarray(sheet, float) + w * np.asarray(surface, float)
