"""pyrt/workers.py through Integrator.render(): rendering in several processes (fork,
spawn and forkserver: PYRT_START_METHOD chooses for the whole suite), how the work is
split, errors in worker processes and scripts without the main guard."""
import contextlib
import io
import multiprocessing
import os
import pickle
import re
import signal
import sys
import warnings
from types import SimpleNamespace

import numpy as np
import pytest

import pyrt.rows
import pyrt.sampling
import pyrt.workers
from AppRenderer import sphere_test_scene
from helpers import (PixelGrey, StepAt, fov90_scene, render_image, run_python,
                     small_cornell_box, wait_for_worker)
from PyRT_Core import *
from PyRT_Integrators import *


# ------------------------------------------------------------------------------------------
# Parallel rendering
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("samples", [1, 4])
def test_one_and_two_workers_give_identical_images(tmp_path, capfd, worker_first, samples):
    one = render_image(PhongIntegrator(str(tmp_path / "one")), small_cornell_box(64),
                       workers=1, samples_per_pixel=samples)
    worker_first()
    two = render_image(PhongIntegrator(str(tmp_path / "two")), small_cornell_box(64),
                       workers=2, samples_per_pixel=samples)
    assert "one process" not in capfd.readouterr().err
    assert one.any()
    assert np.array_equal(one, two)


class WorkerDiesInItsFirstBlock(PixelGrey):
    """PixelGrey whose worker process dies (exit code 3) at its first pixel; this process
    renders nothing before that."""

    def __init__(self, filename_, marker):
        super().__init__(filename_)
        self.marker = str(marker)

    def compute_color(self, ray):
        if multiprocessing.parent_process() is not None:  # a worker process
            open(self.marker, "w").close()
            os._exit(3)
        wait_for_worker(self.marker)
        return super().compute_color(ray)


def test_worker_that_dies_holding_a_block_leaves_it_to_this_process(tmp_path, capfd):
    image = render_image(WorkerDiesInItsFirstBlock(str(tmp_path / "img"),
                                                   tmp_path / "worker_started"),
                         fov90_scene(3, 8), workers=2)
    assert (tmp_path / "worker_started").exists()
    assert "a worker process stopped early (exit code 3)" in capfd.readouterr().err
    for y in range(8):
        for x in range(3):
            assert tuple(image[y, x]) == ((x + 10 * y) / 100,) * 3, (x, y)


class ProcessIdAsRed(PixelGrey):
    """PixelGrey whose red channel is the id of the process that rendered the pixel."""

    def compute_color(self, ray):
        grey = super().compute_color(ray)
        return RGBColor(float(os.getpid()), grey.g, grey.b)


def test_two_workers_are_this_process_and_one_worker_process(tmp_path, monkeypatch,
                                                             worker_first):
    # The image itself says which process rendered each row: this one, and the worker
    # process unless it started too late to take a block.
    started = []  # the ids of the processes the render starts
    start = multiprocessing.process.BaseProcess.start

    def recorded_start(process):
        start(process)
        started.append(process.pid)

    monkeypatch.setattr(multiprocessing.process.BaseProcess, "start", recorded_start)
    worker_first()
    image = render_image(ProcessIdAsRed(str(tmp_path / "img")), fov90_scene(4, 32), workers=2)
    assert len(started) == 1, started
    renderers = image[:, :, 0]
    assert (renderers == renderers[:, :1]).all()  # a process renders whole rows
    assert os.getpid() in renderers[:, 0]
    assert set(renderers[:, 0]) <= {os.getpid(), started[0]}
    for y in range(32):
        for x in range(4):
            assert tuple(image[y, x, 1:]) == ((x + 10 * y) / 100,) * 2, (x, y)


def test_error_in_a_worker_process_is_raised_with_the_worker_traceback(tmp_path, worker_first):
    worker_first(raise_in_worker=(ZeroDivisionError, ["raised in a worker"]))
    integrator = PhongIntegrator(str(tmp_path / "bad"))
    integrator.add_scene(small_cornell_box(32))
    with pytest.raises(ZeroDivisionError, match="raised in a worker") as raised:
        integrator.render(workers=2, progress=False)
    # where the worker raised it, as a traceback that starts on a line of its own
    where = str(raised.value.__cause__)
    assert where.startswith("\nTraceback (most recent call last):\n"), where
    assert "in _worker\n" in where and "in held_back\n" in where, where


class NeedsTwoArguments(Exception):
    """An exception that pickle cannot rebuild: its __init__ wants two arguments."""

    def __init__(self, reason, code):
        super().__init__(f"{reason} ({code})")


def test_error_that_cannot_leave_a_worker_is_raised_as_its_text(tmp_path, worker_first):
    worker_first(raise_in_worker=(NeedsTwoArguments, ["odd failure", 7]))
    integrator = PhongIntegrator(str(tmp_path / "bad"))
    integrator.add_scene(small_cornell_box(32))
    with pytest.raises(RuntimeError, match=r"NeedsTwoArguments: odd failure \(7\)"):
        integrator.render(workers=2, progress=False)


# ------------------------------------------------------------------------------------------
# How worker processes start
# ------------------------------------------------------------------------------------------
def test_the_variable_chooses_how_worker_processes_start(monkeypatch):
    for method in multiprocessing.get_all_start_methods():
        monkeypatch.setenv("PYRT_START_METHOD", method)
        assert pyrt.workers.start_method() == method


def test_a_start_method_the_system_lacks_is_refused_with_those_it_has(monkeypatch):
    monkeypatch.setenv("PYRT_START_METHOD", "thread")
    with pytest.raises(ValueError, match=re.escape(
            "PYRT_START_METHOD='thread': this system's start methods are "
            + ", ".join(multiprocessing.get_all_start_methods()))):
        pyrt.workers.start_method()


@pytest.mark.parametrize("version, systems_methods, chosen", [
    ((3, 11), ["fork", "spawn", "forkserver"], "fork"),  # Linux
    ((3, 12), ["fork", "spawn", "forkserver"], "forkserver"),
    ((3, 13), ["fork", "spawn", "forkserver"], "forkserver"),
    ((3, 12), ["spawn", "fork", "forkserver"], "spawn"),  # macOS
    ((3, 12), ["spawn"], "spawn"),  # Windows
    ((3, 14), ["forkserver", "fork", "spawn"], "forkserver")])  # Linux, from 3.14 on
def test_unless_chosen_workers_start_as_the_system_says_but_never_fork_from_3_12(
        monkeypatch, version, systems_methods, chosen):
    monkeypatch.delenv("PYRT_START_METHOD", raising=False)
    monkeypatch.setattr(multiprocessing, "get_start_method", lambda allow_none: None)
    monkeypatch.setattr(multiprocessing, "get_all_start_methods", lambda: systems_methods)
    monkeypatch.setattr(pyrt.workers, "sys", SimpleNamespace(version_info=version))
    assert pyrt.workers.start_method() == chosen


@pytest.mark.parametrize("version, scripts_method, chosen", [
    ((3, 11), "fork", "fork"), ((3, 11), "spawn", "spawn"), ((3, 13), "spawn", "spawn"),
    ((3, 13), "fork", "forkserver")])  # or the fixed default: tqdm fixes it as it starts
def test_the_method_a_script_set_is_kept_but_fork_from_3_12(monkeypatch, version,
                                                             scripts_method, chosen):
    monkeypatch.delenv("PYRT_START_METHOD", raising=False)
    monkeypatch.setattr(multiprocessing, "get_start_method", lambda allow_none: scripts_method)
    monkeypatch.setattr(pyrt.workers, "sys", SimpleNamespace(version_info=version))
    assert pyrt.workers.start_method() == chosen


@pytest.mark.skipif("fork" not in multiprocessing.get_all_start_methods(),
                    reason="this system has no fork")
def test_the_variable_chooses_fork_even_from_3_12(monkeypatch):
    monkeypatch.setenv("PYRT_START_METHOD", "fork")
    monkeypatch.setattr(pyrt.workers, "sys", SimpleNamespace(version_info=(3, 13)))
    assert pyrt.workers.start_method() == "fork"


@pytest.mark.skipif(os.environ.get("PYRT_START_METHOD") == "fork",
                    reason="fork is asked for, warning included")
def test_a_render_with_workers_starts_them_without_a_warning(tmp_path, worker_first):
    # Python 3.12 and later warn when a multi-threaded process forks: PyRT does not
    worker_first()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        render_image(PixelGrey(str(tmp_path / "img")), fov90_scene(3, 8), workers=2)
    # (other warnings, such as a ResourceWarning of another test's garbage, may come)
    assert [str(warning.message) for warning in caught if "fork" in str(warning.message)
            ] == []


def test_rows_are_cut_into_blocks_that_shrink_towards_the_end():
    # each block takes a quarter of the rows left per process, at least one row
    assert pyrt.workers._row_blocks(0, 50, 1) == [
        (0, 12), (12, 21), (21, 28), (28, 33), (33, 37), (37, 40), (40, 42), (42, 44),
        (44, 45), (45, 46), (46, 47), (47, 48), (48, 49), (49, 50)]
    assert pyrt.workers._row_blocks(1, 20, 2) == [  # 19 // 8, 17 // 8, 15 // 8, ...
        (1, 3), (3, 5)] + [(y, y + 1) for y in range(5, 20)]
    assert pyrt.workers._row_blocks(5, 5, 2) == []


def test_renders_too_short_for_workers_stay_in_one_process_long_ones_use_every_core():
    assert pyrt.workers.worker_count(0.0) == 1
    assert pyrt.workers.worker_count(0.01) == 1
    assert pyrt.workers.worker_count(1000.0) == pyrt.workers.usable_cores()


@pytest.mark.skipif(not hasattr(os, "sched_setaffinity"), reason="no CPU affinity here")
def test_usable_cores_are_those_this_process_may_run_on():
    allowed = os.sched_getaffinity(0)
    try:
        os.sched_setaffinity(0, {min(allowed)})
        assert pyrt.workers.usable_cores() == 1
    finally:
        os.sched_setaffinity(0, allowed)
    assert pyrt.workers.usable_cores() == len(allowed)


@pytest.mark.parametrize("cpu_count, cores", [(4, 4), (None, 1)])
def test_usable_cores_without_affinity_are_the_cores_of_the_machine(monkeypatch, cpu_count,
                                                                    cores):
    # as on Windows and macOS; os.cpu_count() gives None when it cannot tell
    monkeypatch.delattr(os, "sched_getaffinity", raising=False)
    monkeypatch.setattr(os, "cpu_count", lambda: cpu_count)
    assert pyrt.workers.usable_cores() == cores


# The worker process's function, called here in this process: it renders the blocks it
# takes into the shared image, then sends one message.
def run_worker(integrator, blocks, taken_before=0):
    """Runs pyrt.workers._worker on integrator's image cut into blocks, after this process
    took the first `taken_before` blocks: (the shared image, its finished flags, the
    message the worker sent, the Ctrl+C handler the worker left)."""
    camera = integrator.scene.camera
    mp = multiprocessing.get_context(pyrt.workers.start_method())
    shared = pyrt.workers._SharedImage(mp, (camera.height, camera.width, 3), len(blocks))
    for _ in range(taken_before):
        shared.take()
    receiver, sender = multiprocessing.Pipe(duplex=False)
    ctrl_c = signal.getsignal(signal.SIGINT)
    try:
        pyrt.workers._worker(pickle.dumps(integrator), blocks,
                             pyrt.rows.CourseRows(pyrt.rows.RowStreams(0), Integrator.render.loop), shared, sender)
        worker_ctrl_c = signal.getsignal(signal.SIGINT)
    finally:
        signal.signal(signal.SIGINT, ctrl_c)
        sender.close()
    with receiver:
        assert receiver.poll(0), "the worker sent no message"
        message = receiver.recv()
        with pytest.raises(EOFError):  # nothing more: one message
            receiver.recv()
    return shared.image(), shared.finished_blocks(), message, worker_ctrl_c


def test_worker_renders_the_blocks_not_yet_taken_into_the_shared_image(tmp_path):
    integrator = PixelGrey(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(3, 4))
    image, finished, message, ctrl_c = run_worker(integrator, [(0, 1), (1, 3), (3, 4)],
                                                  taken_before=1)
    assert message is None  # it stopped because every block was done
    assert finished == [0, 1, 1]
    assert not image[0].any()  # this process's block
    for y in range(1, 4):
        for x in range(3):
            assert tuple(image[y, x]) == ((x + 10 * y) / 100,) * 3, (x, y)
    assert ctrl_c == signal.SIG_IGN  # Ctrl+C is handled once, by the main process


class FailsAtRow2(PixelGrey):
    def grey(self, x, y):
        if y == 2:
            raise ZeroDivisionError(f"pixel ({x}, {y})")
        return super().grey(x, y)


def test_worker_sends_the_error_that_stopped_it_with_its_traceback(tmp_path):
    integrator = FailsAtRow2(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(3, 4))
    image, finished, message, _ = run_worker(integrator, [(0, 2), (2, 4)])
    error, where = message
    assert type(error) is ZeroDivisionError and str(error) == "pixel (0, 2)"
    assert where.startswith("Traceback (most recent call last):\n")
    assert "in grey" in where and where.rstrip().endswith("ZeroDivisionError: pixel (0, 2)")
    assert finished == [1, 0]  # the rows before the error are in the image
    assert tuple(image[1, 2]) == (0.12,) * 3


class FailsWithAnErrorPickleCannotRebuild(PixelGrey):
    def grey(self, x, y):
        raise NeedsTwoArguments("odd failure", 7)


def test_worker_sends_an_error_that_cannot_travel_between_processes_as_its_text(tmp_path):
    integrator = FailsWithAnErrorPickleCannotRebuild(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(3, 4))
    _, finished, (error, where), _ = run_worker(integrator, [(0, 4)])
    assert type(error) is RuntimeError
    assert str(error) == "NeedsTwoArguments: odd failure (7)"
    assert "NeedsTwoArguments" in where
    assert finished == [0]


def normal_image_in_one_process(folder):
    """The 24 x 24 Normal image of the sphere scene, rendered in this process: what a
    render that falls back to one process must give."""
    return render_image(NormalIntegrator(str(folder / "plain")),
                        sphere_test_scene(width=24, height=24), workers=1)


class HoldsAnUnloadableValue(NormalIntegrator):
    """Holds an exception that pickles but cannot be rebuilt from its pickle."""

    def __init__(self, filename_):
        super().__init__(filename_)
        self.last_error = NeedsTwoArguments("kept", 1)


def test_integrator_that_cannot_be_unpickled_renders_in_one_process_and_says_why(
        tmp_path, capfd):
    image = render_image(HoldsAnUnloadableValue(str(tmp_path / "odd")),
                         sphere_test_scene(width=24, height=24), workers=2)
    err = capfd.readouterr().err
    assert "one process" in err and "NeedsTwoArguments" in err
    assert np.array_equal(image, normal_image_in_one_process(tmp_path))


# An integrator that exists only in the script that renders it, as students write them.
# Its main process holds back its rendering until a worker process has rendered a row
# or has stopped, as in a render that lasts longer than a worker takes to start.
OWN_INTEGRATOR = '''
import multiprocessing
import os
import time

from PyRT_Integrators import *
from AppRenderer import cornell_box_scene


class DistanceAndIndex(Integrator):
    def __init__(self, filename_):
        super().__init__(filename_ + "_DistanceAndIndex")
        self.held_back = False

    def compute_color(self, ray):
        if not self.held_back:  # once per process
            self.held_back = True
            hold_back()
        hit = self.scene.closest_hit(ray)
        if not hit.has_hit:
            return BLACK
        return RGBColor(1.0 / hit.hit_distance, hit.primitive_index / 10.0, 0.5)


def hold_back():
    if multiprocessing.parent_process() is not None:  # a worker process
        open("worker_rendered", "a").close()
    else:
        deadline = time.monotonic() + 300  # only so that a hung worker cannot hang it
        while (multiprocessing.active_children() and not os.path.exists("worker_rendered")
               and time.monotonic() < deadline):
            time.sleep(0.005)
'''

GUARDED_SPAWN_SCRIPT = OWN_INTEGRATOR + '''
if __name__ == "__main__":
    # force=True: the method may be set already, as CI's run under spawn sets it in every
    # process (a sitecustomize); on Windows and macOS spawn is the default anyway
    multiprocessing.set_start_method("spawn", force=True)
    integrator = DistanceAndIndex("spawned")
    integrator.add_scene(cornell_box_scene(0.75, 2, width=24, height=24))
    integrator.render(workers=2, progress=False)
'''

# Without the guard every worker re-runs the whole script. force=True lets the workers get
# as far as render(), as they do on Windows, where 'spawn' is the default.
UNGUARDED_SPAWN_SCRIPT = OWN_INTEGRATOR + '''
multiprocessing.set_start_method("spawn", force=True)
integrator = DistanceAndIndex("spawned")
integrator.add_scene(cornell_box_scene(0.75, 2, width=24, height=24))
integrator.render(workers=2, progress=False)
'''


def own_integrator_image(folder):
    namespace = {}
    exec(OWN_INTEGRATOR, namespace)
    integrator = namespace["DistanceAndIndex"](str(folder / "in_process"))
    return render_image(integrator, small_cornell_box(24), workers=1)


def run_spawn_script(tmp_path, source):
    script = tmp_path / "student_script.py"
    script.write_text(source)
    return run_python([script.name], cwd=tmp_path)


def test_spawn_start_method_renders_an_own_integrator_with_two_workers(tmp_path):
    result = run_spawn_script(tmp_path, GUARDED_SPAWN_SCRIPT)
    assert result.returncode == 0, result.stderr
    assert "stopped early" not in result.stderr
    image = np.load(tmp_path / "spawned_DistanceAndIndex.npy")
    assert np.array_equal(image, own_integrator_image(tmp_path))


def test_unguarded_spawn_script_still_renders_and_explains_the_main_guard(tmp_path):
    result = run_spawn_script(tmp_path, UNGUARDED_SPAWN_SCRIPT)
    assert result.returncode == 0, result.stderr
    assert 'if __name__ == "__main__":' in result.stdout + result.stderr
    assert ("PyRT: a worker process stopped early (exit code 1); this process renders its "
            "rows. If this script runs on Windows or macOS (or with the 'spawn' start "
            "method), put the code that builds and renders the scene under\n"
            '    if __name__ == "__main__":\n') in result.stderr
    assert not (tmp_path / "worker_rendered").exists()
    image = np.load(tmp_path / "spawned_DistanceAndIndex.npy")
    assert np.array_equal(image, own_integrator_image(tmp_path))


class HalfNormal(NormalIntegrator):
    """Holds a lambda, which cannot be pickled for worker processes."""

    def __init__(self, filename_):
        super().__init__(filename_)
        self.scale = lambda color: color * 0.5

    def compute_color(self, ray):
        return self.scale(super().compute_color(ray))


def test_integrator_holding_a_lambda_renders_in_one_process_and_says_why(tmp_path, capfd):
    half = render_image(HalfNormal(str(tmp_path / "half")),
                        sphere_test_scene(width=32, height=32), workers=2)
    err = capfd.readouterr().err
    assert err.startswith("PyRT: rendering in one process: integrator.scale cannot be sent "
                          "to worker processes ("), err
    assert err.endswith("); attributes such as lambdas, functions or classes defined inside "
                        "a function, open files or generators prevent it\n"), err
    full = render_image(NormalIntegrator(str(tmp_path / "full")),
                        sphere_test_scene(width=32, height=32), workers=1)
    assert full.any()
    assert np.array_equal(half, full * 0.5)


@pytest.mark.parametrize("height, workers_wanted", [(1, False), (2, True)])
def test_workers_are_wanted_for_two_blocks_of_rows_not_for_one(tmp_path, capfd, height,
                                                               workers_wanted):
    # workers=2 cuts 1 row into 1 block and 2 rows into 2: only then does PyRT try to
    # send the integrator to a worker (and says why it cannot: the lambda)
    render_image(HalfNormal(str(tmp_path / "half")), fov90_scene(3, height), workers=2)
    assert ("rendering in one process" in capfd.readouterr().err) == workers_wanted


def test_with_a_debugger_attached_renders_in_one_process_and_says_why(tmp_path, capfd):
    def tracer(frame, event, arg):  # what pdb and VSCode's debugger install
        return None

    sys.settrace(tracer)
    try:
        image = render_image(NormalIntegrator(str(tmp_path / "debugged")),
                             sphere_test_scene(width=24, height=24), workers=2)
    finally:
        sys.settrace(None)
    assert capfd.readouterr().err.splitlines() == [
        "PyRT: rendering in one process: a debugger is attached (so that breakpoints in "
        "compute_color work)"]
    assert np.array_equal(image, normal_image_in_one_process(tmp_path))


@pytest.mark.parametrize("debugger", ["debugpy", "pydevd"])
def test_with_vscode_s_debugger_loaded_renders_in_one_process_and_says_why(tmp_path, capfd,
                                                                          monkeypatch,
                                                                          debugger):
    # VSCode's debugger (debugpy, built on pydevd) may trace through its own means
    monkeypatch.setitem(sys.modules, debugger, type(sys)(debugger))
    image = render_image(NormalIntegrator(str(tmp_path / "debugged")),
                         sphere_test_scene(width=24, height=24), workers=2)
    assert "a debugger is attached" in capfd.readouterr().err
    assert np.array_equal(image, normal_image_in_one_process(tmp_path))


def test_coverage_measurement_is_no_debugger_workers_still_render(tmp_path, capfd,
                                                                  worker_first):
    def tracer(frame, event, arg):  # as coverage.py's Python tracer
        return None

    tracer.__module__ = "coverage.pytracer"
    worker_first()
    sys.settrace(tracer)
    try:
        image = render_image(NormalIntegrator(str(tmp_path / "measured")),
                             sphere_test_scene(width=24, height=24), workers=2)
    finally:
        sys.settrace(None)
    assert "one process" not in capfd.readouterr().err
    assert np.array_equal(image, normal_image_in_one_process(tmp_path))


def render_normal_with_two_workers(filename):
    """(the image, what PyRT printed to stderr meanwhile): the processes a forkserver starts
    do not write to the test's stderr."""
    with contextlib.redirect_stderr(io.StringIO()) as err:
        image = render_image(NormalIntegrator(filename),
                             sphere_test_scene(width=24, height=24), workers=2)
    return image, err.getvalue()


def test_render_inside_a_pool_worker_renders_in_one_process_and_says_why(tmp_path):
    # A teaching assistant may render every student's integrator in a multiprocessing.Pool,
    # whose (daemonic) workers may not start processes of their own.
    with multiprocessing.get_context(pyrt.workers.start_method()).Pool(1) as pool:
        image, err = pool.apply(render_normal_with_two_workers, (str(tmp_path / "pooled"),))
    assert err.splitlines() == [
        "PyRT: rendering in one process: this process is itself a daemonic worker process "
        "(of a multiprocessing.Pool, say), which may not start processes"]
    assert np.array_equal(image, normal_image_in_one_process(tmp_path))


class TickingClock:
    """A perf_counter for pyrt.workers that moves on `tick` seconds at
    every reading: a render takes the time the test says, however loaded the machine is."""

    def __init__(self, tick):
        self.now, self.tick = 0.0, tick

    def __call__(self):
        self.now += self.tick
        return self.now


def with_clock_and_two_cores(monkeypatch, tick):
    clock = SimpleNamespace(perf_counter=TickingClock(tick))
    monkeypatch.setattr(pyrt.workers, "time", clock)
    monkeypatch.setattr(pyrt.workers, "usable_cores", lambda: 2)


def test_short_render_with_all_cores_stays_in_this_process(tmp_path, monkeypatch):
    # docs/performance.md: short renders stay in one process, where starting workers
    # would cost more.
    # The first of the 4 rows takes one tick, 1 ms: the other 3 would take 3 ms in one
    # process; the refined pixels (2 a row) are timed until they fill a row's 5 pixels,
    # rows 0 to 2, 1 ms each: the last row's 2 would take 1 ms. Both far less than
    # PARALLEL_MIN_SECONDS.
    with_clock_and_two_cores(monkeypatch, 0.001)

    def no_workers(*args):
        raise AssertionError("a short render started worker processes")

    monkeypatch.setattr(pyrt.workers, "_render_with_workers", no_workers)
    image = render_image(StepAt(str(tmp_path / "img"), 2.3), fov90_scene(5, 4),
                         samples_per_pixel=4, adaptive=True)  # workers=None: all cores
    assert (image[:, 0] == 1.0).all() and (image[:, 3:] == 0.0).all()


def test_long_render_with_all_cores_renders_each_pass_with_a_worker_per_other_core(
        tmp_path, monkeypatch):
    # The same render where a tick is 1 s. The centre rays: the first row, timed in this
    # process, takes 1 s, so the other 3 would take 3 s, more than PARALLEL_MIN_SECONDS for
    # any start method: rows 1 to 3, one block each, go to this process and 1 worker (2
    # cores). The refined pixels, 2 a row: the first row takes 1 s, longer than
    # PARALLEL_MIN_SECONDS, so its time tells: 0.5 s a pixel, 3 s for the 6 of rows 1 to 3,
    # which go to this process and 1 worker again.
    with_clock_and_two_cores(monkeypatch, 1.0)
    passes = []
    with_workers = pyrt.workers._render_with_workers

    def recorded(camera, blocks, rows, count, *args):
        passes.append((type(rows).__name__, blocks, count))
        yield from with_workers(camera, blocks, rows, count, *args)

    monkeypatch.setattr(pyrt.workers, "_render_with_workers", recorded)
    image = render_image(StepAt(str(tmp_path / "img"), 2.3), fov90_scene(5, 4),
                         samples_per_pixel=4, adaptive=True)
    assert passes == [("CourseRows", [(1, 2), (2, 3), (3, 4)], 1),
                      ("SampledRows", [(1, 2), (2, 3), (3, 4)], 1)]
    one_process = render_image(StepAt(str(tmp_path / "one"), 2.3), fov90_scene(5, 4),
                               workers=1, samples_per_pixel=4, adaptive=True)
    assert np.array_equal(image, one_process)


@pytest.mark.parametrize("adaptive, passes_made", [
    (False, ["SampledRows"]), (True, ["CourseRows", "SampledRows"])])
def test_render_with_two_workers_renders_every_pass_with_them(tmp_path, monkeypatch, adaptive,
                                                              passes_made):
    # however short the render: workers=2 is an order
    passes = []
    with_workers = pyrt.workers._render_with_workers

    def recorded(camera, blocks, rows, *args):
        passes.append(type(rows).__name__)
        yield from with_workers(camera, blocks, rows, *args)

    monkeypatch.setattr(pyrt.workers, "_render_with_workers", recorded)
    render_image(StepAt(str(tmp_path / "img"), 2.3), fov90_scene(5, 8), workers=2,
                 samples_per_pixel=4, adaptive=adaptive)
    assert passes == passes_made
