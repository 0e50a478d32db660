"""
Epoxy push rod: the follower train's vibration as it ages
=========================================================

A steel cam drives a flat tappet on a neat-epoxy push rod, aged a year at 40 °C and 85 %
relative humidity. The push rod is elastic: the follower train has a natural frequency,
and above a dynamic jump speed the tappet leaves the cam.
"""

# %%
# The push rod and its spring, wet
# --------------------------------

import fickcam
from fickcam.scene import examples as example_scenes
from fickcam.cli.reporting import summary

ds = fickcam.run(example_scenes.path("epoxy_follower_vibration"))
print(summary(ds, notices=False))


# %%
# Dynamic against rigid follower
# ------------------------------
# Displacement and contact force of the elastic follower train against the rigid one
# over a turn, at several ages.

figures = fickcam.plotting.plot(ds, kind="vibration")


# %%
# What it says
# ------------
# As the epoxy takes up water and softens, the natural frequency falls from about 480 to
# 450 Hz and the dynamic jump speed from 2824 to 2768 rpm.
