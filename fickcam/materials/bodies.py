"""Volume, mass and mass moment of inertia (about the axis normal to the plane of
motion) of the moving bodies, from dimensions already scaled by their strains.

Link: a bar of ``length`` between boss centres, ``width`` x ``thickness``, with a
hollow cylindrical boss of the same thickness at each end (Singh & Sanyal 2016,
Figure 3 and Table 5). Unlike Table 5, (i) the bar's own term is m (L^2 + W^2)/12 (the
axis normal to the plane of motion, not m (W^2 + T^2)/12), (ii) each boss is carried to
the link's centre of mass by the parallel-axis term m_cyl (L/2)^2, and (iii) the bar
material lying inside the bosses is counted once, not twice. All functions are
vectorised (numpy broadcasting over the dimensions).
"""
from __future__ import annotations

import numpy as np

from .hygrothermal import wet_mass


def _strip_of_disc(radius, half_width, centre_distance):
    """Area and polar second moment, about a point ``centre_distance`` away along the bar
    axis, of the half-disc strip {0 <= u <= sqrt(R^2 - y^2), |y| <= h} (the bar inside a
    boss): A = h w + R^2 asin(h/R), J = d^2 I1 - d I2 + I3/3 + I4 with w = sqrt(R^2 - h^2)."""
    r, h, d = (np.asarray(a, float) for a in (radius, half_width, centre_distance))
    w = np.sqrt(np.clip(r ** 2 - h ** 2, 0.0, None))
    arc = np.arcsin(np.clip(h / r, -1.0, 1.0))
    i1 = h * w + r ** 2 * arc                                     # integral of w dy
    i2 = 2.0 * h * r ** 2 - 2.0 * h ** 3 / 3.0                      # integral of w^2 dy
    i3 = h * (5 * r ** 2 - 2 * h ** 2) * w / 4.0 + 3.0 * r ** 4 * arc / 4.0  # integral of w^3 dy
    i4 = h * (2 * h ** 2 - r ** 2) * w / 4.0 + r ** 4 * arc / 4.0    # integral of y^2 w dy
    return i1, d ** 2 * i1 - d * i2 + i3 / 3.0 + i4


def link_section(length, width, boss_outer_radius, boss_inner_radius):
    """(area, polar second moment about the centre) of the link outline in its plane.
    NaN where the outline is not a link (width > 2 Ro, Ri >= Ro, or bosses overlapping).

    Parameters
    ----------
    length : float or array_like
        The distance between the boss centres [m].
    width : float or array_like
        The bar's width [m].
    boss_outer_radius, boss_inner_radius : float or array_like
        The bosses' outer radius and hole radius [m].

    Returns
    -------
    tuple of numpy.ndarray
        The area [m^2] and the polar second moment about the centre [m^4].
    """
    L, W, ro, ri = (np.asarray(a, float) for a in (length, width, boss_outer_radius, boss_inner_radius))
    d = L / 2.0
    strip_area, strip_j = _strip_of_disc(ro, W / 2.0, d)
    area = L * W + 2.0 * np.pi * (ro ** 2 - ri ** 2) - 2.0 * strip_area
    polar = (L * W * (L ** 2 + W ** 2) / 12.0
             + 2.0 * np.pi * (ro ** 4 / 2.0 + ro ** 2 * d ** 2)
             - 2.0 * np.pi * (ri ** 4 / 2.0 + ri ** 2 * d ** 2)
             - 2.0 * strip_j)
    bad = (W > 2.0 * ro) | (ri >= ro) | (L < 2.0 * ro) | (ri < 0)
    return np.where(bad, np.nan, area), np.where(bad, np.nan, polar)


def link_body(length, width, thickness, boss_outer_radius, boss_inner_radius, density):
    """(volume m^3, mass kg, inertia about the centre of mass kg m^2) of a link of uniform
    ``density``: V = T A, m = rho V, I = rho T J (J = polar second moment of the outline).

    Parameters
    ----------
    length, width, boss_outer_radius, boss_inner_radius
        The outline [m], as in :func:`link_section`.
    thickness : float or array_like
        The link's thickness T [m].
    density : float or array_like
        rho [kg/m^3].

    Returns
    -------
    tuple of numpy.ndarray
        Volume [m^3], mass [kg] and inertia about the centre of mass [kg m^2].
    """
    area, polar = link_section(length, width, boss_outer_radius, boss_inner_radius)
    volume = np.asarray(thickness, float) * area
    return volume, density * volume, density * np.asarray(thickness, float) * polar


def _aged(body, dry_args, wet_args, dry_density, moisture):
    """(volume, mass, inertia) after swelling: wet dimensions from ``wet_args``, mass
    m_dry (1 + M/100) (definition of M; not wet density x wet volume as Singh & Sanyal 2016,
    Table 6),
    spread uniformly over the swollen body."""
    _, dry_mass, _ = body(*dry_args, dry_density)
    volume, _, inertia_per_density = body(*wet_args, 1.0)
    mass = wet_mass(dry_mass, moisture)
    return volume, mass, mass / volume * inertia_per_density


def _stretch(value, strain):
    return np.multiply(value, 1.0 + np.asarray(strain, float))


def aged_link_body(length, width, thickness, boss_outer_radius, boss_inner_radius, dry_density,
                   moisture, strain_axial, strain_transverse, strain_thickness):
    """Link after swelling: length scales by (1 + eps_axial), width by (1 + eps_transverse),
    thickness by (1 + eps_thickness), boss radii by the mean in-plane strain.

    Parameters
    ----------
    length, width, thickness, boss_outer_radius, boss_inner_radius
        The dry link [m], as in :func:`link_body`.
    dry_density : float
        The link's dry density [kg/m^3].
    moisture : float or array_like
        The link's mean moisture M [weight %].
    strain_axial, strain_transverse, strain_thickness : float or array_like
        The free strains along the link, across it and through its thickness [-].

    Returns
    -------
    tuple of numpy.ndarray
        The swollen link's volume [m^3], its wet mass [kg] and inertia [kg m^2].
    """
    radial = 0.5 * (np.asarray(strain_axial, float) + strain_transverse)
    dry = (length, width, thickness, boss_outer_radius, boss_inner_radius)
    wet = (_stretch(length, strain_axial), _stretch(width, strain_transverse),
           _stretch(thickness, strain_thickness), _stretch(boss_outer_radius, radial),
           _stretch(boss_inner_radius, radial))
    return _aged(link_body, dry, wet, dry_density, moisture)


def aged_disc_body(outer_radius, thickness, inner_radius, dry_density, moisture, strain_radial,
                   strain_thickness):
    """Disc or annulus after swelling (radii by the in-plane, thickness by the through-thickness
    strain).

    Parameters
    ----------
    outer_radius, thickness, inner_radius
        The dry disc [m], as in :func:`disc_body`.
    dry_density : float
        The density before moisture uptake [kg/m^3].
    moisture : float or array_like
        The mean moisture [weight %].
    strain_radial, strain_thickness : float or array_like
        The free strains in the plane and through the thickness [-].

    Returns
    -------
    tuple of numpy.ndarray
        (volume [m^3], mass [kg], inertia about the axis [kg m^2]) after swelling.
    """
    dry = (outer_radius, thickness, inner_radius)
    wet = (_stretch(outer_radius, strain_radial), _stretch(thickness, strain_thickness),
           _stretch(inner_radius, strain_radial))
    return _aged(disc_body, dry, wet, dry_density, moisture)


def aged_plate_body(profile_x, profile_y, thickness, bore_radius, dry_density, moisture,
                    strain_x, strain_y, strain_thickness):
    """Cam plate after swelling: profile x by (1 + eps_x), y by (1 + eps_y) (cam axes), bore
    by the mean in-plane strain; strains may be arrays of shape (k,) -> results (k,).

    Parameters
    ----------
    profile_x, profile_y, thickness, bore_radius
        The dry cam plate [m], as in :func:`plate_body`.
    dry_density : float
        Dry density [kg/m^3].
    moisture : float or array_like
        Mean moisture content of the plate [weight %].
    strain_x, strain_y, strain_thickness : float or array_like
        The free strains along the cam axes x, y and through the thickness [-].

    Returns
    -------
    tuple of numpy.ndarray
        Volume [m^3], mass [kg] and inertia about the cam's axis of rotation
        [kg m^2], each of shape (k,) for strains of shape (k,).
    """
    sx = np.asarray(strain_x, float)[..., None]
    sy = np.asarray(strain_y, float)[..., None]
    bore = _stretch(bore_radius, 0.5 * (np.asarray(strain_x, float) + strain_y))
    dry = (profile_x, profile_y, thickness, bore_radius)
    wet = (_stretch(profile_x, sx), _stretch(profile_y, sy), _stretch(thickness, strain_thickness),
           bore)
    return _aged(plate_body, dry, wet, dry_density, moisture)


def disc_body(outer_radius, thickness, inner_radius=0.0, density=1.0):
    """(volume, mass, inertia about the axis) of a disc or annulus: I = m (Ro^2 + Ri^2)/2.

    Parameters
    ----------
    outer_radius : float or array_like
        Ro [m].
    thickness : float or array_like
        The disc's thickness [m].
    inner_radius : float or array_like
        Ri [m]; 0 for a full disc.
    density : float
        The uniform density [kg/m^3].

    Returns
    -------
    tuple of numpy.ndarray
        Volume [m^3], mass [kg] and inertia about the disc's axis [kg m^2].
    """
    ro, ri, t = (np.asarray(a, float) for a in (outer_radius, inner_radius, thickness))
    volume = np.pi * (ro ** 2 - ri ** 2) * t
    mass = density * volume
    return volume, mass, mass * (ro ** 2 + ri ** 2) / 2.0


def polygon_section(x, y):
    """Shoelace formulas for a closed polygon (last point not repeated, counter-clockwise;
    points along the last axis, leading axes vectorised):
    (area, centroid x, centroid y, polar second moment about the origin)
    (Steger 1996, the moments of order 0, 1 and 2).

    Parameters
    ----------
    x, y : array_like
        The vertices, along the last axis [m].

    Returns
    -------
    tuple of numpy.ndarray
        Area [m^2], centroid x and y [m], polar second moment of area about the origin
        [m^4].

    References
    ----------
    Steger, C. (1996). On the calculation of arbitrary moments of polygons. Technical
    Report FGBV-96-05, Forschungsgruppe Bildverstehen, Informatik IX, Technische
    Universitaet Muenchen.
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    x, y = np.broadcast_arrays(x, y)
    xn, yn = np.roll(x, -1, axis=-1), np.roll(y, -1, axis=-1)
    cross = x * yn - xn * y
    area = cross.sum(axis=-1) / 2.0
    cx = ((x + xn) * cross).sum(axis=-1) / (6.0 * area)
    cy = ((y + yn) * cross).sum(axis=-1) / (6.0 * area)
    ixx = ((y ** 2 + y * yn + yn ** 2) * cross).sum(axis=-1) / 12.0
    iyy = ((x ** 2 + x * xn + xn ** 2) * cross).sum(axis=-1) / 12.0
    return area, cx, cy, ixx + iyy


def plate_body(profile_x, profile_y, thickness, bore_radius=0.0, density=1.0):
    """(volume, mass, inertia about the origin = the cam's axis of rotation) of a prismatic
    cam plate with a centred bore of ``bore_radius``.

    Parameters
    ----------
    profile_x, profile_y : array_like
        The outline [m], counter-clockwise about the axis of rotation, last point not
        repeated.
    thickness : float
        The plate's thickness [m].
    bore_radius : float
        The bore's radius [m].
    density : float
        The plate's uniform density [kg/m^3].

    Returns
    -------
    tuple of numpy.ndarray
        The plate's volume [m^3], mass [kg] and inertia about its axis [kg m^2].
    """
    area, _, _, polar = polygon_section(profile_x, profile_y)
    area = area - np.pi * bore_radius ** 2
    polar = polar - np.pi * bore_radius ** 4 / 2.0
    volume = thickness * area
    return volume, density * volume, density * thickness * polar
