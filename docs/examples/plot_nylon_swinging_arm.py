"""
Acetal cam with a nylon swinging arm
====================================

An acetal cam drives a nylon swinging roller arm, a year at 30 °C and 85 % relative
humidity. Both parts absorb water: the arm grows longer while the cam grows larger.
"""

# %%
# A pivoted arm that swells
# -------------------------

import fickcam
from fickcam.scene import examples as example_scenes
from fickcam.cli.reporting import summary

ds = fickcam.run(example_scenes.path("nylon_swinging_arm"))
print(summary(ds, notices=False))


# %%
# Arm angle and pressure angle
# ----------------------------
# The arm's angle, angular velocity and acceleration and the pressure angle over one
# turn, at several ages.

figures = fickcam.plotting.plot(ds, kind="kinematics")


# %%
# What it says
# ------------
# Cam and arm both swell: the summary above gives how far each quantity has moved from
# the design by the end of the year, and the figure where in the turn it moved.
