"""A run builds each thing of its scene once: the climate (and the record it reads), each
mechanism (its design, polydyne correction, profile and arm), each mechanism's parts and
the cam's profile file, whatever the run asks of them afterwards (plans, solves, the
as-designed values, the limit search). Counted, not timed."""
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
