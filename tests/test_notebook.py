"""fickcam in a Jupyter notebook, executed by nbclient as a user's kernel runs it: figures
inline and the backend left alone, no Python or numpy warning text and no unlabelled
message in any output, a user error as its message alone, progress that leaves its
summary line, with and without ipywidgets."""
from __future__ import annotations

import re

import pytest

nbformat = pytest.importorskip("nbformat")
pytest.importorskip("nbclient")
pytest.importorskip("ipykernel")

from notebook_session import CELLS, execute, notebook  # noqa: E402

pytestmark = pytest.mark.slow

#: text that only Python, numpy, tqdm or a traceback writes
FOREIGN = re.compile(r"\b(?!Fickcam)\w*Warning: |All-NaN|Traceback|site-packages|"
                     r"IProgress not found|warnings\.warn\(")
#: a stderr line a user may see: fickcam's own, a FickcamWarning (with the user's line of
#: code under it), or a note of the 'fickcam' logger as the user's logging set-up formats it
LABELLED = re.compile(r"^(fickcam: |\S+:\d+: FickcamWarning: |  \S|fickcam(\.\w+)*: (INFO|"
                      r"WARNING|DEBUG): )")
SUMMARY = re.compile(r"^fickcam: run singh2017-cam: 2 parts, 3 ageing times in [\d.]+ s$")


@pytest.fixture(scope="module")
def session(tmp_path_factory):
    """The whole notebook, executed once."""
    book = execute(notebook(), tmp_path_factory.mktemp("notebook"))
    markers = [marker for marker, _ in CELLS]
    return {marker: cell.outputs for marker, cell in zip(markers, book.cells)}


def texts(outputs):
    """Every text a cell shows: streams, plain-text displays and error lines."""
    for out in outputs:
        if out.output_type == "stream":
            yield out.text
        elif out.output_type in ("display_data", "execute_result"):
            yield out.data.get("text/plain", "")
        elif out.output_type == "error":
            yield "\n".join(out.traceback)


def images(outputs) -> int:
    return sum("image/png" in out.get("data", {}) for out in outputs)


def test_figures_show_inline_and_the_backend_stays(session):
    assert "matplotlib_inline" in session["start"][0].text
    assert session["end"][0].text.rstrip().endswith("True")  # the same backend at the end
    assert images(session["plot_all"]) >= 6  # uptake, kinematics, drift, profile, dynamics...
    assert images(session["plot_kinds"]) == images(session["plot_all"])
    for marker in ("xarray_plot", "fourbar", "hot", "end", "fit"):
        assert images(session[marker]) >= 1, marker
    assert images(session["sweep"]) >= 2  # the sweep's outputs over the humidity, and over time


def test_no_cell_shows_foreign_warning_text_or_an_unlabelled_line(session):
    for marker, outputs in session.items():
        if marker == "bad_scene":
            continue
        for text in texts(outputs):
            assert not FOREIGN.search(text), (marker, text)
        for out in outputs:
            if out.output_type == "stream" and out.name == "stderr":
                lines = [line for line in out.text.splitlines() if line.strip()]
                assert all(LABELLED.match(line) for line in lines), (marker, out.text)


def test_a_warning_is_a_fickcam_warning_at_the_users_line_and_notes_need_the_logger(session):
    hot = "".join(out.text for out in session["hot"] if out.output_type == "stream")
    assert "FickcamWarning: cam at t = 30 d: service temperature 150.0 degC reached the wet " \
           "Tg" in hot and "hot_ds = fickcam.run(hot)" in hot
    quiet = "".join(out.text for out in session["fourbar"] if out.output_type == "stream")
    loud = "".join(out.text for out in session["notes"] if out.output_type == "stream")
    assert "Grashof class" not in quiet  # notes are off until the user switches them on
    assert "fickcam.simulation.ageing: INFO: at t = 0 h to 1 h (2 ageing times): Grashof class: " \
           "crank-rocker" in loud


def test_a_user_error_is_its_message_alone(session):
    [error] = [out for out in session["bad_scene"] if out.output_type == "error"]
    shown = re.sub(r"\x1b\[[\d;]*m", "", "\n".join(error.traceback))
    assert error.ename == "SceneError"
    assert shown == "SceneError: bad_cam.yaml:41 cam.thicknes: unknown key; did you mean " \
                    "'thickness'?"


def test_the_scene_and_a_selection_say_their_units(session):
    [scene] = session["scene"]
    assert "climate:   60 d at 113 degC, 80 % RH" in scene.data["text/plain"]
    assert "<table>" in scene.data["text/html"] and "1000 rpm" in scene.data["text/html"]
    assert len(scene.data["text/plain"].splitlines()) <= 8
    [attrs] = session["select"]
    assert "'time_span_s': 5184000.0" in attrs.data["text/plain"]


@pytest.mark.parametrize("widgets", [True, False], ids=["ipywidgets", "text"])
def test_progress_leaves_its_summary_line_alone(session, widgets, tmp_path):
    if widgets:
        pytest.importorskip("ipywidgets")
        outputs = session["run"]
    else:
        book = execute(notebook(without_widgets=True, only={"start", "scene", "run"}), tmp_path)
        outputs = book.cells[-1].outputs
    shown = [out.data["text/plain"] for out in outputs if out.output_type == "display_data"]
    assert len(shown) == 1 and SUMMARY.match(shown[0]), shown
    for text in texts(outputs):
        assert not FOREIGN.search(text) and "\r" not in text, text
