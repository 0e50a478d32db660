"""
The four-bar as Singh & Sanyal compute it: states given directly
================================================================

The same four-bar in 3502 resin computed the paper's way, without diffusion: as built,
hot and dry, then hot at its equilibrium moisture of 5 %, each state given directly in
``environment.state``.
"""

# %%
# Strains and temperatures as the paper states them
# -------------------------------------------------

import fickcam
from fickcam.scene import examples as example_scenes
from fickcam.cli.reporting import summary

ds = fickcam.run(example_scenes.path("singh2016_states"))
print(summary(ds, notices=False))


# %%
# Rocker angle in three states
# ----------------------------
# The rocker angle's shift from the design over a crank turn in each state.

figures = fickcam.plotting.plot(ds, kind="linkage")


# %%
# What it says
# ------------
# Hot and saturated, the rocker angle shifts by about 2.1°, as in the paper.
