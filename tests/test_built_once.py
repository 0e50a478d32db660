"""A run builds each thing of its scene once: the climate (and the record it reads), each
mechanism (its design, polydyne correction, profile and arm), each mechanism's parts and
the cam's profile file, whatever the run asks of them afterwards (plans, solves, the
as-designed values, the limit search); and followed from the run, the scene (or one of its
sections) enters each module at most twice. Counted, not timed."""
from __future__ import annotations

from collections import Counter
from functools import cached_property
from pathlib import Path

import pytest

import fickcam
from fickcam.cam import mechanism as cam_mechanism
from fickcam.cam import profile as cam_profile
from fickcam.climate.environment import Environment
from fickcam.linkage import mechanism as linkage_mechanism

CONFIGS = Path(__file__).resolve().parents[1] / "configs"


@pytest.fixture
def built(monkeypatch):
    """What a run builds, counted by kind: ``environment``, ``record``, ``profile_file``,
    ``CamMechanism``, ``LinkageMechanism`` and their ``parts``."""
    counts: Counter = Counter()

    def counting(name, function):
        def counted(*args, **kwargs):
            counts[name] += 1
            return function(*args, **kwargs)
        return counted

    monkeypatch.setattr(Environment, "from_section",
                        classmethod(counting("environment", Environment.from_section.__func__)))
    import fickcam.climate.environment as environment_module

    monkeypatch.setattr(environment_module, "read_record",
                        counting("record", environment_module.read_record))
    monkeypatch.setattr(cam_profile, "read_profile_csv",
                        counting("profile_file", cam_profile.read_profile_csv))
    for cls in (cam_mechanism.CamMechanism, linkage_mechanism.LinkageMechanism):
        monkeypatch.setattr(cls, "__init__", counting(cls.__name__, cls.__init__))
        parts = cached_property(counting(f"{cls.__name__}.parts", cls.parts.func))
        parts.__set_name__(cls, "parts")
        monkeypatch.setattr(cls, "parts", parts)
    return counts


@pytest.mark.parametrize("name, expected", [
    # a cam with limits: the limit search re-runs the model at extra times
    ("singh2017_cam", {"environment": 1, "CamMechanism": 1, "CamMechanism.parts": 1}),
    # a cam given by points, made to compensate (``design:``): made and as designed
    ("singh2017_cam_compensated", {"environment": 1, "profile_file": 1, "CamMechanism": 2,
                                   "CamMechanism.parts": 2}),
    # a weather record
    ("eccentric_cam_greensboro", {"environment": 1, "record": 1, "CamMechanism": 1,
                                  "CamMechanism.parts": 1}),
    # a four-bar made to compensate
    ("fourbar_r914_humid_compensated", {"environment": 1, "LinkageMechanism": 2,
                                        "LinkageMechanism.parts": 2}),
])
def test_a_run_builds_its_climate_mechanisms_parts_and_files_once(name, expected, built):
    fickcam.run(CONFIGS / f"{name}.yaml")
    assert dict(built) == expected


def entries_of_the_scene(scene) -> Counter:
    """Per fickcam module, how many times a run of ``scene`` calls into it from another
    module passing the scene or one of its sections (its own methods aside)."""
    import sys

    from fickcam.simulation import simulate

    held = {id(scene), id(scene.model)}
    for model in (scene.model, scene.as_designed_model):
        if model is not None:
            held |= {id(model)} | {id(getattr(model, name)) for name in model.model_fields
                                    if getattr(model, name) is not None}
    entries: Counter = Counter()

    def profiler(frame, event, arg):
        module = frame.f_globals.get("__name__", "")
        if event != "call" or not module.startswith("fickcam"):
            return
        code = frame.f_code
        names = code.co_varnames[:code.co_argcount + code.co_kwonlyargcount]
        values = [frame.f_locals.get(name) for name in names]
        if names and names[0] == "self" and values[0] is scene:
            return
        caller = frame.f_back.f_globals.get("__name__", "") if frame.f_back else ""
        if caller != module and any(id(value) in held for value in values):
            entries[module] += 1

    sys.setprofile(profiler)
    try:
        simulate.run(scene)
    finally:
        sys.setprofile(None)
    return entries


@pytest.mark.parametrize("name", ["singh2017_cam", "singh2017_cam_compensated",
                                  "fourbar_r914_humid_compensated"])
def test_followed_from_the_run_a_scene_enters_each_module_at_most_twice(name):
    entries = entries_of_the_scene(fickcam.load_scene(CONFIGS / f"{name}.yaml"))
    assert entries and max(entries.values()) <= 2, entries
