"""Four-bar velocities, accelerations and centre-of-mass motion against numerical
differentiation of the closed-form positions (true time derivatives)."""
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from fickcam.linkage import FourBarDesign, FourBarState, fourbar_response
from test_linkage_positions import grashof_linkages

H = 1e-5  # s


def response(links, assembly, omega2, alpha2, theta2, fractions=(0.5, 0.5, 0.5), p=(0.0, 0.0)):
    design = FourBarDesign(*links, coupler_point_distance=p[0], coupler_point_angle=p[1],
                           crank_speed=omega2, crank_angular_acceleration=alpha2, assembly=assembly)
    state = FourBarState(links, (1.0, 1.0, 1.0), (0.1, 0.1, 0.1), fractions)
    return fourbar_response(design, state, theta2).variables


def central(f_minus, f, f_plus):
    """First and second central differences in time."""
    return (f_plus - f_minus) / (2 * H), (f_plus - 2 * f + f_minus) / H ** 2


def wrapped(x):
    return np.angle(np.exp(1j * x))


def central_angle(f_minus, f, f_plus):
    """Central differences of an angle, immune to 2 pi jumps between samples."""
    up, down = wrapped(f_plus - f), wrapped(f - f_minus)
    return (up + down) / (2 * H), (up - down) / H ** 2


@settings(max_examples=40, deadline=None)
@given(grashof_linkages(), st.sampled_from(["open", "crossed"]), st.floats(1.0, 30.0),
       st.floats(-50.0, 50.0))
def test_angular_velocities_and_accelerations_match_numerical_differentiation(links, assembly, omega2,
                                                                              alpha2):
    theta0 = np.linspace(0, 2 * np.pi, 24, endpoint=False) + 0.1
    # theta2(t) = theta0 + omega2 t + alpha2 t^2 / 2 about t = 0: omega and alpha at t = 0
    samples = [response(links, assembly, omega2 + alpha2 * t, alpha2,
                        theta0 + omega2 * t + 0.5 * alpha2 * t * t)
               for t in (-H, 0.0, H)]
    mid = samples[1]
    for angle, rate, accel in (("coupler_angle", "coupler_angular_velocity", "coupler_angular_acceleration"),
                               ("rocker_angle", "rocker_angular_velocity", "rocker_angular_acceleration")):
        d1, d2 = central_angle(*(s[angle] for s in samples))
        scale = np.abs(mid[rate]).max() + omega2
        assert np.allclose(mid[rate], d1, atol=1e-6 * scale), angle
        scale2 = np.abs(mid[accel]).max() + omega2 ** 2 + abs(alpha2)
        assert np.allclose(mid[accel], d2, atol=2e-3 * scale2), angle


@settings(max_examples=30, deadline=None)
@given(grashof_linkages(), st.floats(1.0, 30.0), st.floats(-50.0, 50.0),
       st.tuples(*[st.floats(0.0, 1.0)] * 3))
def test_centre_of_mass_velocity_and_acceleration_match_numerical_differentiation(links, omega2, alpha2,
                                                                                  fractions):
    from fickcam.linkage.kinematics import centre_of_mass_motion

    theta0 = np.linspace(0, 2 * np.pi, 12, endpoint=False) + 0.05
    states = []
    for t in (-H, 0.0, H):
        v = response(links, "open", omega2 + alpha2 * t, alpha2, theta0 + omega2 * t + 0.5 * alpha2 * t * t)
        w2 = np.full_like(theta0, omega2 + alpha2 * t)
        states.append(centre_of_mass_motion(
            links, fractions, (theta0 + omega2 * t + 0.5 * alpha2 * t * t, v["coupler_angle"], v["rocker_angle"]),
            (w2, v["coupler_angular_velocity"], v["rocker_angular_velocity"]),
            (np.full_like(theta0, alpha2), v["coupler_angular_acceleration"], v["rocker_angular_acceleration"])))
    d1, d2 = central(*(s[0] for s in states))
    _, vel, acc = states[1]
    v = response(links, "open", omega2, alpha2, theta0, fractions)
    assert np.allclose(v["link_com_velocity_x"][:3] + 1j * v["link_com_velocity_y"][:3], vel)
    assert np.all(v["link_com_velocity_x"][3] == 0) and np.all(v["link_com_acceleration_y"][3] == 0)

    scale = np.abs(vel).max() + omega2 * max(links)
    assert np.allclose(vel, d1, atol=1e-6 * scale)
    scale2 = np.abs(acc).max() + (omega2 ** 2 + abs(alpha2)) * max(links)
    assert np.allclose(acc, d2, atol=2e-3 * scale2)
