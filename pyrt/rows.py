"""PyRT rows: how one row of an image is made, in whichever process renders it.

render_block makes a block of rows with the row function of a render's pass: CourseRows,
the rows integrator.render_row makes (the ray through each pixel's centre), or
SampledRows, N jittered rays in every pixel or in the pixels adaptive sampling picks, with
an estimate of each pixel's error. Each row draws its random numbers from a stream of its
own (RowStreams), so that an image is the same for any number of worker processes.
"""
import random
from math import sqrt
from typing import NamedTuple

import numpy as np

from PyRT_Common import INFINITY, RGBColor, Ray, Vector3D, check_constants

SAMPLE_SEED = 0x5079_5254  # "PyRT"


# ------------------------------------------------------------------------------------------
# Rows of the image
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
        """Seeds Python's and numpy's global generators for row y."""
        random.seed(f"{self.seed}:{self.number}:{y}")
        # one 32-bit number, distinct for every row of every pass (y < 2^20), as cheap to
        # seed from as numpy allows (a list of numbers takes four times as long)
        np.random.seed((self.seed ^ (self.number << 20) ^ y) & 0xFFFF_FFFF)


def render_block(integrator, y0, y1, rows):
    """Rows y0 .. y1-1 of the image, each from rows(integrator, y), the row function of a
    render's pass (which calls integrator.render_row or traces the samples of its
    pixels), with the row's own random stream, as an array of shape
    (y1 - y0, width, rows.channels)."""
    block = []
    for y in range(y0, y1):
        rows.streams.start(y)
        block.append(rows(integrator, y))
    check_constants(f"{type(integrator).__name__}.render")
    try:
        return np.array(block, dtype=float).reshape(y1 - y0, -1, rows.channels)
    except (TypeError, ValueError):
        raise _first_bad_color(integrator, block, y0) from None


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
    out. The error estimate compares the two samples of each pair (sampled_pixels)."""
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


def sampled_pixels(integrator, y, samples, xs):
    """The pixels xs of row y, each from camera rays through the points pixel_offsets gives
    it: per pixel six numbers, the average colour (r, g, b) of its samples and the
    estimated squared error of each channel of that average (error_variance_weight).
    Pixels of the row not in xs are zeros. The colours are summed in the order of the
    cells, as Integrator.render_row always has, so that an image is the same bit for bit
    whichever way it is rendered."""
    camera = integrator.scene.camera
    compute_color = integrator.compute_color
    pairs = stratum_pairs(samples)
    weight = error_variance_weight(samples) if pairs else 0.0
    row = [0.0] * (6 * camera.width)
    for x, offsets in zip(xs, pixel_offsets(samples, y, camera.width, xs)):
        r = g = b = 0.0
        colors = []
        for u, v in offsets:
            direction = camera.get_direction(x, y, u, v)
            color = compute_color(Ray(Vector3D(0.0, 0.0, 0.0), direction, INFINITY, 0.0))
            try:
                r += color.r
                g += color.g
                b += color.b
            except (AttributeError, TypeError):
                raise not_a_color(integrator, color, x, y) from None
            colors.append((color.r, color.g, color.b))  # the values, should color change
        sr = sg = sb = 0.0
        for k, l in pairs:
            (rk, gk, bk), (rl, gl, bl) = colors[k], colors[l]
            sr += (rk - rl) ** 2
            sg += (gk - gl) ** 2
            sb += (bk - bl) ** 2
        row[6 * x:6 * x + 6] = (r / samples, g / samples, b / samples,
                                sr * weight, sg * weight, sb * weight)
    return row


def sampled_row(integrator, y, samples):
    """Integrator.render_row with more than one sample per pixel: each pixel x gets the
    average colour of camera rays through the points pixel_offsets gives it."""
    row = sampled_pixels(integrator, y, samples, list(range(integrator.scene.camera.width)))
    return [value for i, value in enumerate(row) if i % 6 < 3]


class CourseRows:
    """Rows as integrator.render_row makes them: the ray through each pixel's centre for
    one sample per pixel, and the rows of an integrator that makes them itself."""

    channels = 3

    def __init__(self, samples, streams):
        self.samples = samples
        self.streams = streams

    def __call__(self, integrator, y):
        return integrator.render_row(y, self.samples)

    def pixels(self, y0, y1, width):
        return (y1 - y0) * width


class SampledRows:
    """Rows of N jittered samples per pixel with their error estimate (sampled_pixels), in
    every pixel, or in the pixels that `refined` marks."""

    channels = 6

    def __init__(self, samples, streams, refined=None):
        self.samples = samples
        self.streams = streams
        self.refined = refined

    def __call__(self, integrator, y):
        if self.refined is None:
            xs = list(range(integrator.scene.camera.width))
        else:
            xs = np.flatnonzero(self.refined[y]).tolist()
        return sampled_pixels(integrator, y, self.samples, xs)

    def pixels(self, y0, y1, width):
        if self.refined is None:
            return (y1 - y0) * width
        return int(self.refined[y0:y1].sum())


