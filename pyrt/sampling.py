"""PyRT sampling: what a render samples, which rays each pixel gets, and how accurate
their average is.

One sample per pixel is the course's ray through the pixel's centre; N samples are the
jittered rays of pyrt.rows (SampledRows), whose spread estimates the error of their
average. UniformSampling gives every pixel N rays; AdaptiveSampling first traces the
centre rays, then N rays in the pixels that differ from a neighbour (refined_pixels).
Each is a plan of passes over the image (RenderPass): the row function that makes each
row, and what becomes of the rows. `render` runs the passes, with a progress bar each,
through pyrt.workers (who renders them); a render reports its estimated error beside the
image.
"""
import contextlib
import json
import sys
from pathlib import Path
from typing import NamedTuple

import numpy as np
from tqdm import tqdm

from PyRT_Common import is_number, plt
from pyrt.images import display_image, write_atomically
from pyrt.rows import CourseRows, RowStreams, SampledRows
from pyrt.workers import render_blocks

# The default tolerance of adaptive sampling: neighbouring pixels whose colours, as the PNG
# shows them, differ by more than 3% of its range (8 of its 255 steps) are both refined.
ADAPTIVE_TOLERANCE = 0.03


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


class RenderPass(NamedTuple):
    """One pass over the image: its row function (CourseRows or SampledRows, picklable for
    the worker processes), keep(y0, block), which takes the rendered block of rows in this
    process and returns its colours, and the words that tell the progress bar which pass
    it is."""
    rows: object
    keep: object
    description: str = ""


class UniformSampling:
    """N rays through every pixel: the ray through its centre for N = 1; for N > 1 the
    jittered grid of pixel_offsets, with an estimate of each pixel's error."""

    adaptive = False
    tolerance = None

    def __init__(self, samples):
        self.samples = samples
        # the estimated squared error of each pixel and channel: PyRT traces the N > 1 rays
        # of each pixel itself and sees their spread (None: it did not)
        self.variance = None

    def render(self, integrator, loop, workers, seed, progress):
        """Renders the passes into the scene's image, each by `workers` processes (None: as
        many as repay starting them), with the integrator's render loop `loop` (a LoopBody)
        run once per row; shows a progress bar for each pass. Returns the names that the
        loop asked this process to save the image under (pyrt.rows.TaskStandIns)."""
        image = integrator.scene.rendered_image
        height, width = image.shape[:2]
        saved = []
        for rendering in self.passes(integrator, seed, loop, saved):
            rows = rendering.rows
            with tqdm(total=rows.pixels(0, height, width), unit="px", unit_scale=True,
                      disable=not progress, mininterval=0.5,
                      desc=type(integrator).__name__ + rendering.description) as bar, \
                    contextlib.closing(render_blocks(integrator, rows, workers)) as blocks:
                for y0, block in blocks:  # consecutive rows, in any order
                    image[y0:y0 + len(block)] = rendering.keep(y0, block)
                    bar.update(rows.pixels(y0, y0 + len(block), width))
        return saved

    def passes(self, integrator, seed, loop, saved):
        """The passes of the render, each planned once the passes before it are done; their
        rows draw random numbers from streams made from seed (RowStreams)."""
        if self.samples == 1:
            yield RenderPass(CourseRows(RowStreams(seed), loop, saved), lambda y0, block: block)
            return
        self.variance = np.zeros(integrator.scene.rendered_image.shape)
        yield RenderPass(SampledRows(self.samples, RowStreams(seed), loop, saved),
                         self._keep_sampled)

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
                print(f"No error estimate: {type(integrator).__name__} renders its pixels "
                      "itself (a render loop of its own), so PyRT does not see its samples")
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

    def passes(self, integrator, seed, loop, saved):
        image = integrator.scene.rendered_image
        self.centre = np.zeros(image.shape)
        self.variance = np.zeros(image.shape)
        yield RenderPass(CourseRows(RowStreams(seed, 0), loop, saved), self._keep_centre,
                         " centre rays")
        display = display_image(self.centre, integrator.tonemap)
        self.refined = refined_pixels(display, self.tolerance)
        if not self.refined.any():
            return
        # its time is measured on its first rows (pyrt.workers.render_blocks): a refined
        # pixel's rays cost more than a centre ray each
        yield RenderPass(SampledRows(self.samples, RowStreams(seed, 1), loop, saved,
                                     self.refined),
                         self._keep_refined, f" {self.samples} rays at edges")

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


def sampling_plan(integrator, samples, adaptive, tolerance, traced):
    """UniformSampling or AdaptiveSampling for render()'s arguments, checked; traced: PyRT
    chooses the integrator's camera rays (False: its loop renders its pixels itself)."""
    if not isinstance(adaptive, (bool, np.bool_)):
        raise ValueError(f"render: adaptive must be True or False, got {adaptive!r}")
    if not (is_number(tolerance) and 0.0 <= tolerance <= 1.0):
        raise ValueError(f"render: tolerance must be a number from 0 to 1 (a fraction of the "
                         f"image's range as its PNG shows it), got {tolerance!r}")
    if adaptive and samples == 1:
        raise ValueError("render: adaptive=True needs samples_per_pixel >= 2, the rays the "
                         "pixels at edges get; with 1 every pixel gets the ray through its centre")
    if adaptive and not traced:
        print(f"PyRT: {type(integrator).__name__} renders its pixels itself (a render loop of "
              f"its own), so adaptive sampling cannot choose its rays: every pixel gets "
              f"{samples}", file=sys.stderr)
    if adaptive and traced:
        return AdaptiveSampling(samples, float(tolerance))
    return UniformSampling(samples)
