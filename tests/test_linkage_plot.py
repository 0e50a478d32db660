"""`fickcam plot --kind linkage` works on a result Dataset (degrees, m, N m)."""
import numpy as np
import pytest

from fickcam.linkage import FourBarDesign, FourBarState, fourbar_response

xr = pytest.importorskip("xarray")


def tiny_dataset():
    crank = np.arange(0.0, 360.0, 10.0)
    rows = []
    for growth in (1.0, 1.01, 1.02):
        links = (0.1 * growth, 0.16 * growth, 0.16 * growth, 0.2)
        design = FourBarDesign(0.1, 0.16, 0.16, 0.2, coupler_point_distance=0.08, crank_speed=10.0)
        rows.append(fourbar_response(design, FourBarState(links, (0.1, 0.2, 0.2), (1e-4, 4e-4, 4e-4)),
                                     np.radians(crank)).variables)
    data = {}
    for name, scale in (("rocker_angle", 180 / np.pi), ("coupler_angle", 180 / np.pi),
                        ("transmission_angle", 180 / np.pi), ("coupler_point_x", 1.0),
                        ("coupler_point_y", 1.0), ("input_torque", 1.0)):
        data[name] = (("time", "crank_angle"), np.stack([r[name] for r in rows]) * scale)
    times = np.array([0.0, 7.0, 30.0])  # ageing time [d]
    return xr.Dataset(data, coords={"time": times, "crank_angle": crank}, attrs={"scene_name": "tiny"})


def test_linkage_plots_are_written(tmp_path):
    from fickcam.plotting.linkage import plot

    written = plot(tiny_dataset(), tmp_path).paths
    assert [p.name for p in written] == ["linkage_coupler_curve.png", "linkage_rocker.png",
                                         "linkage_transmission_torque.png"]
    assert all(p.exists() and p.stat().st_size > 5000 for p in written)
