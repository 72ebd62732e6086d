"""Fixtures shared by several test modules, and Hypothesis's profiles.

A plain run of the tests, CI's included, draws the same property-test examples every
time (the profile "repeatable", derandomized): it cannot fail by chance.
tests/hunt_flaky.py sets PYRT_HYPOTHESIS_PROFILE=hunt, which draws new examples from each
run's --hypothesis-seed."""
import os

import pytest
from hypothesis import settings

from helpers import APP, run_python

settings.register_profile("repeatable", derandomize=True)
settings.register_profile("hunt", derandomize=False)
settings.load_profile(os.environ.get("PYRT_HYPOTHESIS_PROFILE", "repeatable"))


@pytest.fixture(scope="session")
def all_figures(tmp_path_factory):
    """`python AppRenderer.py --all-figures --no-window` run once for the whole suite, as a
    student runs it, at the default 500 x 500 pixels of the course's references (rendering
    the six images takes a few seconds): (its CompletedProcess, its output folder)."""
    out = tmp_path_factory.mktemp("all_figures")
    return run_python([APP, "--all-figures", "--no-window", "--out", out], cwd=out), out
