"""The demo cam and four-bar configs give the results recorded before the diffusion
package was reorganised (HEAD 343268f), within the accuracy the run itself estimates.

Moisture of a part may move by the sum of the old and the new error estimates
(relative to the part's surface swing); mechanism scalars follow the moisture through
small strains, so they may move by at most that relative amount times 10 (a strain
coefficient of 1e-2 per weight % or less, on values of order one)."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import fickcam

REFERENCE = json.loads((Path(__file__).parent / "data" / "refactor_reference.json").read_text())
ROOT = Path(__file__).resolve().parents[1]


def _values(values) -> np.ndarray:
    return np.array([np.nan if v is None else v for v in values], float)


@pytest.mark.parametrize("name", sorted(REFERENCE))
def test_demo_configs_agree_with_the_results_before_the_reorganisation(name):
    ref = REFERENCE[name]
    ds = fickcam.run(ROOT / "configs" / f"{name}.yaml")
    assert [str(p) for p in ds.part.values] == ref["part_order"]
    estimates = ds.attrs["diffusion"]
    if isinstance(estimates, str):
        import ast
        estimates = ast.literal_eval(estimates)
    old = _values(ref["variables"]["moisture_content"]).reshape(ref["times"], -1)
    swing = np.nanmax(np.abs(_values(ref["variables"]["equilibrium_moisture_content"]).reshape(
        ref["times"], -1)), axis=0)
    allowed = np.array([ref["error_estimate"].get(p, 0.0) + estimates.get(p, {}).get(
        "error_estimate", 0.0) for p in ref["part_order"]]) * swing + 1e-12
    for variable in ("moisture_content", "surface_moisture_content"):
        before = _values(ref["variables"][variable]).reshape(old.shape)
        now = ds[variable].values
        assert np.array_equal(np.isnan(before), np.isnan(now)), variable
        gap = np.nan_to_num(np.abs(now - before))
        layer = 4.0 if variable.startswith("surface") else 1.0  # the layer's own tolerance
        assert np.all(gap <= layer * allowed[None, :]), (variable, gap.max(axis=0), allowed)
    relative = 10 * float(np.max(allowed / np.maximum(swing, 1e-300)))
    for variable, values in ref["variables"].items():
        if variable.endswith("moisture_content"):
            continue
        before = _values(values)
        now = np.ravel(ds[variable].values)
        assert np.array_equal(np.isnan(before), np.isnan(now)), variable
        finite = np.isfinite(before)
        assert np.allclose(now[finite], before[finite], rtol=relative, atol=0.0), variable
