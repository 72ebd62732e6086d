"""Fixtures shared by several test modules, and Hypothesis's profiles.

A plain run of the tests, CI's included, draws the same property-test examples every
time (the profile "repeatable", derandomized): it cannot fail by chance.
tests/hunt_flaky.py sets PYRT_HYPOTHESIS_PROFILE=hunt, which draws new examples from each
run's --hypothesis-seed."""
import multiprocessing
import os

import pytest
from hypothesis import settings

import PyRT_Workers
from helpers import APP, run_python, wait_for_file

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


@pytest.fixture
def worker_first(monkeypatch, tmp_path):
    """Makes this process hold back its first block of rows until a worker process has
    finished one, and the worker hold back its first block until this process has taken
    one, so that both surely render part of the image, however the processes are
    scheduled. Call it before the render; it returns the marker file a worker leaves once
    its first block is in the image.

    raise_in_worker = (exception class, arguments): the worker raises that exception in its
    first block, once it has rendered the rows and left the marker: as an error in
    compute_color does, it leaves the block unfinished. interrupt: this process is stopped
    with Ctrl+C after its first block. Forked workers inherit the patched functions."""
    def install(raise_in_worker=None, interrupt=False):
        marker = tmp_path / "worker_rendered"
        taken = tmp_path / "this_process_took_a_block"
        render_block, finish = PyRT_Workers.render_block, PyRT_Workers._SharedImage.finish

        def finish_and_mark(shared, i):  # only worker processes finish blocks
            finish(shared, i)
            marker.touch()

        def held_back(integrator, y0, y1, samples):
            in_worker = multiprocessing.parent_process() is not None
            if in_worker:  # else it could take every block before this process takes one
                wait_for_file(taken)
            else:
                taken.touch()
                wait_for_file(marker)
            rows = render_block(integrator, y0, y1, samples)
            if in_worker and raise_in_worker:
                marker.touch()
                error_class, arguments = raise_in_worker
                raise error_class(*arguments)
            if interrupt and not in_worker:
                raise KeyboardInterrupt
            return rows

        monkeypatch.setattr(PyRT_Workers._SharedImage, "finish", finish_and_mark)
        monkeypatch.setattr(PyRT_Workers, "render_block", held_back)
        return marker
    return install
