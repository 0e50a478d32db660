"""The aged motion of a cam given by points, solved once per ageing time
(fickcam.cam.profile.aged_profile_motion), against the same cam in closed form.

Reference: a nylon eccentric disc (e = 4 mm, R = 23 mm) on a radial roller (10 mm),
swollen isotropically by 1.2 %: the follower height is Y = -e cos(theta) +
sqrt((R + r)^2 - e^2 sin^2(theta)) (Norton, Design of Machinery, 5th ed., sec. 8.6).
The points are the disc's own working profile, kept at full precision (a CSV rounds
them to 1e-12 m, which its second derivatives amplify)."""
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from scipy.interpolate import PPoly

from fickcam.cam.design import CamState, cam_design
from fickcam.cam.geometry import working_outline
from fickcam.cam.model import cam_response
from fickcam.cam.profile import aged_profile_motion, make_profile, piece_roots

THETA = np.radians(np.arange(0.0, 360.0, 2.0))
STRAIN = 0.012
SECTION = {"material": "nylon", "thickness": "10 mm", "speed": "300 rpm", "gravity": True,
           "eccentric": {"eccentricity": "4 mm", "radius": "23 mm"},
           "follower": {"kind": "roller", "roller_radius": "10 mm", "mass": "0.737 kg",
                        "spring_rate": "660.02 N/m"}}
SWOLLEN = CamState(cam_strain_x=STRAIN, cam_strain_y=STRAIN)


def closed_form_disc():
    return cam_design(SECTION)


def as_points(design, n):
    """The cam given by n points of its working profile (full precision)."""
    profile = make_profile(*working_outline(design, n=n))
    return replace(design, kind="profile", profile=profile,
                   base_circle_radius=profile.radii()[0])


def relative_errors(design, n):
    """max |points - closed form| / max |closed form| of the displacement and the contact
    force over the turn, and of the jump speed, for the cam given by n points."""
    exact = cam_response(design, SWOLLEN, THETA).variables
    points = cam_response(as_points(design, n), SWOLLEN, THETA).variables
    return np.array([np.max(np.abs(points[k] - exact[k])) / np.max(np.abs(exact[k]))
                     for k in ("follower_displacement", "contact_force")] +
                    [abs(points["jump_speed"] / exact["jump_speed"] - 1.0)])


def test_the_closed_form_reference_is_the_disc_on_its_roller():
    design = closed_form_disc()
    e, pitch = 4e-3 * (1 + STRAIN), 23e-3 * (1 + STRAIN) + 10e-3
    height = -e * np.cos(THETA) + np.sqrt(pitch ** 2 - (e * np.sin(THETA)) ** 2)
    y = cam_response(design, SWOLLEN, THETA).variables["follower_displacement"]
    assert np.max(np.abs(y - (height - height.min()))) < 1e-12 * e


def test_points_converge_to_the_closed_form_cam_at_the_splines_orders():
    """Halving the point spacing: the displacement error falls as h^6 (the quintic
    spline's own error, de Boor, A Practical Guide to Splines, 2001, ch. XIII), the
    contact force and the jump speed, which read the second derivative, as h^4."""
    design = closed_form_disc()
    coarse, fine = relative_errors(design, 48), relative_errors(design, 96)
    orders = np.log2(coarse / fine)
    assert orders[0] == pytest.approx(6.0, abs=0.4)
    assert orders[1:] == pytest.approx([4.0, 4.0], abs=0.4)
    assert np.all(fine < [1e-10, 1e-6, 1e-6])  # the errors behind these orders, at 96 points


def test_the_motion_at_any_angle_is_the_motion_on_the_whole_turn():
    """One angle at a time (as the jump-speed search asks) gives what the whole grid gives:
    both are Newton's method from the same table, to its picometre tolerance."""
    design = as_points(closed_form_disc(), 360)
    motion = aged_profile_motion(design.profile, STRAIN, STRAIN, 10e-3, 0.0, False)
    together = np.array(motion(THETA))
    alone = np.array([np.concatenate(motion(np.array([t]))) for t in THETA]).T
    scale = np.max(np.abs(together), axis=1, keepdims=True)
    assert np.max(np.abs(alone - together) / scale) < 1e-9


@settings(max_examples=30, deadline=None)
@given(st.lists(st.floats(-1.0, 1.0, allow_subnormal=False), min_size=12, max_size=40),
       st.integers(1, 5), st.floats(-0.5, 0.5))
@example(values=[0.0] * 9 + [-0.75, -0.5, 0.0], degree=2, shift=0.0)  # a root at the last end
def test_piece_roots_are_the_roots_scipy_finds(values, degree, shift):
    """piece_roots solves only the pieces that can reach zero; it finds the roots
    PPoly.roots finds on every piece (simple roots, to 1e-9 of the breakpoint spacing)."""
    from scipy.interpolate import make_interp_spline

    x = np.arange(len(values), dtype=float)
    curve = PPoly.from_spline(make_interp_spline(x, np.asarray(values) + shift, k=degree))
    expected = curve.roots(extrapolate=False)
    expected = np.unique(expected[np.isfinite(expected)])
    found = piece_roots(curve)
    simple = expected[np.abs(curve.derivative()(expected)) > 1e-6]  # a tangential root is
    # ill-posed for either method
    assert all(np.min(np.abs(found - r), initial=np.inf) < 1e-9 for r in simple)
    assert np.all(np.abs(curve(found)) <= 1e-9 * np.max(np.abs(curve.c)))
