"""Helpers of the example gallery (sphinx-gallery runs the scripts in ``docs/examples/``)."""
from __future__ import annotations

SHOWN = "__fickcam_figures_shown__"  # the figures already on the page, kept (ids stay unique)


def _figures_in(value):
    """The matplotlib figures a value holds: a Figure, or a list of them (plot's Figures)."""
    from matplotlib.figure import Figure

    if isinstance(value, Figure):
        return [value]
    if isinstance(value, (list, tuple)):
        return [item for item in value if isinstance(item, Figure)]
    return []


class TightFigures:
    """sphinx-gallery's image scraper for the figures fickcam's plot functions return.

    fickcam draws on :class:`matplotlib.figure.Figure` objects without pyplot, so the stock
    scraper, which asks pyplot, sees none of them: this one saves every figure that a code
    block left in the example's variables and that no earlier block saved, then what pyplot
    holds (an xarray ``.plot()``). Figures are cropped to what is drawn, as fickcam saves
    them, so that legends outside the axes are kept.
    """

    def __repr__(self):  # a stable name, so that Sphinx's environment stays cached
        return "fickcam-tight-figures"

    def __call__(self, block, block_vars, gallery_conf):
        import matplotlib.pyplot as plt
        from sphinx_gallery.scrapers import figure_rst, matplotlib_scraper

        names = block_vars["example_globals"]
        shown = names.setdefault(SHOWN, [])
        paths = []
        for value in list(names.values()):
            for figure in _figures_in(value):
                if any(figure is seen for seen in shown):
                    continue
                shown.append(figure)
                path = next(block_vars["image_path_iterator"])
                figure.savefig(path, bbox_inches="tight")
                plt.close(figure)  # one pyplot made: the stock scraper below would save it again
                paths.append(path)
        own = figure_rst(paths, gallery_conf["src_dir"]) if paths else ""
        return own + matplotlib_scraper(block, block_vars, gallery_conf, bbox_inches="tight")


def script_names_only(app, docname, source):
    """Sphinx's ``source-read``: a gallery page's output names a script as a reader who
    downloads it does (``plot_x.py:26: FickcamWarning: ...``), not by the path it was built
    from."""
    if docname.startswith("gallery/"):
        from pathlib import Path

        folder = str(Path(app.srcdir) / "examples") + "/"
        source[0] = source[0].replace(folder, "")


def setup(app):
    """Register the gallery's page filter."""
    app.connect("source-read", script_names_only)
