"""
Nylon eccentric cam through two years of Greensboro weather
===========================================================

The nylon eccentric cam aged through a real climate: two passes of the typical
meteorological year (TMY3) of Greensboro, North Carolina, read from the data that ships
with pvlib (the ``weather`` extra).
"""

# %%
# Two years outdoors, hour by hour
# --------------------------------

import fickcam
from fickcam.scene import examples as example_scenes
from fickcam.cli.reporting import summary

ds = fickcam.run(example_scenes.path("eccentric_cam_greensboro"))
print(summary(ds, notices=False))


# %%
# Moisture through the seasons
# ----------------------------
# The cam's moisture against ageing time through the two weather years.

figures = fickcam.plotting.plot(ds, kind="uptake")


# %%
# What it says
# ------------
# Outdoors the cam does not saturate as in a constant damp climate: its moisture follows
# the seasons, and the summary above gives where it ends after two years.
