"""Four-bar angular velocities and accelerations in closed form, and the motion of
the links' centres of mass (Norton, Design of Machinery 5th ed., ch. 6 and 7).

Inputs are the positions theta2..4 (rad) on one branch and the crank's angular
velocity omega2 (rad/s) and acceleration alpha2 (rad/s^2): true time derivatives.
"""
from __future__ import annotations

import numpy as np


def angular_velocities(a, b, c, theta2, theta3, theta4, omega2):
    """(omega3, omega4) in rad/s, Norton ch. 6:
    omega3 = a omega2 sin(t4 - t2) / (b sin(t3 - t4)),
    omega4 = a omega2 sin(t2 - t3) / (c sin(t4 - t3)).

    Parameters
    ----------
    a, b, c : float
        Crank, coupler and rocker lengths [m].
    theta2, theta3, theta4 : array_like
        Crank, coupler and rocker angles [rad] on one branch.
    omega2 : float or array_like
        The crank's angular velocity [rad/s].

    Returns
    -------
    tuple of numpy.ndarray
        (omega3, omega4) [rad/s].

    References
    ----------
    Norton (2012), ch. 6; in full in :mod:`fickcam.linkage`.
    """
    omega3 = a * omega2 * np.sin(theta4 - theta2) / (b * np.sin(theta3 - theta4))
    omega4 = a * omega2 * np.sin(theta2 - theta3) / (c * np.sin(theta4 - theta3))
    return omega3, omega4


def angular_accelerations(a, b, c, theta2, theta3, theta4, omega2, omega3, omega4, alpha2=0.0):
    """(alpha3, alpha4) in rad/s^2, Norton ch. 7:
    alpha3 = (C D - A F)/(A E - B D), alpha4 = (C E - B F)/(A E - B D) with
    A = c sin t4, B = b sin t3, D = c cos t4, E = b cos t3,
    C = a alpha2 sin t2 + a omega2^2 cos t2 + b omega3^2 cos t3 - c omega4^2 cos t4,
    F = a alpha2 cos t2 - a omega2^2 sin t2 - b omega3^2 sin t3 + c omega4^2 sin t4.

    Parameters
    ----------
    a, b, c : float
        Crank, coupler and rocker lengths [m].
    theta2, theta3, theta4 : array_like
        Crank, coupler and rocker angles [rad].
    omega2, omega3, omega4 : float or array_like
        Their angular velocities [rad/s].
    alpha2 : float or array_like
        The crank's angular acceleration [rad/s^2].

    Returns
    -------
    tuple of numpy.ndarray
        (alpha3, alpha4) [rad/s^2].
    """
    A, B = c * np.sin(theta4), b * np.sin(theta3)
    D, E = c * np.cos(theta4), b * np.cos(theta3)
    C = (a * alpha2 * np.sin(theta2) + a * omega2 ** 2 * np.cos(theta2)
         + b * omega3 ** 2 * np.cos(theta3) - c * omega4 ** 2 * np.cos(theta4))
    F = (a * alpha2 * np.cos(theta2) - a * omega2 ** 2 * np.sin(theta2)
         - b * omega3 ** 2 * np.sin(theta3) + c * omega4 ** 2 * np.sin(theta4))
    det = A * E - B * D
    return (C * D - A * F) / det, (C * E - B * F) / det


def rotating_point(r, theta, omega, alpha):
    """Position, velocity and acceleration (complex, m, m/s, m/s^2) of a point at radius
    r on a link turning at theta, omega, alpha about a fixed or moving origin:
    R = r e^{i theta}, V = i omega R (Norton ch. 6), A = (i alpha - omega^2) R (ch. 7).

    Parameters
    ----------
    r : float
        Radius of the point from the link's pivot [m].
    theta : array_like
        The link's angle [rad].
    omega : float or array_like
        Its angular velocity [rad/s].
    alpha : float or array_like
        Its angular acceleration [rad/s^2].

    Returns
    -------
    tuple of numpy.ndarray
        (R [m], V [m/s], A [m/s^2]) as x + i y, relative to the pivot.
    """
    R = r * np.exp(1j * np.asarray(theta))
    return R, 1j * omega * R, (1j * alpha - np.asarray(omega) ** 2) * R


def centre_of_mass_motion(lengths, fractions, thetas, omegas, alphas):
    """Complex position, velocity and acceleration of the centres of mass of crank,
    coupler and rocker, each at ``fraction`` of its pin-to-pin length from its first pin
    (O2, A, O4); coupler terms add the motion of A (relative-motion eqs. 6.5, 7.4).

    Parameters
    ----------
    lengths : sequence of float
        (a, b, c, d): crank, coupler, rocker and frame lengths [m].
    fractions : sequence of float
        Each link's centre of mass as a fraction of its pin-to-pin length [-].
    thetas : sequence of array_like
        (theta2, theta3, theta4) [rad].
    omegas : sequence of array_like
        (omega2, omega3, omega4) [rad/s].
    alphas : sequence of array_like
        (alpha2, alpha3, alpha4) [rad/s^2].

    Returns
    -------
    tuple of numpy.ndarray
        Positions [m], velocities [m/s] and accelerations [m/s^2] as x + i y, each of
        shape (3,) + the angles' shape (crank, coupler, rocker).
    """
    a, b, c, d = lengths
    crank_pin = rotating_point(a, thetas[0], omegas[0], alphas[0])
    g2 = rotating_point(fractions[0] * a, thetas[0], omegas[0], alphas[0])
    g3_rel = rotating_point(fractions[1] * b, thetas[1], omegas[1], alphas[1])
    g4 = rotating_point(fractions[2] * c, thetas[2], omegas[2], alphas[2])
    g3 = tuple(p + q for p, q in zip(crank_pin, g3_rel))
    g4 = (g4[0] + d, g4[1], g4[2])
    return tuple(np.stack([g2[k], g3[k], g4[k]]) for k in range(3))
