"""
Carbon/epoxy cam plate as drawn: a keyway and lightening holes
==============================================================

A cam plate given by its DXF drawing: quasi-isotropic carbon(T300)/epoxy(8551-7), 10 mm
thick, its working profile a cycloidal rise and return of 12 mm on a 40 mm base circle, a
16 mm bore with a keyway for a 5 x 5 key and three lightening holes of 14 mm. Half a year
at 70 °C and 85 % relative humidity. Every edge takes up water, the holes' too, and the
aged working profile is the drawn outline displaced by the plate's moisture field.
"""

# %%
# The drawn plate
# ---------------
# The scene names the drawing (``drawing: carbon_epoxy_cam_plate.dxf``); `fickcam check`
# says what it read: the plate's dry mass, centre of mass and moment of inertia about the
# axis, from the outline and every hole by Green's theorem.

import matplotlib.pyplot as plt
import numpy as np
import yaml
from matplotlib.tri import Triangulation

import fickcam
from fickcam.cli.reporting import summary
from fickcam.drawing.planform import inside
from fickcam.plotting.cam import polar, radial_deviation
from fickcam.scene import examples as example_scenes

scene = fickcam.load_scene(example_scenes.path("carbon_epoxy_cam_plate"))
cam = scene.mechanisms[0]
planform = cam.planform
print("\n".join(cam.described()))


def draw_plate(ax, colour="k", width=1.0):
    """The drawn outline and holes, in mm."""
    for loop in planform.loops:
        x, y = np.vstack([loop.points, loop.points[:1]]).T * 1e3
        ax.plot(x, y, color=colour, lw=width)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")


# %%
# The outline as read
# -------------------
# The working profile (a polyline of 720 points), the keyed bore (an arc and three lines)
# and the lightening holes (circles), about the cam's axis: the planform the moisture is
# solved on.

fig, ax = plt.subplots(figsize=(5, 5))
draw_plate(ax)
ax.plot(0, 0, "k+", ms=10)
ax.set_ylabel("y [mm]")
ax.set_title("drawn cam plate, about its axis")
fig.tight_layout()

# %%
# Ageing
# ------

ds = fickcam.run(scene)
print(summary(ds, notices=False))

# %%
# The moisture field over the plate
# ---------------------------------
# The moisture at mid-thickness over the plate at three ages: the water comes in through
# the faces and through every edge, the lightening holes' and the bore's too, so the
# plate between the holes fills last.

x, y = (ds[f"cell_{a}"].sel(part="cam").values for a in "xy")
cells = Triangulation(x * 1e3, y * 1e3)
centres = np.column_stack([x[cells.triangles].mean(axis=1), y[cells.triangles].mean(axis=1)])
material = inside(centres, planform.outer)
for hole in planform.holes:
    material &= ~inside(centres, hole)
cells.set_mask(~material)
picks = [1, 2, 4]
top = float(np.nanmax(ds["moisture"].sel(part="cam")))
fig, axes = plt.subplots(1, 3, figsize=(11, 4), sharey=True)
for ax, k in zip(axes, picks):
    shading = ax.tripcolor(cells, ds["moisture"].sel(part="cam").isel(time=k).values,
                           shading="gouraud", vmin=0.0, vmax=top, cmap="Blues")
    draw_plate(ax, width=0.6)
    ax.set_title(f"{float(ds['time'][k]):g} d")
axes[0].set_ylabel("y [mm]")
fig.colorbar(shading, ax=axes, label="moisture at mid-thickness [%]", shrink=0.8)

# %%
# The displaced outline
# ---------------------
# The aged working profile at three ages against the drawn one, its displacement from the
# drawing multiplied by 2000 so that it shows (a quasi-isotropic carbon/epoxy plate swells
# by a few micrometres): the plate grows about its axis as its moisture rises.

SCALE = 2000
angle, radius = polar(ds["profile_x_design"].values, ds["profile_y_design"].values)
order = np.argsort(angle)
angle, radius = angle[order], radius[order]
unit = np.radians(angle)
fig, ax = plt.subplots(figsize=(5.5, 5.5))
draw_plate(ax, colour="0.5", width=0.8)
for k in picks:
    aged = ds["profile_x"].isel(time=k).values, ds["profile_y"].isel(time=k).values
    shown = radius + SCALE * radial_deviation((angle, radius), *aged)
    ax.plot(np.append(shown * np.cos(unit), shown[0] * np.cos(unit[0])) * 1e3,
            np.append(shown * np.sin(unit), shown[0] * np.sin(unit[0])) * 1e3,
            label=f"{float(ds['time'][k]):g} d")
ax.set_ylabel("y [mm]")
ax.set_title(f"aged working profile, displacement from the drawing × {SCALE}\n"
             f"(grey: the plate as drawn)", fontsize=10)
ax.legend(loc="lower left", fontsize=8)
fig.tight_layout()

# %%
# What the field's unevenness adds
# --------------------------------
# The same plate aged with its profile scaled by its mean strain
# (``aged_profile: mean_strain``): the radius of the displaced outline minus the scaled
# one's, over the polar angle. The wet rims of the holes and of the profile swell before
# the core, and the profile moves by what the field gives, beyond its mean.

path = example_scenes.path("carbon_epoxy_cam_plate")
data = yaml.safe_load(path.read_text())
data["cam"].update(aged_profile="mean_strain", drawing=str(path.parent / data["cam"]["drawing"]))
scaled = fickcam.run(fickcam.load_scene(data))
fig, ax = plt.subplots(figsize=(7, 3.5))
for k in picks:
    field = radial_deviation((angle, radius), ds["profile_x"].isel(time=k).values,
                             ds["profile_y"].isel(time=k).values)
    mean = radial_deviation((angle, radius), scaled["profile_x"].isel(time=k).values,
                            scaled["profile_y"].isel(time=k).values)
    ax.plot(angle, (field - mean) * 1e6, label=f"{float(ds['time'][k]):g} d")
ax.axhline(0.0, color="k", lw=0.8, ls="--")
ax.set_xlabel("polar angle on the cam [deg]")
ax.set_ylabel("field − mean strain [µm]")
ax.legend(fontsize=8)
fig.tight_layout()
