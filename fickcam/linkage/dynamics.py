"""Kinetostatic (Newton-Euler) force analysis of the four-bar: joint forces and the
input torque, Norton, Design of Machinery 5th ed., ch. 11.

Unknowns per crank angle, x = [F12x, F12y, F32x, F32y, F43x, F43y, F14x, F14y, T12]:
F_ij is the force of link i on link j (1 = frame), so F12 acts on the crank at O2,
F32 on the crank at A, F43 on the coupler at B and F14 on the rocker at O4; T12 is the
driving torque on the crank. R_ij is the vector from the centre of mass of link j to
the joint with link i. Gravity g acts along -y (the frame line O2->O4 is +x).
"""
from __future__ import annotations

import numpy as np

STANDARD_GRAVITY = 9.80665  # m/s^2
JOINTS = ("O2", "A", "B", "O4")
JOINT_MEANING = {"O2": "frame on crank (F12)", "A": "coupler on crank (F32)",
                 "B": "rocker on coupler (F43)", "O4": "frame on rocker (F14)"}


def _cross_row(rx, ry):
    """Coefficients (of Fx, Fy) of the moment R x F = Rx Fy - Ry Fx."""
    return -ry, rx


def kinetostatics(masses, inertias, com_acceleration, alphas, pins, com_position,
                  gravity: float = 0.0, rocker_torque: float = 0.0):
    """Solve Norton ch. 11 at every crank angle (the module docstring names the
    unknowns).

    Parameters
    ----------
    masses : sequence of float
        Crank, coupler and rocker masses [kg].
    inertias : sequence of float
        Their moments of inertia about their centres of mass [kg m^2].
    com_acceleration : array_like of complex
        (3, n) accelerations of the centres of mass [m/s^2], x + i y.
    alphas : sequence of array_like
        (alpha2, alpha3, alpha4), each (n,) [rad/s^2].
    pins : sequence of array_like of complex
        Positions of O2, A, B and O4, each (n,) [m].
    com_position : array_like of complex
        (3, n) positions of the centres of mass [m].
    gravity : float
        g along -y [m/s^2]; 0 ignores gravity.
    rocker_torque : float
        External torque on the rocker [N m], counter-clockwise positive (Norton's T4).

    Returns
    -------
    tuple
        The joint forces, complex (4, n) [N] at O2, A, B and O4 (F12, F32, F43, F14), and
        the driving torque T12, (n,) [N m]; NaN where the positions are not finite.

    References
    ----------
    Norton (2012), ch. 11; in full in :mod:`fickcam.linkage`.
    """
    o2, pa, pb, o4 = pins
    g2, g3, g4 = com_position
    n = np.broadcast(o2, g2).shape[-1]
    m = np.asarray(masses, float)
    inertia = np.asarray(inertias, float)
    # equivalent loads m (a_G - g): gravity g = -g e_y
    load = m[:, None] * (np.asarray(com_acceleration) + 1j * gravity)
    r12, r32 = o2 - g2, pa - g2
    r23, r43 = pa - g3, pb - g3
    r34, r14 = pb - g4, o4 - g4
    M = np.zeros((n, 9, 9))
    rhs = np.zeros((n, 9))
    # link 2: F12 + F32 = m2 aG2;  T12 + R12 x F12 + R32 x F32 = I2 alpha2
    M[:, 0, 0] = M[:, 0, 2] = 1.0
    M[:, 1, 1] = M[:, 1, 3] = 1.0
    M[:, 2, 0], M[:, 2, 1] = _cross_row(r12.real, r12.imag)
    M[:, 2, 2], M[:, 2, 3] = _cross_row(r32.real, r32.imag)
    M[:, 2, 8] = 1.0
    # link 3: F43 - F32 = m3 aG3;  R43 x F43 - R23 x F32 = I3 alpha3
    M[:, 3, 4], M[:, 3, 2] = 1.0, -1.0
    M[:, 4, 5], M[:, 4, 3] = 1.0, -1.0
    M[:, 5, 4], M[:, 5, 5] = _cross_row(r43.real, r43.imag)
    cx, cy = _cross_row(r23.real, r23.imag)
    M[:, 5, 2], M[:, 5, 3] = -cx, -cy
    # link 4: F14 - F43 = m4 aG4;  R14 x F14 - R34 x F43 + T4 = I4 alpha4
    M[:, 6, 6], M[:, 6, 4] = 1.0, -1.0
    M[:, 7, 7], M[:, 7, 5] = 1.0, -1.0
    M[:, 8, 6], M[:, 8, 7] = _cross_row(r14.real, r14.imag)
    cx, cy = _cross_row(r34.real, r34.imag)
    M[:, 8, 4], M[:, 8, 5] = -cx, -cy
    rhs[:, 0], rhs[:, 1] = load[0].real, load[0].imag
    rhs[:, 2] = inertia[0] * alphas[0]
    rhs[:, 3], rhs[:, 4] = load[1].real, load[1].imag
    rhs[:, 5] = inertia[1] * alphas[1]
    rhs[:, 6], rhs[:, 7] = load[2].real, load[2].imag
    rhs[:, 8] = inertia[2] * alphas[2] - rocker_torque
    ok = np.isfinite(M).all(axis=(1, 2)) & np.isfinite(rhs).all(axis=1)
    x = np.full((n, 9), np.nan)
    if ok.any():
        x[ok] = np.linalg.solve(M[ok], rhs[ok][..., None])[..., 0]
    forces = np.stack([x[:, 0] + 1j * x[:, 1], x[:, 2] + 1j * x[:, 3],
                       x[:, 4] + 1j * x[:, 5], x[:, 6] + 1j * x[:, 7]])
    return forces, x[:, 8]


def kinetic_energy(masses, inertias, com_velocity, omegas):
    """KE = sum_j (m_j |v_Gj|^2 + I_Gj omega_j^2) / 2 over crank, coupler, rocker.

    Parameters
    ----------
    masses, inertias : sequence of float
        As in :func:`kinetostatics`: masses [kg], inertias [kg m^2].
    com_velocity : array_like of complex
        (3, n) velocities of the centres of mass [m/s].
    omegas : sequence of array_like
        (omega2, omega3, omega4) [rad/s].

    Returns
    -------
    numpy.ndarray
        The kinetic energy at each crank angle [J].
    """
    m = np.asarray(masses, float)[:, None]
    inertia = np.asarray(inertias, float)[:, None]
    return 0.5 * np.sum(m * np.abs(com_velocity) ** 2 + inertia * np.asarray(omegas) ** 2, axis=0)


def rms(values):
    """Root mean square over the finite samples (uniform crank-angle grid).

    Parameters
    ----------
    values : array_like
        Samples [any unit], NaN where undefined.

    Returns
    -------
    float
        Their RMS [the samples' unit]; NaN when none is finite.
    """
    values = np.asarray(values, float)
    return float(np.sqrt(np.nanmean(values ** 2))) if np.isfinite(values).any() else float("nan")
