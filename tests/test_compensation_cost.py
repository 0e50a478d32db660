"""What compensation costs, counted (not timed): the diffusion solves of `compensate --at`
and `--over` against those of one run of the scene, and the made scene's run (which
reuses the fixed point's last diffusion) against a fresh run of the written scene."""
from __future__ import annotations

import logging

import numpy as np
import yaml

import fickcam
from fickcam.compensation import compensate, write_scene
from fickcam.compensation.core import RELATIVE_TOLERANCE, Target
from fickcam.compensation.solve import settles_next

SOLVER = "fickcam.diffusion.dispatch"  # logs one debug record per diffusion solve

NYLON_DISC = {
    "name": "nylon-disc",
    "environment": {"reference_temperature": "23 degC",
                    "history": [{"duration": "2 years", "temperature": "40 degC",
                                 "relative_humidity": "90 %"}]},
    "materials": {"nylon": {"plastic": "nylon"}},
    "cam": {"material": "nylon", "eccentric": {"eccentricity": "4 mm", "radius": "23 mm"},
            "thickness": "10 mm", "bore_radius": "0 mm", "speed": "300 rpm",
            "follower": {"kind": "roller", "roller_radius": "10 mm", "mass": "0.737 kg",
                         "spring_rate": "660 N/m", "spring_preload": "0 N",
                         "external_load": "0 N"}},
    "limits": {"follower_displacement": {"deviation": "0.1 mm"}},
    "outputs": {"ageing_times": {"every": "60 d"}, "angle_step": "6 deg"},
}


def solves(caplog) -> int:
    return sum(record.name == SOLVER for record in caplog.records)


def test_compensation_solves_diffusion_about_as_often_as_two_runs(tmp_path, caplog):
    """One run, --at 6 months and --over two years of a nylon disc, each counted: a
    compensation solves no more than two runs of the scene (design, made; the made one
    takes the fixed point's last diffusion) and one solve of the disc (at its first made
    size). Three full runs, as each fixed-point step once was, would solve three runs'."""
    path = tmp_path / "disc.yaml"
    path.write_text(yaml.safe_dump(NYLON_DISC))
    caplog.set_level(logging.DEBUG, logger=SOLVER)
    fickcam.run(path)
    one_run = solves(caplog)
    assert one_run >= 1
    for asked in ({"at": "6 months"}, {"over": ("0 d", "2 years")}):
        caplog.clear()
        comp = compensate(path, **asked)
        assert solves(caplog) <= 2 * one_run + 1, asked
        assert comp.iterations <= 3, asked


def test_made_scene_run_equals_a_fresh_run_of_the_written_scene(tmp_path):
    """The made scene's run reuses the diffusion of the fixed point's last step (solved
    at a size within a few 1e-6 of the made one): its drift equals a fresh run's of the
    written scene to far below the fixed point's tolerance of the compensation."""
    path = tmp_path / "disc.yaml"
    path.write_text(yaml.safe_dump(NYLON_DISC))
    comp = compensate(path, at="6 months")
    written = write_scene(comp, fickcam.load_scene(path), tmp_path / "made.yaml")
    fresh = fickcam.run(written)
    shared = np.intersect1d(fresh.time.values, comp.after.time.values)
    made = comp.after.follower_displacement.sel(time=shared).values
    again = fresh.follower_displacement.sel(time=shared).values
    design = comp.before.follower_displacement.sel(time=shared).values
    compensation = np.max(np.abs(design - made))  # what compensating moved it by, m
    assert np.max(np.abs(made - again)) <= RELATIVE_TOLERANCE * compensation


def test_next_move_is_predicted_from_the_contraction():
    """x = 1 / (1 + eps0 (1 + k x)) contracts by about q = eps0 k per step; after two
    steps the predicted next move q |x2 - x1| decides: settled when it is within the
    tolerance (1e-6 of the compensation), not when the contraction is slow."""
    target = Target("link", "length", "link", ("strain_longitudinal",), 1.0)
    for k, expected in ((1e-3, True), (30.0, False)):
        def step(x, k=k):
            return 1.0 / (1.0 + 0.01 * (1.0 + k * x))

        x0 = 1.0
        x1 = step(x0)
        x2 = step(x1)
        assert settles_next([x0], [x1], [x2], [target]) is expected
