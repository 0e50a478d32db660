"""Exact (series) solutions of Fick's second law for parts whose shape
separates: the sheet, the solid finite cylinder (a ``Disc`` without bore) and
the rectangular bar, each with constant diffusivities and a unit step of the
surface concentration at time zero.

Conventions
-----------
* Dimensionless positions: ``sheet_profile`` takes z/h in [0, 1];
  ``cylinder_profile`` takes r/a in [0, 1].
* Fourier numbers: sheet t* = D t / h^2 (h = full thickness, both faces
  exposed); cylinder t* = D t / a^2 (a = radius).
* Rescaled time ``tau`` (s): tau = integral of exp(-Ea / (R T(t))) dt, so that
  D0_i * tau (m^2) is the diffusion "exposure" along axis i.
* Contact (surface) layer of depth d:
  - Sheet: the two face layers 0 <= z <= d and h - d <= z <= h.
  - Disc: the rim layer a - d <= r <= a over the full thickness.
  - Bar: the shell of points closer than d to any of the six faces (the bar
    minus the inner box shrunk by d on every side).
  When the layer covers the whole part its mean is the part mean.

Every fraction here is (C - C0) / (Cs - C0): 0 before the step, 1 at
saturation. The unaccomplished fraction 1 - F of a product region multiplies
(Crank 1975 §5.3 / Carslaw & Jaeger 1959 §1.16, product solutions), pointwise
and for means over product sub-regions.

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
- Carslaw, H. S. & Jaeger, J. C. (1959). Conduction of Heat in Solids, 2nd ed. Oxford:
  Clarendon Press.
"""
from __future__ import annotations

import numpy as np

from ..problem.geometry import LAYER_DEPTH
from .series import (cylinder_core_mean, cylinder_profile, cylinder_uptake, sheet_interval_mean,
                     sheet_profile, sheet_uptake)


# -------------------------------------------------------- geometry responses
def exact_available(geometry) -> bool:
    """True when ``step_response`` / ``exact_history`` have an exact solution:
    Sheet, Bar, and Disc without bore.

    Parameters
    ----------
    geometry : Sheet, Disc, Bar, CamPlate or LinkBar
        The part, its lengths in [m].

    Returns
    -------
    bool
        True for a Sheet, a Bar or a Disc whose inner radius is 0.
    """
    return geometry.exact_route is not None


def _sheet_layer_mean(fourier, depth_fraction):
    """Mean over the two face layers of relative depth d/h (1 - core)."""
    if depth_fraction >= 0.5:
        return sheet_uptake(fourier)
    core = 1.0 - 2.0 * depth_fraction
    core_mean = sheet_interval_mean(depth_fraction, 1.0 - depth_fraction, fourier)
    return (sheet_uptake(fourier) - core * core_mean) / (1.0 - core)


def _box_sides(geometry):
    """(lengths, axis indices) of the sheets whose product is the part."""
    if geometry.exact_route == "sheet":
        return (geometry.thickness,), (2,)
    return (geometry.length, geometry.width, geometry.thickness), (0, 1, 2)


def _box_response(geometry, pre_exponential, tau, depth):
    """Mean and shell-layer mean of a sheet or a bar (product of sheets)."""
    lengths, axes = _box_sides(geometry)
    whole, core, core_volume = 1.0, 1.0, 1.0
    for length, axis in zip(lengths, axes):
        fourier = pre_exponential[axis] * tau / length ** 2
        whole = whole * (1.0 - sheet_uptake(fourier))
        fraction = min(depth / length, 0.5)
        core_volume *= 1.0 - 2.0 * fraction
        if fraction < 0.5:
            core = core * (1.0 - sheet_interval_mean(fraction, 1.0 - fraction, fourier))
    mean = 1.0 - whole
    if geometry.exact_route == "sheet":
        layer = _sheet_layer_mean(pre_exponential[2] * tau / lengths[0] ** 2, min(depth / lengths[0], 0.5))
    elif core_volume <= 0.0:
        layer = mean
    else:
        layer = (mean - core_volume * (1.0 - core)) / (1.0 - core_volume)
    return mean, layer


def _disc_response(disc, pre_exponential, tau, depth):
    """Finite solid cylinder = infinite cylinder (radial D) x sheet (axial D)."""
    radial = pre_exponential[0] * tau / disc.outer_radius ** 2
    axial = sheet_uptake(pre_exponential[2] * tau / disc.thickness ** 2)
    cylinder = cylinder_uptake(radial)
    rho = 1.0 - depth / disc.outer_radius
    if rho <= 0.0:
        rim = cylinder
    else:
        rim = (cylinder - rho ** 2 * cylinder_core_mean(rho, radial)) / (1.0 - rho ** 2)
    mean = 1.0 - (1.0 - cylinder) * (1.0 - axial)
    layer = 1.0 - (1.0 - rim) * (1.0 - axial)
    return mean, layer


def _check_exact(geometry, pre_exponential):
    if not exact_available(geometry):
        raise ValueError(f"no exact solution for {type(geometry).__name__}")
    if geometry.exact_route == "disc" and pre_exponential[0] != pre_exponential[1]:
        raise ValueError("a Disc needs equal radial diffusivities Dx = Dy")


def step_response(geometry, pre_exponential, tau, surface_layer_depth=LAYER_DEPTH):
    """Unit-step response (fraction mean uptake, fraction mean over the contact
    layer) at rescaled times ``tau`` (s; D0_i tau in m^2). Products per
    Crank 1975 §5.3 (1 - F multiplies). See the module docstring for the
    layer definitions.

    Parameters
    ----------
    geometry : Sheet, Bar or Disc
        The part (a Disc without bore), its lengths in [m].
    pre_exponential : sequence of float
        D0 along x, y, z [m^2/s] (a Disc: x = y radial, z axial).
    tau : array_like
        Rescaled times [s] (D0_i tau in [m^2]).
    surface_layer_depth : float
        The contact layer's depth [m].

    Returns
    -------
    mean, layer : numpy.ndarray
        The fractional uptake (C - C0) / (Cs - C0) of the volume and of the contact layer
        [-], each clipped to [0, 1], shaped like ``tau``.

    Raises
    ------
    ValueError
        When the part has no exact solution, or a Disc's Dx and Dy differ.

    References
    ----------
    Crank (1975) §5.3; Carslaw & Jaeger (1959) §1.16 (see the module docstring).
    """
    _check_exact(geometry, pre_exponential)
    tau = np.maximum(np.asarray(tau, float), 0.0)
    if geometry.exact_route == "disc":
        mean, layer = _disc_response(geometry, pre_exponential, tau, surface_layer_depth)
    else:
        mean, layer = _box_response(geometry, pre_exponential, tau, surface_layer_depth)
    return np.clip(mean, 0.0, 1.0), np.clip(layer, 0.0, 1.0)


def _point_coordinates(geometry, points):
    """``points``: dict name -> (n,) m. Sheet: 'z'; Bar: 'x', 'y', 'z' from a
    corner; Disc: 'r' (from the axis) and 'z' (from a face)."""
    return {name: np.asarray(value, float) for name, value in points.items()}


def step_field(geometry, pre_exponential, tau, points):
    """Fractional concentration, shape (n_tau, n_points), at ``points``
    (dict of coordinate arrays, see ``_point_coordinates``).

    Parameters
    ----------
    geometry : Sheet, Bar or Disc
        A Sheet, a Bar or a solid Disc; lengths [m].
    pre_exponential : sequence of float
        The pre-exponential diffusivities per axis [m^2/s]; a Disc's x and y are
        its radial D0 and must agree.
    tau : array_like
        Rescaled times [s], shape (n_tau,).
    points : dict of str to numpy.ndarray
        Coordinates [m]: Sheet ``z``; Bar ``x``, ``y``, ``z`` from a corner; Disc ``r``
        from the axis and ``z`` from a face.

    Returns
    -------
    numpy.ndarray
        The fraction (C - C0) / (Cs - C0) [-], shape (n_tau, n_points).

    Raises
    ------
    ValueError
        For a part without a product solution (an annulus, a prism) or a Disc with
        Dx != Dy.
    """
    _check_exact(geometry, pre_exponential)
    tau = np.maximum(np.asarray(tau, float), 0.0)[:, None]
    p = _point_coordinates(geometry, points)
    if geometry.exact_route == "disc":
        radial = cylinder_profile(p["r"][None, :] / geometry.outer_radius,
                                  pre_exponential[0] * tau / geometry.outer_radius ** 2)
        axial = sheet_profile(p["z"][None, :] / geometry.thickness,
                              pre_exponential[2] * tau / geometry.thickness ** 2)
        return 1.0 - (1.0 - radial) * (1.0 - axial)
    lengths, axes = _box_sides(geometry)
    deficit = 1.0
    for length, axis in zip(lengths, axes):
        name = "xyz"[axis]
        deficit = deficit * (1.0 - sheet_profile(p[name][None, :] / length,
                                                 pre_exponential[axis] * tau / length ** 2))
    return 1.0 - deficit


def saturation_tau(geometry, pre_exponential) -> tuple[float, float]:
    """(fastest, slowest) rescaled diffusion times L^2/D0 of the part's
    directions; beyond SATURATION_FOURIER x slowest every response is 1.

    Parameters
    ----------
    geometry : Sheet, Bar or Disc
        The part (Sheet, Bar or Disc), lengths in [m].
    pre_exponential : sequence of float
        D0 per axis x, y, z [m^2/s].

    Returns
    -------
    tuple of float
        The shortest and longest L^2 / D0 over the part's directions [s] of rescaled time.
    """
    if geometry.exact_route == "disc":
        scales = [geometry.outer_radius ** 2 / pre_exponential[0],
                  geometry.thickness ** 2 / pre_exponential[2]]
    else:
        lengths, axes = _box_sides(geometry)
        scales = [length ** 2 / pre_exponential[axis] for length, axis in zip(lengths, axes)]
    return min(scales), max(scales)
