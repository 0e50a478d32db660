"""
The demo cam with a two-phase (Langmuir) matrix
===============================================

The demo carbon/epoxy cam with a SYNTHETIC two-phase matrix: part of the water binds to
the resin (Carter & Kibler's Langmuir model), so uptake continues long after Fick's law
would have saturated. 180 days at 113 °C and 80 % relative humidity.

The scene is ``singh2017_cam_two_phase.yaml``, one of the examples that come with fickcam
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

ds = fickcam.run(fickcam.load_scene(example_scenes.path("singh2017_cam_two_phase")))
print(summary(ds, notices=False))


# %%
# Free and bound water
# --------------------
# Moisture of cam and follower against ageing time.

figures = plot(ds, kind="uptake")


# %%
# What it says
# ------------
# The bound water keeps the cam taking up moisture, and growing, for months after the
# free water has saturated; the summary above gives when the follower's motion leaves
# its band.
