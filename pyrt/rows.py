"""PyRT rows: how one task of a render is made, in whichever process renders it.

A task is one row of a pass: its random stream starts (RowStreams.start), then the
integrator's own render loop (the body of Integrator.render, LoopBody) runs once with the
scene's camera, set_pixel and save_image stood in for (TaskStandIns): a camera over the
task's rays (TaskCamera), a buffer that keeps each ray's colour (set_pixel), and a save
that waits for the end of the render. The row function of the pass (CourseRows: the ray
through each pixel's centre; SampledRows: N jittered rays in every pixel or in the
pixels adaptive sampling picks) chooses the rays and makes the row of the image from
their colours, so that an image is the same for any number of worker processes.
"""
import random
from itertools import chain
from math import sqrt
from typing import NamedTuple

import numpy as np

from PyRT_Common import RGBColor, check_constants

SAMPLE_SEED = 0x5079_5254  # "PyRT"


# ------------------------------------------------------------------------------------------
# The random stream of a row
# ------------------------------------------------------------------------------------------
class RowStreams(NamedTuple):
    """The random numbers of a render's rows: before row y of pass `number` is made,
    Python's global generator (what random.random() and the course's random() draw from)
    is seeded from (seed, number, y), and numpy's global generator (np.random.uniform and
    the like, with which students draw their rotations) from the same three numbers. Each
    row has a stream of its own, whichever process renders it and whatever it rendered
    before, so the image is the same for any number of workers; seed is one draw of
    Python's generator as the render starts."""

    seed: int
    number: int = 0

    def start(self, y):
        """Starts row y's random streams: the one place where a row's generators are
        seeded (Python's and numpy's global generators here)."""
        random.seed(f"{self.seed}:{self.number}:{y}")
        # one 32-bit number, distinct for every row of every pass (y < 2^20), as cheap to
        # seed from as numpy allows (a list of numbers takes four times as long)
        np.random.seed((self.seed ^ (self.number << 20) ^ y) & 0xFFFF_FFFF)


# ------------------------------------------------------------------------------------------
# The integrator's loop, run once per task
# ------------------------------------------------------------------------------------------
# The undecorated render loops (pyrt.rendering.render_loop), by the name of their function:
# a worker process finds them here once it has imported the integrator's module.
_LOOP_BODIES = {}


def _loop_key(function):
    # a spawned worker imports the main script as __mp_main__
    module = "__main__" if function.__module__ == "__mp_main__" else function.__module__
    return f"{module}.{function.__qualname__}"


class LoopBody(NamedTuple):
    """An integrator's undecorated render loop, by name: what a task runs, picklable for
    the worker processes (see loop_body)."""

    key: str

    def __call__(self, integrator):
        return _LOOP_BODIES[self.key](integrator)


def loop_body(function) -> LoopBody:
    """Registers function, an undecorated render loop (body(integrator)), for the tasks."""
    key = _loop_key(function)
    _LOOP_BODIES[key] = function
    return LoopBody(key)


class TaskCamera:
    """The scene's camera as the render loop and compute_color see it during a task: a
    camera over the task's rays, a column of them, width = 1 and height = their number,
    whose get_direction(0, y) is the direction of ray y (of the task's pixels, through
    their centres or through the points of several samples). A column, because the
    course's loop runs over y inside its loop over x: its inner loop then runs over all
    the task's rays at once. Its other attributes (vertical_fov, aspect_ratio, ...) are
    the scene's camera's, which is `camera`."""

    def __init__(self, camera, directions):
        self.camera = camera
        self.directions = directions
        self.width = 1
        self.height = len(directions)

    def get_direction(self, x, y, u=0.5, v=0.5):
        """The direction of the task's ray y (x is 0: the task is one column of rays)."""
        return self.directions[y]

    def __getattr__(self, name):
        return getattr(self.camera, name)


class TaskStandIns:
    """What the scene's set_pixel and save_image are during a task: set_pixel(pixel_val, 0,
    y) keeps the colour of the task's ray y, in `colors` (the values, should pixel_val
    change later); save_image keeps the name asked for in `saved`, for the render to
    save once every task is done. `pixel_of(y)` gives the image's pixel of ray y, for the
    messages."""

    def __init__(self, integrator, saved):
        self.integrator = integrator
        self.saved = saved
        self.colors = []
        self.pixel_of = None

    def start(self, count, pixel_of):
        self.colors = [None] * count
        self.pixel_of = pixel_of

    def set_pixel(self, pixel_val, x, y):
        try:
            self.colors[y] = (pixel_val.r, pixel_val.g, pixel_val.b)
        except AttributeError:
            raise not_a_color(self.integrator, pixel_val, *self.pixel_of(y)) from None
        except IndexError:
            raise IndexError(f"Scene.set_pixel: pixel ({x}, {y}) is outside this task's "
                             f"column of {len(self.colors)} rays") from None

    def save_image(self, full_filename, tonemap=True):
        self.saved.append(full_filename)

    def unset(self):
        """The first ray number of the task whose colour set_pixel was not given, or None."""
        if None not in self.colors:
            return None
        return self.colors.index(None)


STOOD_IN_FOR = ("camera", "set_pixel", "save_image")


def render_block(integrator, y0, y1, rows):
    """Rows y0 .. y1-1 of the image, each from a task of the row function rows (its rays,
    the integrator's loop on them, their colours made into the row), with the row's own
    random stream, as an array of shape (y1 - y0, width, rows.channels)."""
    scene = integrator.scene
    camera = scene.camera
    own = {name: vars(scene)[name] for name in STOOD_IN_FOR if name in vars(scene)}
    stand_ins = TaskStandIns(integrator, rows.saved)
    scene.set_pixel, scene.save_image = stand_ins.set_pixel, stand_ins.save_image
    block = []
    try:
        for y in range(y0, y1):
            rows.streams.start(y)
            directions, pixel_of = rows.rays(camera, y)
            stand_ins.start(len(directions), pixel_of)
            scene.camera = TaskCamera(camera, directions)
            rows.loop(integrator)
            missing = stand_ins.unset()
            if missing is not None:
                raise RuntimeError(f"{type(integrator).__name__}.render: the loop set no "
                                   f"colour for pixel {pixel_of(missing)} (it calls "
                                   "scene.set_pixel(color, x, y) for every pixel)")
            # flat at once: a block's colours kept as tuples would slow every row after
            block.append(list(chain.from_iterable(rows.row(integrator, camera, y,
                                                           stand_ins.colors))))
    finally:
        for name in STOOD_IN_FOR:
            vars(scene).pop(name, None)
        vars(scene).update(own)
    check_constants(f"{type(integrator).__name__}.render")
    try:
        return np.array(block, dtype=float).reshape(y1 - y0, camera.width, rows.channels)
    except (TypeError, ValueError):
        raise _first_bad_color(integrator, block, y0, rows.channels) from None


def not_a_color(integrator, color, x, y):
    """The TypeError for compute_color returning `color`, not an RGBColor, at pixel (x, y)."""
    hint = " (is a return statement missing?)" if color is None else ""
    return TypeError(f"{type(integrator).__name__}.compute_color returned {color!r} for pixel "
                     f"({x}, {y}){hint}; it must return an RGBColor, such as "
                     "RGBColor(r, g, b) or BLACK, with numbers as channels")


def _first_bad_color(integrator, rows, y0, channels):
    """The TypeError for the first pixel whose channels are not all numbers (rows: flat,
    `channels` numbers a pixel)."""
    for y, row in enumerate(rows, y0):
        for x in range(len(row) // channels):
            color = row[channels * x:channels * x + 3]
            if not all(isinstance(c, (int, float, np.number)) for c in color):
                return not_a_color(integrator, RGBColor(*color), x, y)
    return ValueError("render: the colours of the image do not form an array")


# ------------------------------------------------------------------------------------------
# Sampling patterns
# ------------------------------------------------------------------------------------------
def stratum_grid(samples):
    """(rows, columns) of the grid of cells (strata) that N = samples rays share in a
    pixel: a x b cells with a * b = N, as square as N allows (4 x 4 for 16, 2 x 4 for 8,
    1 x 7 for 7)."""
    a = max(d for d in range(1, int(sqrt(samples)) + 1) if samples % d == 0)
    return a, samples // a


def pixel_offsets(samples, y, width, xs=None):
    """For each pixel of row y (or each pixel x of xs), the (u, v) points inside it that
    are sampled.

    N samples form a jittered grid of a x b cells (stratum_grid): one random point in
    each cell, cell k in row k // b and column k % b, so the samples cover the pixel
    evenly. The random numbers depend only on the row, so an image is the same on every
    run and for any number of workers."""
    a, b = stratum_grid(samples)
    jitter = np.random.default_rng((SAMPLE_SEED, y)).random((width, samples, 2))
    if xs is not None:
        jitter = jitter[xs]
    cell = np.arange(samples)
    u = (cell % b + jitter[:, :, 0]) / b
    v = (cell // b + jitter[:, :, 1]) / a
    return np.stack((u, v), axis=2).tolist()


def stratum_pairs(samples):
    """The cells of pixel_offsets paired with a neighbour, as (k, l) pairs of cell numbers:
    side by side when the grid's rows have an even number of cells, one above the other
    when its columns have, else (N odd) consecutive cells row by row, the last one left
    out. The error estimate compares the two samples of each pair (SampledRows.row)."""
    a, b = stratum_grid(samples)
    if b % 2 == 1 and a % 2 == 0:
        order = [row * b + column for column in range(b) for row in range(a)]
    else:
        order = list(range(samples))
    return list(zip(order[0::2], order[1::2]))


def error_variance_weight(samples):
    """w such that w * sum(d^2), over the pairs of stratum_pairs with d the difference of
    their two samples, estimates the squared error of the mean of the pixel's N jittered
    samples (one colour channel).

    Let each pair be one cell of twice the size holding two independent samples
    ("collapsed strata"): the mean of N such samples has the unbiased variance estimate
    sum(d^2) / (2 P N), P pairs (sum(d^2) / N^2 for N even). One sample in each of the
    N cells is more accurate than that: the error comes from the edges in the pixel, and
    there the variance of jittered sampling falls as N^(-3/2) (an edge crosses about
    sqrt(N) cells, each adding a variance of order 1/N^2). The N/2 double cells have
    (N/2)^(-3/2) / 2 = sqrt(2) N^(-3/2): sqrt(2) times the variance of the N cells, so
    w = 1 / (sqrt(2) * 2 P * N)."""
    return 1.0 / (sqrt(2.0) * 2 * len(stratum_pairs(samples)) * samples)


def _pixel_colors(integrator, colors, x, y):
    """colors, the colours of pixel (x, y)'s samples, checked to be numbers."""
    for color in colors:
        if not all(isinstance(c, (int, float, np.number)) for c in color):
            raise not_a_color(integrator, RGBColor(*color), x, y)
    return colors


class CourseRows:
    """Rows of the course's rays: the ray through each pixel's centre
    (Camera.row_directions), its colour the pixel's."""

    channels = 3

    def __init__(self, streams, loop, saved=None):
        self.streams = streams
        self.loop = loop
        self.saved = [] if saved is None else saved

    def rays(self, camera, y):
        """(the directions of row y's rays, the pixel (x, y) of each ray number)."""
        return camera.row_directions(y), lambda x: (x, y)

    def row(self, integrator, camera, y, colors):
        return colors

    def pixels(self, y0, y1, width):
        return (y1 - y0) * width


class SampledRows(CourseRows):
    """Rows of N jittered samples per pixel with their error estimate, in every pixel, or
    in the pixels that `refined` marks (the others zeros): per pixel six numbers, the
    average colour (r, g, b) of its samples and the estimated squared error of each
    channel of that average (error_variance_weight). The colours are summed in the order
    of the cells, so that an image is the same bit for bit whichever way it is rendered."""

    channels = 6

    def __init__(self, samples, streams, loop, saved=None, refined=None):
        super().__init__(streams, loop, saved)
        self.samples = samples
        self.refined = refined

    def pixels_of_row(self, y, width):
        if self.refined is None:
            return list(range(width))
        return np.flatnonzero(self.refined[y]).tolist()

    def rays(self, camera, y):
        xs = self.pixels_of_row(y, camera.width)
        directions = [camera.get_direction(x, y, u, v)
                      for x, offsets in zip(xs, pixel_offsets(self.samples, y, camera.width, xs))
                      for u, v in offsets]
        samples = self.samples
        return directions, lambda i: (xs[i // samples], y)

    def row(self, integrator, camera, y, colors):
        samples = self.samples
        pairs = stratum_pairs(samples)
        weight = error_variance_weight(samples) if pairs else 0.0
        row = [(0.0,) * 6] * camera.width
        for i, x in enumerate(self.pixels_of_row(y, camera.width)):
            pixel = _pixel_colors(integrator, colors[i * samples:(i + 1) * samples], x, y)
            r = g = b = 0.0
            for cr, cg, cb in pixel:
                r += cr
                g += cg
                b += cb
            sr = sg = sb = 0.0
            for k, l in pairs:
                (rk, gk, bk), (rl, gl, bl) = pixel[k], pixel[l]
                sr += (rk - rl) ** 2
                sg += (gk - gl) ** 2
                sb += (bk - bl) ** 2
            row[x] = (r / samples, g / samples, b / samples,
                      sr * weight, sg * weight, sb * weight)
        return row

    def pixels(self, y0, y1, width):
        if self.refined is None:
            return (y1 - y0) * width
        return int(self.refined[y0:y1].sum())
