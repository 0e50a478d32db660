"""Exact moisture and thin-plate swelling stress of a free annulus (hollow disc) whose
faces, rim and bore all hold one surface value Ms from t = 0 (uniform M0 before),
written independently of fickcam for its tests.

Moisture: the product of the hollow cylinder's and the sheet's unaccomplished fractions
(Carslaw & Jaeger, Conduction of Heat in Solids, 2nd ed., Oxford 1959, §1.16),
Ms - M = (Ms - M0) U_c(r) U_s(z), with

- the hollow cylinder a < r < b, both surfaces held (Crank, The Mathematics of Diffusion,
  2nd ed., Oxford 1975, §5.3.3, eqs. 5.48-5.50 for this case; Carslaw & Jaeger 1959
  §13.3): U_c = sum_n c_n U0(alpha_n r) exp(-D alpha_n^2 t), U0(x) = J0(x) Y0(b alpha) -
  J0(b alpha) Y0(x), the alpha_n the roots of U0(a alpha) = 0, c_n the projection of 1
  on U0 with weight r: int r U0 dr = [r U1 / alpha], int r U0^2 dr = [r^2 (U0^2 + U1^2) / 2]
  (U1 = J1(x) Y0(b alpha) - J0(b alpha) Y1(x));
- the sheet 0 < z < h (Crank 1975 eq. 4.17): U_s = sum_k 4 / ((2k+1) pi)
  sin((2k+1) pi z / h) exp(-(2k+1)^2 pi^2 D t / h^2), thickness mean eq. 4.18.

Stress: a thin free plate that stays plane (no bending, the field being symmetric in z):
the thin annulus under the thickness-mean free strain beta M(r) (Timoshenko & Goodier,
Theory of Elasticity, 3rd ed., McGraw-Hill 1970, sec. 152, alpha T -> beta M),

    sigma_r = E beta / r^2 [ (r^2 - a^2) / (b^2 - a^2) I(b) - I(r) ],
    sigma_t = E beta / r^2 [ (r^2 + a^2) / (b^2 - a^2) I(b) + I(r) ] - E beta M(r),
    I(r) = int_a^r M r' dr',

plus the equibiaxial through-thickness term -E beta (M(r, z) - M(r)) / (1 - nu)
(sec. 150). Both in-plane stresses are principal.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.optimize import brentq
from scipy.special import j0, j1, y0, y1


def hollow_roots(a: float, b: float, count: int) -> np.ndarray:
    """The first ``count`` positive roots alpha of J0(a alpha) Y0(b alpha) - J0(b alpha)
    Y0(a alpha) (1/m), bracketed on a grid of a tenth of their spacing pi / (b - a)."""
    def f(alpha):
        return j0(a * alpha) * y0(b * alpha) - j0(b * alpha) * y0(a * alpha)
    step = 0.1 * np.pi / (b - a)
    grid = np.arange(1, 10 * count + 40) * step
    values = f(grid)
    change = np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:]))[:count]
    assert change.size == count
    return np.array([brentq(f, grid[i], grid[i + 1], xtol=1e-14 / (b - a)) for i in change])


@dataclass(frozen=True)
class Annulus:
    """Inner radius a, outer radius b, thickness h (m), diffusivity D (m^2/s), Young's
    modulus E (Pa), Poisson ratio nu, swelling coefficient beta (per weight %), initial
    and surface moisture (weight %)."""

    a: float
    b: float
    h: float
    d: float
    e: float = 3e9
    nu: float = 0.35
    beta: float = 3e-3
    initial: float = 0.0
    surface: float = 2.0
    count: int = 400

    @cached_property
    def roots(self) -> np.ndarray:
        return hollow_roots(self.a, self.b, self.count)

    def _cylinder(self, alpha, r):
        """(U0, U1) at alpha r, shape (modes, points)."""
        x = np.outer(alpha, r)
        yb, jb = y0(self.b * alpha)[:, None], j0(self.b * alpha)[:, None]
        return j0(x) * yb - jb * y0(x), j1(x) * yb - jb * y1(x)

    def _coefficients(self, alpha):
        (_, u1), ends = self._cylinder(alpha, np.array([self.a, self.b])), np.array([self.a, self.b])
        projection = (ends * u1 / alpha[:, None]) @ np.array([-1.0, 1.0])
        norm = (ends ** 2 * u1 ** 2 / 2.0) @ np.array([-1.0, 1.0])
        return projection / norm

    def cylinder(self, r, t) -> tuple[np.ndarray, np.ndarray]:
        """(U_c(r), int_a^r U_c r' dr') at time t (s), for radii r (m)."""
        alpha = self.roots
        weight = self._coefficients(alpha) * np.exp(-self.d * alpha ** 2 * t)
        u0, u1 = self._cylinder(alpha, np.asarray(r, float))
        (_, u1a) = self._cylinder(alpha, np.array([self.a]))
        integral = (np.asarray(r, float)[None, :] * u1 - self.a * u1a) / alpha[:, None]
        return weight @ u0, weight @ integral

    def sheet(self, z, t) -> tuple[np.ndarray, float]:
        """(U_s(z), thickness mean of U_s) at time t (s), for heights z (m)."""
        k = 2 * np.arange(self.count) + 1.0
        decay = np.exp(-(k * np.pi) ** 2 * self.d * t / self.h ** 2)
        profile = (4.0 / (k * np.pi) * decay) @ np.sin(np.outer(k, np.asarray(z, float)) * np.pi / self.h)
        return profile, float(np.sum(8.0 / (k * np.pi) ** 2 * decay))

    def moisture(self, r, z, t) -> np.ndarray:
        """M(r, z) (weight %), shape (len(r), len(z))."""
        u_c, _ = self.cylinder(r, t)
        u_s, _ = self.sheet(z, t)
        return self.surface - (self.surface - self.initial) * np.outer(u_c, u_s)

    def stresses(self, r, z, t) -> tuple[np.ndarray, np.ndarray]:
        """(sigma_r, sigma_t) (Pa), shape (len(r), len(z)), relative to the stress-free
        initial moisture (a uniform part of M leaves a free plate unstressed)."""
        r = np.asarray(r, float)
        swing = self.surface - self.initial
        u_c, integral_u = self.cylinder(np.append(r, self.b), t)
        u_s, mean_u_s = self.sheet(z, t)
        mean = swing * (1.0 - u_c[:-1] * mean_u_s)                    # M(r) - M0, thickness mean
        integral = swing * (0.5 * (np.append(r, self.b) ** 2 - self.a ** 2)
                            - integral_u * mean_u_s)                     # int_a^r (M - M0) r dr
        whole = integral[-1] / (self.b ** 2 - self.a ** 2)
        eb = self.e * self.beta
        radial = eb / r ** 2 * ((r ** 2 - self.a ** 2) * whole - integral[:-1])
        hoop = eb / r ** 2 * ((r ** 2 + self.a ** 2) * whole + integral[:-1]) - eb * mean
        local = swing * (1.0 - np.outer(u_c[:-1], u_s))
        through = -eb / (1.0 - self.nu) * (local - mean[:, None])
        return radial[:, None] + through, hoop[:, None] + through

    def extremes(self, t, points: int = 4001) -> tuple[float, float]:
        """(largest tensile, largest compressive) principal stress (Pa) over the annulus:
        radii graded towards both surfaces (Chebyshev points), the faces and the
        mid-plane (M is monotone in z between them, so the extremes lie there)."""
        r = self.a + (self.b - self.a) * 0.5 * (1.0 - np.cos(np.linspace(0.0, np.pi, points)))
        radial, hoop = self.stresses(r, np.array([0.0, 0.5 * self.h]), t)
        both = np.stack([radial, hoop])
        return float(both.max()), float(both.min())
