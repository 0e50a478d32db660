"""
The demo cam with a two-phase (Langmuir) matrix
===============================================

The demo carbon/epoxy cam with a SYNTHETIC two-phase matrix: part of the water binds to
the resin (Carter & Kibler's Langmuir model), so uptake continues long after Fick's law
would have saturated. 180 days at 113 °C and 80 % relative humidity.
"""

# %%
# Free and bound water in the matrix
# ----------------------------------

import fickcam
from fickcam.scene import examples as example_scenes
from fickcam.cli.reporting import summary

ds = fickcam.run(example_scenes.path("singh2017_cam_two_phase"))
print(summary(ds, notices=False))


# %%
# Free and bound water
# --------------------
# Moisture of cam and follower against ageing time.

figures = fickcam.plotting.plot(ds, kind="uptake")


# %%
# What it says
# ------------
# The bound water keeps the cam taking up moisture, and growing, for months after the
# free water has saturated; the summary above gives when the follower's motion leaves
# its band.
