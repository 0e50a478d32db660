"""A notebook as a new user writes it from the guide (small scenes, so that it runs in
seconds): scenes shown, runs with progress, every public plotting function, xarray's
``.plot()``, a part past its wet glass transition, a two-case sweep, a material fit and a
misspelt key. Executed with
nbclient by ``test_notebook.py``; ``python tests/notebook_session.py OUT.ipynb`` writes and
executes it to look at (``jupyter nbconvert --to html``)."""
from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: (marker, source): the marker names the cell for the test's checks
CELLS = [
    ("start", """\
import logging, matplotlib, yaml
import fickcam
BACKEND = matplotlib.get_backend()
print("backend:", BACKEND)"""),
    ("scene", f"""\
data = yaml.safe_load(open({str(ROOT / 'configs' / 'singh2017_cam.yaml')!r}))
data["outputs"] = {{"ageing_times": ["0 d", "30 d", "60 d"], "angle_step": "6 deg"}}
scene = fickcam.load_scene(data, file_name="cam.yaml")
scene"""),
    ("run", """\
ds = fickcam.run(scene, progress=True)"""),
    ("plot_all", """\
fickcam.plotting.plot(ds)"""),
    ("plot_kinds", """\
import importlib
from IPython.display import display
for kind in fickcam.plotting.available_kinds(ds):
    module, function, _ = fickcam.plotting.KINDS[kind]
    display(getattr(importlib.import_module(f"fickcam.plotting.{module}"), function)(ds))"""),
    ("xarray_plot", """\
ds.lift.plot()"""),
    ("fourbar", f"""\
four = yaml.safe_load(open({str(ROOT / 'configs' / 'singh2016_fourbar.yaml')!r}))
four["outputs"] = {{"ageing_times": ["0 h", "1 h", "2.5 h", "3 h"], "angle_step": "10 deg"}}
linkage = fickcam.run(four)
fickcam.plotting.plot(linkage, kind="linkage")"""),
    ("notes", """\
logging.basicConfig(format="%(name)s: %(levelname)s: %(message)s")
logging.getLogger("fickcam").setLevel(logging.INFO)
four_again = fickcam.run(four)"""),
    ("hot", """\
logging.getLogger("fickcam").setLevel(logging.WARNING)
hot = dict(data, environment={"history": [{"duration": "60 d", "temperature": "150 degC",
                                           "relative_humidity": "85 %"}]})
hot_ds = fickcam.run(hot)
fickcam.plotting.plot(hot_ds, kind="kinematics")"""),
    ("sweep", """\
from fickcam.sweep import run_sweep
with open("cam.yaml", "w") as file:
    yaml.safe_dump(data, file)
with open("sweep.yaml", "w") as file:
    yaml.safe_dump({"base": "cam.yaml",
                    "grid": {"environment.history.0.relative_humidity": ["50 %", "80 %"]}}, file)
swept = fickcam.open_result(run_sweep("sweep.yaml", "sweep.h5"))
fickcam.plotting.plot(swept)"""),
    ("fit", """\
from fickcam.fit import fit_weight_gain, plot_fit
from fickcam.fit.synthetic import d5229_times, synthetic_specimen
import numpy as np
rng = np.random.default_rng(13)
coupons = [synthetic_specimen(f"s{k}", 333.15, 85.0, 2e-3, d5229_times(60.0), 2.0, 5e-12, rng, 0.01)
           for k in range(2)]
plot_fit(fit_weight_gain(coupons, "3502", name="coupons"))"""),
    ("select", """\
from fickcam.results.query import select
select(ds, "lift", time="6 weeks").attrs"""),
    ("bad_scene", """\
bad = dict(data)
bad["cam"] = dict(data["cam"], thicknes=data["cam"]["thickness"])
fickcam.load_scene(bad, file_name="bad_cam.yaml")"""),
    ("end", """\
import matplotlib.pyplot as plt
plt.plot([0, 1], [0, 1])
print("backend:", matplotlib.get_backend(), matplotlib.get_backend() == BACKEND)"""),
]

#: the first cell of the notebook that runs without ipywidgets
WITHOUT_WIDGETS = 'import sys; sys.modules["ipywidgets"] = None  # as if not installed'


def notebook(without_widgets: bool = False, only=None):
    """The notebook (nbformat v4); ``only``: the markers of the cells kept."""
    import nbformat

    cells = [source for marker, source in CELLS if only is None or marker in only]
    if without_widgets:
        cells.insert(0, WITHOUT_WIDGETS)
    book = nbformat.v4.new_notebook()
    book.cells = [nbformat.v4.new_code_cell(source) for source in cells]
    book.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                   "language": "python"}
    return book


def execute(book, folder: Path):
    """Run ``book`` in a fresh kernel in ``folder`` (errors stay in their cells)."""
    from nbclient import NotebookClient

    NotebookClient(book, timeout=600, kernel_name="python3", allow_errors=True,
                   resources={"metadata": {"path": str(folder)}}).execute()
    return book


if __name__ == "__main__":
    import nbformat

    target = Path(sys.argv[1])
    nbformat.write(execute(notebook("--without-widgets" in sys.argv), target.parent), target)
