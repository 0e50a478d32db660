"""Climate history: held and ramped segments, CSV histories, exposure."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fickcam.climate.environment import Environment, read_history_csv
from fickcam.scene.load import EnvironmentSection

DAY = 86400.0


def section(history, **extra):
    return EnvironmentSection.model_validate({"history": history, **extra})


def test_held_segments_step_at_segment_starts():
    env = Environment.from_section(section([
        {"duration": "10 d", "temperature": "60 degC", "relative_humidity": "80 %"},
        {"duration": "5 d", "temperature": "30 degC", "relative_humidity": "20 %"}]))
    t = np.array([0, 5, 10 - 1e-9, 10, 12, 15, 20]) * DAY
    assert np.allclose(env.temperature(t), [333.15] * 3 + [303.15] * 4)
    assert np.allclose(env.relative_humidity(t), [80] * 3 + [20] * 4)
    assert env.end == 15 * DAY


def test_ramp_is_linear_from_previous_end_values():
    env = Environment.from_section(section([
        {"duration": "1 d", "temperature": 300, "relative_humidity": 0},
        {"duration": "2 d", "temperature": 360, "relative_humidity": 90, "ramp": True}]))
    t = np.array([1.0, 1.5, 2.0, 3.0]) * DAY
    assert np.allclose(env.temperature(t), [300, 315, 330, 360])
    assert np.allclose(env.relative_humidity(t), [0, 22.5, 45, 90])


def test_csv_history_with_units_in_header(tmp_path):
    path = tmp_path / "chamber.csv"
    path.write_text("time [d],temperature [degC],relative_humidity [%]\n0,20,50\n10,80,90\n")
    record = read_history_csv(path)
    assert np.allclose(record.time, [0, 10 * DAY]) and np.allclose(record.temperature, [293.15, 353.15])
    env = Environment.from_samples(record.time, record.temperature, record.relative_humidity, 296.15)
    assert np.isclose(env.temperature(5 * DAY), 323.15)
    assert np.isclose(env.relative_humidity(2.5 * DAY), 60.0)


@pytest.mark.parametrize("text, fragment", [
    ("time [d],temperature [degC]\n0,20\n1,30\n", "bad.csv:1: no column relative_humidity"),
    ("time [d],temperature [degC],relative_humidity [%]\n0,20,50\n0,30,60\n",
     r"bad.csv:3 time: repeated timestamp \(also on line 2\)"),
    ("time [d],temperature [degC],relative_humidity [%]\n0,20,50\n1,30,160\n",
     "bad.csv:3 relative_humidity: 160 % is outside 0 to 100 %"),
    ("time [parsec],temperature [degC],relative_humidity [%]\n0,20,50\n1,30,60\n", "wrong dimension"),
    ("time [d],temperature [degC],relative_humidity [%]\n0,20,50\n1,x,60\n",
     "bad.csv:3 temperature: 'x' is not a number"),
])
def test_bad_csv_history_is_refused_with_reason(tmp_path, text, fragment):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=fragment):
        read_history_csv(path)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.floats(0.1, 100), st.floats(250, 400), st.floats(0, 100),
                          st.booleans()), min_size=1, max_size=6),
       st.floats(0, 1))
def test_history_stays_within_segment_values(segments, where):
    history = [{"duration": d * DAY, "temperature": T, "relative_humidity": f"{rh!r} %", "ramp": r and i > 0}
               for i, (d, T, rh, r) in enumerate(segments)]
    env = Environment.from_section(section(history))
    t = np.linspace(0, env.end * 1.1, 200)
    temps = [s[1] for s in segments]
    rh = env.relative_humidity(t)
    assert np.all(env.temperature(t) >= min(temps) - 1e-9)
    assert np.all(env.temperature(t) <= max(temps) + 1e-9)
    assert np.all((rh >= -1e-9) & (rh <= 100 + 1e-9))
