"""
The two-phase cam through a daily chamber log
=============================================

The two-phase cam aged through a SYNTHETIC daily chamber log (181 readings around
113 °C and 80 % relative humidity, joined linearly) instead of a constant climate.
"""

# %%
# Day by day through the chamber's log
# ------------------------------------

import fickcam
from fickcam.scene import examples as example_scenes
from fickcam.cli.reporting import summary

ds = fickcam.run(example_scenes.path("singh2017_cam_two_phase_daily"))
print(summary(ds, notices=False))


# %%
# Moisture through the log
# ------------------------
# Moisture of cam and follower against ageing time through the log.

figures = fickcam.plotting.plot(ds, kind="uptake")


# %%
# What it says
# ------------
# With the chamber's swings the follower leaves its band at about 15 days.
