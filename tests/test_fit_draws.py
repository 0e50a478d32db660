"""Monte Carlo draws of a fitted material with the covariance ``fickcam fit`` recorded."""
import numpy as np
import pytest
import yaml

import fickcam
from fickcam.cli.main import main
from fickcam.sweep import load_sweep

from test_scene_errors import LINKAGE_SCENE

# the fitted block of the materials guide's "Calibrating a material" example
FITTED = {"matrix": "3502",
          "diffusivity": {"pre_exponential": "9.08355e-08 m^2/s", "activation_energy": "30.1843 kJ/mol"},
          "saturation": {"coefficient": "5.00092 %", "exponent": 1.40037},
          "fit": {"source": "weight_gain_synthetic_epoxy.csv",
                  "covariance": {"diffusivity": [[0.000263166, 0.7294], [0.7294, 2027.29]],
                                 "saturation": [[1.32657e-06, 9.08278e-07],
                                                [9.08278e-07, 8.27984e-07]]}}}
SAMPLES = 4000


def write(tmp_path, material=FITTED, random="  materials.resin.fit: {covariance: true}\n"):
    scene = yaml.safe_load(LINKAGE_SCENE)
    scene["materials"]["resin"] = material
    (tmp_path / "base.yaml").write_text(yaml.safe_dump(scene, sort_keys=False))
    path = tmp_path / "mc.yaml"
    path.write_text(f"base: base.yaml\nsamples: {SAMPLES}\nseed: 7\nrandom:\n{random}")
    return path


def test_ln_d0_and_ea_are_drawn_jointly_with_the_fits_covariance(tmp_path):
    """Sample mean and covariance of (ln D0, Ea) and (a, b) against the fit's: means within
    4 standard errors, variances within 4 x sqrt(2/n) = 9 %, the +0.99 correlation kept."""
    sweep = load_sweep(write(tmp_path))
    coords = sweep.coordinates()
    names = [p.path for p in sweep.parameters]
    assert names == ["materials.resin.diffusivity.pre_exponential",
                     "materials.resin.diffusivity.activation_energy",
                     "materials.resin.saturation.coefficient", "materials.resin.saturation.exponent"]
    ln_d0 = np.log(coords["materials__resin__diffusivity__pre_exponential"])
    ea = coords["materials__resin__diffusivity__activation_energy"]
    a = coords["materials__resin__saturation__coefficient"]
    b = coords["materials__resin__saturation__exponent"]
    for (x, y), mean, cov in (((ln_d0, ea), (np.log(9.08355e-08), 30184.3),
                               FITTED["fit"]["covariance"]["diffusivity"]),
                              ((a, b), (5.00092, 1.40037), FITTED["fit"]["covariance"]["saturation"])):
        sample = np.cov(np.vstack([x, y]))
        sd = np.sqrt(np.diag(cov))
        assert abs(x.mean() - mean[0]) < 4 * sd[0] / np.sqrt(SAMPLES)
        assert abs(y.mean() - mean[1]) < 4 * sd[1] / np.sqrt(SAMPLES)
        np.testing.assert_allclose(np.diag(sample), np.diag(cov), rtol=4 * np.sqrt(2 / SAMPLES))
        rho = cov[0][1] / (sd[0] * sd[1])
        assert np.corrcoef(x, y)[0, 1] == pytest.approx(rho, abs=0.01)
    assert np.corrcoef(ln_d0, ea)[0, 1] > 0.98  # never drawn independently


def test_every_drawn_case_is_a_valid_scene_and_the_seed_repeats_it(tmp_path):
    sweep = load_sweep(write(tmp_path))
    scene = fickcam.load_scene(sweep.scene_dict(sweep.cases[0]))
    assert scene.model.materials["resin"].diffusivity.pre_exponential > 0
    again = load_sweep(write(tmp_path))
    assert again.cases[5].values == sweep.cases[5].values


@pytest.mark.parametrize("material, random, reason", [
    ({"matrix": "R914"}, "  materials.resin.fit: {covariance: true}\n",
     "materials.resin has no fit.covariance to draw from"),
    (FITTED, "  materials.resin.diffusivity.pre_exponential: {covariance: true}\n",
     "covariance: true goes with a path materials.NAME.fit"),
    (FITTED, "  materials.resin.fit: {covariance: true, normal: [1, 2]}\n", "give exactly one of"),
])
def test_a_covariance_draw_without_a_fit_is_refused_at_its_line(tmp_path, capsys, material, random,
                                                                 reason):
    path = write(tmp_path, material, random)
    assert main(["sweep", str(path), "-o", str(tmp_path / "out.h5")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"{path}:5 random.") and reason in err, err
