"""Kinetostatics: energy balance over a revolution, power balance at every crank
angle, and hand-calculated cases."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fickcam.linkage import FourBarDesign, FourBarState, fourbar_response
from fickcam.linkage.dynamics import STANDARD_GRAVITY, kinetic_energy
from fickcam.linkage.kinematics import centre_of_mass_motion
from test_linkage_positions import grashof_linkages
from tolerance import roundoff

N = 2000
THETA2 = np.linspace(0, 2 * np.pi, N, endpoint=False)


def solve(links, masses, inertias, fractions=(0.5, 0.5, 0.5), omega2=10.0, alpha2=0.0,
          gravity=False, load=0.0, assembly="open", theta2=THETA2):
    design = FourBarDesign(*links, crank_speed=omega2, crank_angular_acceleration=alpha2,
                           assembly=assembly, gravity=gravity, rocker_load_torque=load)
    return fourbar_response(design, FourBarState(links, masses, inertias, fractions), theta2).variables


def energies(v, links, masses, inertias, fractions, omega2):
    omegas = (np.full(N, omega2), v["coupler_angular_velocity"], v["rocker_angular_velocity"])
    position, velocity, _ = centre_of_mass_motion(
        links, fractions, (THETA2, v["coupler_angle"], v["rocker_angle"]), omegas,
        (np.zeros(N), v["coupler_angular_acceleration"], v["rocker_angular_acceleration"]))
    kinetic = kinetic_energy(masses, inertias, velocity, omegas)
    potential = STANDARD_GRAVITY * np.sum(np.asarray(masses)[:, None] * position.imag, axis=0)
    return kinetic, potential


def spectral_derivative(f):
    """d f / d theta2 of a periodic sample over one turn (exact for smooth f)."""
    k = np.fft.rfftfreq(N, 1.0 / N)
    return np.fft.irfft(1j * k * np.fft.rfft(f), N)


masses_st = st.tuples(*[st.floats(0.05, 5.0)] * 3)
inertias_st = st.tuples(*[st.floats(1e-4, 0.05)] * 3)
fractions_st = st.tuples(*[st.floats(0.0, 1.0)] * 3)


@settings(max_examples=25, deadline=None)
@given(grashof_linkages(), masses_st, inertias_st, fractions_st, st.sampled_from(["open", "crossed"]))
def test_input_torque_does_no_net_work_over_a_revolution(links, masses, inertias, fractions, assembly):
    v = solve(links, masses, inertias, fractions, assembly=assembly)
    torque = v["input_torque"]
    assert np.isfinite(torque).all()
    work = torque.mean() * 2 * np.pi           # integral of T d theta2 (periodic, uniform grid)
    # the mean of n values carries n eps max|T| of round-off (Higham sec. 3.1)
    assert abs(work) < 1e-9 * np.abs(torque).mean() * 2 * np.pi + \
        2 * np.pi * roundoff(torque, operations=torque.size)


@settings(max_examples=25, deadline=None)
@given(grashof_linkages(), masses_st, inertias_st, fractions_st, st.floats(-5.0, 5.0),
       st.booleans())
def test_input_power_equals_rate_of_change_of_mechanical_energy(links, masses, inertias, fractions,
                                                                load, gravity):
    """T12 omega2 + T4 omega4 = d(KE + PE)/dt at every crank angle (constant omega2)."""
    omega2 = 10.0
    v = solve(links, masses, inertias, fractions, omega2=omega2, gravity=gravity, load=load)
    kinetic, potential = energies(v, links, masses, inertias, fractions, omega2)
    total = kinetic + (potential if gravity else 0.0)
    rate = spectral_derivative(total) * omega2
    power = v["input_torque"] * omega2 + load * v["rocker_angular_velocity"]
    scale = np.abs(v["input_torque"] * omega2).max() + np.abs(load * v["rocker_angular_velocity"]).max()
    # spectral derivative of n samples: round-off of the energy amplified by up to n / 2
    assert np.abs(power - rate).max() < 1e-6 * scale + \
        roundoff(total * omega2, operations=64 * total.size)


def test_crank_alone_needs_inertia_and_gravity_torque_by_hand():
    """Only the crank has mass (m = 2 kg at r = 0.04 m, I_G = 3e-3 kg m^2): by hand
    T = (I_G + m r^2) alpha2 + m g r cos theta2; joints A and B carry no force."""
    links, m, r, ig, alpha2 = (0.1, 0.16, 0.16, 0.2), 2.0, 0.04, 3e-3, 7.0
    v = solve(links, (m, 0.0, 0.0), (ig, 0.0, 0.0), fractions=(r / 0.1, 0.5, 0.5), omega2=12.0,
              alpha2=alpha2, gravity=True)
    expected = (ig + m * r * r) * alpha2 + m * STANDARD_GRAVITY * r * np.cos(THETA2)
    # Newton-Euler: a small dense solve per angle, equal up to round-off of the forces
    np.testing.assert_allclose(v["input_torque"], expected, rtol=0,
                               atol=roundoff(expected, v["joint_force"] * 0.1))
    np.testing.assert_allclose(v["joint_force"][1:3], 0.0, rtol=0, atol=roundoff(v["joint_force"]))
    # F12 = m (a_G + g e_y): radial part m r omega^2 at 0 deg with alpha2 tangential
    f12 = v["joint_force_x"][0, 0] + 1j * v["joint_force_y"][0, 0]
    assert f12 == pytest.approx(m * (-r * 144.0 + 1j * r * alpha2) + 1j * m * STANDARD_GRAVITY)


def test_massless_linkage_balances_a_rocker_load_by_virtual_work():
    """Statics by hand (virtual work, Norton sec. 11.9): T12 omega2 + T4 omega4 = 0."""
    links = (0.1, 0.16, 0.16, 0.2)
    v = solve(links, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), load=3.0, omega2=5.0)
    expected = -3.0 * v["rocker_angular_velocity"] / 5.0
    np.testing.assert_allclose(v["input_torque"], expected, rtol=0, atol=roundoff(expected))


def test_peak_and_rms_torque_summarise_the_cycle():
    v = solve((0.1, 0.16, 0.16, 0.2), (0.15, 0.2, 0.2), (1e-4, 4e-4, 4e-4))
    assert v["peak_input_torque"] == pytest.approx(np.abs(v["input_torque"]).max())
    assert v["rms_input_torque"] == pytest.approx(np.sqrt(np.mean(v["input_torque"] ** 2)))
    assert 0 < v["rms_input_torque"] < v["peak_input_torque"]
