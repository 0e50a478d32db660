"""`fickcam fit` as a user runs it: bad CSV rows refused at their line, the fitted
YAML loads into a scene whose run reproduces the weighed points, the plot is drawn."""
import numpy as np
import pytest
import yaml

import fickcam
from fickcam.cli.main import main
from fickcam.diffusion.problem.exposure import GAS_CONSTANT
from fickcam.fit.synthetic import d5229_times, synthetic_specimen, write_weight_gain_csv

HEADER = "specimen,temperature [degC],relative_humidity [%],thickness [mm],dry_mass [g],time [d],mass [g]\n"
GOOD = "a,60,85,2,5.0,0,5.0\na,60,85,2,5.0,1,5.02\na,60,85,2,5.0,2,5.03\n"


def run_cli(tmp_path, text, capsys, *extra):
    path = tmp_path / "coupons.csv"
    path.write_text(text)
    code = main(["fit", str(path), "--matrix", "3502", "-o", str(tmp_path / "out.yaml"), *extra])
    return code, capsys.readouterr()


@pytest.mark.parametrize("text, where, reason", [
    (HEADER + "a,60,85,2,5.0,0,5.0\na,60,85,2,5.0,2,5.02\na,60,85,2,5.0,1,5.03\n",
     "coupons.csv:4 time:", "times must increase"),
    (HEADER + GOOD + "b,60,85,2,5.0,0,-5.0\n", "coupons.csv:5 mass:", "must be positive"),
    (HEADER.replace("time [d]", "time") + GOOD, "coupons.csv:1 time:", "missing unit"),
    (HEADER + GOOD + "a,60,85,2.5,5.0,3,5.03\n", "coupons.csv:5 thickness:", "changes its thickness"),
    (HEADER + GOOD + "a,70,85,2,5.0,3,5.03\n", "coupons.csv:5 temperature:", "changes its temperature"),
    (HEADER + "a,60,85,2,5.0,0,5.0\na,60,85,2,5.0,1 fortnight,5.02\n", "coupons.csv:3 time:", "not a number"),
    (HEADER.replace("time [d]", "time [kg]") + GOOD, "coupons.csv:2 time:", "wrong dimension"),
    (HEADER.replace("mass [g]\n", "mass [g],colour\n") + GOOD, "coupons.csv:1 colour:", "unknown column"),
    (HEADER.replace(",dry_mass [g]", "") + "a,60,85,2,0,5.0\n", "coupons.csv:1 dry_mass:", "missing column"),
    (HEADER + "a,60,85,2,5.0,0,5.0\na,60,85,2,5.0,1,5.02\n", "coupons.csv:2 specimen:", "at least 3"),
    (HEADER + "a,60,85,2,5.0,0,5.0\na,60,85,2,5.0,1,4.99\na,60,85,2,5.0,2,4.98\n", "coupons.csv:4 mass:",
     "gains no moisture"),
])
def test_bad_rows_are_refused_at_their_line_with_exit_2(tmp_path, capsys, text, where, reason):
    code, out = run_cli(tmp_path, text, capsys)
    assert code == 2
    first = out.err.splitlines()[0]
    assert first.endswith(first.split(": ", 1)[-1]) and "Traceback" not in out.err
    assert where in out.err and reason in out.err


def test_too_few_weighings_to_determine_d_are_said_so_and_the_yaml_still_loads(tmp_path, capsys):
    from fickcam.materials import MaterialSpec

    code, out = run_cli(tmp_path, HEADER + GOOD, capsys)
    assert code == 0 and "NOT determined" in out.out
    entry = yaml.safe_load((tmp_path / "out.yaml").read_text())["materials"]["coupons"]
    assert MaterialSpec.model_validate(entry).fit.activation_energy_from == "library"


def test_unknown_library_matrix_is_bad_input(tmp_path, capsys):
    path = tmp_path / "c.csv"
    path.write_text(HEADER + GOOD)
    assert main(["fit", str(path), "--matrix", "unobtainium", "-o", str(tmp_path / "o.yaml")]) == 2
    assert "unknown matrix" in capsys.readouterr().err


def _coupons(tmp_path, rng):
    """SYNTHETIC coupons of the library resin 3502 at 60 degC / 85 % RH, sealed edges."""
    d, mm = 4e-12, 3.0
    coupons = [synthetic_specimen(f"s{k}", 333.15, 85.0, 2e-3, d5229_times(56.0), mm, d, rng, 0.005 * mm)
               for k in range(2)]
    return write_weight_gain_csv(coupons, tmp_path / "resin.csv", ["SYNTHETIC"], dry_mass_g=5.0), coupons


def test_fitted_yaml_runs_in_a_scene_and_reproduces_the_weighed_points(tmp_path, capsys):
    rng = np.random.default_rng(4)
    csv_path, coupons = _coupons(tmp_path, rng)
    code = main(["fit", str(csv_path), "--matrix", "3502", "-o", str(tmp_path / "fit.yaml"),
                 "--plot", str(tmp_path / "fit.png")])
    out = capsys.readouterr().out
    assert code == 0 and "Ea kJ/mol" in out and "library" in out
    assert (tmp_path / "fit.png").stat().st_size > 10_000
    block = yaml.safe_load((tmp_path / "fit.yaml").read_text())["materials"]
    assert list(block) == ["resin"] and block["resin"]["fit"]["source"] == "resin.csv"
    picked = np.arange(1, coupons[0].time.size, 3)       # every third weighing keeps the run short
    times = coupons[0].time[picked]
    scene = {
        "name": "coupon-check",
        "environment": {"reference_temperature": "23 degC",
                        "history": [{"duration": "56 d", "temperature": "60 degC", "relative_humidity": "85 %"}]},
        "materials": block,
        # a thin eccentric disc: radius 1 m, 2 mm thick, so that its edge adds < 0.2 % of Mm
        "cam": {"material": "resin", "eccentric": {"eccentricity": "4 mm", "radius": "1 m"},
                "thickness": "2 mm", "speed": "10 rpm",
                "follower": {"kind": "roller", "roller_radius": "10 mm", "mass": "0.1 kg",
                             "spring_rate": "100 N/m"}},
        "outputs": {"ageing_times": [f"{t / 86400:.9g} d" for t in times], "angle_step": "10 deg"},
    }
    ds = fickcam.run(fickcam.load_scene(scene))
    run = ds["moisture_content"].sel(part="cam").values
    scatter = 0.005 * 3.0
    for specimen in coupons:
        difference = run - specimen.moisture[picked]
        assert np.sqrt(np.mean(difference ** 2)) < 1.5 * scatter
        assert np.max(np.abs(difference)) < 4 * scatter


def test_fit_record_is_validated_by_the_scene_loader(tmp_path):
    from pydantic import ValidationError

    from fickcam.materials import MaterialSpec

    good = {"matrix": "3502", "fit": {"source": "x.csv", "covariance": {"diffusivity": [[1.0, 0.5], [0.5, 1.0]]}}}
    assert MaterialSpec.model_validate(good).fit.covariance.diffusivity[0][1] == 0.5
    for bad in ([[1.0, 2.0], [2.0, 1.0]], [[1.0, 0.5], [0.4, 1.0]]):
        with pytest.raises(ValidationError):
            MaterialSpec.model_validate({**good, "fit": {"source": "x.csv", "covariance": {"diffusivity": bad}}})
    with pytest.raises(ValidationError):
        MaterialSpec.model_validate({**good, "fit": {"source": "x.csv", "colour": "red"}})


def test_python_api_returns_a_dataclass_and_a_dataset(tmp_path):
    rng = np.random.default_rng(5)
    csv_path, _ = _coupons(tmp_path, rng)
    report = fickcam.fit_weight_gain(csv_path, "3502", name="mine")
    ds = report.to_dataset()
    assert report.name == "mine" and ds.sizes["condition"] == 1
    assert ds["diffusivity"].attrs["units"] == "m2/s"
    assert ds["diffusivity_low"].item() < ds["diffusivity"].item() < ds["diffusivity_high"].item()


def _material_of(yaml_text):
    from fickcam.materials import MaterialSpec, resolve

    block = yaml.safe_load(yaml_text)["materials"]
    (name, entry), = block.items()
    return resolve(name, MaterialSpec.model_validate(entry)), entry


def test_composite_ply_values_map_to_matrix_overrides_that_give_the_ply_back(tmp_path):
    """The scene's composite (Chamis) turns the written matrix values back into the
    measured through-thickness D22 and ply Mm."""
    from fickcam.fit import fit_weight_gain, materials_yaml

    rng = np.random.default_rng(6)
    coupons = [synthetic_specimen(f"p{k}", 343.15, rh, 2e-3, d5229_times(56.0), 1.5 * (rh / 100) ** 1.2,
                                  2e-12, rng, 0.005) for k, rh in enumerate((50.0, 85.0))]
    report = fit_weight_gain(coupons, "8551-7", fiber="T300", fiber_volume_fraction=0.6, name="cfrp")
    material, entry = _material_of(materials_yaml(report))
    assert entry["fit"]["ply"]["diffusivity_factor"] == pytest.approx(report.diffusivity_factor, rel=1e-3)
    diffusivity = material.diffusivity_for()
    d22 = diffusivity.pre_exponential[2] * np.exp(-diffusivity.activation_energy / (GAS_CONSTANT * 343.15))
    assert d22 == pytest.approx(report.conditions[0].diffusivity.value, rel=1e-3)
    for condition in report.conditions:
        ply = material.saturation_moisture(343.15, condition.relative_humidity)
        assert ply == pytest.approx(condition.saturation.value, rel=0.01)


def test_non_fickian_data_write_a_runnable_two_phase_block_with_the_free_water_diffusivity(tmp_path):
    from fickcam.fit import fit_weight_gain, materials_yaml

    rng = np.random.default_rng(13)
    coupons = [synthetic_specimen(f"s{k}", 333.15, 85.0, 2e-3, d5229_times(140.0), 2.0, 5e-12, rng, 0.01,
                                  gamma=3e-7, beta=1e-6) for k in range(2)]
    report = fit_weight_gain(coupons, "3502", name="wet")
    text = materials_yaml(report)
    assert report.non_fickian == ["60 degC / 85 % RH"]
    assert "\n    sorption: {model: langmuir, binding_rate:" in text
    material, entry = _material_of(text)
    assert material.absorbs and entry["fit"]["non_fickian"][0]["condition"] == "60 degC / 85 % RH"
    law, (_, fit) = material.sorption_law(), report.two_phase_fits()[0]
    assert law.binding.pre_exponential == pytest.approx(fit.binding_rate.value, rel=1e-3)
    free = material.diffusivity_for().pre_exponential[2] * np.exp(
        -material.diffusivity_for().activation_energy / (GAS_CONSTANT * 333.15))
    assert free == pytest.approx(fit.diffusivity.value, rel=1e-3)
    assert material.saturation_moisture(333.15, 85.0) == pytest.approx(fit.saturation.value, rel=1e-3)


def _sealed_and_open(tmp_path):
    """Noise-free SYNTHETIC coupons of 3502 at 60 degC / 85 % RH in one file: ``sealed``
    (edges sealed: empty width and length cells) and ``open`` (20 x 20 mm, edges open)."""
    rng = np.random.default_rng(0)
    d, mm, times = 4e-12, 3.0, d5229_times(56.0)
    coupons = [synthetic_specimen("sealed", 333.15, 85.0, 2e-3, times, mm, d, rng, 0.0),
               synthetic_specimen("open", 333.15, 85.0, 2e-3, times, mm, d, rng, 0.0,
                                  width=20e-3, length=20e-3)]
    return write_weight_gain_csv(coupons, tmp_path / "mixed.csv", ["SYNTHETIC"]), d, mm


def test_empty_width_and_length_cells_mean_sealed_edges_beside_open_coupons(tmp_path, capsys):
    from fickcam.fit import fit_weight_gain
    from fickcam.fit.data import read_weight_gain

    path, d, mm = _sealed_and_open(tmp_path)
    rows = path.read_text().splitlines()
    assert rows[1].startswith("specimen,") and ",20,20," in rows[-1] and ",,," in rows[2]
    sealed, opened = read_weight_gain(path)
    assert (sealed.width, sealed.length) == (None, None)
    assert (opened.width, opened.length) == pytest.approx((20e-3, 20e-3))
    # each coupon fitted with its own model gives the D it was made with (noise-free data,
    # moisture written to 1e-4 %, 3e-5 of Mm); the sealed coupon taken as open gives
    # 0.84 D, the open one taken as sealed 1.20 D (its edges' share of the uptake)
    report = fit_weight_gain(path, "3502")
    for fit in report.specimen_fits:
        assert fit.diffusivity.value == pytest.approx(d, rel=1e-3)
        assert fit.saturation.value == pytest.approx(mm, rel=1e-3)
    code = main(["fit", str(path), "--matrix", "3502", "-o", str(tmp_path / "out.yaml")])
    out = capsys.readouterr()
    assert code == 0 and out.err == "", out.err
    assert "mixed" in yaml.safe_load((tmp_path / "out.yaml").read_text())["materials"]


@pytest.mark.parametrize("edit, where", [
    (lambda row: row.replace(",20,20,", ",20,,"), "length: empty cell: give width and length together"),
    (lambda row: row.replace(",20,20,", ",25,25,"), "width: specimen 'open' changes its width"),
])
def test_width_and_length_come_together_and_stay_the_same(tmp_path, capsys, edit, where):
    path, _, _ = _sealed_and_open(tmp_path)
    rows = path.read_text().splitlines()
    rows[-1] = edit(rows[-1])
    path.write_text("\n".join(rows) + "\n")
    assert main(["fit", str(path), "--matrix", "3502", "-o", str(tmp_path / "out.yaml")]) == 2
    err = capsys.readouterr().err
    assert f"mixed.csv:{len(rows)} {where}" in err and "Traceback" not in err
    assert not (tmp_path / "out.yaml").exists()


def test_a_coupons_width_and_length_may_be_given_on_one_of_its_rows(tmp_path):
    from fickcam.fit.data import read_weight_gain

    path, _, _ = _sealed_and_open(tmp_path)
    rows = path.read_text().splitlines()
    rows = [row.replace(",20,20,", ",,,") if row.startswith("open,") and k < len(rows) - 1 else row
            for k, row in enumerate(rows)]
    path.write_text("\n".join(rows) + "\n")
    sealed, opened = read_weight_gain(path)
    assert sealed.width is None and opened.width == pytest.approx(20e-3)
