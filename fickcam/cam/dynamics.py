"""Follower kinematic relations, forces, torque, jump, Hertz stress, friction and wear.

All functions are vectorised over the cam angle; SI throughout. Sign conventions:
the cam turns counter-clockwise, the follower lifts along +y at x = offset, the
pressure angle phi is positive when the common normal leans towards -x, and the cam
pushes on the follower with Fn (-sin phi, cos phi).

The papers are cited in full in :mod:`fickcam.cam`.
"""
from __future__ import annotations

import numpy as np

STANDARD_GRAVITY = 9.80665  # m/s^2


def pressure_angle(height, dy, offset):
    """phi = atan((dy/dtheta - e)/(s0 + y)) with s0 + y the pitch-point height
    (Norton, Design of Machinery 5th ed., ch. 8).

    Parameters
    ----------
    height : float or array_like
        The pitch-point height s0 + y above the cam axis [m].
    dy : float or array_like
        The follower velocity per cam angle dy/dtheta [m/rad].
    offset : float
        The follower's offset e from the cam axis [m].

    Returns
    -------
    numpy.ndarray
        The pressure angle phi [rad].

    References
    ----------
    R. L. Norton, *Design of Machinery*, 5th ed., McGraw-Hill, 2012, ch. 8.
    """
    return np.arctan2(dy - offset, height)


def pitch_radius_of_curvature(height, dy, d2y, offset):
    """Radius of curvature of the pitch curve of a translating (offset) follower, from
    the follower motion alone (kinematic inversion; reduces to Norton ch. 8,
    rho = (R^2 + y'^2)^1.5/(R^2 + 2 y'^2 - R y''), for e = 0). Positive = convex.

    Parameters
    ----------
    height : float or array_like
        The pitch-point height s0 + y [m].
    dy : float or array_like
        dy/dtheta [m/rad].
    d2y : float or array_like
        d2y/dtheta2 [m/rad^2].
    offset : float
        The follower's offset e [m].

    Returns
    -------
    numpy.ndarray
        The pitch curve's radius of curvature [m], positive where convex.

    References
    ----------
    R. L. Norton, *Design of Machinery*, 5th ed., McGraw-Hill, 2012, ch. 8.
    """
    ax, ay = height, dy - offset
    bx, by = 2.0 * dy - offset, d2y - height
    return np.hypot(ax, ay) ** 3 / -(ax * by - ay * bx)


def flat_radius_of_curvature(height, d2y):
    """rho = Rb + y + y'' for a flat-faced follower (Norton ch. 8), height = Rb + y.

    Parameters
    ----------
    height : float or array_like
        Rb + y [m].
    d2y : float or array_like
        y'' = d2y/dtheta2 [m/rad^2].

    Returns
    -------
    numpy.ndarray
        The cam's radius of curvature under the face [m].
    """
    return height + d2y


def axial_force(mass, acceleration, spring_rate, spring_deflection, preload, external_load,
                gravity: bool):
    """Force the cam must supply along the follower axis: m a + k x + F0 + P (+ m g)
    (Newton along the axis; Norton, Design of Machinery 5th ed., ch. 15; Madhukar et al.
    2023 sec. 5.5 F_c = m y'' + s y + m g; Singh & Sanyal 2017 Table 19 adds the inertia
    term with the opposite sign, F_i = -m y'', a slip).

    Parameters
    ----------
    mass : float
        The follower train's effective mass [kg].
    acceleration : float or array_like
        The follower acceleration [m/s^2].
    spring_rate : float
        The return spring's rate [N/m].
    spring_deflection : float or array_like
        The spring's deflection from its preloaded length [m].
    preload : float
        The spring preload [N].
    external_load : float or array_like
        The external load along the axis [N].
    gravity : bool
        Add the follower's weight (a vertical follower lifting against gravity).

    Returns
    -------
    numpy.ndarray
        The axial force [N].
    """
    weight = mass * STANDARD_GRAVITY if gravity else 0.0
    return mass * acceleration + spring_rate * spring_deflection + preload + external_load + weight


def guide_friction_factor(mu, overhang, guide_length, stem_diameter):
    """G = 2 mu l1/l2 + mu - mu^2 d/l2 of a stem in a guide bush (Yadav et al. 2017
    p. 3; Rothbart, Cam Design Handbook 2004, ch. 6).

    Parameters
    ----------
    mu : float
        The stem-bush friction coefficient [-].
    overhang : float
        The stem's length l1 beyond the bush, to the contact [m].
    guide_length : float
        The bush's length l2 [m].
    stem_diameter : float
        The stem's diameter d [m].

    Returns
    -------
    float
        The guide friction factor G [-].
    """
    return 2.0 * mu * overhang / guide_length + mu - mu ** 2 * stem_diameter / guide_length


def normal_force(axial, phi, velocity, guide_factor):
    """Contact force along the common normal: Fn = F / (cos phi - s G |sin phi|), s = sign
    of the follower velocity (guide friction opposes the motion) (Yadav et al. 2017 p. 3,
    F_n = P/(cos a - G sin a) while rising).

    Parameters
    ----------
    axial : float or array_like
        The axial force F [N] (:func:`axial_force`).
    phi : float or array_like
        The pressure angle [rad].
    velocity : float or array_like
        The follower velocity (its sign matters) [m/s].
    guide_factor : float
        G [-] (:func:`guide_friction_factor`).

    Returns
    -------
    numpy.ndarray
        The normal contact force Fn [N].
    """
    return axial / (np.cos(phi) - np.sign(velocity) * guide_factor * np.abs(np.sin(phi)))


def contact_torque(contact_x, contact_y, force, phi):
    """Torque the camshaft supplies: the moment about the cam axis of the contact force
    on the follower, Fn (-sin phi, cos phi), at the contact point.

    Parameters
    ----------
    contact_x, contact_y : float or array_like
        The contact point relative to the cam axis [m].
    force : float or array_like
        The normal contact force Fn [N].
    phi : float or array_like
        The pressure angle [rad].

    Returns
    -------
    numpy.ndarray
        The camshaft torque [N m].
    """
    return contact_x * force * np.cos(phi) + contact_y * force * np.sin(phi)


def power_torque(force, phi, dy):
    """T = Fn cos(phi) dy/dtheta, from T omega = (Fn cos phi) v (power balance; Yadav et
    al. 2017 p. 3: T0 = Fn (y'/omega) cos a).

    Parameters
    ----------
    force : float or array_like
        The normal contact force Fn [N].
    phi : float or array_like
        The pressure angle [rad].
    dy : float or array_like
        dy/dtheta [m/rad].

    Returns
    -------
    numpy.ndarray
        The camshaft torque [N m].
    """
    return force * np.cos(phi) * dy


def jump_speed(mass, d2y, holding_force):
    """Smallest cam speed at which m omega^2 y''(theta) + S(theta) reaches zero somewhere
    (contact force vanishes: jump; Norton ch. 15 'follower jump'); S = spring + preload +
    load (+ weight) are speed-independent. The contact force m omega^2 y'' + S first vanishes
    where S / (-m y'') is least over y'' < 0; a follower that is not held (S < 0 somewhere,
    or S = 0 where y'' < 0) leaves the cam at any speed (0). Where S = 0 and y'' > 0 (a spring
    without preload at the lowest point) the cam's own acceleration holds the follower on.

    Parameters
    ----------
    mass : float
        The follower train's effective mass [kg].
    d2y : numpy.ndarray
        d2y/dtheta2 over the cycle [m/rad^2].
    holding_force : numpy.ndarray
        The speed-independent force S pressing the follower on the cam [N].

    Returns
    -------
    float
        The jump speed [rad/s]; inf when the follower never pulls away, 0 when it is not
        held: S < 0 somewhere, or S = 0 where y'' < 0 (S within round-off of its largest
        value counts as 0).
    """
    holding_force = np.asarray(holding_force, float)
    d2y = np.asarray(d2y, float)
    zero = 16 * np.finfo(float).eps * float(np.max(np.abs(holding_force), initial=0.0))
    pulling = d2y < 0.0
    if np.any(holding_force < -zero) or np.any(holding_force[pulling] <= zero):
        return 0.0
    if not np.any(pulling):
        return float("inf")
    return float(np.sqrt(np.min(holding_force[pulling] / (-mass * d2y[pulling]))))


def effective_modulus(e1, nu1, e2, nu2):
    """E* with 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (Johnson, Contact Mechanics 1985, eq. 4.22).

    Parameters
    ----------
    e1, e2 : float or array_like
        The Young's moduli of the two bodies [Pa].
    nu1, nu2 : float or array_like
        Their Poisson's ratios [-].

    Returns
    -------
    numpy.ndarray
        The contact modulus E* [Pa].

    References
    ----------
    K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985,
    doi:10.1017/CBO9781139171731.
    """
    return 1.0 / ((1.0 - nu1 ** 2) / e1 + (1.0 - nu2 ** 2) / e2)


def hertz_line_pressure(force, length, cam_radius, follower_radius, e_star):
    """Peak Hertz pressure of two cylinders in line contact, p0 = sqrt(F E*/(pi L R)),
    1/R = 1/rho_cam + 1/R_follower (a flat face: 1/R_follower = 0; a concave cam: rho < 0)
    (Johnson 1985 eq. 4.45; Norton, Machine Design, eq. 7.22). 0 where F <= 0, NaN where
    the curvatures give no contact ellipse (1/R <= 0).

    Parameters
    ----------
    force : float or array_like
        The contact force [N].
    length : float
        The contact length along the cylinders' axes [m].
    cam_radius : float or array_like
        The cam profile's radius of curvature [m] (negative where concave).
    follower_radius : float or None
        The roller's radius [m]; None for a flat face.
    e_star : float or array_like
        The contact modulus E* [Pa] (:func:`effective_modulus`).

    Returns
    -------
    numpy.ndarray
        The peak pressure p0 [Pa].

    References
    ----------
    K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, eq. 4.45,
    doi:10.1017/CBO9781139171731.
    """
    inverse = 1.0 / cam_radius + (0.0 if follower_radius is None else 1.0 / follower_radius)
    load = np.maximum(force, 0.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        p = np.sqrt(load * e_star * inverse / (np.pi * length))
    return np.where(inverse > 0, p, np.nan)


def hertz_line_half_width(pressure, cam_radius, follower_radius, e_star):
    """Half-width b of the line-contact strip, from p0 = E* b / (2 R) (Johnson 1985 eq. 4.43),
    with 1/R as in :func:`hertz_line_pressure`.

    Parameters
    ----------
    pressure : float or array_like
        The peak pressure p0 [Pa].
    cam_radius : float or array_like
        The cam profile's radius of curvature [m].
    follower_radius : float or None
        The roller's radius [m]; None for a flat face.
    e_star : float or array_like
        The contact modulus E* [Pa].

    Returns
    -------
    numpy.ndarray
        The half-width b [m].
    """
    inverse = 1.0 / cam_radius + (0.0 if follower_radius is None else 1.0 / follower_radius)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(inverse > 0, 2.0 * pressure / (e_star * inverse), np.nan)


#: largest principal shear stress under a Hertz line contact and its depth, as fractions of
#: p0 and of the half-width b (Johnson, Contact Mechanics, 1985, §4.2 and Fig. 4.5)
SUBSURFACE_SHEAR_RATIO = 0.30
SUBSURFACE_SHEAR_DEPTH = 0.786


def subsurface_shear(pressure, half_width):
    """(tau_max, depth) below a line contact: 0.30 p0 at z = 0.786 b (Johnson 1985 §4.2).

    Parameters
    ----------
    pressure : float or array_like
        The peak Hertz pressure p0 [Pa].
    half_width : float or array_like
        The contact half-width b [m].

    Returns
    -------
    tuple of numpy.ndarray
        The largest principal shear stress [Pa] and its depth below the surface [m].
    """
    return SUBSURFACE_SHEAR_RATIO * pressure, SUBSURFACE_SHEAR_DEPTH * half_width


def archard_wear_per_revolution(coefficient, hardness, force, length, slide_ratio):
    """Wear depth of the cam surface per revolution at each profile point (Archard: depth
    rate = K/H p v_s; integrated over one pass through a contact of load F/L per unit width,
    travelling along the cam at omega rho while sliding at v_s: h = K/H (F/L) v_s/(omega rho))
    (Archard 1953; Rothbart 2004 ch. 12).

    Parameters
    ----------
    coefficient : float
        Archard's dimensionless wear coefficient K [-].
    hardness : float
        The cam surface's hardness H [Pa].
    force : float or array_like
        The contact force [N].
    length : float
        The contact length [m].
    slide_ratio : float or array_like
        The sliding speed over the contact's travel speed along the cam,
        v_s / (omega rho) [-].

    Returns
    -------
    numpy.ndarray
        The wear depth per revolution [m].

    References
    ----------
    J. F. Archard, "Contact and rubbing of flat surfaces", *Journal of Applied Physics*
    24(8), 981-988, 1953, doi:10.1063/1.1721448.
    """
    return coefficient / hardness * np.maximum(force, 0.0) / length * slide_ratio


def empirical_wear_depth(sliding_length, pressure, hardness_1, hardness_2, mu,
                         a0=1.13e-5, a1=1.00, a2=2.69, a3=3.23):
    """Linear wear Z = l a0 (P0/H1)^a1 (H2/H1)^a2 mu^a3 (Yadav et al. 2017 p. 3
    and Table 2.1; the printed formula has mu^a1, the coefficients table and the worked
    example use a3). Units as the paper: P0 in Pa over hardness numbers, l in m.

    Parameters
    ----------
    sliding_length : float or array_like
        The sliding distance l [m].
    pressure : float or array_like
        The contact pressure P0 [Pa].
    hardness_1, hardness_2 : float
        The hardness numbers H1 and H2 of the worn surface and its counterpart (as the
        paper's fit takes them).
    mu : float
        The friction coefficient [-].
    a0, a1, a2, a3 : float
        The fit's coefficients (Yadav et al. 2017, Table 2.1).

    Returns
    -------
    numpy.ndarray
        The linear wear Z [m].
    """
    return sliding_length * a0 * (pressure / hardness_1) ** a1 * (hardness_2 / hardness_1) ** a2 \
        * mu ** a3
