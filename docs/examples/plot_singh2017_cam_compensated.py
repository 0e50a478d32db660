"""
The same cam made to compensate: it stays in spec for 60 days
=============================================================

The demo carbon/epoxy cam as ``fickcam compensate --over "0 d" "60 d" --points`` makes
it: the profile given by its points, smaller by the growth it will see, and the
original geometry kept under ``design:``. Its limits are checked against that design.
"""

# %%
# The made profile, aged the same
# -------------------------------

import fickcam
from fickcam.scene import examples as example_scenes
from fickcam.cli.reporting import summary

ds = fickcam.run(example_scenes.path("singh2017_cam_compensated"))
print(summary(ds, notices=False))


# %%
# The limits of the compensated cam
# ---------------------------------
# The follower's largest deviation from the designed motion now stays far inside the
# 0.25 mm band for the whole 60 days; the other limits hold as before.

figures = fickcam.plotting.plot(ds, kind="limits")


# %%
# What it says
# ------------
# Made to these dimensions, the cam stays in spec for the whole window: the deviation is
# about a tenth of the band the cam as drawn broke.
