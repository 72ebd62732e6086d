"""PyRT rendering: what Integrator.render() needs besides the course's loop.

``Integrator.render()`` (PyRT_Integrators.py) is the loop: every pixel, a ray,
``compute_color``, the colour stored in the image, the image saved. This module holds the
render around it: the checks made before any work, with messages that say what to fix
(check_render), and the passes of a render (rendered_blocks) with their progress bar,
the partial image saved on Ctrl+C and the report of NaN or infinite pixels. Which rays
each pixel gets is pyrt.sampling's; rendering on every core, pyrt.workers'; the fast
queries used meanwhile, pyrt.acceleration's.

Nothing here changes an image: one process or several give the same pixels, bit for bit.
"""
import ast
import contextlib
import inspect
import multiprocessing
import random
import sys
import tempfile
import textwrap
from pathlib import Path

import numpy as np
from tqdm import tqdm

from pyrt.acceleration.accelerated import accelerated
from PyRT_Common import is_number
from pyrt.images import opencv_problem
from pyrt.sampling import ADAPTIVE_TOLERANCE, sampling_plan
from pyrt.workers import render_blocks


# ------------------------------------------------------------------------------------------
# Checks before rendering
# ------------------------------------------------------------------------------------------
def check_render(integrator, workers, samples_per_pixel, adaptive=False,
                 tolerance=ADAPTIVE_TOLERANCE):
    """(scene, workers, sampling) checked, with the scene's image allocated and cleared and
    sampling the plan of the rays (sampling_plan); or the error that says what to call or
    change first. Nothing is rendered before every check has passed."""
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
    if integrator.traces_rays and is_stub(type(integrator).compute_color):
        raise NotImplementedError(f"{name}.render: {name}.compute_color is still the "
                                  "course's stub (its body is `pass`): write it before "
                                  f"rendering with {name}")
    check_inputs = getattr(integrator, "check_inputs", None)
    if check_inputs is not None:  # what an integrator checks of its own inputs (a GP pool)
        check_inputs()
    samples = _check_count("samples_per_pixel", samples_per_pixel)
    if workers is not None:
        workers = _check_count("workers", workers, "None (all cores) or a whole number >= 1")
    sampling = sampling_plan(integrator, samples, adaptive, tolerance)
    problem = opencv_problem()
    if problem:  # or the render would be done, and its PNG not written
        raise RuntimeError(f"{name}.render: {problem}")
    _check_writable(Path(integrator.get_filename()).resolve().parent)
    shape = (scene.camera.height, scene.camera.width, 3)
    if scene.rendered_image is None or scene.rendered_image.shape != shape:
        scene.rendered_image = np.zeros(shape)
    scene.rendered_image.fill(0.0)
    return scene, workers, sampling


def is_stub(function) -> bool:
    """Whether function's body is only `pass` (a docstring and comments aside), as the
    course's stubs are; False when its source cannot be read."""
    try:
        tree = ast.parse(textwrap.dedent(inspect.getsource(function)))
    except (OSError, TypeError, SyntaxError):
        return False
    body = tree.body[0].body if tree.body and hasattr(tree.body[0], "body") else []
    if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
        body = body[1:]  # the docstring
    return len(body) == 1 and isinstance(body[0], ast.Pass)


def _check_count(name, value, allowed="a whole number >= 1"):
    """value as an int, or a ValueError naming the render() argument and what is allowed."""
    if not (is_number(value, whole=True) and value >= 1):
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
# The passes of a render
# ------------------------------------------------------------------------------------------
@contextlib.contextmanager
def rendered_blocks(integrator, workers, sampling, progress):
    """Yields an iterator over (first row, rows) blocks that together make the image, in
    any order, rendered by this process and by worker processes, pass after pass of
    sampling (UniformSampling or AdaptiveSampling: a later pass gives some rows again,
    better); shows a progress bar for each pass. The scene's queries are accelerated
    meanwhile (pyrt.acceleration), and nothing may change the scene.

    On Ctrl+C it stops the workers, saves the rows stored so far in the scene's image as
    <filename>_partial and re-raises. When all is done it reports NaN or infinite pixels."""
    scene = integrator.scene
    height, width = scene.camera.height, scene.camera.width

    # The render's one draw of Python's global generator, from which every row's streams
    # are made (pyrt.rows.RowStreams); the generator is given back its state after it when
    # the render ends, and numpy's its state before, however many processes rendered and
    # whatever the rows drew.
    seed = int(random.random() * 2 ** 53)
    after_the_draw = random.getstate()
    numpy_before = np.random.get_state()  # numpy's generator, which the render does not draw

    def passes():
        for rendering in sampling.passes(integrator, workers, seed):
            rows = rendering.rows
            with tqdm(total=rows.pixels(0, height, width), unit="px", unit_scale=True,
                      disable=not progress, mininterval=0.5,
                      desc=type(integrator).__name__ + rendering.description) as bar, \
                    contextlib.closing(render_blocks(integrator, height, rows,
                                                     rendering.workers)) as blocks:
                for y0, block in blocks:
                    yield y0, rendering.keep(y0, block)
                    bar.update(rows.pixels(y0, y0 + len(block), width))

    blocks = passes()
    try:
        with accelerated(integrator, height * width):
            yield blocks
    except KeyboardInterrupt:
        blocks.close()  # stops the worker processes, wherever Ctrl+C struck
        partial = integrator.get_filename() + "_partial"
        scene.save_image(partial, tonemap=integrator.tonemap)
        print(f"\nInterrupted: the rows rendered so far are saved in {partial}.png (.npy, "
              ".hdr)", file=sys.stderr)
        raise
    finally:
        random.setstate(after_the_draw)
        np.random.set_state(numpy_before)
    _report_non_finite(scene.rendered_image, type(integrator).__name__)


def _report_non_finite(image, name):
    """One line on stderr when some pixels are NaN or infinite: how many, and the first."""
    finite = np.isfinite(image)
    if finite.all():
        return
    bad = ~finite.all(axis=2)
    y, x = np.argwhere(bad)[0]
    print(f"PyRT warning: {name}.compute_color returned NaN or infinite values for "
          f"{int(bad.sum())} pixel(s), the first at pixel ({x}, {y}); the PNG shows them as "
          "the image's darkest (NaN) or brightest (infinity) colour", file=sys.stderr)
