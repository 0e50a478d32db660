"""What sweep cases reuse from earlier cases given the same run cache (the planform mesh,
its operator and unit-step response, the outline expansion) is keyed by the exact inputs:
a case that changes the cam thickness or the fibre fraction never gets a stale entry,
and a case that repeats a geometry gets the same numbers as a fresh cache."""
import numpy as np
import pytest
import xarray as xr
import yaml

import fickcam
from fickcam.diffusion import CamPlate, RunCache
from test_sweep_run import small_base


def scene(**changes):
    data = yaml.safe_load(small_base())
    data.pop("limits")
    data["cam"]["thickness"] = changes.get("thickness", data["cam"]["thickness"])
    fraction = changes.get("fraction")
    if fraction is not None:
        data["materials"]["cfrp"]["fiber_volume_fraction"] = fraction
    return fickcam.load_scene(data)


def fresh(data):
    """The run with a cache of its own."""
    return fickcam.run(data)


def test_cam_plates_are_equal_exactly_when_their_values_are():
    x, y = np.cos(np.linspace(0, 6, 50)), np.sin(np.linspace(0, 6, 50))
    plate = CamPlate(x, y, 0.012, 0.01)
    assert plate == CamPlate(x.copy(), y.copy(), 0.012, 0.01)
    assert hash(plate) == hash(CamPlate(x.copy(), y.copy(), 0.012, 0.01))
    assert plate != CamPlate(x, y, 0.0125, 0.01) and plate != CamPlate(x, y, 0.012, 0.011)
    moved = y.copy()
    moved[7] += 1e-12
    assert plate != CamPlate(x, moved, 0.012, 0.01)
    x[3] = 5.0  # the caller's array changes afterwards: the plate keeps its own copy
    assert plate.profile_x[3] != 5.0 and not plate.profile_x.flags.writeable


@pytest.mark.slow
@pytest.mark.parametrize("change", [{"thickness": "12.5 mm"}, {"fraction": 0.55}])
def test_a_changed_thickness_or_fibre_fraction_never_reuses_a_stale_entry(change):
    base, changed, shared = scene(), scene(**change), RunCache()
    fickcam.run(base, cache=shared)
    after_base = fickcam.run(changed, cache=shared)  # the base case's entries are in it
    xr.testing.assert_identical(after_base.drop_attrs(), fresh(changed).drop_attrs())
    assert not after_base.equals(fickcam.run(base, cache=shared))


def test_a_repeated_geometry_reuses_the_step_response_and_gives_the_same_numbers():
    shared = RunCache()

    def responses():
        return {key for key in shared.keys() if key[0] == "planform response"}
    first = fickcam.run(scene(), cache=shared)
    marched = responses()
    again = fickcam.run(scene(), cache=shared)
    assert marched and responses() == marched, "the repeat marched again"
    xr.testing.assert_identical(again.drop_attrs(), first.drop_attrs())
    xr.testing.assert_identical(fresh(scene()).drop_attrs(), first.drop_attrs())


def test_a_sweep_worker_passes_its_cache_to_each_case():
    """``run_case`` with the worker's cache: a second case of the same part marches nothing
    again; the records agree."""
    from fickcam.sweep.case import CaseTask, run_case

    data = yaml.safe_load(small_base())
    data.pop("limits")
    task = CaseTask(0, data, {}, "case 0", ".")
    worker = RunCache()
    first, _ = run_case(task, worker)
    def responses():
        return {key for key in worker.keys() if key[0] == "planform response"}
    marched = responses()
    second, _ = run_case(task, worker)
    assert first["status"] == second["status"] == "ok"
    assert marched and responses() == marched
