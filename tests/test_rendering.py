"""PyRT_Rendering.py through Integrator.render(): rendering in several processes (fork and
spawn), the sampling patterns of samples_per_pixel, the progress of a render, Ctrl+C, and
the checks that give clear errors."""
import json
import math
import multiprocessing
import os
import pickle
import re
import signal
import sys
import time
from types import SimpleNamespace

import numpy as np
import pytest
from tqdm import tqdm

import PyRT_Rendering
from AppRenderer import sphere_test_scene
from make_references import SAMPLED_REFERENCE, SAMPLED_REFERENCE_SIZE
from helpers import (GREY, PNG_TOLERANCE, PixelGrey, fov90_scene, pixel_of, read_png,
                     render_image, run_python, small_cornell_box)
from PyRT_Common import plt
from PyRT_Core import *
from PyRT_Integrators import *


# ------------------------------------------------------------------------------------------
# Parallel rendering
# ------------------------------------------------------------------------------------------
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
        render_block, finish = PyRT_Rendering.render_block, PyRT_Rendering._SharedImage.finish

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

        monkeypatch.setattr(PyRT_Rendering._SharedImage, "finish", finish_and_mark)
        monkeypatch.setattr(PyRT_Rendering, "render_block", held_back)
        return marker
    return install


def wait_for_file(path, seconds=60):
    deadline = time.monotonic() + seconds
    while not os.path.exists(path) and time.monotonic() < deadline:
        time.sleep(0.005)


@pytest.mark.parametrize("samples", [1, 4])
def test_one_and_two_workers_give_identical_images(tmp_path, capfd, worker_first, samples):
    one = render_image(PhongIntegrator(str(tmp_path / "one")), small_cornell_box(64),
                       workers=1, samples_per_pixel=samples)
    marker = worker_first()
    two = render_image(PhongIntegrator(str(tmp_path / "two")), small_cornell_box(64),
                       workers=2, samples_per_pixel=samples)
    assert marker.exists(), "no worker process rendered a block"
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
        wait_for_file(self.marker)
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
    # The image itself says which process rendered each row, whichever finished first.
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
    assert set(renderers[:, 0]) == {os.getpid(), started[0]}
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


def test_rows_are_cut_into_blocks_that_shrink_towards_the_end():
    # each block takes a quarter of the rows left per process, at least one row
    assert PyRT_Rendering._row_blocks(0, 50, 1) == [
        (0, 12), (12, 21), (21, 28), (28, 33), (33, 37), (37, 40), (40, 42), (42, 44),
        (44, 45), (45, 46), (46, 47), (47, 48), (48, 49), (49, 50)]
    assert PyRT_Rendering._row_blocks(1, 20, 2) == [  # 19 // 8, 17 // 8, 15 // 8, ...
        (1, 3), (3, 5)] + [(y, y + 1) for y in range(5, 20)]
    assert PyRT_Rendering._row_blocks(5, 5, 2) == []


def test_renders_too_short_for_workers_stay_in_one_process_long_ones_use_every_core():
    assert PyRT_Rendering.worker_count(0.0) == 1
    assert PyRT_Rendering.worker_count(0.01) == 1
    assert PyRT_Rendering.worker_count(1000.0) == PyRT_Rendering.usable_cores()


@pytest.mark.skipif(not hasattr(os, "sched_setaffinity"), reason="no CPU affinity here")
def test_usable_cores_are_those_this_process_may_run_on():
    allowed = os.sched_getaffinity(0)
    try:
        os.sched_setaffinity(0, {min(allowed)})
        assert PyRT_Rendering.usable_cores() == 1
    finally:
        os.sched_setaffinity(0, allowed)
    assert PyRT_Rendering.usable_cores() == len(allowed)


@pytest.mark.parametrize("cpu_count, cores", [(4, 4), (None, 1)])
def test_usable_cores_without_affinity_are_the_cores_of_the_machine(monkeypatch, cpu_count,
                                                                    cores):
    # as on Windows and macOS; os.cpu_count() gives None when it cannot tell
    monkeypatch.delattr(os, "sched_getaffinity", raising=False)
    monkeypatch.setattr(os, "cpu_count", lambda: cpu_count)
    assert PyRT_Rendering.usable_cores() == cores


# The worker process's function, called here in this process: it renders the blocks it
# takes into the shared image, then sends one message.
def run_worker(integrator, blocks, taken_before=0):
    """Runs PyRT_Rendering._worker on integrator's image cut into blocks, after this process
    took the first `taken_before` blocks: (the shared image, its finished flags, the
    message the worker sent, the Ctrl+C handler the worker left)."""
    camera = integrator.scene.camera
    shared = PyRT_Rendering._SharedImage(multiprocessing.get_context(),
                                         (camera.height, camera.width, 3), len(blocks))
    for _ in range(taken_before):
        shared.take()
    receiver, sender = multiprocessing.Pipe(duplex=False)
    ctrl_c = signal.getsignal(signal.SIGINT)
    try:
        PyRT_Rendering._worker(pickle.dumps(integrator), blocks,
                               PyRT_Rendering._CourseRows(1), shared, sender)
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

    def compute_color(self, ray):
        hit = self.scene.closest_hit(ray)
        if not hit.has_hit:
            return BLACK
        return RGBColor(1.0 / hit.hit_distance, hit.primitive_index / 10.0, 0.5)

    def render_row(self, y, samples_per_pixel=1):
        row = super().render_row(y, samples_per_pixel)
        if multiprocessing.parent_process() is not None:  # a worker process
            open("worker_rendered", "a").close()
        else:
            deadline = time.monotonic() + 60
            while (multiprocessing.active_children() and not os.path.exists("worker_rendered")
                   and time.monotonic() < deadline):
                time.sleep(0.005)
        return row
'''

GUARDED_SPAWN_SCRIPT = OWN_INTEGRATOR + '''
if __name__ == "__main__":
    multiprocessing.set_start_method("spawn")
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
    assert (tmp_path / "worker_rendered").exists(), "no worker process rendered a block"
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
    assert err.startswith("PyRT: rendering in one process: the integrator or its scene cannot "
                          "be sent to worker processes ("), err
    assert err.endswith("); attributes such as lambdas, open files or generators prevent "
                        "it\n"), err
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
    marker = worker_first()
    sys.settrace(tracer)
    try:
        render_image(NormalIntegrator(str(tmp_path / "measured")),
                     sphere_test_scene(width=24, height=24), workers=2)
    finally:
        sys.settrace(None)
    assert "one process" not in capfd.readouterr().err
    assert marker.exists(), "no worker process rendered a block"


def render_normal_with_two_workers(filename):
    return render_image(NormalIntegrator(filename), sphere_test_scene(width=24, height=24),
                        workers=2)


def test_render_inside_a_pool_worker_renders_in_one_process_and_says_why(tmp_path, capfd):
    # A teaching assistant may render every student's integrator in a multiprocessing.Pool,
    # whose (daemonic) workers may not start processes of their own.
    with multiprocessing.Pool(1) as pool:
        image = pool.apply(render_normal_with_two_workers, (str(tmp_path / "pooled"),))
    assert capfd.readouterr().err.splitlines() == [
        "PyRT: rendering in one process: this process is itself a daemonic worker process "
        "(of a multiprocessing.Pool, say), which may not start processes"]
    assert np.array_equal(image, normal_image_in_one_process(tmp_path))


# ------------------------------------------------------------------------------------------
# Anti-aliasing: samples_per_pixel
# ------------------------------------------------------------------------------------------
def test_one_sample_per_pixel_is_the_ray_through_the_pixel_centre(tmp_path):
    integrator = PhongIntegrator(str(tmp_path / "img"))
    image = render_image(integrator, sphere_test_scene(width=20, height=16),
                         samples_per_pixel=1)
    camera = integrator.scene.camera
    for y in range(camera.height):
        for x in range(camera.width):
            color = integrator.compute_color(Ray(Vector3D(0, 0, 0), camera.get_direction(x, y)))
            assert tuple(image[y, x]) == (color.r, color.g, color.b), (x, y)


def test_anti_aliased_image_is_the_same_on_every_run(tmp_path):
    first = render_image(PhongIntegrator(str(tmp_path / "a")), small_cornell_box(24),
                         workers=1, samples_per_pixel=4)
    second = render_image(PhongIntegrator(str(tmp_path / "b")), small_cornell_box(24),
                          workers=1, samples_per_pixel=4)
    assert np.array_equal(first, second)


def error_against_the_sampled_reference(folder, samples, **options):
    """The RMSE of Phong on small_cornell_box rendered with `samples` rays per pixel (and
    render's other options) against the same with 1024 (make_references.py)."""
    name = "_".join([f"spp{samples}", *options])
    image = render_image(PhongIntegrator(str(folder / name)),
                         small_cornell_box(SAMPLED_REFERENCE_SIZE), samples_per_pixel=samples,
                         **options)
    return float(np.sqrt(np.mean((image - np.load(SAMPLED_REFERENCE)) ** 2)))


def test_error_against_a_high_sample_reference_shrinks_with_more_samples(tmp_path):
    errors = [error_against_the_sampled_reference(tmp_path, n) for n in (1, 4, 16, 64)]
    assert errors[0] > errors[1] > errors[2] > errors[3], errors
    # Averaging N samples cuts the error at least like 1/sqrt(N): 64 samples, 8 times.
    assert errors[3] < errors[0] / 8, errors


class PhongAroundRenderRow(PhongIntegrator):
    """Phong making its rows itself, with Integrator.render_row, as an override that adds
    something around each row does; counts its rows."""

    def __init__(self, filename_):
        super().__init__(filename_)
        self.rows = 0

    def render_row(self, y, samples_per_pixel=1):
        self.rows += 1
        return super().render_row(y, samples_per_pixel)


def test_render_row_with_several_samples_gives_the_pixels_of_the_anti_aliased_image(tmp_path):
    # Integrator.render_row(y, N) averages the same jittered rays as render(N) does, summed
    # in the same order: the images agree bit for bit.
    uniform = render_image(PhongIntegrator(str(tmp_path / "uniform")), small_cornell_box(12),
                           workers=1, samples_per_pixel=4)
    integrator = PhongAroundRenderRow(str(tmp_path / "own"))
    image = render_image(integrator, small_cornell_box(12), workers=1, samples_per_pixel=4)
    assert integrator.rows == 12
    assert np.array_equal(image, uniform)
    centre = render_image(PhongIntegrator(str(tmp_path / "centre")), small_cornell_box(12),
                          workers=1)
    assert not np.array_equal(image, centre)


class WhiteAtPixelCentres(Integrator):
    """White for a ray through the centre of its pixel, black for any other ray."""

    def compute_color(self, ray):
        x, y = image_point(ray, self.scene.camera)
        centre = abs(x % 1.0 - 0.5) < 1e-9 and abs(y % 1.0 - 0.5) < 1e-9
        return WHITE if centre else BLACK


def test_render_row_gives_row_y_flat_from_the_centre_rays_or_from_n_samples(tmp_path):
    grey = PixelGrey(str(tmp_path / "img"))
    grey.add_scene(fov90_scene(3, 2))
    assert grey.render_row(1) == [0.1, 0.1, 0.1, 0.11, 0.11, 0.11, 0.12, 0.12, 0.12]
    centres = WhiteAtPixelCentres(str(tmp_path / "img"))
    centres.add_scene(fov90_scene(3, 2))
    assert centres.render_row(1) == [1.0] * 9  # the rays through the centres, by default
    # two samples: one in the left half of each pixel (white), one in the right (black)
    halves = LeftHalfWhite(str(tmp_path / "img"))
    halves.add_scene(fov90_scene(3, 2))
    assert halves.render_row(1, 2) == [0.5] * 9


def test_sampled_pixels_gives_colour_and_error_of_the_pixels_asked_for_zeros_elsewhere(
        tmp_path):
    # LeftHalfWhite with N = 2: mean 1/2 and one pair differing by 1, error 1 / (4 sqrt(2))
    integrator = LeftHalfWhite(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(3, 2))
    row = PyRT_Rendering.sampled_pixels(integrator, 1, 2, [1])
    error = 1 / (4 * math.sqrt(2))
    assert row[:6] == [0.0] * 6 and row[12:] == [0.0] * 6
    assert row[6:12] == pytest.approx([0.5] * 3 + [error] * 3, rel=1e-15)
    # one sample per pixel: no pair of samples, no spread to estimate an error from
    grey = PixelGrey(str(tmp_path / "img"))
    grey.add_scene(fov90_scene(3, 2))
    row = PyRT_Rendering.sampled_pixels(grey, 1, 1, [0, 1, 2])
    assert row[3:6] == row[9:12] == row[15:18] == [0.0] * 3


@pytest.mark.parametrize("samples", [1, 4])
def test_camera_rays_see_objects_however_close_to_the_camera(tmp_path, samples):
    # camera rays start at no surface, so t_min = 0: a wall 0.00005 in front of the camera
    # (less than EPSILON, the t_min of other rays) fills the image; a sphere 0.2 to 0.6 in
    # front of it fills the view of the centre pixel
    wall = InfinitePlane(Vector3D(0, 0, -0.00005), Vector3D(0, 0, 1))
    image = render_image(IntersectionIntegrator(str(tmp_path / "wall")), fov90_scene(3, 3, [
        (wall, GREY)]), workers=1, samples_per_pixel=samples)
    assert (image == (1.0, 0.0, 0.0)).all()
    scene = fov90_scene(3, 3, [(Sphere(Vector3D(0, 0, -0.4), 0.2), GREY)])
    image = render_image(IntersectionIntegrator(str(tmp_path / "ball")), scene, workers=1,
                         samples_per_pixel=samples)
    assert image[1, 1].tolist() == [1.0, 0.0, 0.0]


@pytest.mark.parametrize("option, value, allowed", [
    ("samples_per_pixel", 0, "a whole number >= 1"),
    ("workers", 2.5, "None (all cores) or a whole number >= 1")])
def test_bad_render_option_message_says_what_is_allowed(tmp_path, option, value, allowed):
    integrator = PhongIntegrator(str(tmp_path / "img"))
    integrator.add_scene(sphere_test_scene(width=4, height=4))
    with pytest.raises(ValueError) as error:
        integrator.render(progress=False, **{option: value})
    assert str(error.value) == f"render: {option} must be {allowed}, got {value!r}"


@pytest.mark.parametrize("option, value", [
    *[("samples_per_pixel", value) for value in (0, -1, 2.5, "4", True)],
    *[("workers", value) for value in (0, -1, 2.5, "2", True)]])
def test_bad_render_option_raises_value_error_naming_it(tmp_path, option, value):
    integrator = PhongIntegrator(str(tmp_path / "out" / "img"))
    integrator.add_scene(sphere_test_scene(width=4, height=4))
    with pytest.raises(ValueError, match=re.escape(option)):
        integrator.render(progress=False, **{option: value})
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


# ------------------------------------------------------------------------------------------
# Where the samples go: strata, uniform and adaptive
# ------------------------------------------------------------------------------------------
# N samples per pixel form a grid of a x b cells as square as N allows, a rows and b
# columns, a <= b (README): worked out by hand.
GRIDS = {2: (1, 2), 4: (2, 2), 6: (2, 3), 7: (1, 7), 8: (2, 4), 9: (3, 3), 12: (3, 4),
         16: (4, 4)}


def cells_of(points, rows, columns):
    """The (row, column) cell of each (u, v) point of a pixel cut into rows x columns."""
    return [(math.floor(v * rows), math.floor(u * columns)) for u, v in points]


@pytest.mark.parametrize("samples", GRIDS)
def test_uniform_samples_lie_inside_their_pixel_one_in_each_stratum(samples):
    rows, columns = GRIDS[samples]
    every_cell = sorted((r, c) for r in range(rows) for c in range(columns))
    for y in (0, 7):
        for points in PyRT_Rendering.pixel_offsets(samples, y, 5):
            assert all(0.0 <= u < 1.0 and 0.0 <= v < 1.0 for u, v in points)
            # one point in each cell, in the order of the cells: row by row
            assert cells_of(points, rows, columns) == every_cell


def test_sample_points_are_random_across_and_down_their_cell_independently():
    # where a point lies across its cell says nothing about where it lies down it: over
    # 50 pixels of 4 cells, the two fractions agree nowhere
    rows, columns = GRIDS[4]
    for points in PyRT_Rendering.pixel_offsets(4, 2, 50):
        for (u, v), (r, c) in zip(points, cells_of(points, rows, columns)):
            assert abs((u * columns - c) - (v * rows - r)) > 1e-12


def image_point(ray, camera):
    """(x + u, y + v): where the ray crosses the image plane, in pixels from the image's
    top left corner (get_direction inverted)."""
    d = ray.d
    scale_y = math.tan(camera.vertical_fov / 2)
    x_s = d.x / -d.z / (scale_y * camera.aspect_ratio)
    y_s = d.y / -d.z / scale_y
    return (x_s + 1) * camera.width / 2, (1 - y_s) * camera.height / 2


class StepAt(Integrator):
    """White left of the vertical line X = edge of the image plane (in pixels), black right
    of it; records where every ray crosses the image plane."""

    def __init__(self, filename_, edge):
        super().__init__(filename_ + "_Step")
        self.edge = edge
        self.points = []

    def compute_color(self, ray):
        x, y = image_point(ray, self.scene.camera)
        self.points.append((x, y))
        return WHITE if x < self.edge else BLACK


def samples_per_pixel(points):
    """{(x, y): [(u, v), ...]}: the points grouped by pixel, as offsets inside it."""
    pixels = {}
    for X, Y in points:
        x, y = math.floor(X), math.floor(Y)
        pixels.setdefault((x, y), []).append((X - x, Y - y))
    return pixels


def test_uniform_render_samples_each_pixel_once_in_each_stratum(tmp_path):
    integrator = StepAt(str(tmp_path / "img"), 2.3)
    render_image(integrator, fov90_scene(5, 4), workers=1, samples_per_pixel=8)
    pixels = samples_per_pixel(integrator.points)
    assert sorted(pixels) == [(x, y) for x in range(5) for y in range(4)]
    for points in pixels.values():
        assert sorted(cells_of(points, 2, 4)) == [(r, c) for r in range(2) for c in range(4)]


def test_adaptive_render_refines_both_pixels_across_an_edge_one_sample_per_stratum(tmp_path):
    # The edge at X = 2.3 lies in pixel column 2, whose centre (2.5) is black while that
    # of column 1 (1.5) is white: after the centre rays, columns 1 and 2 get 16 rays, one
    # in each cell of the 4 x 4 grid; the others, which match their neighbours, keep the
    # centre ray alone.
    integrator = StepAt(str(tmp_path / "img"), 2.3)
    image = render_image(integrator, fov90_scene(5, 4), workers=1, samples_per_pixel=16,
                         adaptive=True)
    pixels = samples_per_pixel(integrator.points)
    assert sorted(pixels) == [(x, y) for x in range(5) for y in range(4)]
    every_cell = [(r, c) for r in range(4) for c in range(4)]
    for (x, y), (centre, *others) in pixels.items():  # the centre rays come first
        assert centre == pytest.approx((0.5, 0.5), abs=1e-9), (x, y)
        if x in (1, 2):
            assert sorted(cells_of(others, 4, 4)) == every_cell, (x, y)
        else:
            assert others == [], (x, y)
    # column 1 is white throughout; of column 2 the left 0.3 is: 1 of 4 columns of cells
    # lies wholly left of the edge, and the next one's sample with probability 0.2
    assert (image[:, 1] == 1.0).all()
    assert ((0.25 <= image[:, 2]) & (image[:, 2] <= 0.5)).all()
    assert (image[:, [0]] == 1.0).all() and (image[:, [3, 4]] == 0.0).all()


def test_refined_pixels_get_the_rays_of_uniform_sampling_and_its_colours(tmp_path):
    # README: after the centre ray, which only finds the edge, a refined pixel gets the
    # jittered rays of the uniform N-sample render, so the same colour bit for bit
    uniform = StepAt(str(tmp_path / "uniform"), 2.3)
    uniform_image = render_image(uniform, fov90_scene(5, 4), workers=1, samples_per_pixel=4)
    adaptive = StepAt(str(tmp_path / "adaptive"), 2.3)
    adaptive_image = render_image(adaptive, fov90_scene(5, 4), workers=1,
                                  samples_per_pixel=4, adaptive=True)
    jittered, refined = samples_per_pixel(uniform.points), samples_per_pixel(adaptive.points)
    for x in (1, 2):  # the refined columns
        for y in range(4):
            centre, *others = refined[(x, y)]
            assert centre == pytest.approx((0.5, 0.5), abs=1e-9)
            assert others == jittered[(x, y)], (x, y)
    # the refined columns as uniform sampling made them; the others, white or black
    # throughout, are their centre ray's colour, as they are uniform sampling's
    assert np.array_equal(adaptive_image, uniform_image)


class Constant(Integrator):
    """The same grey for every ray; counts its rays."""

    def __init__(self, filename_):
        super().__init__(filename_ + "_Constant")
        self.calls = 0

    def compute_color(self, ray):
        self.calls += 1
        return RGBColor(0.25, 0.5, 0.75)


def test_adaptive_render_of_an_image_without_edges_traces_only_the_centre_rays(tmp_path):
    integrator = Constant(str(tmp_path / "img"))
    image = render_image(integrator, fov90_scene(7, 5), workers=1, samples_per_pixel=16,
                         adaptive=True)
    assert integrator.calls == 7 * 5
    assert (image == (0.25, 0.5, 0.75)).all()
    accuracy = json.loads((tmp_path / "img_Constant_accuracy.json").read_text())
    assert (accuracy["rays"], accuracy["pixels_with_n_samples"]) == (35, 0)
    assert accuracy["estimated_rmse"] == 0.0
    rays = read_png(tmp_path / "img_Constant_samples.png")
    assert rays.shape == (5, 7, 3)
    assert (rays == rays[0, 0]).all()


def test_sample_map_has_the_image_shape_dark_for_one_ray_bright_for_the_most(tmp_path):
    integrator = StepAt(str(tmp_path / "img"), 2.3)
    render_image(integrator, fov90_scene(5, 4), workers=1, samples_per_pixel=16,
                 adaptive=True)
    rays = read_png(tmp_path / "img_Step_samples.png")
    assert rays.shape == (4, 5, 3)
    colors = plt.get_cmap(PyRT_Rendering.SAMPLE_MAP_COLORS)
    fewest, most = colors(0.0)[:3], colors(1.0)[:3]  # 1 ray and 1 + 16 rays
    for x in range(5):
        expected = most if x in (1, 2) else fewest
        assert rays[:, x] == pytest.approx(np.tile(expected, (4, 1)), abs=PNG_TOLERANCE)


def test_refined_pixels_are_both_of_every_pair_of_neighbours_differing_by_more_than_t():
    # a 4 x 5 display, 0.25 everywhere but pixel (2, 1), whose blue channel is 0.5
    display = np.full((4, 5, 3), 0.25)
    display[1, 2, 2] = 0.5
    refined = PyRT_Rendering.refined_pixels(display, 0.125)
    expected = np.zeros((4, 5), dtype=bool)
    expected[1, 1:4] = expected[0:3, 2] = True  # (2, 1) and its four neighbours
    assert refined.dtype == bool and (refined == expected).all()
    # a difference of exactly the tolerance is not more than it
    assert not PyRT_Rendering.refined_pixels(display, 0.25).any()
    # tolerance 0: any difference, and no pair of equal neighbours
    assert (PyRT_Rendering.refined_pixels(display, 0.0) == expected).all()


class LinearStepAt(Integrator):
    """Grey `left` left of the line X = 2.3 of the image plane, `right` right of it; its PNG
    shows the linear colours without tonemapping, as LazyIntegrator's does."""

    tonemap = False

    def __init__(self, filename_, left, right):
        super().__init__(filename_ + "_Linear")
        self.left, self.right = left, right

    def compute_color(self, ray):
        x, _ = image_point(ray, self.scene.camera)
        grey = self.left if x < 2.3 else self.right
        return RGBColor(grey, grey, grey)


@pytest.mark.parametrize("left, right, refined", [
    (0.2, 0.3, 8),      # 0.1 apart in the PNG: columns 1 and 2 refined
    (0.2, 0.21, 0),     # 0.01 apart: less than the tolerance
    (1.5, 3.0, 0),      # both shown as 1
    (-0.5, -1.0, 0)])   # both shown as 0
def test_adaptive_render_without_tonemapping_compares_the_colours_the_png_shows(
        tmp_path, left, right, refined):
    render_image(LinearStepAt(str(tmp_path / "img"), left, right), fov90_scene(5, 4),
                 workers=1, samples_per_pixel=4, adaptive=True, tolerance=0.03)
    accuracy = json.loads((tmp_path / "img_Linear_accuracy.json").read_text())
    assert accuracy["pixels_with_n_samples"] == refined


def sample_map_colours(samples):
    """The colours of 1 ray and of N + 1 rays (a refined pixel's) in the sample map."""
    colors = plt.get_cmap(PyRT_Rendering.SAMPLE_MAP_COLORS)
    return colors(0.0)[:3], colors(1.0)[:3]


def test_sample_map_is_pale_yellow_for_refined_pixels_whatever_the_others_got(tmp_path):
    # N = 2: 3 rays are the most, in the columns 1 and 2 beside the edge
    render_image(StepAt(str(tmp_path / "img"), 2.3), fov90_scene(5, 4), workers=1,
                 samples_per_pixel=2, adaptive=True)
    rays = read_png(tmp_path / "img_Step_samples.png")
    fewest, most = sample_map_colours(2)
    for x in range(5):
        expected = most if x in (1, 2) else fewest
        assert rays[:, x] == pytest.approx(np.tile(expected, (4, 1)), abs=PNG_TOLERANCE), x
    # every pixel differs from its neighbours: all are refined, all have the most rays
    render_image(PixelGrey(str(tmp_path / "img")), fov90_scene(5, 4), workers=1,
                 samples_per_pixel=4, adaptive=True, tolerance=0.0)
    rays = read_png(tmp_path / "img_PixelGrey_samples.png")
    assert rays == pytest.approx(np.tile(most, (4, 5, 1)), abs=PNG_TOLERANCE)


def test_sample_map_is_a_png_whatever_matplotlib_saves_by_default(tmp_path):
    with plt.rc_context({"savefig.format": "svg"}):
        render_image(StepAt(str(tmp_path / "img"), 2.3), fov90_scene(5, 4), workers=1,
                     samples_per_pixel=4, adaptive=True)
    assert (tmp_path / "img_Step_samples.png").read_bytes().startswith(b"\x89PNG\r\n")


def test_adaptive_render_of_an_image_without_edges_shows_no_bar_for_refining(tmp_path,
                                                                            capfd):
    integrator = Constant(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(7, 5))
    integrator.render(workers=1, samples_per_pixel=16, adaptive=True)
    err = capfd.readouterr().err
    assert "Constant centre rays: 100%" in err
    assert "rays at edges" not in err


class TickingClock:
    """A perf_counter for PyRT_Rendering that moves on `tick` seconds at every reading: a
    render takes the time the test says, however loaded the machine is."""

    def __init__(self, tick):
        self.now, self.tick = 0.0, tick

    def __call__(self):
        self.now += self.tick
        return self.now


def with_clock_and_two_cores(monkeypatch, tick):
    monkeypatch.setattr(PyRT_Rendering, "time", SimpleNamespace(perf_counter=TickingClock(tick)))
    monkeypatch.setattr(PyRT_Rendering, "usable_cores", lambda: 2)


def test_short_render_with_all_cores_stays_in_this_process(tmp_path, monkeypatch):
    # README: short renders stay in one process, where starting workers would cost more.
    # The first of the 4 rows takes one tick, 1 ms: the other 3 would take 3 ms in one
    # process, and the refined pixels as long, far less than PARALLEL_MIN_SECONDS.
    with_clock_and_two_cores(monkeypatch, 0.001)

    def no_workers(*args):
        raise AssertionError("a short render started worker processes")

    monkeypatch.setattr(PyRT_Rendering, "_render_with_workers", no_workers)
    image = render_image(StepAt(str(tmp_path / "img"), 2.3), fov90_scene(5, 4),
                         samples_per_pixel=4, adaptive=True)  # workers=None: all cores
    assert (image[:, 0] == 1.0).all() and (image[:, 3:] == 0.0).all()


def test_long_render_with_all_cores_renders_each_pass_with_a_worker_per_other_core(
        tmp_path, monkeypatch):
    # The same render where a tick is 1 s. The centre rays: the first row, timed in this
    # process, takes 1 s, so the other 3 would take 3 s, more than PARALLEL_MIN_SECONDS for
    # any start method: rows 1 to 3, one block each, go to this process and 1 worker (2
    # cores). The refined pixels: the centre rays took 3 s (4 readings), so the 8 refined
    # pixels of 20 with 4 rays each would take 3 * 8 * 4 / 20 = 4.8 s: rows 0 to 3 again.
    with_clock_and_two_cores(monkeypatch, 1.0)
    passes = []
    with_workers = PyRT_Rendering._render_with_workers

    def recorded(camera, blocks, rows, count, *args):
        passes.append((type(rows).__name__, blocks, count))
        yield from with_workers(camera, blocks, rows, count, *args)

    monkeypatch.setattr(PyRT_Rendering, "_render_with_workers", recorded)
    image = render_image(StepAt(str(tmp_path / "img"), 2.3), fov90_scene(5, 4),
                         samples_per_pixel=4, adaptive=True)
    assert passes == [("_CourseRows", [(1, 2), (2, 3), (3, 4)], 1),
                      ("_SampledRows", [(0, 1), (1, 2), (2, 3), (3, 4)], 1)]
    one_process = render_image(StepAt(str(tmp_path / "one"), 2.3), fov90_scene(5, 4),
                               workers=1, samples_per_pixel=4, adaptive=True)
    assert np.array_equal(image, one_process)


@pytest.mark.parametrize("adaptive, passes_made", [
    (False, ["_SampledRows"]), (True, ["_CourseRows", "_SampledRows"])])
def test_render_with_two_workers_renders_every_pass_with_them(tmp_path, monkeypatch, adaptive,
                                                              passes_made):
    # however short the render: workers=2 is an order
    passes = []
    with_workers = PyRT_Rendering._render_with_workers

    def recorded(camera, blocks, rows, *args):
        passes.append(type(rows).__name__)
        yield from with_workers(camera, blocks, rows, *args)

    monkeypatch.setattr(PyRT_Rendering, "_render_with_workers", recorded)
    render_image(StepAt(str(tmp_path / "img"), 2.3), fov90_scene(5, 8), workers=2,
                 samples_per_pixel=4, adaptive=adaptive)
    assert passes == passes_made


def test_adaptive_render_with_zero_tolerance_refines_every_pixel_as_uniform_sampling_does(
        tmp_path):
    # Every pixel differs from a neighbour: after its centre ray each gets the uniform
    # render's 4 rays, so the image and its estimated error are uniform sampling's.
    samples, size = 4, 16
    uniform = render_image(PhongIntegrator(str(tmp_path / "uniform")), small_cornell_box(size),
                           workers=1, samples_per_pixel=samples)
    adaptive = render_image(PhongIntegrator(str(tmp_path / "adaptive")),
                            small_cornell_box(size), workers=1, samples_per_pixel=samples,
                            adaptive=True, tolerance=0.0)
    assert np.array_equal(adaptive, uniform)
    accuracy = json.loads((tmp_path / "adaptive_Phong_accuracy.json").read_text())
    assert accuracy["pixels_with_n_samples"] == size * size  # every pixel refined
    assert accuracy["rays"] == (1 + samples) * size * size
    expected = json.loads((tmp_path / "uniform_Phong_accuracy.json").read_text())
    assert accuracy["estimated_rmse_rgb"] == expected["estimated_rmse_rgb"]


def test_adaptive_render_error_is_no_higher_than_uniform_sampling_at_the_same_n(tmp_path):
    uniform = error_against_the_sampled_reference(tmp_path, 16)
    adaptive = error_against_the_sampled_reference(tmp_path, 16, adaptive=True)
    centre = error_against_the_sampled_reference(tmp_path, 1)
    # refined pixels are uniform sampling's; the others, where the colour varies smoothly,
    # keep their centre ray, whose error (second order in the pixel's size) is as small as
    # that of uniform sampling's average there, but not always smaller
    assert adaptive <= 1.01 * uniform < centre / 2, (adaptive, uniform, centre)


@pytest.mark.parametrize("samples", [4, 9])
def test_adaptive_image_is_the_same_with_one_and_two_workers(tmp_path, capfd, worker_first,
                                                             samples):
    one = render_image(PhongIntegrator(str(tmp_path / "one")), small_cornell_box(64),
                       workers=1, samples_per_pixel=samples, adaptive=True)
    marker = worker_first()
    two = render_image(PhongIntegrator(str(tmp_path / "two")), small_cornell_box(64),
                       workers=2, samples_per_pixel=samples, adaptive=True)
    assert marker.exists(), "no worker process rendered a block"
    assert "one process" not in capfd.readouterr().err
    assert np.array_equal(one, two)
    assert np.array_equal(np.load(tmp_path / "one_Phong.npy"), one)
    assert (read_png(tmp_path / "one_Phong_samples.png")
            == read_png(tmp_path / "two_Phong_samples.png")).all()


class StopsAtRefinement(StepAt):
    """StepAt that is stopped with Ctrl+C at its first ray away from a pixel centre."""

    def compute_color(self, ray):
        x, y = image_point(ray, self.scene.camera)
        if abs(x % 1.0 - 0.5) > 1e-9 or abs(y % 1.0 - 0.5) > 1e-9:
            raise KeyboardInterrupt
        return super().compute_color(ray)


def test_ctrl_c_while_refining_saves_the_centre_rays_image(tmp_path):
    integrator = StopsAtRefinement(str(tmp_path / "img"), 2.3)
    integrator.add_scene(fov90_scene(5, 4))
    with pytest.raises(KeyboardInterrupt):
        integrator.render(workers=1, progress=False, samples_per_pixel=4, adaptive=True)
    partial = np.load(tmp_path / "img_Step_partial.npy")
    assert (partial[:, :2] == 1.0).all() and (partial[:, 2:] == 0.0).all()


# ------------------------------------------------------------------------------------------
# The error estimate
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("samples, pairs", [
    (2, [(0, 1)]),                              # 1 x 2: side by side
    (4, [(0, 1), (2, 3)]),                      # 2 x 2: side by side, row by row
    (6, [(0, 3), (1, 4), (2, 5)]),              # 2 x 3: rows of 3, so one above the other
    (9, [(0, 1), (2, 3), (4, 5), (6, 7)]),      # 3 x 3: consecutive, the last left out
])
def test_strata_are_paired_with_a_neighbour(samples, pairs):
    assert PyRT_Rendering.stratum_pairs(samples) == pairs


@pytest.mark.parametrize("samples, weight", [
    (2, 1 / (math.sqrt(2) * 2 * 2)),    # P = 1 pair: 1 / (sqrt(2) * 2P * N)
    (4, 1 / (math.sqrt(2) * 16)),       # N even: 1 / (sqrt(2) N^2)
    (9, 1 / (math.sqrt(2) * 8 * 9)),    # P = 4 pairs
])
def test_error_variance_weight_is_one_over_sqrt2_2P_N(samples, weight):
    assert PyRT_Rendering.error_variance_weight(samples) == pytest.approx(weight, rel=1e-15)


class LeftHalfWhite(Integrator):
    """White where the ray crosses the left half of its pixel, black in the right half."""

    def __init__(self, filename_):
        super().__init__(filename_ + "_LeftHalf")

    def compute_color(self, ray):
        x, _ = image_point(ray, self.scene.camera)
        return WHITE if x % 1.0 < 0.5 else BLACK


def test_accuracy_file_holds_the_estimate_worked_out_by_hand(tmp_path, capsys):
    # With 2 samples per pixel (cells: left half, right half) every pixel gets one white
    # and one black sample: mean 0.5, one pair with d = 1, estimated squared error
    # 1 / (sqrt(2) * 2 * 2) in each channel, so the RMSE is sqrt(1 / (4 sqrt(2))).
    image = render_image(LeftHalfWhite(str(tmp_path / "img")), fov90_scene(3, 2),
                         workers=1, samples_per_pixel=2)
    assert (image == 0.5).all()
    accuracy = json.loads((tmp_path / "img_LeftHalf_accuracy.json").read_text())
    rmse = math.sqrt(1 / (4 * math.sqrt(2)))
    assert accuracy["estimated_rmse"] == pytest.approx(rmse, rel=1e-12)
    assert accuracy["estimated_rmse_rgb"] == pytest.approx([rmse] * 3, rel=1e-12)
    assert accuracy["image"] == "img_LeftHalf.png"
    assert (accuracy["samples_per_pixel"], accuracy["adaptive"], accuracy["tolerance"]) == (
        2, False, None)
    assert (accuracy["pixels"], accuracy["rays"], accuracy["rays_per_pixel"]) == (6, 12, 2.0)
    assert accuracy["image_range"] == 0.0
    assert capsys.readouterr().out.splitlines() == [  # an image of range 0: no share of it
        f"Estimated error: RMSE {rmse:.2e} of the linear image, from the spread of each "
        f"pixel's samples; saved in {tmp_path / 'img_LeftHalf_accuracy.json'}"]


class GreyColumn0AndFirstThirdOfColumn1(Integrator):
    """Grey 0.5 in pixel column 0 and in the left third of pixel column 1, black elsewhere."""

    def __init__(self, filename_):
        super().__init__(filename_ + "_Thirds")

    def compute_color(self, ray):
        x, _ = image_point(ray, self.scene.camera)
        return GREY if x < 1.0 + 1.0 / 3.0 else BLACK


def test_adaptive_accuracy_file_and_report_hold_the_estimate_worked_out_by_hand(tmp_path,
                                                                                capsys):
    # 3 x 2 pixels. The centre rays are grey in column 0, black in columns 1 and 2, so
    # columns 0 and 1 are refined (4 of 6 pixels): after the centre ray, N = 9 rays, one in
    # each cell of a 3 x 3 grid. In column 1 the samples of the cells of the left
    # column (0, 3, 6) are grey, the others black: mean 0.5 / 3; of the pairs (0, 1),
    # (2, 3), (4, 5), (6, 7) three differ by 0.5, so the estimated squared error is
    # 3 * 0.25 / (sqrt(2) * 2 * 4 * 9) in each channel. Column 0 is all grey: no error;
    # the pixels of column 2 kept their centre ray and count as exact.
    image = render_image(GreyColumn0AndFirstThirdOfColumn1(str(tmp_path / "img")),
                         fov90_scene(3, 2), workers=1, samples_per_pixel=9, adaptive=True)
    assert image[:, 0] == pytest.approx(np.full((2, 3), 0.5), abs=1e-15)
    assert image[:, 1] == pytest.approx(np.full((2, 3), 0.5 / 3), abs=1e-15)
    assert (image[:, 2] == 0.0).all()
    text = (tmp_path / "img_Thirds_accuracy.json").read_text()
    accuracy = json.loads(text)
    assert text == json.dumps(accuracy, indent=2)  # readable: one entry a line, indented
    rmse = math.sqrt(2 * 3 * 0.25 / (math.sqrt(2) * 2 * 4 * 9) / 6)
    assert accuracy["estimated_rmse"] == pytest.approx(rmse, rel=1e-12)
    assert accuracy["estimated_rmse_rgb"] == pytest.approx([rmse] * 3, rel=1e-12)
    assert (accuracy["samples_per_pixel"], accuracy["adaptive"], accuracy["tolerance"]) == (
        9, True, 0.03)
    assert accuracy["image_range"] == 0.5
    assert (accuracy["pixels"], accuracy["pixels_with_n_samples"]) == (6, 4)
    assert (accuracy["rays"], accuracy["rays_per_pixel"]) == (4 * 10 + 2, pytest.approx(42 / 6))
    assert accuracy["method"] == (
        "the square root of the mean, over pixels and channels, of each pixel's estimated "
        "squared error sum(d^2) / (sqrt(2) * 2P * N), d the difference of the two samples of "
        "each of the P pairs of neighbouring strata; pixels that kept their centre ray count "
        "as exact")
    samples = tmp_path / "img_Thirds_samples.png"
    captured = capsys.readouterr()
    assert captured.err == ""
    assert captured.out.splitlines() == [
        f"Adaptive sampling: 4 of 6 pixels (66.7%) got 9 rays after their centre ray, the "
        f"others their centre ray only: 7.00 rays per pixel, where uniform sampling takes 9. "
        f"Map of the rays per pixel: {samples} (black: 1, pale yellow: 10)",
        f"Estimated error: RMSE {rmse:.2e} of the linear image, {rmse / 0.5:.2%} of its "
        f"range, from the spread of each pixel's samples; saved in "
        f"{tmp_path / 'img_Thirds_accuracy.json'}"]


class ThirdsWithANaNPixel(GreyColumn0AndFirstThirdOfColumn1):
    """GreyColumn0AndFirstThirdOfColumn1 with NaN in pixel (2, 1)."""

    def compute_color(self, ray):
        x, y = image_point(ray, self.scene.camera)
        if (math.floor(x), math.floor(y)) == (2, 1):
            return RGBColor(math.nan, math.nan, math.nan)
        return super().compute_color(ray)


def test_estimate_and_image_range_leave_out_the_pixels_that_are_not_numbers(tmp_path, capfd):
    # As above, but pixel (2, 1) is NaN, which the PNG shows as the darkest colour, as its
    # neighbours: it keeps its centre ray, and the mean is over the other 5 pixels.
    image = render_image(ThirdsWithANaNPixel(str(tmp_path / "img")), fov90_scene(3, 2),
                         workers=1, samples_per_pixel=9, adaptive=True)
    assert np.isnan(image[1, 2]).all()
    accuracy = json.loads((tmp_path / "img_Thirds_accuracy.json").read_text())
    rmse = math.sqrt(2 * 3 * 0.25 / (math.sqrt(2) * 2 * 4 * 9) / 5)
    assert accuracy["estimated_rmse"] == pytest.approx(rmse, rel=1e-12)
    assert accuracy["estimated_rmse_rgb"] == pytest.approx([rmse] * 3, rel=1e-12)
    assert accuracy["image_range"] == 0.5
    assert accuracy["pixels_with_n_samples"] == 4
    assert "1 pixel(s), the first at pixel (2, 1)" in capfd.readouterr().err


class NaNEverywhere(Integrator):
    def compute_color(self, ray):
        return RGBColor(math.nan, math.nan, math.nan)


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # the mean of no numbers
def test_image_without_a_single_number_still_gets_its_accuracy_file(tmp_path, capsys):
    image = render_image(NaNEverywhere(str(tmp_path / "img")), fov90_scene(3, 2), workers=1,
                         samples_per_pixel=2)
    assert np.isnan(image).all()
    accuracy = json.loads((tmp_path / "img_accuracy.json").read_text())
    assert accuracy["image_range"] == 0.0  # no numbers, no range
    assert math.isnan(accuracy["estimated_rmse"])
    assert capsys.readouterr().out.startswith("Estimated error: RMSE nan of the linear image, "
                                              "from the spread")


def test_a_render_without_estimate_or_map_removes_those_of_an_earlier_render(tmp_path):
    scene = fov90_scene(5, 4)
    render_image(StepAt(str(tmp_path / "img"), 2.3), scene, workers=1, samples_per_pixel=4,
                 adaptive=True)
    assert (tmp_path / "img_Step_samples.png").exists()
    render_image(StepAt(str(tmp_path / "img"), 2.3), scene, workers=1, samples_per_pixel=4)
    assert not (tmp_path / "img_Step_samples.png").exists()
    assert (tmp_path / "img_Step_accuracy.json").exists()
    render_image(StepAt(str(tmp_path / "img"), 2.3), scene, workers=1)
    assert not (tmp_path / "img_Step_accuracy.json").exists()


def test_integrator_making_its_own_rows_renders_them_uniformly_and_says_why(tmp_path, capfd):
    image = render_image(LazyIntegrator(str(tmp_path / "img")), fov90_scene(4, 2),
                         workers=1, samples_per_pixel=4, adaptive=True)
    assert image[1, 3] == pytest.approx([3 / 4, 1 / 2, 0.0])
    captured = capfd.readouterr()
    assert captured.err == ("PyRT: LazyIntegrator makes its rows itself (it overrides "
                            "render_row), so adaptive sampling cannot choose its rays: every "
                            "pixel gets 4\n")
    assert captured.out == NO_ESTIMATE
    assert not (tmp_path / "img_Lazy_accuracy.json").exists()


NO_ESTIMATE = ("No error estimate: LazyIntegrator makes its rows itself (it overrides "
               "render_row), so PyRT does not see its samples\n")


def test_integrator_making_its_own_rows_says_only_that_its_error_is_not_estimated(tmp_path,
                                                                                  capfd):
    render_image(LazyIntegrator(str(tmp_path / "img")), fov90_scene(4, 2), workers=1,
                 samples_per_pixel=2)
    assert capfd.readouterr() == (NO_ESTIMATE, "")
    render_image(LazyIntegrator(str(tmp_path / "img")), fov90_scene(4, 2), workers=1)
    assert capfd.readouterr() == ("", "")  # one sample per pixel: nothing to estimate


def test_adaptive_with_one_sample_per_pixel_says_what_adaptive_needs(tmp_path):
    integrator = PhongIntegrator(str(tmp_path / "img"))
    integrator.add_scene(sphere_test_scene(width=4, height=4))
    with pytest.raises(ValueError) as error:
        integrator.render(progress=False, samples_per_pixel=1, adaptive=True)
    assert str(error.value) == (
        "render: adaptive=True needs samples_per_pixel >= 2, the rays the pixels at edges get; "
        "with 1 every pixel gets the ray through its centre")


def test_adaptive_render_with_tolerance_one_refines_nothing(tmp_path):
    # the PNG's colours lie in [0, 1]: no two differ by more than 1
    integrator = StepAt(str(tmp_path / "img"), 2.3)
    image = render_image(integrator, fov90_scene(5, 4), workers=1, samples_per_pixel=4,
                         adaptive=True, tolerance=1)
    assert len(integrator.points) == 20
    assert (image[:, :2] == 1.0).all() and (image[:, 2:] == 0.0).all()  # the centre rays


@pytest.mark.parametrize("options, named", [
    *[({"adaptive": True, "tolerance": value}, "tolerance")
      for value in (-0.01, 1.5, math.nan, math.inf, "0.1", True, None)],
    ({"adaptive": "yes"}, "adaptive"),
    ({"tolerance": -1.0}, "tolerance"),
    ({"adaptive": True, "samples_per_pixel": 1}, "samples_per_pixel")])
def test_bad_adaptive_option_raises_value_error_naming_it(tmp_path, options, named):
    integrator = PhongIntegrator(str(tmp_path / "out" / "img"))
    integrator.add_scene(sphere_test_scene(width=4, height=4))
    options.setdefault("samples_per_pixel", 4)
    with pytest.raises(ValueError, match=re.escape(named)):
        integrator.render(progress=False, **options)
    assert not (tmp_path / "out").exists()


# ------------------------------------------------------------------------------------------
# The progress bar
# ------------------------------------------------------------------------------------------
def final_bar(err, description):
    """The last state of the progress bar `description` that a render wrote to stderr."""
    states = [line for line in err.replace("\r", "\n").splitlines()
              if line.startswith(description + ":")]
    assert states, err
    return states[-1]


@pytest.mark.parametrize("workers, samples", [(1, 1), (None, 2)])
def test_render_shows_a_progress_bar_of_the_pixels_unless_told_not_to(tmp_path, capfd,
                                                                      workers, samples):
    integrator = PixelGrey(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(40, 30))
    integrator.render(workers=workers, samples_per_pixel=samples)  # a progress bar by default
    bar = final_bar(capfd.readouterr().err, "PixelGrey")
    # 1200 pixels, counted with SI prefixes, and the pixels rendered per second
    assert re.match(r"PixelGrey: 100%\|.*\| 1\.20k/1\.20k \[.*px/s\]$", bar), bar
    integrator.render(workers=workers, samples_per_pixel=samples, progress=False)
    assert capfd.readouterr().err == ""


def test_adaptive_render_shows_a_bar_for_the_centre_rays_and_one_for_the_refined_pixels(
        tmp_path, capfd):
    # 20 centre rays; the edge at X = 2.3 refines columns 1 and 2: 8 pixels
    integrator = StepAt(str(tmp_path / "img"), 2.3)
    integrator.add_scene(fov90_scene(5, 4))
    integrator.render(workers=1, samples_per_pixel=16, adaptive=True)
    err = capfd.readouterr().err
    assert re.match(r"StepAt centre rays: 100%\|.*\| 20\.0/20\.0 \[",
                    final_bar(err, "StepAt centre rays"))
    assert re.match(r"StepAt 16 rays at edges: 100%\|.*\| 8\.00/8\.00 \[",
                    final_bar(err, "StepAt 16 rays at edges"))


# ------------------------------------------------------------------------------------------
# Errors students run into
# ------------------------------------------------------------------------------------------
def test_render_before_add_scene_says_to_call_add_scene(tmp_path):
    with pytest.raises(RuntimeError) as error:
        PhongIntegrator(str(tmp_path / "img")).render(progress=False)
    assert str(error.value) == ("PhongIntegrator.render: no scene to render; call "
                                "integrator.add_scene(scene) first")


def test_render_of_a_scene_without_camera_says_to_call_set_camera(tmp_path):
    scene = Scene()
    scene.add_object(Sphere(Vector3D(0, 0, -5), 1))
    integrator = PhongIntegrator(str(tmp_path / "img"))
    integrator.add_scene(scene)
    with pytest.raises(RuntimeError) as error:
        integrator.render(progress=False)
    assert str(error.value) == ("PhongIntegrator.render: the scene has no camera; call "
                                "scene.set_camera(Camera(width, height, fov)) first")


def test_camera_assigned_without_set_camera_is_rendered_at_its_own_size(tmp_path):
    scene = fov90_scene(5, 4)
    scene.camera = Camera(3, 2, 90)  # as scene.camera = ... in a student's script
    image = render_image(PixelGrey(str(tmp_path / "img")), scene, workers=1)
    assert image.shape == (2, 3, 3)
    assert image[1, 2].tolist() == [0.12] * 3


def test_rendering_a_scene_again_starts_from_a_black_image(tmp_path):
    # the partial image of a render stopped at row 3 holds no rows of the render before
    scene = fov90_scene(3, 6)
    render_image(Constant(str(tmp_path / "before")), scene, workers=1)
    integrator = InterruptedAtRow3(str(tmp_path / "img"))
    integrator.add_scene(scene)
    with pytest.raises(KeyboardInterrupt):
        integrator.render(workers=1, progress=False)
    assert not np.load(tmp_path / "img_PixelGrey_partial.npy")[3:].any()


class ReturnsAtCentre(Integrator):
    """Returns `value` for the centre pixel (1, 1) and BLACK elsewhere."""

    def __init__(self, filename_, value):
        super().__init__(filename_)
        self.value = value

    def compute_color(self, ray):
        return self.value if pixel_of(ray, self.scene.camera) == (1, 1) else BLACK


@pytest.mark.parametrize("value", [None, Vector3D(0.1, 0.2, 0.3), (0.1, 0.2, 0.3)],
                         ids=["None", "Vector3D", "tuple"])
def test_compute_color_returning_a_non_colour_names_class_method_and_pixel(tmp_path, value):
    integrator = ReturnsAtCentre(str(tmp_path / "img"), value)
    integrator.add_scene(fov90_scene(3, 3))
    with pytest.raises(TypeError) as error:
        integrator.render(workers=1, progress=False)
    message = str(error.value)
    assert "ReturnsAtCentre" in message
    assert "compute_color" in message
    assert "(1, 1)" in message


MUST_RETURN = ("; it must return an RGBColor, such as RGBColor(r, g, b) or BLACK, with "
               "numbers as channels")


@pytest.mark.parametrize("samples", [1, 4])
@pytest.mark.parametrize("value, shown", [
    (None, "None for pixel (1, 1) (is a return statement missing?)"),
    ((0.1, 0.2, 0.3), "(0.1, 0.2, 0.3) for pixel (1, 1)"),
    (RGBColor(0.5, Vector3D(0.0, 1.0, 0.0), 0.5),
     "RGBColor(0.5, Vector3D(0.0, 1.0, 0.0), 0.5) for pixel (1, 1)"),
], ids=["None", "tuple", "non-number channel"])
def test_compute_color_returning_a_non_colour_says_what_it_returned_and_must_return(
        tmp_path, value, shown, samples):
    integrator = ReturnsAtCentre(str(tmp_path / "img"), value)
    integrator.add_scene(fov90_scene(3, 3))
    with pytest.raises(TypeError) as error:
        integrator.render(workers=1, progress=False, samples_per_pixel=samples)
    assert str(error.value) == "ReturnsAtCentre.compute_color returned " + shown + MUST_RETURN


class BadChannelAtLastPixel(Integrator):
    """Returns a colour with a vector for its green channel at pixel (2, 1), the last of
    its row, and BLACK elsewhere."""

    def compute_color(self, ray):
        bad = RGBColor(0.5, Vector3D(0.0, 1.0, 0.0), 0.5)
        return bad if pixel_of(ray, self.scene.camera) == (2, 1) else BLACK


def test_a_colour_with_a_non_number_channel_at_the_end_of_a_row_is_found_there(tmp_path):
    integrator = BadChannelAtLastPixel(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(3, 3))
    with pytest.raises(TypeError, match=r"for pixel \(2, 1\);"):
        integrator.render(workers=1, progress=False)


class LeavesOutTheLastNumberOfRow2(PixelGrey):
    """Makes its rows itself, and row 2 lacks the blue channel of its last pixel."""

    def render_row(self, y, samples_per_pixel=1):
        row = super().render_row(y, samples_per_pixel)
        return row[:-1] if y == 2 else row


def test_rows_that_do_not_form_an_image_stop_the_render_with_a_value_error(tmp_path):
    integrator = LeavesOutTheLastNumberOfRow2(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(3, 8))
    with pytest.raises(ValueError, match=r"^render: the colours of the image do not form an "
                                         r"array$"):
        integrator.render(workers=1, progress=False)
    assert not (tmp_path / "img_PixelGrey.npy").exists()


class MisspelledAttribute(Integrator):
    def compute_color(self, ray):
        hit = self.scene.closest_hit(ray)
        return RGBColor(hit.hitpoint.x, 0.0, 0.0)


def test_attribute_error_inside_compute_color_is_not_disguised(tmp_path):
    integrator = MisspelledAttribute(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(3, 3, [(Sphere(Vector3D(0, 0, -5), 1), GREY)]))
    with pytest.raises(AttributeError, match="hitpoint"):
        integrator.render(workers=1, progress=False)


class NaNAndInfinity(PixelGrey):
    """PixelGrey with NaN at pixel (1, 0) and infinity at pixel (2, 2)."""

    def grey(self, x, y):
        return {(1, 0): math.nan, (2, 2): math.inf}.get((x, y), super().grey(x, y))


def test_non_finite_pixels_leave_the_rest_of_the_png_intact_and_are_reported(tmp_path, capfd):
    image = render_image(NaNAndInfinity(str(tmp_path / "img")), fov90_scene(3, 3),
                         workers=1)
    assert np.isnan(image[0, 1]).all() and np.isposinf(image[2, 2]).all()
    # The finite greys are (x + 10 y)/100, from 0 at (0, 0) to 0.21 at (1, 2); the
    # tonemapper maps them to ((g - 0) / (0.21 - 0)) ** (1 / 2.5).
    png = read_png(tmp_path / "img_PixelGrey.png")
    for y in range(3):
        for x in range(3):
            if (x, y) not in ((1, 0), (2, 2)):
                expected = ((x + 10 * y) / 100 / 0.21) ** (1 / 2.5)
                assert png[y, x] == pytest.approx([expected] * 3, abs=PNG_TOLERANCE)
    assert capfd.readouterr().err.splitlines() == [
        "PyRT warning: NaNAndInfinity.compute_color returned NaN or infinite values for 2 "
        "pixel(s), the first at pixel (1, 0); the PNG shows them as the image's darkest (NaN) "
        "or brightest (infinity) colour"]


class InterruptedAtRow3(PixelGrey):
    """PixelGrey that is stopped with Ctrl+C when it reaches pixel (0, 3)."""

    def grey(self, x, y):
        if (x, y) == (0, 3):
            raise KeyboardInterrupt
        return super().grey(x, y)


def test_ctrl_c_saves_the_rows_rendered_so_far_and_re_raises(tmp_path, capfd):
    integrator = InterruptedAtRow3(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(3, 6))
    with pytest.raises(KeyboardInterrupt):
        integrator.render(workers=1, progress=False)
    partial = str(tmp_path / "img_PixelGrey_partial")
    for suffix in (".png", ".npy", ".hdr"):
        assert (tmp_path / ("img_PixelGrey_partial" + suffix)).is_file()
    assert not (tmp_path / "img_PixelGrey.npy").exists()
    saved = np.load(partial + ".npy")
    for y in range(3):
        for x in range(3):
            assert tuple(saved[y, x]) == ((x + 10 * y) / 100,) * 3, (x, y)
    assert not saved[3:].any()
    assert partial in capfd.readouterr().err


def test_ctrl_c_with_workers_keeps_the_rows_the_workers_finished(tmp_path, worker_first):
    full = render_image(PhongIntegrator(str(tmp_path / "full")), small_cornell_box(32),
                        workers=1)
    worker_first(interrupt=True)
    integrator = PhongIntegrator(str(tmp_path / "img"))
    integrator.add_scene(small_cornell_box(32))
    with pytest.raises(KeyboardInterrupt):
        integrator.render(workers=2, progress=False)
    partial = np.load(tmp_path / "img_Phong_partial.npy")
    rendered = partial.any(axis=(1, 2))
    assert rendered.any() and not rendered.all()
    assert np.array_equal(partial[rendered], full[rendered])


def test_ctrl_c_between_blocks_stops_the_worker_processes(tmp_path, monkeypatch, worker_first):
    def interrupted(bar, n=1):  # Ctrl+C while render() updates the progress bar
        raise KeyboardInterrupt

    monkeypatch.setattr(tqdm, "update", interrupted)
    worker_first()
    integrator = PhongIntegrator(str(tmp_path / "img"))
    integrator.add_scene(small_cornell_box(128))
    with pytest.raises(KeyboardInterrupt) as raised:  # its traceback keeps render's frame
        integrator.render(workers=2, progress=False)
    assert multiprocessing.active_children() == [], raised


def test_unwritable_output_folder_fails_before_rendering(tmp_path):
    (tmp_path / "afile").write_text("a file, so no folder can be made under it")
    integrator = PixelGrey(str(tmp_path / "afile" / "out" / "img"))
    integrator.add_scene(fov90_scene(3, 3))
    with pytest.raises(OSError) as error:
        integrator.render(workers=1, progress=False)
    assert str(error.value) == (f"render: cannot write the images to "
                                f"{str(tmp_path.resolve() / 'afile' / 'out')!r} (Not a "
                                f"directory); choose another output folder")
    assert integrator.calls == 0


@pytest.mark.skipif(not os.path.isdir("/proc"), reason="needs a folder no one can write to")
def test_existing_folder_where_no_file_can_be_made_fails_before_rendering():
    # /proc exists, and not even root can create a file there
    integrator = PixelGrey("/proc/img")
    integrator.add_scene(fov90_scene(3, 3))
    with pytest.raises(PermissionError, match=r"^render: cannot write the images to '/proc' "):
        integrator.render(workers=1, progress=False)
    assert integrator.calls == 0


def test_render_makes_the_missing_folders_of_its_file_name(tmp_path):
    image = render_image(PixelGrey(str(tmp_path / "new" / "folders" / "img")),
                         fov90_scene(3, 2), workers=1)
    assert image[1, 2].tolist() == [0.12] * 3
