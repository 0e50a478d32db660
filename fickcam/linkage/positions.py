"""Four-bar positions in closed form (Freudenstein 1955, as in Norton, Design of
Machinery 5th ed., sec. 4.5, eqs. 4.8-4.13; Singh & Sanyal 2016 eqs. 15-18).

Notation (Norton): a = crank (link 2, pivot O2 at the origin), b = coupler (3),
c = rocker (4, pivot O4 at (d, 0)), d = frame (1). Angles are measured
counter-clockwise from the frame line O2->O4: theta2 (crank), theta3 (coupler,
line A->B), theta4 (rocker, line O4->B).

Assembly convention (fixed): ``open`` is the root with the minus sign in Norton
eqs. 4.10b and 4.13 (Norton's open circuit); geometrically the coupler-rocker
triangle is counter-clockwise, 0 < theta4 - theta3 < pi, i.e. B lies to the left of
the diagonal A->O4. ``crossed`` is the plus sign, its mirror image across A->O4.
This sign is kept over the whole crank revolution (a branch never switches), so
the angles are continuous wherever the linkage assembles. Where it cannot
(negative discriminant), every output is NaN.

The paper is cited in full in :mod:`fickcam.linkage`.
"""
from __future__ import annotations

import numpy as np

BRANCH = {"open": 1.0, "crossed": -1.0}


def _half_angle_root(p, q, r, sigma):
    """The angle 2 atan(t) of the root t = (-q - sigma sqrt(q^2 - 4 p r)) / (2 p) of
    p t^2 + q t + r = 0, computed without cancellation (the equivalent form
    t = 2 r / (-q + sigma sqrt(...))): of the two (numerator, denominator) pairs the one
    with the larger norm is used, so that neither cancellation nor 0/0 at a toggle spoils
    the angle (t = infinity gives pi). NaN where the discriminant is negative (no assembly)."""
    disc = q * q - 4.0 * p * r
    scale = q * q + 4.0 * np.abs(p * r)
    disc = np.where((disc < 0) & (disc > -1e-13 * scale), 0.0, disc)  # round-off at a toggle
    with np.errstate(invalid="ignore"):
        root = np.sqrt(disc)
    n1, d1 = -q - sigma * root, 2.0 * p
    n2, d2 = 2.0 * r, -q + sigma * root
    second = np.hypot(n2, d2) > np.hypot(n1, d1)
    return 2.0 * np.arctan2(np.where(second, n2, n1), np.where(second, d2, d1))


def rocker_angle(a, b, c, d, theta2, assembly="open"):
    """theta4 (rad), Norton ch. 4 (Freudenstein):
    K1 = d/a, K2 = d/c, K3 = (a^2 - b^2 + c^2 + d^2)/(2 a c);
    A = cos t2 - K1 - K2 cos t2 + K3, B = -2 sin t2, C = K1 - (K2 + 1) cos t2 + K3;
    theta4 = 2 atan[(-B -/+ sqrt(B^2 - 4 A C)) / (2 A)] (minus: open).

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and frame lengths [m] (any one length unit).
    theta2 : array_like
        Crank angles [rad].
    assembly : {"open", "crossed"}
        The branch (see the module docstring).

    Returns
    -------
    numpy.ndarray
        theta4 [rad]; NaN where the linkage does not assemble.

    References
    ----------
    Norton (2012), ch. 4, and Freudenstein (1955); in full in :mod:`fickcam.linkage`.
    """
    theta2 = np.asarray(theta2, float)
    k1, k2, k3 = d / a, d / c, (a * a - b * b + c * c + d * d) / (2.0 * a * c)
    cos2 = np.cos(theta2)
    A = cos2 - k1 - k2 * cos2 + k3
    B = -2.0 * np.sin(theta2)
    C = k1 - (k2 + 1.0) * cos2 + k3
    return _half_angle_root(A, B, C, BRANCH[assembly])


def coupler_angle(a, b, c, d, theta2, assembly="open"):
    """theta3 (rad), Norton ch. 4 (Freudenstein): K4 = d/b,
    K5 = (c^2 - d^2 - a^2 - b^2)/(2 a b); D = cos t2 - K1 + K4 cos t2 + K5,
    E = -2 sin t2, F = K1 + (K4 - 1) cos t2 + K5;
    theta3 = 2 atan[(-E -/+ sqrt(E^2 - 4 D F)) / (2 D)] (minus: open).

    Parameters
    ----------
    a, b, c, d, theta2, assembly
        As in :func:`rocker_angle`: lengths [m], crank angles [rad], branch.

    Returns
    -------
    numpy.ndarray
        theta3 [rad]; NaN where the linkage does not assemble.
    """
    theta2 = np.asarray(theta2, float)
    k1, k4, k5 = d / a, d / b, (c * c - d * d - a * a - b * b) / (2.0 * a * b)
    cos2 = np.cos(theta2)
    D = cos2 - k1 + k4 * cos2 + k5
    E = -2.0 * np.sin(theta2)
    F = k1 + (k4 - 1.0) * cos2 + k5
    return _half_angle_root(D, E, F, BRANCH[assembly])


def positions(a, b, c, d, theta2, assembly="open"):
    """(theta3, theta4) in rad on the ``assembly`` branch, both NaN where either equation
    finds no assembly (Norton ch. 4), and where the crank pin A falls on
    the rocker pivot O4 (a = d at theta2 = 0: B is undetermined).

    Parameters
    ----------
    a, b, c, d : float
        Link lengths [m], in the order of :func:`rocker_angle`.
    theta2 : array_like
        Crank angles [rad].
    assembly : {"open", "crossed"}
        The branch.

    Returns
    -------
    theta3, theta4 : numpy.ndarray
        Coupler and rocker angles [rad].
    """
    theta3 = coupler_angle(a, b, c, d, theta2, assembly)
    theta4 = rocker_angle(a, b, c, d, theta2, assembly)
    diagonal = np.abs(a * np.exp(1j * np.asarray(theta2, float)) - d)
    bad = ~(np.isfinite(theta3) & np.isfinite(theta4)) | (diagonal <= 1e-9 * (a + d))
    return np.where(bad, np.nan, theta3), np.where(bad, np.nan, theta4)


def continuous(theta):
    """Angles wrapped to (-pi, pi] at the first finite sample and unwrapped along the
    last axis across NaN gaps (branch continuity for plotting and differencing).

    Parameters
    ----------
    theta : array_like
        Angles [rad], NaN where undefined; the last axis is the crank angle.

    Returns
    -------
    numpy.ndarray
        The same shape [rad], NaN kept.
    """
    theta = np.asarray(theta, float)
    out = np.full_like(theta, np.nan)
    flat_in, flat_out = theta.reshape(-1, theta.shape[-1]), out.reshape(-1, theta.shape[-1])
    for row_in, row_out in zip(flat_in, flat_out):
        ok = np.isfinite(row_in)
        if ok.any():
            wrapped = np.angle(np.exp(1j * row_in[ok]))
            row_out[ok] = np.unwrap(wrapped)
    return out


def transmission_angle(theta3, theta4):
    """Acute transmission angle mu in [0, pi/2] between coupler and rocker, Norton
    eq. 4.32: theta_tr = |theta3 - theta4| (mod pi); mu = pi - theta_tr if > pi/2.

    Parameters
    ----------
    theta3, theta4 : array_like
        Coupler and rocker angles [rad].

    Returns
    -------
    numpy.ndarray
        mu [rad] in [0, pi/2].
    """
    tr = np.abs(np.mod(np.asarray(theta3) - np.asarray(theta4), np.pi))
    return np.where(tr > np.pi / 2, np.pi - tr, tr)


def joint_positions(a, b, c, d, theta2, theta3, theta4):
    """Complex positions of O2, A, B (from the crank side) and O4 (Norton ch. 4).

    Parameters
    ----------
    a, b, c, d, theta2
        Lengths [m] and crank angles [rad], as :func:`rocker_angle` takes them.
    theta3, theta4 : array_like
        Coupler and rocker angles [rad] at ``theta2`` (``theta4`` is not needed: B is
        reached through the coupler; it is taken for a uniform signature).

    Returns
    -------
    tuple of numpy.ndarray
        (O2, A, B, O4) as x + i y [m] (the lengths' unit), O2 at the origin and O4 at
        (d, 0).
    """
    A = a * np.exp(1j * np.asarray(theta2))
    B = A + b * np.exp(1j * np.asarray(theta3))
    return np.zeros_like(A), A, B, d + 0.0 * A


def coupler_point(a, theta2, theta3, distance, angle):
    """Coupler point P = a e^{i theta2} + p e^{i (theta3 + delta3)} (Norton ch. 4),
    returned as (x, y) in m.

    Parameters
    ----------
    a : float
        Crank length [m].
    theta2 : array_like
        Crank angles [rad].
    theta3 : array_like
        Coupler angles [rad] at ``theta2``.
    distance : float
        Distance p of the point from the crank pin A [m].
    angle : float
        Angle delta3 of the point from the coupler line A->B [rad].

    Returns
    -------
    tuple of numpy.ndarray
        (x, y) [m], the frame's axes (O2 at the origin).
    """
    p = a * np.exp(1j * np.asarray(theta2)) + distance * np.exp(1j * (np.asarray(theta3) + angle))
    return p.real, p.imag


def assembly_gaps(theta2, ok):
    """Contiguous ranges (start, end) in rad of crank angles (sorted grid over one turn)
    where ``ok`` is False; a gap running through 360 deg is joined with one at 0.

    Parameters
    ----------
    theta2 : array_like
        Crank angles over one turn, sorted [rad].
    ok : array_like of bool
        Where the linkage assembles.

    Returns
    -------
    list of tuple of float
        (start, end) [rad] of each gap, the first and last crank angle in it.
    """
    theta2, ok = np.asarray(theta2), np.asarray(ok, bool)
    bad = ~ok
    if not bad.any():
        return []
    if bad.all():
        return [(float(theta2[0]), float(theta2[-1]))]
    gaps, start = [], None
    for k in range(len(bad)):
        if bad[k] and start is None:
            start = k
        if start is not None and (k == len(bad) - 1 or not bad[k + 1]):
            gaps.append([start, k])
            start = None
    if len(gaps) > 1 and gaps[0][0] == 0 and gaps[-1][1] == len(bad) - 1:
        gaps[0][0] = gaps.pop()[0]
    return [(float(theta2[i]), float(theta2[j])) for i, j in gaps]


def toggle_crank_angles(a, b, c, d, assembly="open"):
    """Crank angles (rad, in [0, 2 pi)) of the toggle positions on this branch.

    ``extended`` / ``folded``: crank and coupler collinear (O2 B = b + a or |b - a|),
    the rocker at its two limits (Norton ch. 4). ``crank_limits``: coupler
    and rocker collinear, where a non-rotating input stops, Norton ch. 4:
    theta2 = +/- acos[(a^2 + d^2 - b^2 - c^2)/(2 a d) +/- b c/(a d)].
    Candidates are checked on the chosen branch; none if absent.

    Parameters
    ----------
    a, b, c, d, assembly
        The lengths [m] and the branch, as :func:`rocker_angle` takes them.

    Returns
    -------
    dict of str to list of float
        ``extended``, ``folded`` and ``crank_limits`` -> the crank angles [rad] on the
        branch, sorted (empty where there are none).
    """
    def on_branch(candidates, residual):
        found = [float(np.mod(t, 2 * np.pi)) for t in candidates
                 if np.isfinite(t) and residual(t) < 1e-6]
        return sorted(set(round(t, 12) for t in found))

    def crank_coupler(t):
        t3 = coupler_angle(a, b, c, d, t, assembly)
        return abs(np.sin(t3 - t))

    def coupler_rocker(t):
        t3, t4 = positions(a, b, c, d, t, assembly)
        return abs(np.sin(t4 - t3)) if np.isfinite(t3 + t4) else np.inf

    result = {}
    for name, e, shift in (("extended", b + a, 0.0), ("folded", abs(b - a), np.pi if b > a else 0.0)):
        with np.errstate(invalid="ignore"):
            phi = np.arccos((e * e + d * d - c * c) / (2.0 * e * d)) if e > 0 else np.nan
        result[name] = on_branch([phi + shift, -phi + shift], crank_coupler)
    limits = []
    for sign in (1.0, -1.0):
        with np.errstate(invalid="ignore"):
            t = np.arccos((a * a + d * d - b * b - c * c) / (2 * a * d) + sign * b * c / (a * d))
        limits += [t, -t]
    result["crank_limits"] = on_branch(limits, coupler_rocker)
    return result
