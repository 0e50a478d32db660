"""
Nylon eccentric cam through two years of Greensboro weather
===========================================================

The nylon eccentric cam aged through a real climate: two passes of the typical
meteorological year (TMY3) of Greensboro, North Carolina, read from the data that ships
with pvlib (the ``weather`` extra).

The scene is ``eccentric_cam_greensboro.yaml``, one of the examples that come with fickcam
(``fickcam examples --copy DIR`` writes it to ``DIR`` to edit and run).
"""

# %%
# Run the scene
# -------------
# :func:`fickcam.run` ages it and returns the result, an :class:`xarray.Dataset`;
# the summary is what ``fickcam run`` prints.

import fickcam
from fickcam.scene import examples as example_scenes
from fickcam.plotting import plot
from fickcam.cli.reporting import summary

ds = fickcam.run(fickcam.load_scene(example_scenes.path("eccentric_cam_greensboro")))
print(summary(ds, notices=False))


# %%
# Moisture through the seasons
# ----------------------------
# The cam's moisture against ageing time through the two weather years.

figures = plot(ds, kind="uptake")


# %%
# What it says
# ------------
# Outdoors the cam does not saturate as in a constant damp climate: its moisture follows
# the seasons, and the summary above gives where it ends after two years.
