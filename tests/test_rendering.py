"""PyRT_Rendering.py through Integrator.render(): rendering in several processes (fork and
spawn), the sampling patterns of samples_per_pixel, the progress of a render, Ctrl+C, and
the checks that give clear errors."""
import math
import multiprocessing
import os
import sys
import time

import numpy as np
import pytest
from tqdm import tqdm

import PyRT_Rendering
from AppRenderer import sphere_test_scene
from helpers import (GREY, PNG_TOLERANCE, PixelGrey, fov90_scene, pixel_of, read_png,
                     render_image, run_python, small_cornell_box)
from PyRT_Core import *
from PyRT_Integrators import *


# ------------------------------------------------------------------------------------------
# Parallel rendering
# ------------------------------------------------------------------------------------------
@pytest.fixture
def worker_first(monkeypatch, tmp_path):
    """Makes this process hold back its first block of rows until a worker process has
    finished one, so that both surely render part of the image. Call it before the render;
    it returns the marker file a worker leaves once its first block is in the image.

    raise_in_worker = (exception class, arguments): the worker raises that exception after
    leaving the marker. interrupt: this process is stopped with Ctrl+C after its first
    block. Forked workers inherit the patched functions."""
    def install(raise_in_worker=None, interrupt=False):
        marker = tmp_path / "worker_rendered"
        render_block, finish = PyRT_Rendering.render_block, PyRT_Rendering._SharedImage.finish

        def finish_and_mark(shared, i):  # only worker processes finish blocks
            finish(shared, i)
            marker.touch()
            if raise_in_worker:
                error_class, arguments = raise_in_worker
                raise error_class(*arguments)

        def held_back(integrator, y0, y1, samples):
            if multiprocessing.parent_process() is None:  # this process
                wait_for_file(marker)
            rows = render_block(integrator, y0, y1, samples)
            if interrupt and multiprocessing.parent_process() is None:
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


def test_error_in_a_worker_process_is_raised_with_the_worker_traceback(tmp_path, worker_first):
    worker_first(raise_in_worker=(ZeroDivisionError, ["raised in a worker"]))
    integrator = PhongIntegrator(str(tmp_path / "bad"))
    integrator.add_scene(small_cornell_box(32))
    with pytest.raises(ZeroDivisionError, match="raised in a worker") as raised:
        integrator.render(workers=2, progress=False)
    assert "finish_and_mark" in str(raised.value.__cause__)  # where the worker raised it


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
    assert "one process" in err and "lambda" in err
    full = render_image(NormalIntegrator(str(tmp_path / "full")),
                        sphere_test_scene(width=32, height=32), workers=1)
    assert full.any()
    assert np.array_equal(half, full * 0.5)


def test_with_a_debugger_attached_renders_in_one_process_and_says_why(tmp_path, capfd):
    def tracer(frame, event, arg):  # what pdb and VSCode's debugger install
        return None

    sys.settrace(tracer)
    try:
        image = render_image(NormalIntegrator(str(tmp_path / "debugged")),
                             sphere_test_scene(width=24, height=24), workers=2)
    finally:
        sys.settrace(None)
    err = capfd.readouterr().err
    assert "one process" in err and "debugger" in err
    assert np.array_equal(image, normal_image_in_one_process(tmp_path))


def render_normal_with_two_workers(filename):
    return render_image(NormalIntegrator(filename), sphere_test_scene(width=24, height=24),
                        workers=2)


def test_render_inside_a_pool_worker_renders_in_one_process_and_says_why(tmp_path, capfd):
    # A teaching assistant may render every student's integrator in a multiprocessing.Pool,
    # whose (daemonic) workers may not start processes of their own.
    with multiprocessing.Pool(1) as pool:
        image = pool.apply(render_normal_with_two_workers, (str(tmp_path / "pooled"),))
    err = capfd.readouterr().err
    assert "one process" in err and "daemonic" in err
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


def test_error_against_a_high_sample_reference_shrinks_with_more_samples(tmp_path):
    def render(samples):
        return render_image(PhongIntegrator(str(tmp_path / f"spp{samples}")),
                            small_cornell_box(24), samples_per_pixel=samples)

    reference = render(256)
    errors = [float(np.sqrt(np.mean((render(n) - reference) ** 2))) for n in (1, 4, 16, 64)]
    assert errors[0] > errors[1] > errors[2] > errors[3], errors
    # Averaging N samples cuts the error at least like 1/sqrt(N): 64 samples, 8 times.
    assert errors[3] < errors[0] / 4, errors


@pytest.mark.parametrize("option, value", [
    *[("samples_per_pixel", value) for value in (0, -1, 2.5, "4", True)],
    *[("workers", value) for value in (0, -1, 2.5, "2", True)]])
def test_bad_render_option_raises_value_error_naming_it(tmp_path, option, value):
    integrator = PhongIntegrator(str(tmp_path / "out" / "img"))
    integrator.add_scene(sphere_test_scene(width=4, height=4))
    with pytest.raises(ValueError, match=option):
        integrator.render(progress=False, **{option: value})
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


# ------------------------------------------------------------------------------------------
# Errors students run into
# ------------------------------------------------------------------------------------------
def test_render_before_add_scene_says_to_call_add_scene(tmp_path):
    with pytest.raises(RuntimeError, match=r"add_scene\("):
        PhongIntegrator(str(tmp_path / "img")).render(progress=False)


def test_render_of_a_scene_without_camera_says_to_call_set_camera(tmp_path):
    scene = Scene()
    scene.add_object(Sphere(Vector3D(0, 0, -5), 1))
    integrator = PhongIntegrator(str(tmp_path / "img"))
    integrator.add_scene(scene)
    with pytest.raises(RuntimeError, match=r"set_camera\("):
        integrator.render(progress=False)


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
    reports = [line for line in capfd.readouterr().err.splitlines() if "(1, 0)" in line]
    assert len(reports) == 1
    assert "2 pixel" in reports[0]


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
    with pytest.raises(OSError, match="afile"):
        integrator.render(workers=1, progress=False)
    assert integrator.calls == 0
