"""Re-entrant corners of a drawn planform and meshes graded toward them.

Where a drawn outline turns back into the material (a web meeting a boss, a keyway's
root), the plane-stress field of a free strain that varies near the corner is singular:
u ~ r^lambda about the corner, with lambda the smallest root of Williams' characteristic
equations for a wedge of angle omega with free faces, sin(lambda omega) = -/+ lambda sin(omega)
(Williams 1952). For omega = 3 pi / 2, lambda = 0.5445; for a straight edge (omega = pi)
lambda = 1 and nothing is singular. On quasi-uniform meshes the error of a displacement
read far from the corner then falls only as h^(2 lambda) (about h^1.2 at the web of a
dog-bone link), whatever the elements' order.

Meshes graded toward the corner restore the elements' order: local sizes
h(r) = h (r / R)^(1 - beta) within R of the corner, with beta < lambda / p for elements of
order p, give the energy error O(h^p) and a functional of the displacement (a pin's
centre) O(h^(2p)) (Babuska, Kellogg & Pitkaranta 1979; Apel 1999, ch. 3).

References
----------
- Williams, M. L. (1952). Stress singularities resulting from various boundary conditions
  in angular corners of plates in extension. Journal of Applied Mechanics 19(4), 526-528.
- Babuska, I., Kellogg, R. B. & Pitkaranta, J. (1979). Direct and inverse error estimates
  for finite elements with mesh refinements. Numerische Mathematik 33, 447-471.
  https://doi.org/10.1007/BF01399326
- Apel, T. (1999). Anisotropic Finite Elements: Local Estimates and Applications.
  Stuttgart: Teubner.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

#: a turn of the outline sharper than this is a drawn corner; the chords of a flattened arc
#: turn by less (a chord tolerance of 1e-3 of the radius turns by 5 deg)
CORNER_TURN = math.radians(15.0)
#: the graded zone's radius, as a fraction of the part's extent
GRADED_ZONE = 0.1
#: beta = SAFETY lambda / p: the grading strictly inside what the estimates ask
SAFETY = 0.9
#: a triangle is split while its longest edge exceeds this many target sizes
SPLIT_ABOVE = 1.5
#: at most this many rounds of splitting (each halves the marked triangles' edges)
ROUNDS = 60


def williams_exponent(angle: float) -> float:
    """The smallest exponent lambda of the displacement r^lambda at the vertex of a wedge of
    plane elasticity with both faces free (Williams 1952): the smallest root in (0, 1) of
    sin(lambda omega) + lambda sin(omega) = 0 (symmetric) or sin(lambda omega) -
    lambda sin(omega) = 0 (antisymmetric); 1 where there is none (a convex or straight
    corner: nothing singular).

    Parameters
    ----------
    angle : float
        The wedge's angle omega, the material's side [rad], in (0, 2 pi].

    Returns
    -------
    float
        lambda [-]: 0.5 at a crack (2 pi), 0.5445 at a right-angled re-entrant corner.
    """
    roots = [1.0]
    grid = np.linspace(1e-6, 1.0 - 1e-9, 4001)
    for sign in (1.0, -1.0):
        def equation(exponent, sign=sign):
            return math.sin(exponent * angle) + sign * exponent * math.sin(angle)
        values = np.sin(grid * angle) + sign * grid * math.sin(angle)
        change = np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0)
        roots += [brentq(equation, grid[i], grid[i + 1], xtol=1e-14) for i in change[:1]]
    return float(min(roots))


def reentrant_corners(loops) -> list[tuple[np.ndarray, float]]:
    """The vertices where a planform's loops turn into the material by more than
    ``CORNER_TURN``, with the Williams exponent of each.

    Parameters
    ----------
    loops : sequence of numpy.ndarray
        The closed polygons [m], material on their left (the outline counter-clockwise,
        the holes clockwise), shape (n, 2) each.

    Returns
    -------
    list of tuple
        (the corner [m] (2,), lambda [-]) for each re-entrant corner.
    """
    corners = []
    for loop in loops:
        loop = np.asarray(loop, float)
        before, after = loop - np.roll(loop, 1, axis=0), np.roll(loop, -1, axis=0) - loop
        turn = np.arctan2(before[:, 0] * after[:, 1] - before[:, 1] * after[:, 0],
                          np.sum(before * after, axis=1))
        corners += [(loop[i].copy(), williams_exponent(math.pi - turn[i]))
                    for i in np.flatnonzero(turn < -CORNER_TURN)]
    return corners


def target_sizes(centroids, corners, size: float, radius: float, order: int) -> np.ndarray:
    """The graded mesh's size at triangle centroids: size (r / R)^(1 - beta) within R of a
    corner, beta = ``SAFETY`` lambda / p, the smallest over the corners; inf elsewhere.

    Parameters
    ----------
    centroids : numpy.ndarray
        The points [m], shape (m, 2).
    corners : list of tuple
        (corner [m], lambda [-]) as :func:`reentrant_corners` gives them.
    size : float
        The mesh's size at the graded zone's edge [m].
    radius : float
        The graded zone's radius R [m].
    order : int
        The elements' order p.

    Returns
    -------
    numpy.ndarray
        The target edge lengths [m], shape (m,).
    """
    target = np.full(len(centroids), np.inf)
    for corner, exponent in corners:
        beta = SAFETY * min(exponent, 1.0) / order
        r = np.hypot(*(np.asarray(centroids, float) - corner).T)
        target = np.minimum(target, np.where(r < radius, size * (r / radius) ** (1.0 - beta),
                                             np.inf))
    return target
