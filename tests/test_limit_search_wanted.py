"""The limit search makes only what its limits read: the mechanisms are told the limited
variables (``Mechanism.response(..., wanted=...)``), so a search without a jump-speed limit
runs no jump-speed search, and its crossings are those it finds with every variable made."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import yaml

import fickcam
import fickcam.cam.model as cam_model
import fickcam.simulation.simulate as simulate

CONFIGS = Path(__file__).resolve().parents[1] / "configs"


def _demo_with_limits(tmp_path: Path, limits: dict) -> Path:
    scene = yaml.safe_load((CONFIGS / "singh2017_cam.yaml").read_text())
    scene["limits"] = limits
    scene["outputs"]["file"] = str(tmp_path / "out.h5")
    path = tmp_path / f"cam_{len(limits)}.yaml"
    path.write_text(yaml.safe_dump(scene))
    return path


def _searches_while_limited(monkeypatch) -> list[int]:
    """A counter of the jump-speed searches made while the limit search runs."""
    counted, searching = [0], [False]
    search, limits_dataset = cam_model.continuous_jump_speeds, simulate.limits_dataset

    def counting_search(*args, **kwargs):
        counted[0] += searching[0]
        return search(*args, **kwargs)

    def flagged(*args, **kwargs):
        searching[0] = True
        try:
            return limits_dataset(*args, **kwargs)
        finally:
            searching[0] = False

    monkeypatch.setattr(cam_model, "continuous_jump_speeds", counting_search)
    monkeypatch.setattr(simulate, "limits_dataset", flagged)
    return counted


def test_a_search_without_a_jump_speed_limit_searches_no_jump_speed(tmp_path, monkeypatch):
    displacement = {"follower_displacement": {"deviation": "0.25 mm"}}
    both = {**displacement, "jump_speed": {"min": "1000 rpm"}}
    counted = _searches_while_limited(monkeypatch)
    alone = fickcam.run(_demo_with_limits(tmp_path, displacement))
    assert counted[0] == 0
    with_jump = fickcam.run(_demo_with_limits(tmp_path, both))
    assert counted[0] > 0  # the jump-speed limit's evaluations search it
    crossing = alone["time_out_of_spec"].sel(limit="follower_displacement").values
    assert np.isfinite(crossing)
    # the same crossing as when every variable is made (the other limit's evaluations
    # read the same model at other times)
    np.testing.assert_allclose(
        crossing, with_jump["time_out_of_spec"].sel(limit="follower_displacement").values,
        rtol=1e-9)
    assert "jump_speed" in alone  # the stored run makes every variable
