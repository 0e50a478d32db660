"""What sweep cases reuse from earlier cases given the same run cache (the planform mesh,
its operator and unit-step response, the outline expansion) is keyed by the exact inputs:
a case that changes the cam thickness or the fibre fraction never gets a stale entry,
a case that repeats a geometry gets the same numbers as a fresh cache, cases that differ
only in what the outline does not read (an isotropic part's D0) share its expansion, and a
sampled value that changes the plan (D0, a temperature) gets the parts of it that change
built again; every case equals its single run with a fresh cache."""
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

import fickcam
from fickcam.diffusion import CamPlate, RunCache
from fickcam.simulation.planning import plan_parts
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


# ---------------------------------------------------------------- what a worker's cases share

ECCENTRIC = Path(__file__).resolve().parents[1] / "configs" / "eccentric_cam.yaml"


def bored_nylon_cam(pre_exponential: str = "3.85e-4 m^2/s", temperature: str = "40 degC"):
    """The nylon eccentric cam with a 5 mm bore (a CamPlate: the plane model, its outline
    expansion, mesh and step response) and its diffusivity's D0 written out, as a Monte
    Carlo of an uncertain D0 or climate would vary them; three ageing times."""
    data = yaml.safe_load(ECCENTRIC.read_text())
    data["cam"]["bore_radius"] = "5 mm"
    data["materials"]["nylon"]["matrix_properties"] = {"diffusivity": {
        "pre_exponential": pre_exponential, "activation_energy": "50 kJ/mol"}}
    data["environment"]["history"][0]["temperature"] = temperature
    data["outputs"] = {"ageing_times": ["0 d", "90 d", "180 d"], "angle_step": "10 deg"}
    data["diffusion"] = {"accuracy": 5e-3}
    return data


def worker_case(data: dict, cache: RunCache) -> xr.Dataset:
    """A sweep worker's run of one case (``run_case`` with the worker's cache), as the
    journal carries it."""
    from fickcam.sweep.case import CaseTask, run_case
    from fickcam.sweep.journal import decode_dataset

    record, payload = run_case(CaseTask(0, data, {}, "case 0", str(ECCENTRIC.parent)), cache)
    assert record["status"] == "ok", record["message"]
    return decode_dataset(payload)


def plane_plan(data: dict):
    """The cam's plane plan, as ``fickcam check`` shows it."""
    chosen, = (plan for part, plan in plan_parts(fickcam.load_scene(data))[-1]
               if part.name == "cam")
    assert chosen.model == "plane"
    return chosen


def built(cache: RunCache, tag: str) -> list:
    return [key for key in cache.keys() if key[0] == tag]


@pytest.mark.slow  # six runs of a cam and three plans (about 1 s each)
def test_cases_of_another_d0_share_the_outline_but_not_what_d0_changes_in_the_plan():
    """D0 of an isotropic part does not scale its outline (the scaled coordinates read only
    D_z / D_x and D_z / D_y), so a worker's cases share the outline's expansion and chords;
    D0 does move the ages the outputs read, so the plans differ (sheet cells, the step
    response's end, for the smallest D0 no mesh at all) and the step responses are each
    case's own; the mesh is shared exactly when the plans' spacing and growth agree. Every
    case equals its single run with a fresh cache, exactly."""
    values = ["3.85e-4 m^2/s", "2e-4 m^2/s", "1e-4 m^2/s"]
    scenes = [bored_nylon_cam(value) for value in values]
    plans = [plane_plan(data) for data in scenes]
    assert len({(p.cells, p.steps) for p in plans}) == 3, "D0 does not change the plan here"
    assert plans[-1].cells == 0 and plans[0].cells > 0   # the smallest D0: no mesh
    worker = RunCache()
    for data in scenes:
        xr.testing.assert_identical(worker_case(data, worker).drop_attrs(),
                                    worker_case(data, RunCache()).drop_attrs())
    assert len(built(worker, "outline expansion")) == 1
    assert len(built(worker, "outline chords")) == 1
    meshed = [p for p in plans if p.cells > 0]
    assert len(built(worker, "planform mesh")) == len({(p.finest, p.growth) for p in meshed})
    assert len(built(worker, "planform response")) == len(meshed)


@pytest.mark.slow  # four runs of the demo cam at its own accuracy (about 1 s each)
def test_a_temperature_that_changes_the_mesh_spacing_gets_its_own_mesh():
    """The demo cam at 113 and 111.9 degC: the faster diffusion moves the ages the plan's
    mesh must serve and so its finest spacing; the second case builds its own mesh (the
    outline's expansion, which no temperature changes, it shares) and equals its single
    run."""
    def demo(temperature):
        data = yaml.safe_load(small_base())
        data.pop("limits")
        data["diffusion"]["accuracy"] = 1e-3
        data["environment"]["history"][0]["temperature"] = temperature
        return data
    scenes = [demo("113 degC"), demo("111.9 degC")]
    first, second = (plane_plan(data) for data in scenes)
    assert first.finest != second.finest
    worker = RunCache()
    for data in scenes:
        xr.testing.assert_identical(worker_case(data, worker).drop_attrs(),
                                    worker_case(data, RunCache()).drop_attrs())
    assert len(built(worker, "planform mesh")) == 2
    assert len(built(worker, "outline expansion")) == 1
