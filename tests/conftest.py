"""Fixtures shared by several test modules."""
import pytest

from helpers import APP, run_python


@pytest.fixture(scope="session")
def all_figures(tmp_path_factory):
    """`python AppRenderer.py --all-figures --no-window` run once for the whole suite, as a
    student runs it, at the default 500 x 500 pixels of the course's references (rendering
    the six images takes a few seconds): (its CompletedProcess, its output folder)."""
    out = tmp_path_factory.mktemp("all_figures")
    return run_python([APP, "--all-figures", "--no-window", "--out", out], cwd=out), out
