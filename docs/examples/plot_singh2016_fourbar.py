"""
R914 four-bar at 118 °C and 100 % RH, hour by hour
==================================================

Singh & Sanyal's (2016) R914 four-bar put into 118 °C and 100 % relative humidity,
computed with moisture diffusing into its links, every 10 minutes. At this temperature the
wet resin's glass transition is reached within hours.
"""

# %%
# Three hours near the wet glass transition
# -----------------------------------------

import fickcam
from fickcam.scene import examples as example_scenes
from fickcam.cli.reporting import summary

ds = fickcam.run(example_scenes.path("singh2016_fourbar"))
print(summary(ds, notices=False))


# %%
# Moisture uptake of the links
# ----------------------------
# Mean moisture of each link against ageing time, until the run stops a part whose
# surface layer reaches its wet glass transition temperature (a notice says when).

figures = fickcam.plotting.plot(ds, kind="uptake")


# %%
# What it says
# ------------
# The links take up water fast at 118 °C; after about 2.5 hours their surface reaches
# its wet glass transition, and fickcam stops computing them there, keeping the earlier
# results.
