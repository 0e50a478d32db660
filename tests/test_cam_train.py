"""Elastic follower train (Norton's single-DOF model): the Fourier steady state against
an independent solve_ivp shooting solution, the rigid limit, the closed-form residual
vibration of a cycloidal rise, the train stiffness of a rod or lever."""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.linalg import expm

from fickcam.cam import CamDesign, CamState, cam_response
from fickcam.cam import dynamics as dyn
from fickcam.cam import train as tr
from fickcam.cam.motion import follower_motion, segments_from_spec
from fickcam.cam.spec import Segment

THETA = np.radians(np.arange(0.0, 360.0, 1.0))
STATE = CamState(cam_surface_modulus=5e9, cam_surface_poisson=0.35)


def design(law="polynomial_345", stiffness=2e5, zeta=0.05, spring=3000.0, lift=0.015,
           speed=60.0, rise=120.0):
    segments = segments_from_spec([Segment(dwell=math.radians(60)),
                                   Segment(rise=lift, over=math.radians(rise), law=law),
                                   Segment(dwell=math.radians(220 - rise)),
                                   Segment(**{"return": lift}, over=math.radians(80), law=law)])
    return CamDesign("motion", 0.05, 0.01, speed, "roller", 0.8, segments=segments,
                     roller_radius=0.012, spring_rate=spring, spring_preload=40.0,
                     external_load=25.0, train=("stiffness", stiffness), damping_ratio=zeta)


def elastic(d, theta=THETA):
    rigid = cam_response(d, STATE, theta).variables
    return rigid, tr.dynamic_response(d, STATE, theta, rigid).variables


def shooting_solution(d, load, theta):
    """Periodic state by an independent route: integrate the ODE over one turn with
    solve_ivp from rest, get the monodromy matrix from expm, solve for the periodic start,
    and integrate again (forcing from the motion law itself, not from its Fourier series)."""
    train = tr.Train(d.train[1], d.follower_mass, d.spring_rate, d.damping_ratio, load)
    m, c, k, ks, w = train.mass, train.damping, train.stiffness, train.spring_rate, d.speed

    def rhs(t, z):
        s, ds, _, _ = follower_motion(d.segments, np.array([w * t]))
        x, v = z
        return [v, (k * (s[0] - x) + c * (w * ds[0] - v) - ks * x - load) / m]

    period = 2 * math.pi / w
    options = dict(method="DOP853", rtol=1e-10, atol=1e-14, max_step=period / 60)
    forced = solve_ivp(rhs, (0, period), [0.0, 0.0], **options).y[:, -1]
    monodromy = expm(np.array([[0.0, 1.0], [-(k + ks) / m, -c / m]]) * period)
    start = np.linalg.solve(np.eye(2) - monodromy, forced)
    run = solve_ivp(rhs, (0, period), start, t_eval=np.append(theta / w, period), **options)
    return run.y[:, :-1], start, run.y[:, -1]


@pytest.mark.slow
@pytest.mark.parametrize("law, stiffness", [("polynomial_345", 2e5), ("cycloidal", 6e4)])
def test_fourier_steady_state_matches_solve_ivp_run_to_periodicity(law, stiffness):
    d = design(law, stiffness)
    rigid, dynamic = elastic(d)
    load = 40.0 + 25.0
    (x, v), start, end = shooting_solution(d, load, THETA)
    scale = np.max(np.abs(x))
    assert abs(end[0] - start[0]) < 1e-7 * scale  # periodic
    assert abs(end[1] - start[1]) < 1e-7 * d.speed * scale
    assert np.max(np.abs(dynamic["dynamic_follower_displacement"] - x)) < 1e-6 * scale
    s = follower_motion(d.segments, THETA)
    train = tr.train_of(d, STATE, load)
    axial = train.stiffness * (s[0] - x) + train.damping * (d.speed * s[1] - v)
    force = dyn.normal_force(axial, rigid["pressure_angle"], v, 0.0)
    assert np.max(np.abs(dynamic["dynamic_contact_force"] - force)) < 1e-6 * np.max(np.abs(force))


def test_stiff_train_tends_to_the_rigid_follower():
    errors = []
    for k in (1e8, 1e10):
        rigid, dynamic = elastic(design(stiffness=k))
        peak = np.max(np.abs(rigid["contact_force"]))
        errors.append(np.max(np.abs(dynamic["dynamic_contact_force"] - rigid["contact_force"])) / peak)
        assert np.max(np.abs(dynamic["dynamic_follower_displacement"] -
                             rigid["follower_displacement"])) < 2e3 / k
    # the 3-4-5 law's jerk steps ring the train: force error ~ k dj/wn^3 ~ k^-1/2
    assert errors[1] < 1e-3 and errors[1] < errors[0] / 5
    rigid, dynamic = elastic(design(stiffness=1e12))
    assert dynamic["dynamic_jump_speed"] == pytest.approx(rigid["jump_speed"], rel=2e-3)


@pytest.mark.parametrize("stiffness, spring", [(4e4, 0.0), (1.1e5, 3000.0), (2.5e5, 0.0)])
def test_residual_vibration_of_cycloidal_rise_matches_closed_form(stiffness, spring):
    """Undamped follower from rest: the free vibration left in the dwell after the first
    cycloidal rise is g h |sin pi r|/(pi r |1 - r^2|) (derived in tr.cycloidal_residual_amplitude)."""
    d = design("cycloidal", stiffness, zeta=0.0, spring=spring, rise=90.0)
    residual = tr.residual_vibrations(d, STATE)
    train = tr.train_of(d, STATE, 0.0)
    rise_time = math.radians(90.0) / d.speed
    expected = tr.cycloidal_residual_amplitude(0.015, rise_time, train.natural_frequency,
                                               stiffness / (stiffness + spring))
    assert residual[0] == pytest.approx(expected, rel=1e-8)


def test_cycloidal_residual_formula_against_direct_integration():
    """The closed form itself against solve_ivp of u'' + wn^2 u = -s'' (independent check)."""
    h, t1, wn = 0.01, 0.05, 2 * math.pi * 47.0

    def rhs(t, z):
        acc = 2 * math.pi * h / t1 ** 2 * math.sin(2 * math.pi * t / t1) if t < t1 else 0.0
        return [z[1], -wn ** 2 * z[0] - acc]

    u, v = solve_ivp(rhs, (0, t1), [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-16).y[:, -1]
    assert math.hypot(u, v / wn) == pytest.approx(tr.cycloidal_residual_amplitude(h, t1, wn), rel=1e-8)


def test_natural_frequency_and_section_stiffness():
    rod = tr.rod_stiffness(3e9, 0.1, 0.01)
    assert rod == pytest.approx(3e9 * math.pi * 0.01 ** 2 / 4 / 0.1)
    lever = tr.lever_stiffness(3e9, 0.1, 0.02, 0.01)
    assert lever == pytest.approx(3 * 3e9 * 0.02 * 0.01 ** 3 / 12 / 0.1 ** 3)
    d = design()
    d = CamDesign(**{**d.__dict__, "train": ("rod", 0.1, 0.01)})
    wet = tr.train_of(d, CamState(follower_mass=1.0, follower_train_modulus=2e9), 0.0)
    assert wet.stiffness == pytest.approx(rod * 2 / 3)
    assert wet.natural_frequency == pytest.approx(math.sqrt((rod * 2 / 3 + 3000.0) / 1.0))


def test_scene_stiffness_adds_elastic_variables_and_leaves_rigid_results_unchanged():
    import yaml

    import fickcam

    scene = yaml.safe_load(open("configs/singh2017_cam.yaml"))
    scene["outputs"] = {"ageing_times": ["0 d", "60 d"], "angle_step": "2 deg"}
    rigid = fickcam.run(scene)
    scene["cam"]["follower"]["stiffness"] = {"rod": {"length": "120 mm", "diameter": "12 mm"}}
    ds = fickcam.run(scene)
    for name in ("follower_displacement", "contact_force", "jump_speed"):
        assert np.array_equal(ds[name].values, rigid[name].values)
    assert "dynamic_contact_force" not in rigid
    assert ds["dynamic_contact_force"].dims == ("time", "cam_angle")
    assert ds["natural_frequency"].attrs["units"] == "Hz"
    assert ds["dynamic_jump_speed"].attrs["units"] == "rpm"
    assert ds["residual_vibration"].dims == ("time",)
    # the CFRP rod softens as it absorbs water: its stiffness falls and the follower gains mass
    assert ds["follower_train_stiffness"].values[1] < ds["follower_train_stiffness"].values[0]
    assert ds["natural_frequency"].values[1] < ds["natural_frequency"].values[0]


def test_series_on_the_result_grid_equals_the_direct_sum():
    coefficients = tr.harmonics(follower_motion(design().segments, np.linspace(0, 2 * np.pi, 1024,
                                                                               endpoint=False))[0])
    for order in (0, 1):
        fast = tr.at_angles(coefficients, np.radians(np.arange(0.0, 360.0, 1.5)), order, 60.0)
        direct = tr.series(coefficients, np.radians(np.arange(0.0, 360.0, 1.5)), order, 60.0)
        assert np.allclose(fast, direct, rtol=0, atol=1e-12 * np.max(np.abs(direct)))
