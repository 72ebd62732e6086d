"""PyRT worker processes: the rows of an image rendered on every core.

render_blocks renders the blocks of rows of one pass of a render in this process, and,
when the render is long enough to repay starting them, in worker processes on the other
cores too. Every process takes the next block not yet taken; workers write their rows
into an image in shared memory. The image is the same, bit for bit, whatever the number
of processes.
"""
import copy
import copyreg
import io
import mmap
import multiprocessing
import multiprocessing.connection
import os
import pickle
import signal
import sys
import time
import traceback

import numpy as np

from PyRT_Core import BRDF, Camera, PointLight, Primitive, Scene
from pyrt.acceleration.accelerated import accelerated, debugger_attached, plain
from pyrt.rows import render_block

# With workers=None, a render that one process would finish sooner than this stays in
# one process: starting workers would cost more than they save. Forked workers (Linux)
# start in milliseconds; spawned ones (Windows, macOS) first import everything again,
# which takes longer. This process renders meanwhile, so a worker that starts late only
# takes fewer rows.
PARALLEL_MIN_SECONDS = {"fork": 0.2, "spawn": 2.0, "forkserver": 2.0}
# The course's classes whose objects the workers receive pickled, besides the integrator's
# own class: unpickled with their attributes set one by one (_restore_state), they keep
# CPython's compact attribute layout, which pickle's default (updating obj.__dict__) gives
# up, making every attribute read of a render slower.
COMPACT_CLASSES = (Scene, Primitive, BRDF, PointLight, Camera)
# The environment variable that chooses how worker processes start, one of
# multiprocessing's start methods ("fork", "spawn", "forkserver"); the tests use it to run
# under each. Unset: see start_method.
START_METHOD_VARIABLE = "PYRT_START_METHOD"


def render_blocks(integrator, rows, workers):
    """Yields (first row, block) blocks of the image, each from render_block with the row
    function rows, in any order, rendered by `workers` processes; None: as many as repay
    starting them, which the time of the first rows tells. Each process renders with the
    scene's queries accelerated (pyrt.acceleration), and nothing may change the scene."""
    camera = integrator.scene.camera
    with accelerated(integrator, camera.height * camera.width):
        yield from _render_blocks(integrator, camera.height, rows, workers)


def _render_blocks(integrator, height, rows, workers):
    """render_blocks, with this process's queries accelerated."""
    first = 0
    if workers is None:
        width = integrator.scene.camera.width
        start = time.perf_counter()
        while True:  # one row after the other, until they tell the time per pixel
            yield first, render_block(integrator, first, first + 1, rows)
            first += 1
            done, elapsed = rows.pixels(0, first, width), time.perf_counter() - start
            if first == height or done >= width or elapsed > PARALLEL_MIN_SECONDS["fork"]:
                break
        # the rest, at the time per pixel of the rows timed (a pass of adaptive sampling
        # has rows of few pixels and rows of many)
        workers = worker_count(elapsed / max(done, 1) * rows.pixels(first, height, width))
    blocks = _row_blocks(first, height, workers)
    payload = None
    if workers > 1 and len(blocks) > 1:
        payload, renderer, reason = _worker_payload(integrator)
        if reason:
            print(f"PyRT: rendering in one process: {reason}", file=sys.stderr)
    if payload is None:
        for y0, y1 in blocks:
            yield y0, render_block(integrator, y0, y1, rows)
        return
    yield from _render_with_workers(integrator.scene.camera, blocks, rows,
                                    min(workers, len(blocks)) - 1, payload, renderer)


def worker_count(seconds):
    """The processes for rows that one process would render in `seconds`: every usable
    core when the render is long enough for workers to pay off, else 1."""
    return usable_cores() if seconds > PARALLEL_MIN_SECONDS[start_method()] else 1


def start_method():
    """How worker processes start: PYRT_START_METHOD when set, else the method the script
    set with multiprocessing.set_start_method, else the system's default; but from Python
    3.12 on, 'forkserver' where these give 'fork'."""
    chosen = os.environ.get(START_METHOD_VARIABLE)
    if chosen:
        methods = multiprocessing.get_all_start_methods()
        if chosen not in methods:
            raise ValueError(f"{START_METHOD_VARIABLE}={chosen!r}: this system's start "
                             "methods are " + ", ".join(methods))
        return chosen
    # the first of all start methods is the system's default
    chosen = (multiprocessing.get_start_method(allow_none=True)
              or multiprocessing.get_all_start_methods()[0])
    # numpy's and OpenCV's thread pools make the process multi-threaded, and a forked
    # child of such a process may deadlock on a lock a thread held: Python 3.12 warns of
    # it at each fork, and Python 3.14 makes forkserver Linux's default. (A method that
    # reads 'fork' may be no one's choice: tqdm, for one, fixes the default as it starts.)
    if chosen == "fork" and sys.version_info >= (3, 12):
        return "forkserver"
    return chosen


def _render_with_workers(camera, blocks, rows, count, payload, renderer):
    """Yields the blocks rendered by this process, with renderer (a copy of the integrator
    unpickled from payload), and by `count` worker processes.

    Every process takes the next block not yet taken (a counter in shared memory), so
    this process renders from the start and a worker that starts late simply takes
    fewer. Workers write their rows straight into an image in shared memory and raise a
    flag per finished block: no pixels travel through pipes, and no process waits for
    another to hand out work. Each worker sends one message as it stops: None, or the
    error that stopped it."""
    mp = multiprocessing.get_context(start_method())
    shared = _SharedImage(mp, (camera.height, camera.width, rows.channels), len(blocks))
    unreported = dict(enumerate(blocks))
    workers = []  # (process, receiving end of its pipe)
    for _ in range(count):
        receiver, sender = mp.Pipe(duplex=False)
        process = mp.Process(target=_worker, args=(payload, blocks, rows, shared, sender),
                             daemon=True)
        process.start()
        sender.close()
        workers.append((process, receiver))
    running = list(workers)
    with accelerated(renderer):
        yield from _render_alongside(renderer, blocks, rows, shared, unreported, workers,
                                     running)


def _render_alongside(renderer, blocks, rows, shared, unreported, workers, running):
    """The blocks of _render_with_workers that this process renders, with those the
    workers report meanwhile; stops the workers at the end."""
    try:
        while (i := shared.take()) is not None:
            y0, y1 = unreported.pop(i)
            yield y0, render_block(renderer, y0, y1, rows)
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
        yield y0, render_block(renderer, y0, y1, rows)


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


def _restore_state(obj, state):
    """Unpickles obj's attributes one by one, which keeps CPython's compact layout."""
    for name, value in state.items():
        setattr(obj, name, value)


class _CompactPickler(pickle.Pickler):
    """A pickler whose objects of the classes `compact` unpickle with _restore_state."""

    def __init__(self, file, compact):
        super().__init__(file)
        self.compact = compact

    def reducer_override(self, obj):
        if isinstance(obj, self.compact):
            # what pickle's default does, with _restore_state setting the attributes
            return copyreg.__newobj__, (type(obj),), vars(obj), None, None, _restore_state
        return NotImplemented


def compact_pickle(integrator):
    """The integrator pickled for the worker processes: it, and its objects of
    COMPACT_CLASSES, unpickle with CPython's compact attribute layout (_restore_state)."""
    data = io.BytesIO()
    _CompactPickler(data, COMPACT_CLASSES + (type(integrator),)).dump(integrator)
    return data.getvalue()


def _worker_payload(integrator):
    """(the pickled integrator for the worker processes, a copy unpickled from it, None),
    or (None, None, why they cannot be used). The workers get the scene without its image,
    which they do not need.

    The main process renders its share with the copy: pickling made CPython move the
    attributes of the originals into dictionaries, where every read is slower; the
    unpickled copy keeps the compact layout."""
    if debugger_attached():
        return None, None, "a debugger is attached (so that breakpoints in compute_color work)"
    if multiprocessing.current_process().daemon:
        return None, None, ("this process is itself a daemonic worker process (of a "
                            "multiprocessing.Pool, say), which may not start processes")
    scene = copy.copy(integrator.scene)
    scene.rendered_image = None
    integrator = copy.copy(integrator)
    integrator.scene = scene
    plain(scene)  # each process sets up its own accelerated queries
    plain(integrator)
    try:
        payload = compact_pickle(integrator)
        return payload, pickle.loads(payload), None
    except Exception as error:  # pickle raises several types, all meaning the same here
        where = unpicklable_part(integrator, "integrator")
        return None, None, (f"{where or 'the integrator or its scene'} cannot be sent to "
                            f"worker processes ({type(error).__name__}: {error}); attributes "
                            "such as lambdas, functions or classes defined inside a function, "
                            "open files or generators prevent it")


def unpicklable_part(obj, name, depth=4):
    """The name of the innermost part of obj (its attributes, the items of its lists,
    tuples and dictionaries, `depth` levels down) that pickle refuses, such as
    'integrator.myGP[0].p_func'; None when pickle takes obj, or when nothing below it
    is to blame."""
    try:
        pickle.dumps(obj)
        return None
    except Exception:
        pass
    if depth > 0:
        if isinstance(obj, (list, tuple)):
            parts = [(f"{name}[{i}]", item) for i, item in enumerate(obj)]
        elif isinstance(obj, dict):
            parts = [(f"{name}[{key!r}]", item) for key, item in obj.items()]
        else:
            parts = [(f"{name}.{key}", item) for key, item in getattr(obj, "__dict__", {}).items()]
        for part_name, part in parts:
            found = unpicklable_part(part, part_name, depth - 1)
            if found:
                return found
    return name


class _SharedImage:
    """What the processes rendering one image share: the image (of shape (height, width,
    numbers per pixel)), how many blocks have been taken and a finished flag per block."""

    def __init__(self, mp, shape, blocks):
        self.shape = shape
        size = int(np.prod(shape))
        if mp.get_start_method() == "fork":
            # Forked workers inherit this mapping. Its pages are zeroed as they are first
            # written, half of them by the worker, where RawArray zeroes the whole image
            # here, before the worker can start.
            self.buffer = mmap.mmap(-1, size * 8)
        else:
            self.buffer = mp.RawArray("d", size)
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


def _worker(payload, blocks, rows, shared, results):
    """A worker process: renders the blocks it takes into the shared image."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl+C is handled once, by the main process
    try:
        integrator = pickle.loads(payload)
        image = shared.image()
        with accelerated(integrator):
            while (i := shared.take()) is not None:
                y0, y1 = blocks[i]
                image[y0:y1] = render_block(integrator, y0, y1, rows)
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
