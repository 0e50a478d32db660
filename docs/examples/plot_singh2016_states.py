"""
The four-bar as Singh & Sanyal compute it: states given directly
================================================================

The same four-bar in 3502 resin computed the paper's way, without diffusion: as built,
hot and dry, then hot at its equilibrium moisture of 5 %, each state given directly in
``environment.state``.

The scene is ``singh2016_states.yaml``, one of the examples that come with fickcam
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

ds = fickcam.run(fickcam.load_scene(example_scenes.path("singh2016_states")))
print(summary(ds, notices=False))


# %%
# Rocker angle in three states
# ----------------------------
# The rocker angle's shift from the design over a crank turn in each state.

figures = plot(ds, kind="linkage")


# %%
# What it says
# ------------
# Hot and saturated, the rocker angle shifts by about 2.1°, as in the paper.
