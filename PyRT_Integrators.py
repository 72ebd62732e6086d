"""PyRT integrators: the algorithms that turn a scene into an image.

An integrator answers one question, ``compute_color(ray)``: what colour arrives along this
ray? ``render()`` asks it once per pixel, for the ray from the camera through the pixel's
centre, and saves the image. Write your own integrator by subclassing ``Integrator`` and
overriding ``compute_color``.
"""
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
from pathlib import Path

from tqdm import tqdm

from PyRT_Common import *
from PyRT_Common import __all__ as _common_names, _restore_state, check_constants

__all__ = _common_names + [
    "Integrator", "LazyIntegrator", "IntersectionIntegrator", "DepthIntegrator",
    "NormalIntegrator", "PhongIntegrator",
]

INFINITY = float("inf")
# A shadow ray stops this fraction short of its light, so a light lying exactly on a
# surface is not hidden by that surface.
SHADOW_EPSILON = 1e-6
# Secondary rays start this far above the surface, relative to the size of the hit point's
# coordinates: far above the rounding error of a hit point (about 1e-16 relative), far below
# any detail of the scene, and the same at every scale of the scene.
OFFSET_SCALE = 2.0 ** -32
# With workers=None, a render that one process would finish sooner than this stays in
# one process: starting workers would cost more than they save. Forked workers (Linux)
# start in milliseconds; spawned ones (Windows, macOS) first import everything again,
# which took 0.65 s on a 2-core Linux machine and takes longer on most laptops. This
# process renders meanwhile, so a worker that starts late only takes fewer rows.
PARALLEL_MIN_SECONDS = {"fork": 0.2, "spawn": 2.0, "forkserver": 2.0}
SAMPLE_SEED = 0x5079_5254  # "PyRT"


# ------------------------------------------------------------------------------------------
# Integrator base class
# ------------------------------------------------------------------------------------------
class Integrator(ABC):
    """Renders ``scene`` into ``filename`` = filename_ + experiment_name (+ '.png', ...).

    The rendering loop, for every pixel (x, y) of the camera:
        ray = the ray from the camera origin through the centre of pixel (x, y)
        scene.set_pixel(self.compute_color(ray), x, y)
    then ``scene.save_image(self.get_filename())``.
    """

    __setstate__ = _restore_state

    tonemap = True  # the PNG goes through the course's tonemapper (see Scene.save_image)

    def __init__(self, filename_, experiment_name=""):
        self.filename = filename_ + experiment_name
        self.scene = None

    def get_filename(self):
        return self.filename

    def add_scene(self, scene):
        self.scene = scene

    @abstractmethod
    def compute_color(self, ray):
        """The RGBColor arriving along ray."""

    def render(self, workers=None, samples_per_pixel=1, progress=True):
        """Renders every pixel and saves the image.

        workers: how many processes render, this one included: None uses every core (for
            renders long enough to gain from them), 1 renders in this process only. The
            image is the same either way.
        samples_per_pixel: rays per pixel, averaged; 1 is the ray through the centre, more
            (jittered over an even grid inside the pixel) smooth jagged edges.
        progress: show a progress bar with the time left."""
        if getattr(multiprocessing.current_process(), "_inheriting", False):
            # A worker process is importing the main script, and the script renders at
            # import: it is not guarded by `if __name__ == "__main__":`. The main process
            # sees the worker fail and renders on its own, saying why.
            raise SystemExit(1)
        scene = self._checked_scene()
        samples = _check_count("samples_per_pixel", samples_per_pixel)
        if workers is not None:
            workers = _check_count("workers", workers, "None (all cores) or a whole number >= 1")
        filename = self.get_filename()
        _check_writable(Path(filename).resolve().parent)
        height, width = scene.camera.height, scene.camera.width
        if scene.rendered_image is None or scene.rendered_image.shape != (height, width, 3):
            scene.rendered_image = np.zeros((height, width, 3))
        image = scene.rendered_image
        image.fill(0.0)
        bar = tqdm(total=height * width, unit="px", unit_scale=True, disable=not progress,
                   desc=type(self).__name__, mininterval=0.5)
        blocks = self._render_blocks(height, samples, workers)
        try:
            for y0, rows in blocks:
                image[y0:y0 + len(rows)] = rows
                bar.update(rows.shape[0] * width)
        except KeyboardInterrupt:
            blocks.close()  # stops the worker processes, wherever Ctrl+C struck
            bar.close()
            scene.save_image(filename + "_partial", tonemap=self.tonemap)
            print(f"\nInterrupted: the rows rendered so far are saved in "
                  f"{filename}_partial.png (.npy, .hdr)", file=sys.stderr)
            raise
        bar.close()
        _report_non_finite(image, type(self).__name__)
        scene.save_image(filename, tonemap=self.tonemap)

    def render_rows(self, y0, y1, samples_per_pixel=1):
        """Rows y0 .. y1-1 of the image as an array of shape (y1 - y0, width, 3)."""
        rows = [self.row_colors(y, samples_per_pixel) for y in range(y0, y1)]
        check_constants(f"{type(self).__name__}.render")
        try:
            return np.array(rows, dtype=float).reshape(y1 - y0, -1, 3)
        except (TypeError, ValueError):
            raise self._first_bad_color(rows, y0) from None

    def row_colors(self, y, samples_per_pixel=1):
        """The channels of row y, flat: [r0, g0, b0, r1, g1, b1, ...]. Pixel x gets the
        colour arriving along the camera ray through it, averaged over samples_per_pixel
        rays. (A flat list of floats becomes an array three times faster than a list of
        (r, g, b) tuples.)

        Camera rays start at no surface, so t_min = 0: they see objects at any distance."""
        camera = self.scene.camera
        compute_color = self.compute_color
        row = []
        if samples_per_pixel == 1:
            for direction in camera.row_directions(y):
                color = compute_color(Ray(Vector3D(0.0, 0.0, 0.0), direction, INFINITY, 0.0))
                try:
                    row += (color.r, color.g, color.b)
                except AttributeError:
                    raise self._not_a_color(color, len(row) // 3, y) from None
            return row
        for x, offsets in enumerate(_pixel_offsets(samples_per_pixel, y, camera.width)):
            r = g = b = 0.0
            for u, v in offsets:
                direction = camera.get_direction(x, y, u, v)
                color = compute_color(Ray(Vector3D(0.0, 0.0, 0.0), direction, INFINITY, 0.0))
                try:
                    r += color.r
                    g += color.g
                    b += color.b
                except (AttributeError, TypeError):
                    raise self._not_a_color(color, x, y) from None
            row += (r / samples_per_pixel, g / samples_per_pixel, b / samples_per_pixel)
        return row

    def _first_bad_color(self, rows, y0):
        """The TypeError for the first pixel whose channels are not all numbers."""
        for y, row in enumerate(rows, y0):
            for x in range(len(row) // 3):
                channels = row[3 * x:3 * x + 3]
                if not all(isinstance(c, (int, float, np.number)) for c in channels):
                    return self._not_a_color(RGBColor(*channels), x, y)
        return ValueError("render: the colours of the image do not form an array")

    def _not_a_color(self, color, x, y):
        hint = " (is a return statement missing?)" if color is None else ""
        return TypeError(f"{type(self).__name__}.compute_color returned {color!r} for pixel "
                         f"({x}, {y}){hint}; it must return an RGBColor, such as "
                         "RGBColor(r, g, b) or BLACK, with numbers as channels")

    def _checked_scene(self):
        scene = self.scene
        if scene is None:
            raise RuntimeError(f"{type(self).__name__}.render: no scene to render; call "
                               "integrator.add_scene(scene) first")
        if getattr(scene, "camera", None) is None:
            raise RuntimeError(f"{type(self).__name__}.render: the scene has no camera; call "
                               "scene.set_camera(Camera(width, height, fov)) first")
        return scene

    def _render_blocks(self, height, samples, workers):
        """Yields (first row, rows) blocks of the image, in any order."""
        first = 0
        if workers is None:  # time the first row to see whether workers would pay off
            start = time.perf_counter()
            yield 0, self.render_rows(0, 1, samples)
            first = 1
            rest = (time.perf_counter() - start) * (height - 1)
            method = multiprocessing.get_context().get_start_method()
            workers = usable_cores() if rest > PARALLEL_MIN_SECONDS[method] else 1
        blocks = _row_blocks(first, height, workers)
        payload = None
        if workers > 1 and len(blocks) > 1:
            payload, renderer, reason = _worker_payload(self)
            if reason:
                print(f"PyRT: rendering in one process: {reason}", file=sys.stderr)
        if payload is None:
            for y0, y1 in blocks:
                yield y0, self.render_rows(y0, y1, samples)
            return
        yield from self._render_with_workers(blocks, samples, min(workers, len(blocks)) - 1,
                                             payload, renderer)

    def _render_with_workers(self, blocks, samples, count, payload, renderer):
        """Yields the blocks rendered by this process, with renderer (a copy of this
        integrator unpickled from payload), and by `count` worker processes.

        Every process takes the next block not yet taken (a counter in shared memory), so
        this process renders from the start and a worker that starts late simply takes
        fewer. Workers write their rows straight into an image in shared memory and raise a
        flag per finished block: no pixels travel through pipes, and no process waits for
        another to hand out work. Each worker sends one message as it stops: None, or the
        error that stopped it."""
        mp = multiprocessing.get_context()
        camera = self.scene.camera
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
                yield y0, renderer.render_rows(y0, y1, samples)
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
            yield y0, renderer.render_rows(y0, y1, samples)


# ------------------------------------------------------------------------------------------
# Rendering helpers: sampling, worker processes, checks
# ------------------------------------------------------------------------------------------
def _pixel_offsets(samples, y, width):
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


def _report_non_finite(image, name):
    if np.isfinite(image).all():
        return
    bad = ~np.isfinite(image).all(axis=2)
    count = int(bad.sum())
    if count:
        y, x = np.argwhere(bad)[0]
        print(f"PyRT warning: {name}.compute_color returned NaN or infinite values for "
              f"{count} pixel(s), the first at pixel ({x}, {y}); the PNG shows them as the "
              "image's darkest (NaN) or brightest (infinity) colour", file=sys.stderr)


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
            image[y0:y1] = integrator.render_rows(y0, y1, samples)
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


# ------------------------------------------------------------------------------------------
# Lazy integrator (Assignment 1.1)
# ------------------------------------------------------------------------------------------
class LazyIntegrator(Integrator):
    """Colours pixel (x, y) by its position: (x/width, y/height, 0), red growing to the
    right and green downwards. It traces no rays, and its PNG shows the linear values
    without tonemapping, as Figure 2 of the course does."""

    tonemap = False

    def __init__(self, filename_, experiment_name=""):
        super().__init__(filename_ + "_Lazy", experiment_name)

    def row_colors(self, y, samples_per_pixel=1):
        """One exact value per pixel, however many samples are asked for."""
        camera = self.scene.camera
        green = y / camera.height
        return [c for x in range(camera.width) for c in (x / camera.width, green, 0.0)]

    def compute_color(self, ray):
        """A ray carries no pixel position, so on its own it gets BLACK (see row_colors)."""
        return BLACK


# ------------------------------------------------------------------------------------------
# Intersection integrator (Assignment 1.2)
# ------------------------------------------------------------------------------------------
class IntersectionIntegrator(Integrator):
    """RED where the ray hits any object, BLACK where it escapes."""

    def __init__(self, filename_, experiment_name=""):
        super().__init__(filename_ + "_Intersection", experiment_name)

    def compute_color(self, ray):
        return RED if self.scene.any_hit(ray) else BLACK


# ------------------------------------------------------------------------------------------
# Depth and Normal integrators (Assignment 1.3)
# ------------------------------------------------------------------------------------------
class DepthIntegrator(Integrator):
    """Grey c = max(1 - hit_distance / max_depth, 0) at the closest hit: white close to the
    camera, black at max_depth and beyond or on a miss."""

    def __init__(self, filename_, max_depth_=10, experiment_name=""):
        super().__init__(filename_ + "_Depth", experiment_name)
        if isinstance(max_depth_, bool) or not isinstance(max_depth_, (int, float, np.number)) \
                or not 0.0 < max_depth_ < INFINITY:
            raise ValueError(f"DepthIntegrator: max_depth_ must be a positive finite distance, "
                             f"got {max_depth_!r}")
        self.max_depth = max_depth_

    def compute_color(self, ray):
        hit = self.scene.closest_hit(ray)
        if not hit.has_hit:
            return BLACK
        c = 1.0 - hit.hit_distance / self.max_depth
        return RGBColor(c, c, c) if c > 0.0 else BLACK  # c = max(1 - distance/max_depth, 0)


class NormalIntegrator(Integrator):
    """The closest hit's unit normal n shown as a colour, c = (n + (1, 1, 1)) / 2, which
    maps each component from [-1, 1] to [0, 1]."""

    def __init__(self, filename_, experiment_name=""):
        super().__init__(filename_ + "_Normal", experiment_name)

    def compute_color(self, ray):
        hit = self.scene.closest_hit(ray)
        if not hit.has_hit:
            return BLACK
        n = hit.normal
        return RGBColor((n.x + 1.0) / 2.0, (n.y + 1.0) / 2.0, (n.z + 1.0) / 2.0)


# ------------------------------------------------------------------------------------------
# Phong integrator (Assignment 1.4)
# ------------------------------------------------------------------------------------------
class PhongIntegrator(Integrator):
    """The course's Phong model with Lambertian surfaces, at the closest hit p with normal n:

        colour = kd (x) i_a + sum over the point lights visible from p of
                 intensity (x) BRDF.get_value(wi, wo, n) / r^2

    wi is the unit direction from p to the light, r its distance, wo the direction back
    along the ray, (x) the per-channel product. A light is visible when no object lies
    between p and the light; one behind the surface (n.wi <= 0) cannot contribute, so it
    costs no shadow ray. There is no specular term."""

    def __init__(self, filename_, experiment_name=""):
        super().__init__(filename_ + "_Phong", experiment_name)

    def compute_color(self, ray):
        scene = self.scene
        hit = scene.closest_hit(ray)
        if not hit.has_hit:
            return BLACK
        brdf = scene.object_list[hit.primitive_index].BRDF
        if brdf is None:
            raise ValueError(f"PhongIntegrator: object {hit.primitive_index} of the scene has "
                             "no BRDF; call obj.set_BRDF(Lambertian(RGBColor(...))) on it")
        kd, i_a = brdf.kd, scene.i_a
        r, g, b = kd.r * i_a.r, kd.g * i_a.g, kd.b * i_a.b
        p, n = hit.hit_point, hit.normal
        px, py, pz, nx, ny, nz = p.x, p.y, p.z, n.x, n.y, n.z
        d = ray.d
        wo = Vector3D(-d.x, -d.y, -d.z)
        offset = OFFSET_SCALE * (max(abs(px), abs(py), abs(pz)) + hit.hit_distance)
        # Shadow rays start just above the surface (on the light's side of it) and ignore
        # the first `offset` of their way, which skips the surface itself and, on an edge
        # where two walls meet, the other wall. Both scale with the scene, where a fixed
        # t_min would be too large for tiny scenes and too small for huge ones.
        sx, sy, sz = px + nx * offset, py + ny * offset, pz + nz * offset
        for light in scene.pointLights:
            pos = light.pos
            lx, ly, lz = pos.x - px, pos.y - py, pos.z - pz
            # The light's height above the surface: at or below `offset` it is behind the
            # surface or lies on it, and lights no part of it.
            if lx * nx + ly * ny + lz * nz <= offset:
                continue
            r2 = lx * lx + ly * ly + lz * lz
            distance = sqrt(r2)
            wx, wy, wz = lx / distance, ly / distance, lz / distance
            if scene.occluded(sx, sy, sz, wx, wy, wz, offset,
                              distance * (1.0 - SHADOW_EPSILON) - offset):
                continue
            f = brdf.get_value(Vector3D(wx, wy, wz), wo, n)
            intensity = light.intensity
            r += intensity.r * f.r / r2
            g += intensity.g * f.g / r2
            b += intensity.b * f.b / r2
        return RGBColor(r, g, b)
