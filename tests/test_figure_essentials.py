"""What every figure of a result must get right, checked on the drawn figures of a cam, a
four-bar and a cam aged in a daily climate record: labelled axes with units, legends that
cover no data, one colour per ageing time across figures, visible drift, and a climate
panel that shows the record between the stored ageing times."""
import re
from pathlib import Path

import matplotlib
import numpy as np
import pytest
import yaml
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

import fickcam
from fickcam import plotting
from fickcam.climate.environment import piecewise_linear_summary

matplotlib.use("Agg")

CONFIGS = Path(__file__).resolve().parents[1] / "configs"
UNIT = re.compile(r"\[[^\]]+\]")
AGE = re.compile(r"^t = [0-9.e+-]+ (d|h|min)$")


def short_scene(name: str, **changes) -> dict:
    data = yaml.safe_load((CONFIGS / f"{name}.yaml").read_text())
    data["outputs"] = {"ageing_times": ["0 d", "7 d", "30 d", "60 d"], "angle_step": "5 deg"}
    data.update(changes)
    return data


def daily_record(path: Path, days: int = 60) -> tuple[float, float]:
    """An hourly chamber log: 20 +/- 12 degC over each day (20 degC at every midnight, so
    the stored ageing times, all at midnight, see none of the swing); RH 50 +/- 30 %."""
    hours = np.arange(24 * days + 1)
    phase = 2 * np.pi * hours / 24
    temperature, humidity = 20 + 12 * np.sin(phase), 50 - 30 * np.sin(phase)
    rows = [f"{h},{t:.6f},{rh:.6f}" for h, t, rh in zip(hours, temperature, humidity)]
    path.write_text("time [h],temperature [degC],relative_humidity [%]\n" + "\n".join(rows) + "\n")
    return float(temperature.min()), float(temperature.max())


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    folder = tmp_path_factory.mktemp("scenes")
    cold, hot = daily_record(folder / "chamber.csv")
    record = short_scene("singh2017_cam")
    record["environment"] = {"reference_temperature": "23 degC", "history_file": "chamber.csv"}
    record.pop("limits")
    (folder / "record.yaml").write_text(yaml.safe_dump(record))
    return {"cam": fickcam.run(fickcam.load_scene(short_scene("singh2017_cam"))),
            "fourbar": fickcam.run(fickcam.load_scene(short_scene("fourbar_r914_humid"))),
            "record": fickcam.run(fickcam.load_scene(folder / "record.yaml")),
            "record_range": (cold, hot)}


def drawn(ds, folder) -> dict[str, Figure]:
    """Every figure `fickcam plot` draws for ``ds``, by file name, as it would be saved,
    drawn once on an Agg canvas (the PNG itself is not written: rendering it too doubled
    the cost, and the checks read the drawn artists)."""
    figures = {}

    def keep(fig, path, *args, **kwargs):
        # the file's name, also when it is written to a temporary file renamed over it
        figures[re.sub(r"^\.(.+)\.[^.]+\.tmp$", r"\1", Path(path).name)] = fig

    with pytest.MonkeyPatch.context() as monkeypatch:
        monkeypatch.setattr(Figure, "savefig", keep)  # matplotlib's, to keep the figures
        plotting.plot(ds, folder)
    for fig in figures.values():
        FigureCanvasAgg(fig).draw()
    return figures


@pytest.fixture(scope="module")
def figures(results, tmp_path_factory):
    return {name: drawn(results[name], tmp_path_factory.mktemp(name))
            for name in ("cam", "fourbar", "record")}


def data_axes(fig):
    return [ax for ax in fig.axes if ax.axison and (ax.get_lines() or ax.collections)
            and ax.get_label() != "<colorbar>"]


def x_label(ax) -> str:
    """The x label of ``ax``, or of the panel under it that shares its x axis."""
    return next((a.get_xlabel() for a in ax.get_shared_x_axes().get_siblings(ax) if a.get_xlabel()), "")


def test_every_data_axis_has_labels_with_units(figures):
    for result, by_name in figures.items():
        for name, fig in by_name.items():
            for ax in data_axes(fig):
                for label in (x_label(ax), ax.get_ylabel()):
                    assert UNIT.search(label), f"{result}/{name}: axis label {label!r} has no unit"


def points_in(ax, box) -> int:
    """How many drawn data points of ``ax``'s lines lie inside ``box`` (display units)."""
    inside = 0
    for line in ax.get_lines():
        xy = line.get_xydata()
        xy = xy[np.all(np.isfinite(xy), axis=1)]
        if len(xy) < 3:  # reference lines (axhline) and legend-only entries
            continue
        shown = ax.transData.transform(xy)
        inside += int(np.sum((shown[:, 0] > box.x0) & (shown[:, 0] < box.x1)
                             & (shown[:, 1] > box.y0) & (shown[:, 1] < box.y1)))
    return inside


def test_legends_cover_no_data(figures):
    for result, by_name in figures.items():
        for name, fig in by_name.items():
            renderer = fig.canvas.get_renderer()
            for ax in fig.axes:
                legend = ax.get_legend()
                if legend is None:
                    continue
                box = legend.get_window_extent(renderer)
                assert points_in(ax, box) == 0, f"{result}/{name}: legend covers data"


def test_each_ageing_time_has_one_colour_in_every_figure_of_a_result(figures):
    for result, by_name in figures.items():
        colours: dict[str, set] = {}
        for fig in by_name.values():
            for ax in fig.axes:
                for line in ax.get_lines():
                    if AGE.match(line.get_label()):
                        colours.setdefault(line.get_label(), set()).add(
                            matplotlib.colors.to_hex(line.get_color()))
        assert len(colours) >= 3, result
        assert all(len(c) == 1 for c in colours.values()), (result, colours)
        assert len({c.pop() for c in colours.values()}) == len(colours)  # and they differ


def drift_axes(fig):
    return [ax for ax in data_axes(fig)
            if re.search(r"− design|from design|design radius", ax.get_ylabel())]


def test_drift_fills_a_visible_part_of_its_axis(figures):
    checked = 0
    for result in ("cam", "fourbar"):
        for name, fig in figures[result].items():
            for ax in drift_axes(fig):
                values = np.concatenate([line.get_ydata() for line in ax.get_lines()
                                         if len(line.get_xdata()) > 2])
                low, high = ax.get_ylim()
                assert np.ptp(values[np.isfinite(values)]) > 0.3 * (high - low), (name, ax.get_ylabel())
                checked += 1
    assert checked >= 6


def test_plan_views_state_how_much_the_drift_is_exaggerated(figures):
    for result, name in (("cam", "cam_profile.png"), ("fourbar", "linkage_coupler_curve.png")):
        plan = figures[result][name].axes[0]
        factor = re.search(r"deviation from the design ×(\d+)", plan.get_title())
        assert factor and int(factor.group(1)) >= 2, plan.get_title()


def test_deviation_limits_are_labelled_with_what_they_plot(figures):
    labels = [ax.get_ylabel().replace("\n", " ") for ax in figures["cam"]["limits.png"].axes]
    assert any("|follower_displacement − design|" in label for label in labels), labels
    assert not any(label.startswith("follower_displacement [") for label in labels)


def test_climate_panel_draws_the_record_between_the_ageing_times(results, figures):
    cold, hot = results["record_range"]
    stored = results["record"]["temperature"].values - 273.15
    assert np.ptp(stored) < 0.5  # every ageing time is at midnight: the swing is unseen there
    temperature_ax = figures["record"]["uptake.png"].axes[0]
    band = temperature_ax.collections[0].get_paths()[0].vertices[:, 1]
    assert band.min() == pytest.approx(cold, abs=1e-6) and band.max() == pytest.approx(hot, abs=1e-6)
    means = results["record"]["climate_temperature"].values - 273.15
    np.testing.assert_allclose(means, 20.0, atol=1e-9)  # a whole sine period per day


def test_temperature_and_humidity_have_axes_of_their_own(figures):
    """Under a constant climate both are flat lines: on twin axes they would share pixels."""
    uptake = figures["cam"]["uptake.png"]
    climate = [ax for ax in uptake.axes if "temperature" in ax.get_ylabel()
               or "humidity" in ax.get_ylabel()]
    assert len(climate) == 2
    top, bottom = (ax.get_window_extent() for ax in climate)
    assert top.y0 > bottom.y1  # stacked, not overlaid


def test_interval_summary_is_exact_for_steps_and_ramps():
    """A ramp 1 -> 3 over [0, 10], a step to 5 held to 20, a step to 2 held (and past 30):
    means are the integrals by hand, extremes the values the pieces reach."""
    change = np.array([0.0, 10.0, 20.0, 30.0])
    mean, low, high = piecewise_linear_summary(change, np.array([1.0, 5.0, 2.0]),
                                               np.array([3.0, 5.0, 2.0]),
                                               np.array([0.0, 5.0, 15.0, 25.0, 40.0]))
    np.testing.assert_allclose(mean, [1.5, (2.5 * 5 + 5 * 5) / 10, (5 * 5 + 2 * 5) / 10, 2.0])
    np.testing.assert_array_equal(low, [1.0, 2.0, 2.0, 2.0])
    np.testing.assert_array_equal(high, [2.0, 5.0, 5.0, 2.0])
