"""Helpers of the example gallery (sphinx-gallery runs the scripts in ``docs/examples/``)."""
from __future__ import annotations


class TightFigures:
    """sphinx-gallery's matplotlib scraper, saving each figure as fickcam's own plots are
    saved: cropped to what is drawn, so that legends outside the axes are kept."""

    def __repr__(self):  # a stable name, so that Sphinx's environment stays cached
        return "fickcam-tight-figures"

    def __call__(self, block, block_vars, gallery_conf):
        from sphinx_gallery.scrapers import matplotlib_scraper

        return matplotlib_scraper(block, block_vars, gallery_conf, bbox_inches="tight")
