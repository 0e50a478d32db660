"""The exact short-time expansion of a planform's unit-step uptake (``ShortTime``), its
error indicator, and the sheet fraction it is weighted by (the plane model's product)."""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.special import erf, erfc

from ..exact.series import cylinder_short_coefficients, ierfc, sheet_uptake
from ..problem.cache import RunCache, run_cache
from ..problem.scaling import planar_scale
from .polygon import (CORNER_TURN, first_exits, loop_length, resample_loop, turning_angles,
                      vertex_normals)

TAIL_FROM = 4          # first term of the disc series left to the error indicator
CHORD_RAYS = 256       # rays cast per outline loop for the facing-edge term


@dataclass(frozen=True)
class ShortTime:
    """Short-time expansion of the planform's unit-step uptake, scaled coordinates.

    For a plane region with piecewise smooth boundary, Dirichlet data 1, initial
    value 0 and unit diffusivity, the uptake fraction is
    F(t) = [2 P sqrt(t/pi) - (sum_i c(gamma_i)) t + (b_2/2) K_2 t^(3/2)
    + (b_3/2) K_3 t^2] / A + ...
    (Carslaw & Jaeger 1959 §13.3 / Crank 1975 eq. 5.24 for the disc,
    4 sqrt(t/pi) - t - t^(3/2)/(3 sqrt(pi)); van den Berg & Srisatkunarajah 1990
    for the corner term c(gamma) of a polygon vertex of interior angle gamma; a
    smooth arc is the limit of vertices of small turning e, c = e/2, giving (1/2)
    integral of curvature). The t^(k+1)/2 coefficient of a smooth boundary is an
    integral of local invariants (van den Berg & Gilkey 1994, J. Funct. Anal. 120,
    48-71); for k <= 3 the only one of the right dimension is K_k = integral kappa^k ds
    (kappa signed: negative round a hole; kappa_ss integrates to 0), so the disc's
    coefficients b_k (Crank eq. 5.24 continued, ``exact._cylinder_short_coefficients``)
    fix it: (b_k / 2) K_k. From k = 4 on, kappa_s enters too. The error indicator is
    the disc's tail sum_{k=4..8} |b_k| integral |kappa|^k ds t^(k+1)/2 (the exact tail of
    a circle or annulus) with a geometric remainder that turns infinite where the terms
    stop falling, kappa t^(3/2) per corner (curved sides at a corner), and the edge facing
    each point across the part (``facing_edges``); on annuli it is at least twice the
    error wherever the outlines' own 1e-5 allows to tell. The layer of depth delta under the
    contact edge follows the half-space solution erfc(x / 2 sqrt t) (Crank 1975 eq. 2.45)
    with first-order curvature terms, averaged over the depth; its indicator is the
    second-order size kappa^2 delta (sqrt t + delta) / 2 (3-13x the error measured on
    discs).

    All lengths are scaled (physical x sqrt(D_z / D_i) / thickness) and so dimensionless.

    Parameters
    ----------
    area : float
        A, the planform's scaled area [-].
    perimeter : float
        P, its scaled perimeter [-].
    corner_sum : float
        sum_i c(gamma_i) over corners and smooth turning [-].
    curvature_square : float
        K_2 = integral kappa^2 ds over smooth arcs [-].
    curvature_cube : float
        K_3 = integral kappa^3 ds (signed) over smooth arcs [-].
    curvature_moments : numpy.ndarray
        integral |kappa|^k ds over smooth arcs, k = 0..8 [-].
    corner_curvature : float
        The sum over corners of the adjacent |kappa| [-].
    max_curvature : float
        The largest |kappa| of the outline [-].
    contact_weights : numpy.ndarray
        The contact segments' edge-length weights [-], summing to 1.
    contact_depths : numpy.ndarray
        The scaled layer depth along each contact segment [-].
    contact_curvature : numpy.ndarray
        The scaled curvature of each contact segment [-].
    contact_kappa_square : float
        The layer-weighted mean of kappa^2 over the contact edge [-].
    chords : numpy.ndarray
        The inward normals' lengths inside the part (``inward_chords``) [-].
    chord_lengths : numpy.ndarray
        The outline length each chord stands for [-].

    References
    ----------
    - Carslaw & Jaeger (1959) §13.3; Crank (1975) eqs. 2.45 and 5.24 (see ``exact.separable``).
    - M. van den Berg and S. Srisatkunarajah, "Heat flow and Brownian motion for a region
      in R^2 with a polygonal boundary", *Probability Theory and Related Fields* 86(1),
      41-52, 1990.
    - M. van den Berg and P. B. Gilkey, "Heat content asymptotics of a Riemannian manifold
      with boundary", *Journal of Functional Analysis* 120, 48-71, 1994.
    """

    area: float
    perimeter: float
    corner_sum: float
    curvature_square: float       # K_2 over smooth arcs
    curvature_cube: float         # K_3 = integral kappa^3 ds (signed) over smooth arcs
    curvature_moments: np.ndarray  # integral |kappa|^k ds over smooth arcs, k = 0..8
    corner_curvature: float       # sum over corners of the adjacent |kappa|
    max_curvature: float
    contact_weights: np.ndarray   # (k,) edge-length weights, sum 1
    contact_depths: np.ndarray    # (k,) scaled layer depth along each contact segment
    contact_curvature: np.ndarray  # (k,) scaled curvature of each contact segment
    contact_kappa_square: float   # layer-weighted mean of kappa^2 over the contact edge
    chords: np.ndarray            # (r,) length of inward normals inside the part (``inward_chords``)
    chord_lengths: np.ndarray     # (r,) outline length each chord stands for

    def uptake(self, tau):
        tau = np.asarray(tau, float)
        b = _disc_coefficients()
        return (2 * self.perimeter * np.sqrt(tau / np.pi) - self.corner_sum * tau
                + 0.5 * b[2] * self.curvature_square * tau ** 1.5
                + 0.5 * b[3] * self.curvature_cube * tau ** 2) / self.area

    def uptake_error(self, tau):
        tau = np.asarray(tau, float)
        b = _disc_coefficients()
        terms = [abs(b[k]) * self.curvature_moments[k] * tau ** (0.5 * (k + 1))
                 for k in range(TAIL_FROM, b.size)]
        return (sum(terms) + _geometric_remainder(terms[-2], terms[-1])
                + self.corner_curvature * tau ** 1.5 + self.facing_edges(tau)) / self.area

    def facing_edges(self, tau):
        """Uptake from the edge facing each part of the outline across the part, which the
        local expansion leaves out: the first image term of a sheet of the chord's width w,
        4 sqrt(t) ierfc(w / 2 sqrt t) per unit length (Crank 1975 eqs. 4.15, 4.20), doubled
        (on rings of width 0.5-1.5 it alone reached 0.99 of the error)."""
        root = np.sqrt(np.asarray(tau, float))[..., None]
        argument = self.chords / (2.0 * np.maximum(root, 1e-300))
        near = argument < 6.0  # ierfc(6) < 1e-17
        image = np.zeros(argument.shape)
        image[near] = ierfc(argument[near])
        return (8.0 * root * image) @ self.chord_lengths

    def layer_uptake(self, tau):
        """Mean over the contact layer: erfc(x / 2 sqrt t) (Crank 1975 eq. 2.45) with the
        first-order curvature terms of a cylinder, c = sqrt(a/r) erfc(...) (Carslaw &
        Jaeger 1959 §13.3) and area weight r/a, i.e. (1 - kappa x / 2) erfc over a
        layer of area (1 - kappa delta / 2) delta per unit length, integrated in closed
        form (``layer_integrals``)."""
        tau = np.atleast_1d(np.asarray(tau, float))
        depth, kappa = self.contact_depths, self.contact_curvature
        scale = 2 * np.sqrt(np.maximum(tau, 1e-300))[:, None]   # (t, 1)
        flat, first = layer_integrals(depth[None, :] / scale)
        integral = scale * flat - 0.5 * kappa[None, :] * scale ** 2 * first
        band = integral / (depth * (1 - 0.5 * kappa * depth))[None, :]
        return band @ self.contact_weights

    def layer_error(self, tau):
        tau = np.asarray(tau, float)
        depth = float(np.max(self.contact_depths))  # second order in kappa, measured on discs
        return 0.5 * self.contact_kappa_square * depth * (np.sqrt(tau) + depth)

    def switch(self, tolerance: float) -> float:
        """Largest scaled time (on a log grid, ``SWITCH_GRID``) up to which the uptake error
        indicator times the sheet's unsaturated fraction (Crank 1975 eq. 4.18) stays <=
        tolerance: the grid is read in blocks up to its first point above (the later ones,
        where every chord's facing edge counts, are not needed); kept per tolerance."""
        if tolerance not in self._switches:
            self._switches[tolerance] = _first_above(self.weighted_error_at, tolerance)
        return self._switches[tolerance]

    def weighted_error_at(self, tau) -> np.ndarray:
        """The uptake error indicator x the sheet's unsaturated fraction at scaled ``tau``."""
        return weighted(self.uptake_error(tau), sheet_fraction(tau))

    @cached_property
    def _switches(self) -> dict:
        return {}


SWITCH_GRID = np.geomspace(1e-8, 1e4, 1201)   # 100 points a decade
SWITCH_BLOCK = 100


def _first_above(error_at, tolerance: float) -> float:
    """The ``SWITCH_GRID`` point before the first where ``error_at`` exceeds ``tolerance``
    (0 at the first point, the last point where none does), read a block at a time."""
    grid = SWITCH_GRID
    for start in range(0, grid.size, SWITCH_BLOCK):
        error = error_at(grid[start:start + SWITCH_BLOCK])
        above = np.flatnonzero(~(error <= tolerance))
        if above.size:
            first = start + int(above[0])
            return float(grid[first - 1]) if first > 0 else 0.0
    return float(grid[-1])


def layer_integrals(z):
    """(int_0^z erfc(s) ds, int_0^z s erfc(s) ds), so that int_0^delta (1 - kappa x / 2)
    erfc(x / a) dx = a first - (kappa / 2) a^2 second at z = delta / a. The first is
    1/sqrt(pi) - ierfc(z) (Carslaw & Jaeger 1959 Appendix II, ierfc(z) = exp(-z^2)/sqrt(pi)
    - z erfc(z)), written z erfc(z) - expm1(-z^2)/sqrt(pi) (two positive terms, no
    cancellation for small z); the second, by parts with erfc' = -2 exp(-s^2)/sqrt(pi)
    (Abramowitz & Stegun 1964 §7.1) and int_0^z s^2 exp(-s^2) ds = sqrt(pi) erf(z)/4
    - z exp(-z^2)/2, is z^2 erfc(z)/2 + erf(z)/4 - z exp(-z^2)/(2 sqrt(pi)). Exact where
    the 12-point Gauss rule they replace was not (sqrt(t) << delta: a steep erfc).

    Parameters
    ----------
    z : array_like
        The upper limit delta / (2 sqrt t) [-] (held at 40, where erfc is 0).

    Returns
    -------
    first : numpy.ndarray
        int_0^z erfc(s) ds [-].
    second : numpy.ndarray
        int_0^z s erfc(s) ds [-].

    References
    ----------
    M. Abramowitz and I. A. Stegun, *Handbook of Mathematical Functions*, National Bureau
    of Standards, 1964, §7.1; Carslaw & Jaeger (1959), Appendix II.
    """
    z = np.minimum(np.asarray(z, float), 40.0)  # erfc(40) = 0: both integrals are complete
    tail = erfc(z)
    first = z * tail - np.expm1(-z * z) / np.sqrt(np.pi)
    second = 0.5 * z * z * tail + 0.25 * erf(z) - z * np.exp(-z * z) / (2 * np.sqrt(np.pi))
    return first, second


def _geometric_remainder(before, last):
    """Terms after ``last`` bounded by a geometric series of the ratio r = last / before:
    last r / (1 - r); infinite once the terms stop falling (the asymptotic series has
    left its useful range). On annuli this kept the indicator above the true error
    (it was 1.4x below it without)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(before > 0, last / before, 0.0)
        return np.where(ratio < 1.0, last * ratio / (1.0 - ratio), np.inf)


def _disc_coefficients() -> np.ndarray:
    return cylinder_short_coefficients()


def corner_coefficient(gamma: np.ndarray) -> np.ndarray:
    """c(gamma) = integral_0^inf 4 sinh((pi - gamma) x) / (sinh(pi x) cosh(gamma x)) dx
    (van den Berg & Srisatkunarajah 1990; c(pi/2) = 4/pi reproduces the product of
    two half-spaces, Crank 1975 eq. 4.51), by the trapezoidal rule on [0, 60/pi].

    Parameters
    ----------
    gamma : numpy.ndarray
        The corners' interior angles [rad], in (0, 2 pi).

    Returns
    -------
    numpy.ndarray
        c(gamma) [-], the corner's coefficient of -t in the uptake times A.

    References
    ----------
    van den Berg & Srisatkunarajah (1990), see ``ShortTime``.
    """
    gamma = np.asarray(gamma, float)[:, None]
    x = np.linspace(1e-9, 60 / np.pi, 6001)[None, :]
    integrand = 4 * np.sinh((np.pi - gamma) * x) / (np.sinh(np.pi * x) * np.cosh(gamma * x))
    return np.trapezoid(integrand, x, axis=1)


def expansion_of(part, d, layer_depth: float | None = None,
                 cache: RunCache | None = None) -> ShortTime | None:
    """The outline's short-time expansion in scaled coordinates as plan and solve both see it
    (circles sampled at thickness / 20 or finer); None when the outline has none. Made once
    per run (``cache``; None: a fresh one): plan and solve of one part share it, and so do
    the cases of a sweep worker whose diffusivities scale the outline alike (it reads ``d``
    only through ``planar_scale``: equal ratios D_z / D_x, D_z / D_y, e.g. an isotropic
    part whatever its D0, give the same expansion).

    Parameters
    ----------
    part : CamPlate or LinkBar
        The prismatic part, its lengths in [m].
    d : tuple of float
        D0 along x, y, z [m^2/s].
    layer_depth : float, optional
        The contact layer's depth [m]; None: thickness / 100.
    cache : RunCache, optional
        The run's cache.

    Returns
    -------
    ShortTime or None
        The expansion; None when the outline has none (overlapping bosses, or no contact layer).
    """
    cache = run_cache(cache)
    depth = part.thickness / 100 if layer_depth is None else layer_depth
    scale = tuple(float(s) for s in planar_scale(part, d))   # all of d the expansion reads
    return cache.get(("outline expansion", part, scale, depth), lambda: short_time(
        part, np.asarray(scale), depth, part.thickness / 20, cache))


def weighted(indicator, weight):
    """indicator x weight, infinite wherever the indicator is (also where the weight is 0).

    Parameters
    ----------
    indicator : array_like
        An error indicator [-] (inf: no bound).
    weight : array_like
        Its weight [-], e.g. the sheet's unsaturated fraction.

    Returns
    -------
    numpy.ndarray
        The product [-], inf where the indicator is not finite.
    """
    indicator = np.asarray(indicator, float)
    with np.errstate(invalid="ignore"):  # inf x 0
        product = indicator * weight
    return np.where(np.isfinite(indicator), product, np.inf)


def sheet_fraction(tau):
    """Unsaturated fraction of the through-thickness sheet, exact (Crank 1975 eqs. 4.18 / 4.20).

    Parameters
    ----------
    tau : array_like
        Scaled time tau* = D_z t / h^2 [-].

    Returns
    -------
    numpy.ndarray
        1 - F(tau*) [-].
    """
    return 1.0 - sheet_uptake(np.maximum(tau, 0.0))


def short_time(part, scale: np.ndarray, layer_depth: float, spacing: float,
               cache: RunCache | None = None) -> ShortTime | None:
    """The expansion's coefficients in scaled coordinates (x' = x * scale); ``cache``: the
    run's, which keeps the outline's chords for the other layer depth.

    Parameters
    ----------
    part : CamPlate or LinkBar
        The prismatic part, its lengths in [m].
    scale : numpy.ndarray
        Physical -> scaled in-plane factors sqrt(D_z / D_i) / thickness [1/m].
    layer_depth : float
        The contact layer's depth [m].
    spacing : float
        The largest gap along the outline's arcs [m].
    cache : RunCache, optional
        The run's cache.

    Returns
    -------
    ShortTime or None
        The coefficients; None without loops, with a clockwise outline or without a contact layer.
    """
    found = part.boundary_loops(spacing)
    if found is None:
        return None
    loops, contact = found
    area = perimeter = corners = curvature_square = curvature_cube = 0.0
    corner_curvature = max_curvature = 0.0
    moments = np.zeros(_disc_coefficients().size)
    weights, depths, curvatures = [], [], []
    scaled = [loop * scale[None, :] for loop in loops]
    chords, chord_lengths = outline_chords(part, tuple(float(s) for s in scale), spacing,
                                           run_cache(cache))
    for loop, p, is_contact in zip(loops, scaled, contact):
        length = np.hypot(*(np.roll(p, -1, axis=0) - p).T)
        turn = turning_angles(p)
        smooth = np.abs(turn) < CORNER_TURN
        corners += 0.5 * turn[smooth].sum() + corner_coefficient(np.pi - turn[~smooth]).sum()
        ds = 0.5 * (length + np.roll(length, 1))
        kappa = np.where(smooth, turn / ds, 0.0)
        curvature_square += np.sum(kappa ** 2 * ds)
        curvature_cube += np.sum(kappa ** 3 * ds)
        moments += np.abs(kappa)[None, :] ** np.arange(moments.size)[:, None] @ ds
        corner_curvature += np.sum(np.maximum(np.abs(np.roll(kappa, 1)),
                                              np.abs(np.roll(kappa, -1)))[~smooth])
        max_curvature = max(max_curvature, float(np.max(np.abs(kappa))))
        area += 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
        perimeter += length.sum()
        if is_contact:
            # physical normal n of each segment -> scaled strip width delta / |S^-1 n|
            physical = np.roll(loop, -1, axis=0) - loop
            normal = np.column_stack([physical[:, 1], -physical[:, 0]])
            normal /= np.hypot(*normal.T)[:, None]
            depths.append(layer_depth / np.hypot(*(normal / scale[None, :]).T))
            weights.append(length * depths[-1])
            curvatures.append(0.5 * (kappa + np.roll(kappa, -1)))
    weights = np.concatenate(weights)
    if not (area > 0 and weights.sum() > 0):  # clockwise outline or no layer: mesh only
        return None
    return ShortTime(area, perimeter, corners, curvature_square, curvature_cube, moments,
                     corner_curvature, max_curvature,
                     weights / weights.sum(), np.concatenate(depths), np.concatenate(curvatures),
                     float(np.concatenate(curvatures) ** 2 @ (weights / weights.sum())),
                     chords, chord_lengths)


def outline_chords(part, scale: tuple[float, float], spacing: float, cache: RunCache):
    """``inward_chords`` of the part's outline (its ``boundary_loops`` at ``spacing``) scaled by
    ``scale``, once per run (``cache``): plan and solve ask for the expansion at two layer
    depths, which leave the chords alone (half the expansion's cost). Read-only arrays.

    Parameters
    ----------
    part : CamPlate or LinkBar
        The prismatic part, its lengths in [m].
    scale : tuple of float
        Physical -> scaled in-plane factors [1/m].
    spacing : float
        The outline's sampling [m].
    cache : RunCache
        The run's cache.

    Returns
    -------
    tuple of numpy.ndarray
        The chords and the outline length each stands for, scaled [-].
    """
    def build():
        loops, _ = part.boundary_loops(spacing)
        factor = np.asarray(scale)
        return inward_chords([loop * factor[None, :] for loop in loops],
                             0.25 * spacing * float(np.max(factor)))
    return cache.get(("outline chords", part, scale, spacing), build)


def inward_chords(loops: list[np.ndarray], spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """(chord, outline length it stands for) at ``CHORD_RAYS`` points evenly spaced along
    each closed polyline of ``loops`` (material on the left): the length of the inward
    normal ray inside the outline, up to its first exit through any loop
    (``polygon.first_exits``, exact); a ray that never leaves (an open outline) gets
    4 times the outline's extent.

    Parameters
    ----------
    loops : list of numpy.ndarray
        Closed polylines, material on the left, scaled [-].
    spacing : float
        The outline's sampling, scaled [-]: crossings within 1e-6 of it are the ray's start.

    Returns
    -------
    chords : numpy.ndarray
        The inward chords' lengths [-].
    lengths : numpy.ndarray
        The outline length each stands for [-].
    """
    rays = [resample_loop(loop, loop_length(loop) / CHORD_RAYS) for loop in loops]
    start = np.vstack(rays)
    lengths = np.concatenate([np.full(len(ray), loop_length(loop) / len(ray))
                              for ray, loop in zip(rays, loops)])
    chords = first_exits(start, np.vstack([vertex_normals(ray) for ray in rays]), loops,
                         1e-6 * spacing)
    far = 4.0 * float(np.max(np.ptp(np.vstack(loops), axis=0)))
    return np.where(np.isfinite(chords), chords, far), lengths
