"""
Acetal four-bar with a drawn dog-bone crank
===========================================

A four-bar whose crank comes from its DXF drawing: an acetal (POM) dog-bone, two bosses of
14 mm radius joined by a web 8 mm wide, its pin holes 100 mm apart on layer PIN. The
coupler and rocker are bars between bosses given by their lengths, the frame is steel.
Three months at 40 °C and 90 % relative humidity.
"""

# %%
# The drawn crank
# ---------------
# The scene names the drawing (``crank: {drawing: {file: acetal_dogbone_crank.dxf,
# pin_layer: PIN}}``); `fickcam check` says what it read: the distance of the pins, the
# dry mass and where the centre of mass lies.

import matplotlib.pyplot as plt
import numpy as np

import fickcam
from fickcam.cli.reporting import summary
from fickcam.scene import examples as example_scenes

scene = fickcam.load_scene(example_scenes.path("fourbar_acetal_dogbone"))
linkage = scene.mechanisms[0]
print("\n".join(linkage.described()))

# %%
# The outline as read
# -------------------
# The crank's outline and pin holes as read from the drawing, in the link's frame (first
# pin at the origin, the second on +x): the lines and arcs flattened to chords within the
# tolerance the scene's accuracy sets. This is the planform the moisture is solved on.

crank = linkage.drawn["crank"]
fig, ax = plt.subplots(figsize=(7, 2.6))
for loop in crank.planform.loops:
    x, y = np.vstack([loop.points, loop.points[:1]]).T * 1e3
    ax.plot(x, y, color="k", lw=1.2)
ax.set_aspect("equal")
ax.set_xlabel("x along the crank [mm]")
ax.set_ylabel("y [mm]")
ax.set_title(f"drawn crank: pins {crank.length * 1e3:.1f} mm apart")
fig.tight_layout()

# %%
# Ageing
# ------

ds = fickcam.run(scene)
print(summary(ds, notices=False))

# %%
# The web takes up water first
# ----------------------------
# The mean moisture of the drawn dog-bone crank against the coupler, a 20 mm bar between
# bosses: the crank's thin web fills sooner, so in the first week it holds more water and
# grows more, and both reach the same saturation.

fig, ax = plt.subplots(figsize=(6, 3.5))
for link in ("crank", "coupler"):
    ax.plot(ds["time"], ds["moisture_content"].sel(part=link), "o-", label=link)
ax.set_xlabel(f"ageing time [{ds['time'].attrs.get('units', 'd')}]")
ax.set_ylabel("mean moisture [%]")
ax.legend()
fig.tight_layout()

# %%
# Rocker drift
# ------------
# The rocker angle's drift from the design over a crank turn at each age, as the links
# grow with their moisture.

figures = fickcam.plotting.plot(ds, kind="linkage")
