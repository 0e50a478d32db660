"""A limit search whose diffusion is estimated above the requested accuracy tells the user,
end to end through ``fickcam run``.

The time out of spec is searched between the stored ageing times; a concentration-
dependent part is read there from its stored march (dense output), and its estimate is
then the stored one plus the interpolation's. On the nylon eccentric cam with
D(c) = D0 (c/Mm)^2 the stored estimate is about accuracy/2 + 8.1e-4 and the
interpolation adds about 2.4e-4 (measured: 1.71e-3 and 1.95e-3 at accuracy 1.8e-3), so at
an accuracy of 1.8e-3 the stored run is within it and the search is not: the run must say
so as a warning, keep it in the result's notices, and still give the crossing.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from fickcam.cli.main import main

CONFIGS = Path(__file__).resolve().parents[1] / "configs"
ACCURACY = 1.8e-3


def concentration_dependent_cam(tmp_path: Path) -> Path:
    """The example eccentric cam in nylon whose D grows as (c/Mm)^2, with a displacement
    limit crossed between its ageing times 1 d and 180 d."""
    scene = yaml.safe_load((CONFIGS / "eccentric_cam.yaml").read_text())
    scene["materials"]["nylon"]["sorption"] = {"model": "concentration_dependent",
                                               "exponent": 2}
    scene["limits"] = {"follower_displacement": {"deviation": "0.1 mm"}}
    scene["outputs"] = {"ageing_times": ["0 d", "1 d", "180 d"], "angle_step": "2 deg"}
    path = tmp_path / "dc_cam.yaml"
    path.write_text(yaml.safe_dump(scene))
    return path


@pytest.mark.slow
def test_a_search_estimate_above_the_accuracy_reaches_the_user_as_a_warning(tmp_path, capsys):
    result = tmp_path / "dc_cam.nc"
    assert main(["run", str(concentration_dependent_cam(tmp_path)), "-o", str(result),
                 "--accuracy", str(ACCURACY)]) == 0
    captured = capsys.readouterr()
    said = [line for line in captured.err.splitlines() if "limit search" in line]
    assert len(said) == 1, captured.err
    assert said[0].startswith("fickcam: warning: cam: estimated diffusion error ")
    assert "at the limit search's times above the requested accuracy 0.0018" in said[0]
    assert "1 warning(s) above" in captured.out
    with xr.open_dataset(result) as ds:
        assert said[0].removeprefix("fickcam: warning: ") in ds.attrs["notices"]
        crossing = float(ds["time_out_of_spec"].sel(limit="follower_displacement"))
    assert 1.0 < crossing < 180.0 and np.isfinite(crossing)  # days: the crossing is kept
