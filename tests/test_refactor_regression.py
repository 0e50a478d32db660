"""The diffusing parts of the demo cam and four-bar configs give the results recorded
before the diffusion package was reorganised (HEAD 343268f), within the accuracy each
run estimates. The parts' inputs (geometry, diffusivity, the held climate, ageing times,
accuracy) are recorded with the results, so changes to the configs or the material
library elsewhere do not move the reference: the mean and the contact layer may differ
by the sum of the old and the new error estimates (relative to the surface swing), the
layer by LAYER_TOLERANCE times that."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from fickcam.diffusion import Bar, CamPlate, Diffusivity, Disc, Exposure, LinkBar, Sheet, solve
from fickcam.diffusion.accuracy.budget import LAYER_TOLERANCE

REFERENCE = json.loads((Path(__file__).parent / "data" / "refactor_reference.json").read_text())
SHAPES = {"Sheet": Sheet, "Disc": Disc, "Bar": Bar, "CamPlate": CamPlate, "LinkBar": LinkBar}


def _part(record):
    fields = {k: np.asarray(v) if isinstance(v, list) else v
              for k, v in record["fields"].items()}
    exposure = Exposure.piecewise(record["change_times"], record["temperature"],
                                  [record["surface"]], record["initial"])
    return (SHAPES[record["geometry"]](**fields),
            Diffusivity(tuple(record["pre_exponential"]), record["activation_energy"]), exposure)


@pytest.mark.parametrize("name", sorted(REFERENCE))
def test_demo_config_parts_agree_with_the_results_before_the_reorganisation(name):
    record = REFERENCE[name]
    geometry, diffusivity, exposure = _part(record)
    result = solve(geometry, diffusivity, exposure, np.asarray(record["times"]),
                   accuracy=record["accuracy"])
    assert result.model == record["model"]
    swing = abs(record["surface"] - record["initial"])
    allowed = (record["error_estimate"] + result.error_estimate) * swing + 1e-12
    assert np.max(np.abs(result.mean - record["mean"])) <= allowed
    assert np.max(np.abs(result.surface - record["layer"])) <= LAYER_TOLERANCE * allowed
