"""PyRT rendering machinery: what Integrator.render() needs besides the course's loop.

``Integrator.render()`` (PyRT_Integrators.py) is the loop: every pixel, a ray,
``compute_color``, the colour stored in the image, the image saved. This module holds what
makes that loop fast, smooth and safe, so that the integrators' file stays about rendering:

- checks made before any work, with messages that say what to fix;
- sampling patterns: where inside a pixel its rays go when it gets more than one;
- parallel rendering: worker processes on the other cores render blocks of rows into an
  image in shared memory, while this process renders too;
- the progress bar, the partial image saved on Ctrl+C, and the report of NaN or infinite
  pixels.

Nothing here changes an image: one process or several give the same pixels, bit for bit.
"""
import contextlib
import copy
import mmap
import multiprocessing
import multiprocessing.connection
import os
import pickle
import signal
import sys
import tempfile
import time
import traceback
from math import sqrt
from pathlib import Path

import numpy as np
from tqdm import tqdm

from PyRT_Common import RGBColor, Ray, Vector3D, check_constants

INFINITY = float("inf")
# With workers=None, a render that one process would finish sooner than this stays in
# one process: starting workers would cost more than they save. Forked workers (Linux)
# start in milliseconds; spawned ones (Windows, macOS) first import everything again,
# which took 0.65 s on a 2-core Linux machine and takes longer on most laptops. This
# process renders meanwhile, so a worker that starts late only takes fewer rows.
PARALLEL_MIN_SECONDS = {"fork": 0.2, "spawn": 2.0, "forkserver": 2.0}
SAMPLE_SEED = 0x5079_5254  # "PyRT"


# ------------------------------------------------------------------------------------------
# Checks before rendering
# ------------------------------------------------------------------------------------------
def check_render(integrator, workers, samples_per_pixel):
    """(scene, workers, samples_per_pixel) checked, with the scene's image allocated and
    cleared; or the error that says what to call or change first. Nothing is rendered
    before every check has passed."""
    if getattr(multiprocessing.current_process(), "_inheriting", False):
        # A worker process is importing the main script, and the script renders at
        # import: it is not guarded by `if __name__ == "__main__":`. The main process
        # sees the worker fail and renders on its own, saying why.
        raise SystemExit(1)
    name = type(integrator).__name__
    scene = integrator.scene
    if scene is None:
        raise RuntimeError(f"{name}.render: no scene to render; call "
                           "integrator.add_scene(scene) first")
    if getattr(scene, "camera", None) is None:
        raise RuntimeError(f"{name}.render: the scene has no camera; call "
                           "scene.set_camera(Camera(width, height, fov)) first")
    samples = _check_count("samples_per_pixel", samples_per_pixel)
    if workers is not None:
        workers = _check_count("workers", workers, "None (all cores) or a whole number >= 1")
    _check_writable(Path(integrator.get_filename()).resolve().parent)
    shape = (scene.camera.height, scene.camera.width, 3)
    if scene.rendered_image is None or scene.rendered_image.shape != shape:
        scene.rendered_image = np.zeros(shape)
    scene.rendered_image.fill(0.0)
    return scene, workers, samples


def _check_count(name, value, allowed="a whole number >= 1"):
    """value as an int, or a ValueError naming the render() argument and what is allowed."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise ValueError(f"render: {name} must be {allowed}, got {value!r}")
    return int(value)


def _check_writable(folder):
    """Fails before the render, not after it, when the images cannot be saved."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as error:
        raise PermissionError(f"render: cannot write the images to {str(folder)!r} "
                              f"({error.strerror or error}); choose another output folder"
                              ) from None


# ------------------------------------------------------------------------------------------
# Rows of the image
# ------------------------------------------------------------------------------------------
def render_block(integrator, y0, y1, samples_per_pixel):
    """Rows y0 .. y1-1 of the image, each from integrator.render_row, as an array of shape
    (y1 - y0, width, 3)."""
    rows = [integrator.render_row(y, samples_per_pixel) for y in range(y0, y1)]
    check_constants(f"{type(integrator).__name__}.render")
    try:
        return np.array(rows, dtype=float).reshape(y1 - y0, -1, 3)
    except (TypeError, ValueError):
        raise _first_bad_color(integrator, rows, y0) from None


def not_a_color(integrator, color, x, y):
    """The TypeError for compute_color returning `color`, not an RGBColor, at pixel (x, y)."""
    hint = " (is a return statement missing?)" if color is None else ""
    return TypeError(f"{type(integrator).__name__}.compute_color returned {color!r} for pixel "
                     f"({x}, {y}){hint}; it must return an RGBColor, such as "
                     "RGBColor(r, g, b) or BLACK, with numbers as channels")


def _first_bad_color(integrator, rows, y0):
    """The TypeError for the first pixel whose channels are not all numbers."""
    for y, row in enumerate(rows, y0):
        for x in range(len(row) // 3):
            channels = row[3 * x:3 * x + 3]
            if not all(isinstance(c, (int, float, np.number)) for c in channels):
                return not_a_color(integrator, RGBColor(*channels), x, y)
    return ValueError("render: the colours of the image do not form an array")


def _report_non_finite(image, name):
    """One line on stderr when some pixels are NaN or infinite: how many, and the first."""
    if np.isfinite(image).all():
        return
    bad = ~np.isfinite(image).all(axis=2)
    y, x = np.argwhere(bad)[0]
    print(f"PyRT warning: {name}.compute_color returned NaN or infinite values for "
          f"{int(bad.sum())} pixel(s), the first at pixel ({x}, {y}); the PNG shows them as "
          "the image's darkest (NaN) or brightest (infinity) colour", file=sys.stderr)


# ------------------------------------------------------------------------------------------
# Sampling patterns
# ------------------------------------------------------------------------------------------
def pixel_offsets(samples, y, width):
    """For each pixel of row y, the (u, v) points inside it that are sampled.

    N samples form a jittered grid of a x b cells (a*b = N, as square as N allows: 4x4 for
    16, 2x4 for 8): one random point in each cell, so the samples cover the pixel evenly.
    The random numbers depend only on the row, so an image is the same on every run and
    for any number of workers."""
    a = max(d for d in range(1, int(sqrt(samples)) + 1) if samples % d == 0)
    b = samples // a
    jitter = np.random.default_rng((SAMPLE_SEED, y)).random((width, samples, 2))
    cell = np.arange(samples)
    u = (cell % b + jitter[:, :, 0]) / b
    v = (cell // b + jitter[:, :, 1]) / a
    return np.stack((u, v), axis=2).tolist()


def sampled_row(integrator, y, samples):
    """Integrator.render_row with more than one sample per pixel: each pixel x gets the
    average colour of camera rays through the points pixel_offsets gives it."""
    camera = integrator.scene.camera
    compute_color = integrator.compute_color
    row = []
    for x, offsets in enumerate(pixel_offsets(samples, y, camera.width)):
        r = g = b = 0.0
        for u, v in offsets:
            direction = camera.get_direction(x, y, u, v)
            color = compute_color(Ray(Vector3D(0.0, 0.0, 0.0), direction, INFINITY, 0.0))
            try:
                r += color.r
                g += color.g
                b += color.b
            except (AttributeError, TypeError):
                raise not_a_color(integrator, color, x, y) from None
        row += (r / samples, g / samples, b / samples)
    return row


# ------------------------------------------------------------------------------------------
# Rendering the rows: in this process and in worker processes
# ------------------------------------------------------------------------------------------
@contextlib.contextmanager
def rendered_blocks(integrator, workers, samples, progress):
    """Yields an iterator over (first row, rows) blocks that together make the image, in
    any order, rendered by this process and by worker processes; shows a progress bar.
    The scene does not change meanwhile (Scene.unchanged).

    On Ctrl+C it stops the workers, saves the rows stored so far in the scene's image as
    <filename>_partial and re-raises. When all is done it reports NaN or infinite pixels."""
    scene = integrator.scene
    height, width = scene.camera.height, scene.camera.width
    bar = tqdm(total=height * width, unit="px", unit_scale=True, disable=not progress,
               desc=type(integrator).__name__, mininterval=0.5)
    blocks = _render_blocks(integrator, height, samples, workers)

    def counted():
        for y0, rows in blocks:
            yield y0, rows
            bar.update(rows.shape[0] * width)

    try:
        with scene.unchanged():
            yield counted()
    except KeyboardInterrupt:
        blocks.close()  # stops the worker processes, wherever Ctrl+C struck
        bar.close()
        partial = integrator.get_filename() + "_partial"
        scene.save_image(partial, tonemap=integrator.tonemap)
        print(f"\nInterrupted: the rows rendered so far are saved in {partial}.png (.npy, "
              ".hdr)", file=sys.stderr)
        raise
    bar.close()
    _report_non_finite(scene.rendered_image, type(integrator).__name__)


def _render_blocks(integrator, height, samples, workers):
    """Yields (first row, rows) blocks of the image, in any order."""
    first = 0
    if workers is None:  # time the first row to see whether workers would pay off
        start = time.perf_counter()
        yield 0, render_block(integrator, 0, 1, samples)
        first = 1
        rest = (time.perf_counter() - start) * (height - 1)
        method = multiprocessing.get_context().get_start_method()
        workers = usable_cores() if rest > PARALLEL_MIN_SECONDS[method] else 1
    blocks = _row_blocks(first, height, workers)
    payload = None
    if workers > 1 and len(blocks) > 1:
        payload, renderer, reason = _worker_payload(integrator)
        if reason:
            print(f"PyRT: rendering in one process: {reason}", file=sys.stderr)
    if payload is None:
        for y0, y1 in blocks:
            yield y0, render_block(integrator, y0, y1, samples)
        return
    yield from _render_with_workers(integrator.scene.camera, blocks, samples,
                                    min(workers, len(blocks)) - 1, payload, renderer)


def _render_with_workers(camera, blocks, samples, count, payload, renderer):
    """Yields the blocks rendered by this process, with renderer (a copy of the integrator
    unpickled from payload), and by `count` worker processes.

    Every process takes the next block not yet taken (a counter in shared memory), so
    this process renders from the start and a worker that starts late simply takes
    fewer. Workers write their rows straight into an image in shared memory and raise a
    flag per finished block: no pixels travel through pipes, and no process waits for
    another to hand out work. Each worker sends one message as it stops: None, or the
    error that stopped it."""
    mp = multiprocessing.get_context()
    shared = _SharedImage(mp, camera.height, camera.width, len(blocks))
    unreported = dict(enumerate(blocks))
    workers = []  # (process, receiving end of its pipe)
    for _ in range(count):
        receiver, sender = mp.Pipe(duplex=False)
        process = mp.Process(target=_worker, args=(payload, blocks, samples, shared, sender),
                             daemon=True)
        process.start()
        sender.close()
        workers.append((process, receiver))
    running = list(workers)
    try:
        while (i := shared.take()) is not None:
            y0, y1 = unreported.pop(i)
            yield y0, render_block(renderer, y0, y1, samples)
            yield from _reported(shared, unreported, running, timeout=0)
        while unreported and running:  # all blocks are taken: wait for the last ones
            yield from _reported(shared, unreported, running, timeout=0.1)
    except KeyboardInterrupt:
        yield from _reported(shared, unreported, [], timeout=0)  # for the partial image
        raise
    finally:
        shared.stop()
        for process, _ in running:  # its rows are in, or the render stopped on an error
            process.terminate()
        # Until a worker has exited, the memory pages it inherited are shared with this
        # process, copy on write: writing any of them (saving the image) copies it first.
        for process, _ in workers:
            process.join()
    for y0, y1 in list(unreported.values()):  # taken by a worker that stopped early
        yield y0, render_block(renderer, y0, y1, samples)


def usable_cores():
    """How many cores this process may run on."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def _row_blocks(y0, y1, workers):
    """Rows y0 .. y1-1 cut into blocks that shrink towards the end (guided scheduling):
    large blocks cost less to hand out, and the small last ones keep every worker busy
    until the image is done, even when some rows cost far more than others."""
    blocks = []
    while y0 < y1:
        step = max(1, (y1 - y0) // (workers * 4))
        blocks.append((y0, min(y0 + step, y1)))
        y0 += step
    return blocks


def _worker_payload(integrator):
    """(the pickled integrator for the worker processes, a copy unpickled from it, None),
    or (None, None, why they cannot be used). The workers get the scene without its image,
    which they do not need.

    The main process renders its share with the copy: pickling made CPython move the
    attributes of the originals into dictionaries, where every read is slower (renders
    took 10% longer); the unpickled copy keeps the compact layout."""
    trace = sys.gettrace()
    tracer_module = getattr(trace, "__module__", None) or type(trace).__module__
    if "debugpy" in sys.modules or "pydevd" in sys.modules or (
            trace is not None and not tracer_module.startswith("coverage")):
        return None, None, "a debugger is attached (so that breakpoints in compute_color work)"
    if multiprocessing.current_process().daemon:
        return None, None, ("this process is itself a daemonic worker process (of a "
                            "multiprocessing.Pool, say), which may not start processes")
    scene = copy.copy(integrator.scene)
    scene.rendered_image = None
    integrator = copy.copy(integrator)
    integrator.scene = scene
    try:
        payload = pickle.dumps(integrator)
        return payload, pickle.loads(payload), None
    except Exception as error:  # pickle raises several types, all meaning the same here
        return None, None, (f"the integrator or its scene cannot be sent to worker processes "
                            f"({type(error).__name__}: {error}); attributes such as lambdas, "
                            "open files or generators prevent it")


class _SharedImage:
    """What the processes rendering one image share: the image, how many blocks have been
    taken and a finished flag per block."""

    def __init__(self, mp, height, width, blocks):
        self.shape = (height, width, 3)
        if mp.get_start_method() == "fork":
            # Forked workers inherit this mapping. Its pages are zeroed as they are first
            # written, half of them by the worker, where RawArray zeroes all 6 MB of a
            # 500 x 500 image here, before the worker can start.
            self.buffer = mmap.mmap(-1, height * width * 3 * 8)
        else:
            self.buffer = mp.RawArray("d", height * width * 3)
        self.taken = mp.Value("i", 0)
        self.finished = mp.Array("b", blocks)

    def image(self):
        return np.frombuffer(self.buffer).reshape(self.shape)

    def take(self):
        """The index of the next block to render, or None when all are taken."""
        with self.taken.get_lock():
            i = self.taken.value
            if i >= len(self.finished):
                return None
            self.taken.value = i + 1
        return i

    def stop(self):
        with self.taken.get_lock():
            self.taken.value = len(self.finished)

    def finish(self, i):
        with self.finished.get_lock():  # the lock also publishes the rows written before
            self.finished[i] = 1

    def finished_blocks(self):
        with self.finished.get_lock():
            return self.finished[:]


def _worker(payload, blocks, samples, shared, results):
    """A worker process: renders the blocks it takes into the shared image."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl+C is handled once, by the main process
    try:
        integrator = pickle.loads(payload)
        image = shared.image()
        while (i := shared.take()) is not None:
            y0, y1 = blocks[i]
            image[y0:y1] = render_block(integrator, y0, y1, samples)
            shared.finish(i)
        results.send(None)
    except BaseException as error:
        try:
            pickle.loads(pickle.dumps(error))
        except Exception:  # an error that cannot travel between processes: send its text
            error = RuntimeError(f"{type(error).__name__}: {error}")
        results.send((error, traceback.format_exc()))


class _WorkerTraceback(Exception):
    """Where in a worker process an error was raised, shown above the error itself."""

    def __str__(self):
        return "\n" + self.args[0]


def _reported(shared, unreported, running, timeout):
    """Yields the blocks that workers finished since the last call, raises the error that
    stopped a worker, and takes the workers that stopped out of running."""
    ready = multiprocessing.connection.wait([receiver for _, receiver in running], timeout)
    for process, receiver in [worker for worker in running if worker[1] in ready]:
        running.remove((process, receiver))
        try:
            message = receiver.recv()
        except EOFError:  # it died, or could not start
            process.join()
            print(f"PyRT: a worker process stopped early (exit code {process.exitcode}); "
                  "this process renders its rows. If this script runs on Windows or macOS "
                  "(or with the 'spawn' start method), put the code that builds and renders "
                  "the scene under\n    if __name__ == \"__main__\":", file=sys.stderr)
            continue
        if message is not None:
            error, where = message
            raise error from _WorkerTraceback(where)
    flags = shared.finished_blocks()
    image = shared.image()
    for i in [i for i in unreported if flags[i]]:
        y0, y1 = unreported.pop(i)
        yield y0, image[y0:y1]
