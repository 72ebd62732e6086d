"""PyRT sampling: which rays each pixel gets, and how accurate their average is.

One sample per pixel is the course's ray through the pixel's centre. N samples are spread
over a jittered grid of N cells inside the pixel (pixel_offsets), and their spread gives
an estimate of the error of their average (error_variance_weight). UniformSampling gives
every pixel N rays; AdaptiveSampling first traces the centre rays, then N rays in the
pixels that differ from a neighbour (refined_pixels). Each is a plan of passes over the
image (RenderPass), with the row function that makes each row (render_block) and what
becomes of the rows; a render reports its estimated error beside the image.
"""
import json
import sys
import time
from math import sqrt
from pathlib import Path
from typing import NamedTuple

import numpy as np

from PyRT_Common import INFINITY, RGBColor, Ray, Vector3D, check_constants, is_number, plt
from pyrt.images import display_image, write_atomically

SAMPLE_SEED = 0x5079_5254  # "PyRT"
# The default tolerance of adaptive sampling: neighbouring pixels whose colours, as the PNG
# shows them, differ by more than 3% of its range (8 of its 255 steps) are both refined.
ADAPTIVE_TOLERANCE = 0.03


# ------------------------------------------------------------------------------------------
# Rows of the image
# ------------------------------------------------------------------------------------------
def render_block(integrator, y0, y1, rows):
    """Rows y0 .. y1-1 of the image, each from rows(integrator, y), the row function of a
    render's pass (which calls integrator.render_row or traces the samples of its
    pixels), as an array of shape (y1 - y0, width, rows.channels)."""
    block = [rows(integrator, y) for y in range(y0, y1)]
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


def refined_pixels(display, tolerance):
    """Which pixels adaptive sampling refines, as a (height, width) array of booleans:
    both pixels of every pair of neighbours (side by side or one above the other) whose
    colours in `display`, the image as its PNG shows it, differ by more than tolerance in
    some channel.

    A straight edge that crosses a pixel always separates its centre from the centre of
    the neighbour to its right or to its left, or from the one above or below (a
    corner of the pixel lies beyond the edge, and that corner is the midpoint of two
    neighbours' centres, so one of them lies beyond it too): pairs of centre rays find
    every edge wider than the spacing of the pixels and of enough contrast."""
    refined = np.zeros(display.shape[:2], dtype=bool)
    across = (np.abs(np.diff(display, axis=1)) > tolerance).any(axis=2)
    refined[:, :-1] |= across
    refined[:, 1:] |= across
    down = (np.abs(np.diff(display, axis=0)) > tolerance).any(axis=2)
    refined[:-1] |= down
    refined[1:] |= down
    return refined


# ------------------------------------------------------------------------------------------
# Samples per pixel: uniform and adaptive
# ------------------------------------------------------------------------------------------
ACCURACY_SUFFIX = "_accuracy.json"
SAMPLE_MAP_SUFFIX = "_samples.png"
SAMPLE_MAP_COLORS = "inferno"  # black: the fewest rays, through red to pale yellow: the most


class _CourseRows:
    """Rows as integrator.render_row makes them: the ray through each pixel's centre for
    one sample per pixel, and the rows of an integrator that makes them itself."""

    channels = 3

    def __init__(self, samples):
        self.samples = samples

    def __call__(self, integrator, y):
        return integrator.render_row(y, self.samples)

    def pixels(self, y0, y1, width):
        return (y1 - y0) * width


class _SampledRows:
    """Rows of N jittered samples per pixel with their error estimate (sampled_pixels), in
    every pixel, or in the pixels that `refined` marks."""

    channels = 6

    def __init__(self, samples, refined=None):
        self.samples = samples
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


class RenderPass(NamedTuple):
    """One pass over the image: its row function (rows(integrator, y), picklable for the
    worker processes), how many processes render it (None: as many as repay starting
    them), keep(y0, block), which takes the rendered block of rows in this process and
    returns its colours, the words that tell the progress bar which pass it is, and the
    seconds one process is expected to take for it (None: unknown, to be measured)."""
    rows: object
    workers: object
    keep: object
    description: str = ""
    seconds: object = None


class UniformSampling:
    """N rays through every pixel: the ray through its centre for N = 1; for N > 1 the
    jittered grid of pixel_offsets, with an estimate of each pixel's error."""

    adaptive = False
    tolerance = None

    def __init__(self, samples, traced=True):
        self.samples = samples
        # PyRT traces the N > 1 rays of each pixel itself and sees their spread, unless the
        # integrator makes its rows itself
        self.traced = traced and samples > 1
        self.variance = None  # the estimated squared error of each pixel and channel

    def passes(self, integrator, workers):
        """The passes of the render, each planned once the passes before it are done."""
        if not self.traced:
            yield RenderPass(_CourseRows(self.samples), workers, lambda y0, block: block)
            return
        self.variance = np.zeros(integrator.scene.rendered_image.shape)
        yield RenderPass(_SampledRows(self.samples), workers, self._keep_sampled)

    def _keep_sampled(self, y0, block):
        self.variance[y0:y0 + len(block)] = block[:, :, 3:]
        return block[:, :, :3]

    def rays(self):
        """The rays traced in each pixel, as an array of the image's height and width."""
        return np.full(self.variance.shape[:2], self.samples)

    def report(self, integrator):
        """Prints the estimated error of the saved image once and writes it beside the image
        (<filename>_accuracy.json); removes the files of this kind that an earlier render
        left under the same name and that would now describe another image."""
        base = integrator.get_filename()
        if self.variance is None:
            if self.samples > 1:
                print(f"No error estimate: {type(integrator).__name__} makes its rows itself "
                      "(it overrides render_row), so PyRT does not see its samples")
            Path(base + ACCURACY_SUFFIX).unlink(missing_ok=True)
        else:
            self._write_accuracy(integrator.scene.rendered_image, base)
        if not self.adaptive:
            Path(base + SAMPLE_MAP_SUFFIX).unlink(missing_ok=True)

    def _write_accuracy(self, image, base):
        finite = np.isfinite(self.variance) & np.isfinite(image)
        channels = [float(np.sqrt(self.variance[:, :, c][finite[:, :, c]].mean()))
                    for c in range(3)]
        rmse = float(np.sqrt(self.variance[finite].mean()))
        span = float(np.ptp(image[finite])) if finite.any() else 0.0
        rays = self.rays()
        accuracy = {
            "image": Path(base).name + ".png",
            "samples_per_pixel": self.samples,
            "adaptive": self.adaptive,
            "tolerance": self.tolerance,
            "estimated_rmse": rmse,
            "estimated_rmse_rgb": channels,
            "image_range": span,
            "pixels": int(rays.size),
            "pixels_with_n_samples": int((rays >= self.samples).sum()),
            "rays": int(rays.sum()),
            "rays_per_pixel": float(rays.mean()),
            "method": "the square root of the mean, over pixels and channels, of each "
                      "pixel's estimated squared error sum(d^2) / (sqrt(2) * 2P * N), d the "
                      "difference of the two samples of each of the P pairs of neighbouring "
                      "strata; pixels that kept their centre ray count as exact",
        }
        path = Path(base + ACCURACY_SUFFIX)
        write_atomically(path, lambda f: f.write(json.dumps(accuracy, indent=2).encode()))
        share = f", {rmse / span:.2%} of its range" if span > 0.0 else ""
        print(f"Estimated error: RMSE {rmse:.2e} of the linear image{share}, from the spread "
              f"of each pixel's samples; saved in {path}")


class AdaptiveSampling(UniformSampling):
    """Rays where the image needs them: first the ray through every pixel's centre (the
    course's image); then, in the pixels that refined_pixels picks, where two neighbours'
    centre rays differ by more than tolerance as the PNG shows them, the N jittered rays of
    UniformSampling, whose average replaces the centre ray's colour: a refined pixel is
    the uniform render's pixel bit for bit. Its centre ray only found the edge; kept as
    one of the N samples it would stand for a cell it lies on the corner of, which
    measurably raises the error at edges, so a refined pixel traces N + 1 rays. The
    others keep their centre ray, which for a colour that varies smoothly across the
    pixel is its average to second order. The decision is made in this process between
    the two passes, so the image is the same for any number of workers."""

    adaptive = True

    def __init__(self, samples, tolerance):
        super().__init__(samples)
        self.tolerance = tolerance
        self.centre = self.refined = None

    def passes(self, integrator, workers):
        image = integrator.scene.rendered_image
        self.centre = np.zeros(image.shape)
        self.variance = np.zeros(image.shape)
        start = time.perf_counter()
        yield RenderPass(_CourseRows(1), workers, self._keep_centre, " centre rays")
        seconds = time.perf_counter() - start
        display = display_image(self.centre, integrator.tonemap)
        self.refined = refined_pixels(display, self.tolerance)
        count = int(self.refined.sum())
        if count == 0:
            return
        yield RenderPass(_SampledRows(self.samples, self.refined), workers,
                         self._keep_refined, f" {self.samples} rays at edges",
                         # the centre rays' time per ray, for this pass's rays
                         seconds * count * self.samples / self.refined.size)

    def _keep_centre(self, y0, block):
        self.centre[y0:y0 + len(block)] = block
        return block

    def _keep_refined(self, y0, block):
        rows = slice(y0, y0 + len(block))
        refined = self.refined[rows, :, None]
        self.variance[rows] = np.where(refined, block[:, :, 3:], 0.0)
        return np.where(refined, block[:, :, :3], self.centre[rows])

    def rays(self):
        return 1 + self.samples * self.refined

    def report(self, integrator):
        rays = self.rays()
        count = int(self.refined.sum())
        path = integrator.get_filename() + SAMPLE_MAP_SUFFIX
        write_atomically(Path(path), lambda f: plt.imsave(
            f, rays, cmap=SAMPLE_MAP_COLORS, vmin=1, vmax=self.samples + 1, format="png"))
        print(f"Adaptive sampling: {count} of {rays.size} pixels ({count / rays.size:.1%}) "
              f"got {self.samples} rays after their centre ray, the others their centre ray "
              f"only: {rays.mean():.2f} rays per pixel, where uniform sampling takes "
              f"{self.samples}. Map of the rays per pixel: {path} (black: 1, pale yellow: "
              f"{self.samples + 1})")
        super().report(integrator)


def sampling_plan(integrator, samples, adaptive, tolerance):
    """UniformSampling or AdaptiveSampling for render()'s arguments, checked."""
    if not isinstance(adaptive, (bool, np.bool_)):
        raise ValueError(f"render: adaptive must be True or False, got {adaptive!r}")
    if not (is_number(tolerance) and 0.0 <= tolerance <= 1.0):
        raise ValueError(f"render: tolerance must be a number from 0 to 1 (a fraction of the "
                         f"image's range as its PNG shows it), got {tolerance!r}")
    traced = integrator.traces_rays
    if adaptive and samples == 1:
        raise ValueError("render: adaptive=True needs samples_per_pixel >= 2, the rays the "
                         "pixels at edges get; with 1 every pixel gets the ray through its centre")
    if adaptive and not traced:
        print(f"PyRT: {type(integrator).__name__} makes its rows itself (it overrides "
              f"render_row), so adaptive sampling cannot choose its rays: every pixel gets "
              f"{samples}", file=sys.stderr)
    if adaptive and traced:
        return AdaptiveSampling(samples, float(tolerance))
    return UniformSampling(samples, traced)
