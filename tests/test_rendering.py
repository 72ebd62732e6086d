"""pyrt/rendering.py through Integrator.render(): the progress of a render, Ctrl+C, and
the checks that give clear errors."""
import math
import multiprocessing
import os
import re

import numpy as np
import pytest
from tqdm import tqdm

from helpers import (GREY, PNG_TOLERANCE, ConstantGrey, PixelGrey, StepAt, fov90_scene,
                     pixel_of, read_png, render_image, small_cornell_box)
from PyRT_Core import *
from PyRT_Integrators import *
from pyrt.rendering import render_loop


# ------------------------------------------------------------------------------------------
# The progress bar
# ------------------------------------------------------------------------------------------
def final_bar(err, description):
    """The last state of the progress bar `description` that a render wrote to stderr."""
    states = [line for line in err.replace("\r", "\n").splitlines()
              if line.startswith(description + ":")]
    assert states, err
    return states[-1]


@pytest.mark.parametrize("workers, samples", [(1, 1), (None, 2)])
def test_render_shows_a_progress_bar_of_the_pixels_unless_told_not_to(tmp_path, capfd,
                                                                      workers, samples):
    integrator = PixelGrey(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(40, 30))
    integrator.render(workers=workers, samples_per_pixel=samples)  # a progress bar by default
    bar = final_bar(capfd.readouterr().err, "PixelGrey")
    # 1200 pixels, counted with SI prefixes, and the pixels rendered per second
    assert re.match(r"PixelGrey: 100%\|.*\| 1\.20k/1\.20k \[.*px/s\]$", bar), bar
    integrator.render(workers=workers, samples_per_pixel=samples, progress=False)
    assert capfd.readouterr().err == ""


def test_adaptive_render_shows_a_bar_for_the_centre_rays_and_one_for_the_refined_pixels(
        tmp_path, capfd):
    # 20 centre rays; the edge at X = 2.3 refines columns 1 and 2: 8 pixels
    integrator = StepAt(str(tmp_path / "img"), 2.3)
    integrator.add_scene(fov90_scene(5, 4))
    integrator.render(workers=1, samples_per_pixel=16, adaptive=True)
    err = capfd.readouterr().err
    assert re.match(r"StepAt centre rays: 100%\|.*\| 20\.0/20\.0 \[",
                    final_bar(err, "StepAt centre rays"))
    assert re.match(r"StepAt 16 rays at edges: 100%\|.*\| 8\.00/8\.00 \[",
                    final_bar(err, "StepAt 16 rays at edges"))


# ------------------------------------------------------------------------------------------
# Errors students run into
# ------------------------------------------------------------------------------------------
def test_render_before_add_scene_says_to_call_add_scene(tmp_path):
    with pytest.raises(RuntimeError) as error:
        PhongIntegrator(str(tmp_path / "img")).render(progress=False)
    assert str(error.value) == ("PhongIntegrator.render: no scene to render; call "
                                "integrator.add_scene(scene) first")


def test_render_of_a_scene_without_camera_says_to_call_set_camera(tmp_path):
    scene = Scene()
    scene.add_object(Sphere(Vector3D(0, 0, -5), 1))
    integrator = PhongIntegrator(str(tmp_path / "img"))
    integrator.add_scene(scene)
    with pytest.raises(RuntimeError) as error:
        integrator.render(progress=False)
    assert str(error.value) == ("PhongIntegrator.render: the scene has no camera; call "
                                "scene.set_camera(Camera(width, height, fov)) first")


def test_camera_assigned_without_set_camera_is_rendered_at_its_own_size(tmp_path):
    scene = fov90_scene(5, 4)
    scene.camera = Camera(3, 2, 90)  # as scene.camera = ... in a student's script
    image = render_image(PixelGrey(str(tmp_path / "img")), scene, workers=1)
    assert image.shape == (2, 3, 3)
    assert image[1, 2].tolist() == [0.12] * 3


def test_rendering_a_scene_again_starts_from_a_black_image(tmp_path):
    # the partial image of a render stopped at row 3 holds no rows of the render before
    scene = fov90_scene(3, 6)
    render_image(ConstantGrey(str(tmp_path / "before")), scene, workers=1)
    integrator = InterruptedAtRow3(str(tmp_path / "img"))
    integrator.add_scene(scene)
    with pytest.raises(KeyboardInterrupt):
        integrator.render(workers=1, progress=False)
    assert not np.load(tmp_path / "img_PixelGrey_partial.npy")[3:].any()


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


MUST_RETURN = ("; it must return an RGBColor, such as RGBColor(r, g, b) or BLACK, with "
               "numbers as channels")


@pytest.mark.parametrize("samples", [1, 4])
@pytest.mark.parametrize("value, shown", [
    (None, "None for pixel (1, 1) (is a return statement missing?)"),
    ((0.1, 0.2, 0.3), "(0.1, 0.2, 0.3) for pixel (1, 1)"),
    (RGBColor(0.5, Vector3D(0.0, 1.0, 0.0), 0.5),
     "RGBColor(0.5, Vector3D(0.0, 1.0, 0.0), 0.5) for pixel (1, 1)"),
], ids=["None", "tuple", "non-number channel"])
def test_compute_color_returning_a_non_colour_says_what_it_returned_and_must_return(
        tmp_path, value, shown, samples):
    integrator = ReturnsAtCentre(str(tmp_path / "img"), value)
    integrator.add_scene(fov90_scene(3, 3))
    with pytest.raises(TypeError) as error:
        integrator.render(workers=1, progress=False, samples_per_pixel=samples)
    assert str(error.value) == "ReturnsAtCentre.compute_color returned " + shown + MUST_RETURN


class BadChannelAtLastPixel(Integrator):
    """Returns a colour with a vector for its green channel at pixel (2, 1), the last of
    its row, and BLACK elsewhere."""

    def compute_color(self, ray):
        bad = RGBColor(0.5, Vector3D(0.0, 1.0, 0.0), 0.5)
        return bad if pixel_of(ray, self.scene.camera) == (2, 1) else BLACK


def test_a_colour_with_a_non_number_channel_at_the_end_of_a_row_is_found_there(tmp_path):
    integrator = BadChannelAtLastPixel(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(3, 3))
    with pytest.raises(TypeError, match=r"for pixel \(2, 1\);"):
        integrator.render(workers=1, progress=False)


class SkipsTheSecondRay(PixelGrey):
    """The course's loop under PyRT's render_loop, leaving out the second ray of each task
    (a row of the image, its rays a column of the task's camera)."""

    @render_loop
    def render(self):
        cam = self.scene.camera
        for y in range(cam.height):
            if y != 1:
                ray = Ray(Vector3D(0.0, 0.0, 0.0), cam.get_direction(0, y), INFINITY, 0.0)
                self.scene.set_pixel(self.compute_color(ray), 0, y)
        self.scene.save_image(self.get_filename())


def test_a_loop_that_leaves_a_pixel_unset_stops_the_render_naming_it(tmp_path):
    integrator = SkipsTheSecondRay(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(3, 8))
    with pytest.raises(RuntimeError, match=r"^SkipsTheSecondRay.render: the loop set no "
                                           r"colour for pixel \(1, 0\)"):
        integrator.render(workers=1, progress=False)
    assert not (tmp_path / "img_PixelGrey.npy").exists()


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
    assert capfd.readouterr().err.splitlines() == [
        "PyRT warning: NaNAndInfinity.compute_color returned NaN or infinite values for 2 "
        "pixel(s), the first at pixel (1, 0); the PNG shows them as the image's darkest (NaN) "
        "or brightest (infinity) colour"]


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
    with pytest.raises(OSError) as error:
        integrator.render(workers=1, progress=False)
    assert str(error.value) == (f"render: cannot write the images to "
                                f"{str(tmp_path.resolve() / 'afile' / 'out')!r} (Not a "
                                f"directory); choose another output folder")
    assert integrator.calls == 0


@pytest.mark.skipif(not os.path.isdir("/proc"), reason="needs a folder no one can write to")
def test_existing_folder_where_no_file_can_be_made_fails_before_rendering():
    # /proc exists, and not even root can create a file there
    integrator = PixelGrey("/proc/img")
    integrator.add_scene(fov90_scene(3, 3))
    with pytest.raises(PermissionError, match=r"^render: cannot write the images to '/proc' "):
        integrator.render(workers=1, progress=False)
    assert integrator.calls == 0


def test_render_makes_the_missing_folders_of_its_file_name(tmp_path):
    image = render_image(PixelGrey(str(tmp_path / "new" / "folders" / "img")),
                         fov90_scene(3, 2), workers=1)
    assert image[1, 2].tolist() == [0.12] * 3


def test_render_says_in_full_where_it_saved_the_png(tmp_path, monkeypatch, capsys):
    # a relative name is relative to the folder the script is run from, wherever it lies
    monkeypatch.chdir(tmp_path)
    render_image(ConstantGrey("out/img"), fov90_scene(2, 2), workers=1)
    assert capsys.readouterr().out.splitlines() == [
        f"Saved {tmp_path / 'out' / 'img_Constant.png'} (and .npy, .hdr)"]
    assert (tmp_path / "out" / "img_Constant.png").is_file()
