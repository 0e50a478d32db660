"""Four-bar positions: Freudenstein's closed form against an independent
circle-intersection solution, loop closure, branches, assembly gaps, toggles, class."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fickcam.linkage.classify import class_changes, grashof_class
from fickcam.linkage.positions import (
    assembly_gaps,
    coupler_angle,
    continuous,
    joint_positions,
    positions,
    rocker_angle,
    toggle_crank_angles,
    transmission_angle,
)

THETA2 = np.linspace(0, 2 * np.pi, 361)


def circle_intersection(a, b, c, d, theta2, assembly):
    """B as the intersection of the circle of radius b about A and of radius c about O4,
    on the left (open) or right (crossed) of the diagonal A->O4 (independent of Freudenstein)."""
    A = a * np.exp(1j * theta2)
    p = d - A
    f = np.abs(p)
    x = (b * b - c * c + f * f) / (2 * f)
    h = np.sqrt(b * b - x * x)
    side = 1.0 if assembly == "open" else -1.0
    B = A + (x + side * 1j * h) * p / f
    return np.angle(B - A), np.angle(B - d)


def same_angle(x, y):
    return np.abs(np.angle(np.exp(1j * (np.asarray(x) - np.asarray(y)))))


@st.composite
def grashof_linkages(draw):
    """Random crank-rocker or double-crank (crank or frame shortest, S + L < P + Q)."""
    shortest = draw(st.floats(0.02, 0.3))
    others = sorted(draw(st.lists(st.floats(0.35, 1.0), min_size=3, max_size=3)))
    if shortest + others[2] >= others[0] + others[1] - 0.02:
        others[2] = others[0] + others[1] - shortest - 0.02
    order = draw(st.permutations(others))
    if draw(st.booleans()):
        return shortest, order[0], order[1], order[2]   # crank shortest
    return order[0], order[1], order[2], shortest       # frame shortest


@settings(max_examples=60, deadline=None)
@given(grashof_linkages(), st.sampled_from(["open", "crossed"]))
def test_positions_match_independent_loop_closure_on_both_branches(links, assembly):
    a, b, c, d = links
    t3 = coupler_angle(a, b, c, d, THETA2, assembly)
    t4 = rocker_angle(a, b, c, d, THETA2, assembly)
    assert np.isfinite(t3).all() and np.isfinite(t4).all(), grashof_class(a, b, c, d)
    r3, r4 = circle_intersection(a, b, c, d, THETA2, assembly)
    assert same_angle(t3, r3).max() < 1e-8
    assert same_angle(t4, r4).max() < 1e-8


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(0.05, 1.0), min_size=4, max_size=4), st.sampled_from(["open", "crossed"]))
def test_loop_closure_residual_vanishes_wherever_any_linkage_assembles(links, assembly):
    a, b, c, d = links
    t3, t4 = positions(a, b, c, d, THETA2, assembly)
    ok = np.isfinite(t3)
    assert np.array_equal(ok, np.isfinite(t4))
    if not ok.any():
        return
    _, _, B, _ = joint_positions(a, b, c, d, THETA2[ok], t3[ok], t4[ok])
    # sqrt(eps) sensitivity at toggles bounds the residual there
    assert np.abs(B - (d + c * np.exp(1j * t4[ok]))).max() < 1e-7 * (a + b + c + d)
    # where it fails, the diagonal O4-A is outside the coupler-rocker reach
    f = np.abs(d - a * np.exp(1j * THETA2[~ok]))
    assert np.all((f > b + c - 1e-9) | (f < abs(b - c) + 1e-9) | (f < 1e-8))


def test_open_branch_is_the_convex_parallelogram_and_crossed_its_mirror():
    t2 = np.radians(60.0)
    assert same_angle(rocker_angle(1, 2, 1, 2, t2, "open"), t2) < 1e-12
    assert same_angle(coupler_angle(1, 2, 1, 2, t2, "open"), 0.0) < 1e-12
    assert same_angle(rocker_angle(1, 2, 1, 2, t2, "crossed"), t2) > 0.1


def test_transmission_angle_is_acute_angle_between_coupler_and_rocker():
    assert transmission_angle(0.0, np.radians(120)) == pytest.approx(np.radians(60))
    assert transmission_angle(np.radians(10), np.radians(80)) == pytest.approx(np.radians(70))


def test_non_grashof_linkage_reports_its_assembly_gap_around_180_deg():
    a, b, c, d = 0.115, 0.08, 0.08, 0.12   # S + L > P + Q: the crank rocks about 0 deg
    t3 = coupler_angle(a, b, c, d, THETA2)
    gaps = assembly_gaps(THETA2, np.isfinite(t3))
    assert grashof_class(a, b, c, d) == "non-Grashof"
    assert len(gaps) == 1 and gaps[0][0] < np.pi < gaps[0][1]
    limits = toggle_crank_angles(a, b, c, d)["crank_limits"]
    assert len(limits) == 2
    assert limits[0] < gaps[0][0] and limits[1] > gaps[0][1]
    assert gaps[0][0] - limits[0] < np.radians(1.01) and limits[1] - gaps[0][1] < np.radians(1.01)


def test_rocker_limits_occur_at_crank_coupler_toggles():
    a, b, c, d = 0.1, 0.16, 0.16, 0.2
    fine = np.linspace(0, 2 * np.pi, 200001)
    t4 = continuous(rocker_angle(a, b, c, d, fine))
    tog = toggle_crank_angles(a, b, c, d)
    assert fine[np.argmax(t4)] == pytest.approx(tog["folded"][0], abs=1e-4) or \
        fine[np.argmax(t4)] == pytest.approx(tog["extended"][0], abs=1e-4)
    found = sorted([fine[np.argmax(t4)], fine[np.argmin(t4)]])
    assert found == pytest.approx(sorted(tog["extended"] + tog["folded"]), abs=1e-4)


@pytest.mark.parametrize("links, label", [
    ((0.1, 0.16, 0.16, 0.2), "crank-rocker"),
    ((0.2, 0.16, 0.16, 0.1), "double-crank"),
    ((0.16, 0.1, 0.2, 0.16), "double-rocker"),
    ((0.1, 0.2, 0.1, 0.2), "change-point"),
    ((0.115, 0.08, 0.08, 0.12), "non-Grashof"),
])
def test_grashof_class_follows_norton_eq_2_8(links, label):
    assert grashof_class(*links) == label


def test_class_change_and_lost_rotation_are_warned():
    notices = class_changes(["crank-rocker", "crank-rocker", "non-Grashof"], [0.0, 86400.0, 2 * 86400.0])
    assert any("changed from crank-rocker to non-Grashof" in n for n in notices)
    assert any("no longer make a full revolution" in n for n in notices)
    assert class_changes(["crank-rocker"] * 3, [0.0, 1.0, 2.0]) == []
