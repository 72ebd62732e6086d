"""PyRT rendering: the machinery beneath Integrator.render()'s loop, in one decorator.

``Integrator.render()`` (PyRT_Integrators.py) is the course's loop: for every pixel, the
ray through its centre from ``camera.get_direction(x, y)``, ``compute_color``,
``scene.set_pixel``, then ``scene.save_image``. ``@render_loop`` on it makes render() take
PyRT's arguments (workers, samples_per_pixel, progress, adaptive, tolerance) and runs the
loop, undecorated, once per task: one row of a pass, in this process or a worker, after
that row's random stream starts, with the scene's camera, set_pixel and save_image
stood in for (pyrt.rows: a camera over the task's rays, a buffer that sums the samples
in order, the save deferred to the end). ``@image_loop`` is the same for a loop that
renders its pixels itself and traces no camera rays (LazyIntegrator's): run once, here.

The way down, each module entered once: this module (the checks made before any work,
with messages that say what to fix; Ctrl+C; the save and the report of NaN or infinite
pixels) -> pyrt.sampling (what to sample: the passes) -> pyrt.workers (who renders) ->
pyrt.rows (how a task is made) -> the loop, compute_color and the scene's queries
(pyrt.acceleration). Nothing here changes an image: one process or several give the same
pixels, bit for bit.
"""
import ast
import functools
import inspect
import multiprocessing
import random
import sys
import tempfile
import textwrap
from pathlib import Path

import numpy as np

from PyRT_Common import is_number
from pyrt.images import opencv_problem
from pyrt.rows import TaskStandIns, loop_body
from pyrt.sampling import ADAPTIVE_TOLERANCE, sampling_plan


# ------------------------------------------------------------------------------------------
# The decorators
# ------------------------------------------------------------------------------------------
def render_loop(body):
    """Integrator.render's decorator: body(integrator) is the course's loop over every pixel
    of scene.camera; the render() it makes runs it once per task (module docstring)."""
    loop = loop_body(body)

    def render(self, workers=None, samples_per_pixel=1, progress=True, adaptive=False,
               tolerance=ADAPTIVE_TOLERANCE):
        workers, sampling = check_render(self, workers, samples_per_pixel, adaptive,
                                         tolerance)
        _render(self, sampling, lambda seed: sampling.render(self, loop, workers, seed,
                                                            progress))

    render.loop = loop  # the loop, undecorated (a pyrt.rows.LoopBody)
    return _documented(render, body)


def image_loop(body):
    """The decorator of a render loop that renders its pixels itself, tracing no camera
    rays: the render() it makes takes render_loop's arguments and runs body(integrator)
    once, in this process, with the image saved at the end (one exact value per pixel,
    however many samples are asked for)."""

    def render(self, workers=None, samples_per_pixel=1, progress=True, adaptive=False,
               tolerance=ADAPTIVE_TOLERANCE):
        _, sampling = check_render(self, workers, samples_per_pixel, adaptive, tolerance,
                                   traced=False)
        _render(self, sampling, lambda seed: _run_once(self, body))

    return _documented(render, body)


def _documented(render, body):
    """render named and documented as body, with its own signature (PyRT's arguments)."""
    functools.update_wrapper(render, body, updated=())
    del render.__wrapped__  # inspect.signature shows render's arguments, not body's
    return render


def _run_once(integrator, body):
    """body(integrator) with the scene's save_image deferred: the names it asked for."""
    scene = integrator.scene
    saved = []
    own = vars(scene).get("save_image")
    scene.save_image = TaskStandIns(integrator, saved).save_image
    try:
        body(integrator)
    finally:
        del scene.save_image
        if own is not None:
            scene.save_image = own
    return saved


def _render(integrator, sampling, run):
    """Runs run(seed), which renders the scene's image and returns the names its loop asked
    to save it under; then saves it under the last of them (get_filename() when it was
    asked in a worker process only) and reports. seed: the render's one draw of Python's
    global generator, from which every row's streams are made (pyrt.rows.RowStreams); the
    generator is given back its state after it when the render ends, and numpy's global
    generator, which the render does not draw, its state before, however many processes
    rendered and whatever the rows drew.

    On Ctrl+C it saves the rows stored so far in the scene's image as <filename>_partial
    and re-raises. When all is done it reports NaN or infinite pixels."""
    scene = integrator.scene
    seed = int(random.random() * 2 ** 53)
    after_the_draw = random.getstate()
    numpy_before = np.random.get_state()
    try:
        saved = run(seed)
    except KeyboardInterrupt:
        partial = integrator.get_filename() + "_partial"
        scene.save_image(partial, tonemap=integrator.tonemap)
        print(f"\nInterrupted: the rows rendered so far are saved in {partial}.png (.npy, "
              ".hdr)", file=sys.stderr)
        raise
    finally:
        random.setstate(after_the_draw)
        np.random.set_state(numpy_before)
    _report_non_finite(scene.rendered_image, type(integrator).__name__)
    png = scene.save_image(saved[-1] if saved else integrator.get_filename(),
                           tonemap=integrator.tonemap)
    # in full: a relative name is relative to the folder the script was started from
    print(f"Saved {png.absolute()} (and .npy, .hdr)")
    sampling.report(integrator)


# ------------------------------------------------------------------------------------------
# Checks before rendering
# ------------------------------------------------------------------------------------------
def check_render(integrator, workers, samples_per_pixel, adaptive, tolerance, traced=True):
    """(workers, sampling) checked, with the scene's image allocated and cleared and
    sampling the plan of the rays (sampling_plan; traced: PyRT chooses the camera rays);
    or the error that says what to call or change first. Nothing is rendered before every
    check has passed."""
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
    if traced and is_stub(type(integrator).compute_color):
        raise NotImplementedError(f"{name}.render: {name}.compute_color is still the "
                                  "course's stub (its body is `pass`): write it before "
                                  f"rendering with {name}")
    check_inputs = getattr(integrator, "check_inputs", None)
    if check_inputs is not None:  # what an integrator checks of its own inputs (a GP pool)
        check_inputs()
    samples = _check_count("samples_per_pixel", samples_per_pixel)
    if workers is not None:
        workers = _check_count("workers", workers, "None (all cores) or a whole number >= 1")
    sampling = sampling_plan(integrator, samples, adaptive, tolerance, traced)
    problem = opencv_problem()
    if problem:  # or the render would be done, and its PNG not written
        raise RuntimeError(f"{name}.render: {problem}")
    _check_writable(Path(integrator.get_filename()).resolve().parent)
    shape = (scene.camera.height, scene.camera.width, 3)
    if scene.rendered_image is None or scene.rendered_image.shape != shape:
        scene.rendered_image = np.zeros(shape)
    scene.rendered_image.fill(0.0)
    return workers, sampling


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
