"""Each plot kind as a user reads it: drift panels against the design, legends that hide
no curve and speak the user's units, closed coupler curves, tick labels that neither
crowd nor hide behind an offset."""
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

import fickcam
from fickcam import plotting
from fickcam.plotting import tidy_ticks

CONFIGS = Path(__file__).resolve().parents[1] / "configs"


class Kept(dict):
    """A figure writer for the plot functions' ``save`` argument that keeps each figure,
    drawn (ticks laid out), by file name instead of writing it."""

    def __call__(self, fig, path):
        tidy_ticks(fig)
        fig.canvas.draw()
        self[Path(path).name] = fig
        return Path(path)


@pytest.fixture
def figures():
    """The figures the plot functions make, by file name."""
    kept = Kept()
    yield kept
    import matplotlib.pyplot as plt

    plt.close("all")


def scene(name, **outputs):
    data = yaml.safe_load((CONFIGS / f"{name}.yaml").read_text())
    data["outputs"] = outputs
    return data


@pytest.fixture(scope="module")
def cam():
    return fickcam.run(scene("singh2017_cam", ageing_times=["0 d", "30 d", "60 d"], angle_step="3 deg"))


@pytest.fixture(scope="module")
def fourbar():
    return fickcam.run(scene("fourbar_r914_humid", ageing_times=["0 d", "30 d", "365 d"],
                             angle_step="5 deg"))


def lines_of(ax):
    return [line for line in ax.get_lines() if len(line.get_xdata()) > 2]


def legend_clear_of_axes(ax, legend) -> bool:
    fig = ax.figure
    box = legend.get_window_extent(fig.canvas.get_renderer())
    return box.x0 >= ax.get_window_extent().x1


def test_kinematics_has_a_displacement_drift_panel_against_the_design(cam, figures, tmp_path):
    plotting.plot(cam, tmp_path, "kinematics", save=figures)
    fig = figures["cam_kinematics.png"]
    drift_ax = fig.axes[-1]
    assert "− design" in drift_ax.get_ylabel() and "[mm]" in drift_ax.get_ylabel()
    first = lines_of(drift_ax)[0].get_ydata()
    expected = (cam.follower_displacement.isel(time=0) - cam.follower_displacement_design) * 1e3
    assert np.allclose(first, expected.values)
    low, high = drift_ax.get_ylim()
    assert high < 1.0 and high > 0.2  # about 0.26 mm: visible here, invisible at 40 mm scale
    assert legend_clear_of_axes(fig.axes[0], fig.axes[0].get_legend())


def test_dynamics_shows_the_stress_change_and_the_design_values(cam, figures, tmp_path):
    plotting.plot(cam, tmp_path, "dynamics", save=figures)
    assert "Hertz stress [MPa]\n− design" == figures["cam_dynamics.png"].axes[-1].get_ylabel()
    top = figures["cam_jump_stress.png"].axes[0]
    design = [line for line in top.get_lines() if line.get_linestyle() == "--"]
    assert design and design[0].get_ydata()[0] == pytest.approx(float(cam.jump_speed_design))


@pytest.mark.slow
def test_linkage_drift_against_design_and_start_and_a_closed_coupler_curve(fourbar, figures, tmp_path):
    plotting.plot(fourbar, tmp_path, "linkage", save=figures)
    rocker = figures["linkage_rocker.png"].axes
    assert [ax.get_ylabel() for ax in rocker] == ["rocker angle theta4 [deg]", "theta4 − design [deg]",
                                                  "change since t = 0 [deg]"]
    for line in lines_of(figures["linkage_coupler_curve.png"].axes[0]):
        x, y = line.get_xdata(), line.get_ydata()
        assert (x[0], y[0]) == (x[-1], y[-1])  # no gap between 355 deg and 0
    torque = figures["linkage_transmission_torque.png"].axes
    assert legend_clear_of_axes(torque[0], torque[0].get_legend())


def test_uptake_legend_names_only_parts_that_take_up_moisture(fourbar, figures, tmp_path):
    plotting.plot(fourbar, tmp_path, "uptake", save=figures)
    ax = figures["uptake.png"].axes[2]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["crank", "coupler", "rocker", "volume mean", "surface layer"]  # no steel frame
    assert legend_clear_of_axes(ax, ax.get_legend())


def sweep_result(kind: str) -> xr.Dataset:
    """A sweep as `fickcam sweep` writes it: temperature given in degC, stored in K."""
    rng = np.random.default_rng(0)
    days = np.array([0.0, 30.0, 60.0])  # ageing time [d]
    if kind == "grid":
        rh, temp = np.meshgrid([50.0, 65.0, 80.0], [333.15, 358.15], indexing="ij")
        rh, temp = rh.ravel(), temp.ravel()
    else:
        rh, temp = 0.6 + 4e-5 * rng.standard_normal(20), 358.15 + 2 * rng.standard_normal(20)
    n = rh.size
    lift = 0.0381 + 1e-6 * rng.standard_normal((n, 3)).cumsum(axis=1)
    return xr.Dataset(
        {"lift": (("case", "time"), lift, {"units": "m"}),
         "jump_speed": (("case", "time"), 1058.0 + 1e-4 * rng.standard_normal((n, 3)), {"units": "rpm"})},
        coords={"case": np.arange(n), "time": days,
                "first": ("case", rh, {"units": "%" if kind == "grid" else "1",
                                       "dotted_path": "environment.history.0.relative_humidity"
                                       if kind == "grid" else "materials.cfrp.fiber_volume_fraction"}),
                "second": ("case", temp, {"units": "K", "given_units": "degC",
                                          "dotted_path": "environment.history.0.temperature"}),
                "case_status": ("case", np.array(["ok"] * n, dtype=object)),
                "case_description": ("case", np.array(["x"] * n, dtype=object))},
        attrs={"scene_name": "cam", "sweep_kind": "grid" if kind == "grid" else "monte_carlo"})


def test_grid_sweep_legends_speak_the_sweep_files_units(figures, tmp_path):
    plotting.plot(sweep_result("grid"), tmp_path, "sweep", save=figures)
    ax = figures["sweep_jump_speed.png"].axes[0]
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["temperature = 60 °C",
                                                                   "temperature = 85 °C"]
    assert ax.get_xlabel() == "environment.history.0.relative_humidity [%]"


def test_monte_carlo_ticks_neither_crowd_nor_hide_behind_an_offset(figures, tmp_path):
    plotting.plot(sweep_result("monte_carlo"), tmp_path, "sweep", save=figures)
    fig = figures["sweep_jump_speed.png"]
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            assert axis.get_offset_text().get_text() == ""
            boxes = [t.get_window_extent(renderer) for t in axis.get_ticklabels() if t.get_text()]
            boxes = [b for b in boxes if ax.get_window_extent().expanded(1.5, 1.5).overlaps(b)]
            assert not any(a.overlaps(b) for i, a in enumerate(boxes) for b in boxes[i + 1:]), \
                [t.get_text() for t in axis.get_ticklabels()]
    assert fig.axes[2].get_xlabel() == "environment.history.0.temperature [°C]"


def test_a_sweep_over_weather_files_compares_the_sites_over_ageing_time(figures, tmp_path):
    """A grid over ``environment.history_file`` (text values): the at-one-age figure marks
    each site without a line between them, and each output is also drawn over ageing time,
    one line per site, labelled with the site the sweep read from each file (a file
    without a site keeps its name)."""
    sites = np.array(["pvlib:723170TYA.CSV", "pvlib:703165TY.csv"], dtype=object)
    days = np.array([0.0, 30.0, 60.0])  # ageing time [d]
    result = xr.Dataset(
        {"jump_speed": (("case", "time"), np.array([[588.0, 588.4, 588.9], [588.0, 588.2, 588.5]]),
                        {"units": "rpm"})},
        coords={"case": np.arange(2), "time": days,
                "environment__history_file": ("case", sites, {
                    "units": "1", "dotted_path": "environment.history_file",
                    "value_labels": '{"pvlib:703165TY.csv": "Sand Point, AK"}'}),
                "case_status": ("case", np.array(["ok", "ok"], dtype=object))},
        attrs={"scene_name": "cam", "sweep_kind": "grid"})
    plotting.plot(result, tmp_path, "sweep", save=figures)
    at_age = figures["sweep_jump_speed.png"].axes[0]
    assert all(line.get_linestyle() == "None" for line in at_age.get_lines())
    over_time = figures["sweep_jump_speed_over_time.png"].axes[0]
    assert [t.get_text() for t in over_time.get_legend().get_texts()] == [
        "history_file = pvlib:723170TYA.CSV", "Sand Point, AK"]
    assert [t.get_text() for t in at_age.get_xticklabels()] == [
        "Sand Point, AK", "pvlib:723170TYA.CSV"]
    assert [line.get_ydata()[-1] for line in over_time.get_lines()] == [588.9, 588.5]


def test_plotting_leaves_the_backend_and_pyplot_alone_and_returns_its_figures(cam, tmp_path,
                                                                              monkeypatch):
    import matplotlib
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure

    backend, open_figures = matplotlib.get_backend(), plt.get_fignums()
    monkeypatch.chdir(tmp_path)
    shown = plotting.plot(cam)  # no folder: figures only
    assert matplotlib.get_backend() == backend and plt.get_fignums() == open_figures
    assert shown and all(isinstance(fig, Figure) for fig in shown) and shown.paths == []
    assert not list(tmp_path.iterdir())
    assert [fig.get_label() for fig in shown][:2] == ["uptake", "cam_kinematics"]
    assert shown._repr_html_().count("data:image/png;base64,") == len(shown)
    written = plotting.plot(cam, tmp_path / "out", "uptake")
    assert [p.name for p in written.paths] == ["uptake.png"] and len(written) == 1


def test_no_plot_module_touches_pyplot_or_the_backend():
    package = Path(fickcam.__file__).parent
    for path in [*package.glob("plotting/*.py"), package / "fit" / "plot.py"]:
        text = path.read_text()
        assert "matplotlib.use(" not in text and "import matplotlib.pyplot" not in text, path


@pytest.mark.parametrize("which", ["fit", "against_band"])
def test_the_one_figure_plots_return_their_figure_like_every_other(cam, which, tmp_path,
                                                                   monkeypatch):
    """``plot_fit`` and ``plot_against_band`` return :class:`Figures` (shown inline in a
    notebook), write a file only when given one, and leave the backend alone."""
    import matplotlib
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure

    if which == "fit":
        from fickcam.fit import fit_weight_gain, plot_fit
        from fickcam.fit.synthetic import d5229_times, synthetic_specimen

        rng = np.random.default_rng(13)
        coupons = [synthetic_specimen(f"s{k}", 333.15, 85.0, 2e-3, d5229_times(60.0), 2.0, 5e-12,
                                      rng, 0.01) for k in range(2)]
        report = fit_weight_gain(coupons, "3502", name="coupons")
        draw = lambda path=None: plot_fit(report, path)  # noqa: E731
    else:
        from fickcam.plotting.compensation import plot_against_band

        draw = lambda path=None: plot_against_band(cam, cam, path, (0.0, 60.0))  # noqa: E731
    backend, open_figures = matplotlib.get_backend(), plt.get_fignums()
    monkeypatch.chdir(tmp_path)
    shown = draw()
    assert isinstance(shown, plotting.Figures) and len(shown) == 1 and shown.paths == []
    assert isinstance(shown[0], Figure) and not list(tmp_path.iterdir())
    assert shown._repr_html_().count("data:image/png;base64,") == 1
    assert matplotlib.get_backend() == backend and plt.get_fignums() == open_figures
    written = draw(tmp_path / "figure.png")
    assert written.paths == [tmp_path / "figure.png"] and (tmp_path / "figure.png").stat().st_size
    assert written[0].get_label() == "figure"


def test_after_a_wet_tg_stop_the_drift_shows_what_was_computed_and_says_where_and_why(figures,
                                                                                      tmp_path):
    """20 d at 113 degC, then 150 degC: the parts pass their wet Tg, so the mechanism is
    computed at 0 and 10 d only. The drift figure draws the 10 d line and its title says
    from when nothing is computed, and why; with only t = 0 computed it says so in place of
    empty axes."""
    data = scene("singh2017_cam", ageing_times=["0 d", "10 d", "30 d"], angle_step="6 deg")
    data["environment"] = {"history": [
        {"duration": "20 d", "temperature": "113 degC", "relative_humidity": "80 %"},
        {"duration": "40 d", "temperature": "150 degC", "relative_humidity": "85 %"}]}
    hot = fickcam.run(data)
    plotting.plot(hot, tmp_path, "kinematics", save=figures)
    top = figures["cam_drift.png"].axes[0]
    assert [line.get_label() for line in lines_of(top)] == ["t = 10 d"]
    assert top.get_title().replace("\n", " ") == (
        "singh2017-cam: drift from t = 0 d not computed from t = 30 d: at 150 °C the cam and "
        "follower passed their wet Tg (135 °C at t = 10 d)")
    assert "not computed from t = 30 d" in figures["cam_kinematics.png"].axes[0].get_title()
    plotting.plot(hot.isel(time=[0, 2]), tmp_path, "kinematics", save=figures)
    drift = figures["cam_drift.png"].axes
    assert all("no ageing time after t = 0 d is computed" in [t.get_text() for t in ax.texts]
               for ax in drift)


def test_vibration_shows_the_elastic_follower_against_the_rigid_one_and_its_train_over_ageing(
        figures, tmp_path):
    ds = fickcam.run(scene("epoxy_follower_vibration", ageing_times=["0 d", "365 d"],
                           angle_step="5 deg"))
    plotting.plot(ds, tmp_path, "vibration", save=figures)
    over_angle = figures["cam_vibration.png"].axes
    assert [ax.get_ylabel() for ax in over_angle] == [
        "displacement [mm]", "dynamic − kinematic [mm]", "contact force [N]"]
    elastic = [line for line in lines_of(over_angle[0]) if line.get_linestyle() == "-"]
    rigid = [line for line in lines_of(over_angle[0]) if line.get_linestyle() == "--"]
    assert len(elastic) == len(rigid) == 2
    assert np.allclose(elastic[-1].get_ydata(),
                       ds.dynamic_follower_displacement.isel(time=-1).values * 1e3)
    assert np.allclose(rigid[0].get_ydata(), ds.follower_displacement.isel(time=0).values * 1e3)
    assert legend_clear_of_axes(over_angle[0], over_angle[0].get_legend())
    ageing = figures["cam_vibration_ageing.png"].axes
    assert np.allclose(ageing[0].get_lines()[0].get_ydata(), ds.natural_frequency.values)
    assert [t.get_text() for t in ageing[1].get_legend().get_texts()] == ["elastic (dynamic)", "rigid"]
    assert ageing[2].get_ylabel() == "residual vibration [mm]"
