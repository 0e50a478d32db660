"""Set-up that tests in several files share, made once per test process (each
pytest-xdist worker makes its own, so nothing is shared between processes)."""
from pathlib import Path

import pytest

import fickcam

CONFIGS = Path(__file__).resolve().parents[1] / "configs"


@pytest.fixture(scope="session")
def example_result():
    """``configs/NAME.yaml`` run as ``fickcam.run`` runs it, once per test process: a
    function NAME -> a copy of its result (the test may change its copy)."""
    cache = {}

    def result(name: str):
        if name not in cache:
            cache[name] = fickcam.run(CONFIGS / f"{name}.yaml")
        return cache[name].copy(deep=True)

    return result
