"""
Composite box cam: contact deflection and swelling stress
=========================================================

An orthotropic T300/epoxy box cam with two noses, clamped at its bore, after Al-Shamma &
Yousuf (2011), 60 days at 60 °C and 85 % relative humidity. ``cam.elastic: true`` adds
the elastic part: the deflection under the contact load and the stress from swelling.
"""

# %%
# Age the box cam, clamped at its bore
# ------------------------------------

import fickcam
from fickcam.scene import examples as example_scenes
from fickcam.cli.reporting import summary

ds = fickcam.run(example_scenes.path("alshamma2011_box_cam"))
print(summary(ds, notices=False))


# %%
# Deflection and swelling stress
# ------------------------------
# Contact deflection over the cam angle, and the swelling stress and failure index in
# the plate, at several ages.

figures = fickcam.plotting.plot(ds, kind="elastic")


# %%
# What it says
# ------------
# The summary above gives the cam's moisture and the largest deflection and stress at
# the start and the end; the figures show how they change over the cam angle and with
# age.
#
# The warning under the run is about the cam as drawn: its simple-harmonic segments step
# the acceleration at every joint, which excites vibration whatever the cam's age (a
# cycloidal or polynomial law would not).
