"""Fixtures shared by several test modules, and Hypothesis's profiles.

A plain run of the tests, CI's included, draws the same property-test examples every
time (the profile "repeatable", derandomized): it cannot fail by chance.
tools/hunt_flaky.py sets PYRT_HYPOTHESIS_PROFILE=hunt, which draws new examples from each
run's --hypothesis-seed."""
import os

import pytest
from hypothesis import settings

import pyrt.workers
from helpers import APP, HeldBackWorker, counted_calls, run_python, wait_for_worker
from pyrt.acceleration.monte_carlo import AcceleratedCMC

# No deadline: an example's time says nothing about its answer, and a loaded machine is slow
settings.register_profile("repeatable", derandomize=True, deadline=None)
settings.register_profile("hunt", derandomize=False, deadline=None)
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
    finished one (or stopped), and the worker hold back its first block until this process
    has taken one, so that both render part of the image however late a loaded machine
    starts the worker. Call it before the render; it returns the marker file a worker
    leaves once its first block is in the image. A test asserts the image, not the marker:
    which process rendered which rows is the scheduler's choice.

    raise_in_worker = (exception class, arguments): the worker raises that exception in its
    first block, once it has rendered the rows and left the marker: as an error in
    compute_color does, it leaves the block unfinished. interrupt: this process is stopped
    with Ctrl+C after its first block. The worker's side is a HeldBackWorker (helpers.py),
    which reaches workers of every start method."""
    def install(raise_in_worker=None, interrupt=False):
        marker = tmp_path / "worker_rendered"
        taken = tmp_path / "this_process_took_a_block"
        render_block = pyrt.workers.render_block

        def held_back(integrator, y0, y1, samples):  # only this process renders here
            taken.touch()
            wait_for_worker(marker)  # else it could take every block before a worker starts
            rows = render_block(integrator, y0, y1, samples)
            if interrupt:
                raise KeyboardInterrupt
            return rows

        monkeypatch.setattr(pyrt.workers, "render_block", held_back)
        monkeypatch.setattr(pyrt.workers, "_worker",
                            HeldBackWorker(str(marker), str(taken), raise_in_worker))
        return marker
    return install


@pytest.fixture
def fused_calls(monkeypatch):
    """The number of camera rays AcceleratedCMC has answered, as a one-element list."""
    return counted_calls(monkeypatch, AcceleratedCMC)
