"""pyrt/sampling.py through Integrator.render(): samples per pixel, where they go
(strata), uniform and adaptive sampling, and the error estimate."""
import json
import math
import re

import numpy as np
import pytest

import pyrt.rows
import pyrt.sampling
from AppRenderer import sphere_test_scene
from tools.make_references import SAMPLED_REFERENCE, SAMPLED_REFERENCE_SIZE
from helpers import (GREY, PNG_TOLERANCE, ConstantGrey, PixelGrey, StepAt, fov90_scene,
                     image_point, read_png, render_image, small_cornell_box)
from PyRT_Common import plt
from PyRT_Core import *
from PyRT_Integrators import *
from pyrt.rendering import render_loop


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


def error_against_the_sampled_reference(folder, samples, **options):
    """The RMSE of Phong on small_cornell_box rendered with `samples` rays per pixel (and
    render's other options) against the same with 1024 (make_references.py)."""
    name = "_".join([f"spp{samples}", *options])
    image = render_image(PhongIntegrator(str(folder / name)),
                         small_cornell_box(SAMPLED_REFERENCE_SIZE), samples_per_pixel=samples,
                         **options)
    return float(np.sqrt(np.mean((image - np.load(SAMPLED_REFERENCE)) ** 2)))


def test_error_against_a_high_sample_reference_shrinks_with_more_samples(tmp_path):
    errors = [error_against_the_sampled_reference(tmp_path, n) for n in (1, 4, 16, 64)]
    assert errors[0] > errors[1] > errors[2] > errors[3], errors
    # Averaging N samples cuts the error at least like 1/sqrt(N): 64 samples, 8 times.
    assert errors[3] < errors[0] / 8, errors


class PhongRowsOutside(PhongIntegrator):
    """Phong with a render loop of its own under render_loop, rows outside and columns
    inside, as some students write it; counts the tasks it runs."""

    def __init__(self, filename_):
        super().__init__(filename_)
        self.tasks = 0

    @render_loop
    def render(self):
        self.tasks += 1
        cam = self.scene.camera
        for y in range(cam.height):
            for x in range(cam.width):
                ray = Ray(Vector3D(0.0, 0.0, 0.0), cam.get_direction(x, y), INFINITY, 0.0)
                self.scene.set_pixel(self.compute_color(ray), x, y)
        self.scene.save_image(self.get_filename())


def test_a_loop_of_its_own_with_several_samples_gives_the_pixels_of_the_anti_aliased_image(
        tmp_path):
    # the loop runs once per row with the row's N jittered rays in each pixel, and their
    # colours are summed in the order of the cells: the images agree bit for bit
    uniform = render_image(PhongIntegrator(str(tmp_path / "uniform")), small_cornell_box(12),
                           workers=1, samples_per_pixel=4)
    integrator = PhongRowsOutside(str(tmp_path / "own"))
    image = render_image(integrator, small_cornell_box(12), workers=1, samples_per_pixel=4)
    assert integrator.tasks == 12
    assert np.array_equal(image, uniform)
    centre = render_image(PhongIntegrator(str(tmp_path / "centre")), small_cornell_box(12),
                          workers=1)
    assert not np.array_equal(image, centre)


class WhiteAtPixelCentres(Integrator):
    """White for a ray through the centre of its pixel, black for any other ray."""

    def compute_color(self, ray):
        x, y = image_point(ray, self.scene.camera)
        centre = abs(x % 1.0 - 0.5) < 1e-9 and abs(y % 1.0 - 0.5) < 1e-9
        return WHITE if centre else BLACK


def test_render_gives_the_centre_rays_colours_or_the_average_of_n_samples(tmp_path):
    grey = render_image(PixelGrey(str(tmp_path / "img")), fov90_scene(3, 2), workers=1)
    assert grey[1].tolist() == [[0.1] * 3, [0.11] * 3, [0.12] * 3]
    centres = render_image(WhiteAtPixelCentres(str(tmp_path / "img")), fov90_scene(3, 2),
                           workers=1)
    assert centres.tolist() == [[[1.0] * 3] * 3] * 2  # the rays through the centres
    # two samples: one in the left half of each pixel (white), one in the right (black)
    halves = render_image(LeftHalfWhite(str(tmp_path / "img")), fov90_scene(3, 2), workers=1,
                          samples_per_pixel=2)
    assert halves.tolist() == [[[0.5] * 3] * 3] * 2


def sampled_row(integrator, y, samples, refined):
    """Row y of the pass of samples rays in the pixels that refined marks, as a task makes
    it: per pixel the average colour and the estimated squared error of each channel."""
    rows = pyrt.rows.SampledRows(samples, pyrt.rows.RowStreams(0), Integrator.render.loop,
                                 refined=np.array(refined))
    return pyrt.rows.render_block(integrator, y, y + 1, rows)[0]


def test_sampled_rows_give_colour_and_error_of_the_pixels_asked_for_zeros_elsewhere(
        tmp_path):
    # LeftHalfWhite with N = 2: mean 1/2 and one pair differing by 1, error 1 / (4 sqrt(2))
    integrator = LeftHalfWhite(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(3, 2))
    row = sampled_row(integrator, 1, 2, [[False] * 3, [False, True, False]])
    error = 1 / (4 * math.sqrt(2))
    assert row[0].tolist() == row[2].tolist() == [0.0] * 6
    assert row[1].tolist() == pytest.approx([0.5] * 3 + [error] * 3, rel=1e-15)
    # one sample per pixel: no pair of samples, no spread to estimate an error from
    grey = PixelGrey(str(tmp_path / "img"))
    grey.add_scene(fov90_scene(3, 2))
    row = sampled_row(grey, 1, 1, [[True] * 3] * 2)
    assert row[:, 3:].tolist() == [[0.0] * 3] * 3


@pytest.mark.parametrize("samples", [1, 4])
def test_camera_rays_see_objects_however_close_to_the_camera(tmp_path, samples):
    # camera rays start at no surface, so t_min = 0: a wall 0.00005 in front of the camera
    # (less than EPSILON, the t_min of other rays) fills the image; a sphere 0.2 to 0.6 in
    # front of it fills the view of the centre pixel
    wall = InfinitePlane(Vector3D(0, 0, -0.00005), Vector3D(0, 0, 1))
    image = render_image(IntersectionIntegrator(str(tmp_path / "wall")), fov90_scene(3, 3, [
        (wall, GREY)]), workers=1, samples_per_pixel=samples)
    assert (image == (1.0, 0.0, 0.0)).all()
    scene = fov90_scene(3, 3, [(Sphere(Vector3D(0, 0, -0.4), 0.2), GREY)])
    image = render_image(IntersectionIntegrator(str(tmp_path / "ball")), scene, workers=1,
                         samples_per_pixel=samples)
    assert image[1, 1].tolist() == [1.0, 0.0, 0.0]


@pytest.mark.parametrize("option, value, allowed", [
    ("samples_per_pixel", 0, "a whole number >= 1"),
    ("workers", 2.5, "None (all cores) or a whole number >= 1")])
def test_bad_render_option_message_says_what_is_allowed(tmp_path, option, value, allowed):
    integrator = PhongIntegrator(str(tmp_path / "img"))
    integrator.add_scene(sphere_test_scene(width=4, height=4))
    with pytest.raises(ValueError) as error:
        integrator.render(progress=False, **{option: value})
    assert str(error.value) == f"render: {option} must be {allowed}, got {value!r}"


@pytest.mark.parametrize("option, value", [
    *[("samples_per_pixel", value) for value in (0, -1, 2.5, "4", True)],
    *[("workers", value) for value in (0, -1, 2.5, "2", True)]])
def test_bad_render_option_raises_value_error_naming_it(tmp_path, option, value):
    integrator = PhongIntegrator(str(tmp_path / "out" / "img"))
    integrator.add_scene(sphere_test_scene(width=4, height=4))
    with pytest.raises(ValueError, match=re.escape(option)):
        integrator.render(progress=False, **{option: value})
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


# ------------------------------------------------------------------------------------------
# Where the samples go: strata, uniform and adaptive
# ------------------------------------------------------------------------------------------
# N samples per pixel form a grid of a x b cells as square as N allows, a rows and b
# columns, a <= b (docs/sampling.md): worked out by hand.
GRIDS = {2: (1, 2), 4: (2, 2), 6: (2, 3), 7: (1, 7), 8: (2, 4), 9: (3, 3), 12: (3, 4),
         16: (4, 4)}


def cells_of(points, rows, columns):
    """The (row, column) cell of each (u, v) point of a pixel cut into rows x columns."""
    return [(math.floor(v * rows), math.floor(u * columns)) for u, v in points]


@pytest.mark.parametrize("samples", GRIDS)
def test_uniform_samples_lie_inside_their_pixel_one_in_each_stratum(samples):
    rows, columns = GRIDS[samples]
    every_cell = sorted((r, c) for r in range(rows) for c in range(columns))
    for y in (0, 7):
        for points in pyrt.rows.pixel_offsets(samples, y, 5):
            assert all(0.0 <= u < 1.0 and 0.0 <= v < 1.0 for u, v in points)
            # one point in each cell, in the order of the cells: row by row
            assert cells_of(points, rows, columns) == every_cell


def test_sample_points_are_random_across_and_down_their_cell_independently():
    # where a point lies across its cell says nothing about where it lies down it: over
    # 50 pixels of 4 cells, the two fractions agree nowhere
    rows, columns = GRIDS[4]
    for points in pyrt.rows.pixel_offsets(4, 2, 50):
        for (u, v), (r, c) in zip(points, cells_of(points, rows, columns)):
            assert abs((u * columns - c) - (v * rows - r)) > 1e-12


def samples_per_pixel(points):
    """{(x, y): [(u, v), ...]}: the points grouped by pixel, as offsets inside it."""
    pixels = {}
    for X, Y in points:
        x, y = math.floor(X), math.floor(Y)
        pixels.setdefault((x, y), []).append((X - x, Y - y))
    return pixels


def test_uniform_render_samples_each_pixel_once_in_each_stratum(tmp_path):
    integrator = StepAt(str(tmp_path / "img"), 2.3)
    render_image(integrator, fov90_scene(5, 4), workers=1, samples_per_pixel=8)
    pixels = samples_per_pixel(integrator.points)
    assert sorted(pixels) == [(x, y) for x in range(5) for y in range(4)]
    for points in pixels.values():
        assert sorted(cells_of(points, 2, 4)) == [(r, c) for r in range(2) for c in range(4)]


def test_adaptive_render_refines_both_pixels_across_an_edge_one_sample_per_stratum(tmp_path):
    # The edge at X = 2.3 lies in pixel column 2, whose centre (2.5) is black while that
    # of column 1 (1.5) is white: after the centre rays, columns 1 and 2 get 16 rays, one
    # in each cell of the 4 x 4 grid; the others, which match their neighbours, keep the
    # centre ray alone.
    integrator = StepAt(str(tmp_path / "img"), 2.3)
    image = render_image(integrator, fov90_scene(5, 4), workers=1, samples_per_pixel=16,
                         adaptive=True)
    pixels = samples_per_pixel(integrator.points)
    assert sorted(pixels) == [(x, y) for x in range(5) for y in range(4)]
    every_cell = [(r, c) for r in range(4) for c in range(4)]
    for (x, y), (centre, *others) in pixels.items():  # the centre rays come first
        assert centre == pytest.approx((0.5, 0.5), abs=1e-9), (x, y)
        if x in (1, 2):
            assert sorted(cells_of(others, 4, 4)) == every_cell, (x, y)
        else:
            assert others == [], (x, y)
    # column 1 is white throughout; of column 2 the left 0.3 is: 1 of 4 columns of cells
    # lies wholly left of the edge, and the next one's sample with probability 0.2
    assert (image[:, 1] == 1.0).all()
    assert ((0.25 <= image[:, 2]) & (image[:, 2] <= 0.5)).all()
    assert (image[:, [0]] == 1.0).all() and (image[:, [3, 4]] == 0.0).all()


def test_refined_pixels_get_the_rays_of_uniform_sampling_and_its_colours(tmp_path):
    # docs/sampling.md: after the centre ray, which only finds the edge, a refined pixel
    # gets the jittered rays of the uniform N-sample render, so the same colour bit for bit
    uniform = StepAt(str(tmp_path / "uniform"), 2.3)
    uniform_image = render_image(uniform, fov90_scene(5, 4), workers=1, samples_per_pixel=4)
    adaptive = StepAt(str(tmp_path / "adaptive"), 2.3)
    adaptive_image = render_image(adaptive, fov90_scene(5, 4), workers=1,
                                  samples_per_pixel=4, adaptive=True)
    jittered, refined = samples_per_pixel(uniform.points), samples_per_pixel(adaptive.points)
    for x in (1, 2):  # the refined columns
        for y in range(4):
            centre, *others = refined[(x, y)]
            assert centre == pytest.approx((0.5, 0.5), abs=1e-9)
            assert others == jittered[(x, y)], (x, y)
    # the refined columns as uniform sampling made them; the others, white or black
    # throughout, are their centre ray's colour, as they are uniform sampling's
    assert np.array_equal(adaptive_image, uniform_image)


def test_adaptive_render_of_an_image_without_edges_traces_only_the_centre_rays(tmp_path):
    integrator = ConstantGrey(str(tmp_path / "img"))
    image = render_image(integrator, fov90_scene(7, 5), workers=1, samples_per_pixel=16,
                         adaptive=True)
    assert integrator.calls == 7 * 5
    assert (image == (0.25, 0.5, 0.75)).all()
    accuracy = json.loads((tmp_path / "img_Constant_accuracy.json").read_text())
    assert (accuracy["rays"], accuracy["pixels_with_n_samples"]) == (35, 0)
    assert accuracy["estimated_rmse"] == 0.0
    rays = read_png(tmp_path / "img_Constant_samples.png")
    assert rays.shape == (5, 7, 3)
    assert (rays == rays[0, 0]).all()


def test_sample_map_has_the_image_shape_dark_for_one_ray_bright_for_the_most(tmp_path):
    integrator = StepAt(str(tmp_path / "img"), 2.3)
    render_image(integrator, fov90_scene(5, 4), workers=1, samples_per_pixel=16,
                 adaptive=True)
    rays = read_png(tmp_path / "img_Step_samples.png")
    assert rays.shape == (4, 5, 3)
    colors = plt.get_cmap(pyrt.sampling.SAMPLE_MAP_COLORS)
    fewest, most = colors(0.0)[:3], colors(1.0)[:3]  # 1 ray and 1 + 16 rays
    for x in range(5):
        expected = most if x in (1, 2) else fewest
        assert rays[:, x] == pytest.approx(np.tile(expected, (4, 1)), abs=PNG_TOLERANCE)


def test_refined_pixels_are_both_of_every_pair_of_neighbours_differing_by_more_than_t():
    # a 4 x 5 display, 0.25 everywhere but pixel (2, 1), whose blue channel is 0.5
    display = np.full((4, 5, 3), 0.25)
    display[1, 2, 2] = 0.5
    refined = pyrt.sampling.refined_pixels(display, 0.125)
    expected = np.zeros((4, 5), dtype=bool)
    expected[1, 1:4] = expected[0:3, 2] = True  # (2, 1) and its four neighbours
    assert refined.dtype == bool and (refined == expected).all()
    # a difference of exactly the tolerance is not more than it
    assert not pyrt.sampling.refined_pixels(display, 0.25).any()
    # tolerance 0: any difference, and no pair of equal neighbours
    assert (pyrt.sampling.refined_pixels(display, 0.0) == expected).all()


class LinearStepAt(Integrator):
    """Grey `left` left of the line X = 2.3 of the image plane, `right` right of it; its PNG
    shows the linear colours without tonemapping, as LazyIntegrator's does."""

    tonemap = False

    def __init__(self, filename_, left, right):
        super().__init__(filename_ + "_Linear")
        self.left, self.right = left, right

    def compute_color(self, ray):
        x, _ = image_point(ray, self.scene.camera)
        grey = self.left if x < 2.3 else self.right
        return RGBColor(grey, grey, grey)


@pytest.mark.parametrize("left, right, refined", [
    (0.2, 0.3, 8),      # 0.1 apart in the PNG: columns 1 and 2 refined
    (0.2, 0.21, 0),     # 0.01 apart: less than the tolerance
    (1.5, 3.0, 0),      # both shown as 1
    (-0.5, -1.0, 0)])   # both shown as 0
def test_adaptive_render_without_tonemapping_compares_the_colours_the_png_shows(
        tmp_path, left, right, refined):
    render_image(LinearStepAt(str(tmp_path / "img"), left, right), fov90_scene(5, 4),
                 workers=1, samples_per_pixel=4, adaptive=True, tolerance=0.03)
    accuracy = json.loads((tmp_path / "img_Linear_accuracy.json").read_text())
    assert accuracy["pixels_with_n_samples"] == refined


def sample_map_colours(samples):
    """The colours of 1 ray and of N + 1 rays (a refined pixel's) in the sample map."""
    colors = plt.get_cmap(pyrt.sampling.SAMPLE_MAP_COLORS)
    return colors(0.0)[:3], colors(1.0)[:3]


def test_sample_map_is_pale_yellow_for_refined_pixels_whatever_the_others_got(tmp_path):
    # N = 2: 3 rays are the most, in the columns 1 and 2 beside the edge
    render_image(StepAt(str(tmp_path / "img"), 2.3), fov90_scene(5, 4), workers=1,
                 samples_per_pixel=2, adaptive=True)
    rays = read_png(tmp_path / "img_Step_samples.png")
    fewest, most = sample_map_colours(2)
    for x in range(5):
        expected = most if x in (1, 2) else fewest
        assert rays[:, x] == pytest.approx(np.tile(expected, (4, 1)), abs=PNG_TOLERANCE), x
    # every pixel differs from its neighbours: all are refined, all have the most rays
    render_image(PixelGrey(str(tmp_path / "img")), fov90_scene(5, 4), workers=1,
                 samples_per_pixel=4, adaptive=True, tolerance=0.0)
    rays = read_png(tmp_path / "img_PixelGrey_samples.png")
    assert rays == pytest.approx(np.tile(most, (4, 5, 1)), abs=PNG_TOLERANCE)


def test_sample_map_is_a_png_whatever_matplotlib_saves_by_default(tmp_path):
    with plt.rc_context({"savefig.format": "svg"}):
        render_image(StepAt(str(tmp_path / "img"), 2.3), fov90_scene(5, 4), workers=1,
                     samples_per_pixel=4, adaptive=True)
    assert (tmp_path / "img_Step_samples.png").read_bytes().startswith(b"\x89PNG\r\n")


def test_adaptive_render_of_an_image_without_edges_shows_no_bar_for_refining(tmp_path,
                                                                            capfd):
    integrator = ConstantGrey(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(7, 5))
    integrator.render(workers=1, samples_per_pixel=16, adaptive=True)
    err = capfd.readouterr().err
    assert "ConstantGrey centre rays: 100%" in err
    assert "rays at edges" not in err


def test_adaptive_render_with_zero_tolerance_refines_every_pixel_as_uniform_sampling_does(
        tmp_path):
    # Every pixel differs from a neighbour: after its centre ray each gets the uniform
    # render's 4 rays, so the image and its estimated error are uniform sampling's.
    samples, size = 4, 16
    uniform = render_image(PhongIntegrator(str(tmp_path / "uniform")), small_cornell_box(size),
                           workers=1, samples_per_pixel=samples)
    adaptive = render_image(PhongIntegrator(str(tmp_path / "adaptive")),
                            small_cornell_box(size), workers=1, samples_per_pixel=samples,
                            adaptive=True, tolerance=0.0)
    assert np.array_equal(adaptive, uniform)
    accuracy = json.loads((tmp_path / "adaptive_Phong_accuracy.json").read_text())
    assert accuracy["pixels_with_n_samples"] == size * size  # every pixel refined
    assert accuracy["rays"] == (1 + samples) * size * size
    expected = json.loads((tmp_path / "uniform_Phong_accuracy.json").read_text())
    assert accuracy["estimated_rmse_rgb"] == expected["estimated_rmse_rgb"]


def test_adaptive_render_error_is_no_higher_than_uniform_sampling_at_the_same_n(tmp_path):
    uniform = error_against_the_sampled_reference(tmp_path, 16)
    adaptive = error_against_the_sampled_reference(tmp_path, 16, adaptive=True)
    centre = error_against_the_sampled_reference(tmp_path, 1)
    # refined pixels are uniform sampling's; the others, where the colour varies smoothly,
    # keep their centre ray, whose error (second order in the pixel's size) is as small as
    # that of uniform sampling's average there, but not always smaller
    assert adaptive <= 1.01 * uniform < centre / 2, (adaptive, uniform, centre)


@pytest.mark.parametrize("samples", [4, 9])
def test_adaptive_image_is_the_same_with_one_and_two_workers(tmp_path, capfd, worker_first,
                                                             samples):
    one = render_image(PhongIntegrator(str(tmp_path / "one")), small_cornell_box(64),
                       workers=1, samples_per_pixel=samples, adaptive=True)
    worker_first()
    two = render_image(PhongIntegrator(str(tmp_path / "two")), small_cornell_box(64),
                       workers=2, samples_per_pixel=samples, adaptive=True)
    assert "one process" not in capfd.readouterr().err
    assert np.array_equal(one, two)
    assert np.array_equal(np.load(tmp_path / "one_Phong.npy"), one)
    assert (read_png(tmp_path / "one_Phong_samples.png")
            == read_png(tmp_path / "two_Phong_samples.png")).all()


class StopsAtRefinement(StepAt):
    """StepAt that is stopped with Ctrl+C at its first ray away from a pixel centre."""

    def compute_color(self, ray):
        x, y = image_point(ray, self.scene.camera)
        if abs(x % 1.0 - 0.5) > 1e-9 or abs(y % 1.0 - 0.5) > 1e-9:
            raise KeyboardInterrupt
        return super().compute_color(ray)


def test_ctrl_c_while_refining_saves_the_centre_rays_image(tmp_path):
    integrator = StopsAtRefinement(str(tmp_path / "img"), 2.3)
    integrator.add_scene(fov90_scene(5, 4))
    with pytest.raises(KeyboardInterrupt):
        integrator.render(workers=1, progress=False, samples_per_pixel=4, adaptive=True)
    partial = np.load(tmp_path / "img_Step_partial.npy")
    assert (partial[:, :2] == 1.0).all() and (partial[:, 2:] == 0.0).all()


# ------------------------------------------------------------------------------------------
# The error estimate
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("samples, pairs", [
    (2, [(0, 1)]),                              # 1 x 2: side by side
    (4, [(0, 1), (2, 3)]),                      # 2 x 2: side by side, row by row
    (6, [(0, 3), (1, 4), (2, 5)]),              # 2 x 3: rows of 3, so one above the other
    (9, [(0, 1), (2, 3), (4, 5), (6, 7)]),      # 3 x 3: consecutive, the last left out
])
def test_strata_are_paired_with_a_neighbour(samples, pairs):
    assert pyrt.rows.stratum_pairs(samples) == pairs


@pytest.mark.parametrize("samples, weight", [
    (2, 1 / (math.sqrt(2) * 2 * 2)),    # P = 1 pair: 1 / (sqrt(2) * 2P * N)
    (4, 1 / (math.sqrt(2) * 16)),       # N even: 1 / (sqrt(2) N^2)
    (9, 1 / (math.sqrt(2) * 8 * 9)),    # P = 4 pairs
])
def test_error_variance_weight_is_one_over_sqrt2_2P_N(samples, weight):
    assert pyrt.rows.error_variance_weight(samples) == pytest.approx(weight, rel=1e-15)


class LeftHalfWhite(Integrator):
    """White where the ray crosses the left half of its pixel, black in the right half."""

    def __init__(self, filename_):
        super().__init__(filename_ + "_LeftHalf")

    def compute_color(self, ray):
        x, _ = image_point(ray, self.scene.camera)
        return WHITE if x % 1.0 < 0.5 else BLACK


def test_accuracy_file_holds_the_estimate_worked_out_by_hand(tmp_path, capsys):
    # With 2 samples per pixel (cells: left half, right half) every pixel gets one white
    # and one black sample: mean 0.5, one pair with d = 1, estimated squared error
    # 1 / (sqrt(2) * 2 * 2) in each channel, so the RMSE is sqrt(1 / (4 sqrt(2))).
    image = render_image(LeftHalfWhite(str(tmp_path / "img")), fov90_scene(3, 2),
                         workers=1, samples_per_pixel=2)
    assert (image == 0.5).all()
    accuracy = json.loads((tmp_path / "img_LeftHalf_accuracy.json").read_text())
    rmse = math.sqrt(1 / (4 * math.sqrt(2)))
    assert accuracy["estimated_rmse"] == pytest.approx(rmse, rel=1e-12)
    assert accuracy["estimated_rmse_rgb"] == pytest.approx([rmse] * 3, rel=1e-12)
    assert accuracy["image"] == "img_LeftHalf.png"
    assert (accuracy["samples_per_pixel"], accuracy["adaptive"], accuracy["tolerance"]) == (
        2, False, None)
    assert (accuracy["pixels"], accuracy["rays"], accuracy["rays_per_pixel"]) == (6, 12, 2.0)
    assert accuracy["image_range"] == 0.0
    assert capsys.readouterr().out.splitlines() == [  # an image of range 0: no share of it
        f"Saved {tmp_path / 'img_LeftHalf.png'} (and .npy, .hdr)",
        f"Estimated error: RMSE {rmse:.2e} of the linear image, from the spread of each "
        f"pixel's samples; saved in {tmp_path / 'img_LeftHalf_accuracy.json'}"]


class GreyColumn0AndFirstThirdOfColumn1(Integrator):
    """Grey 0.5 in pixel column 0 and in the left third of pixel column 1, black elsewhere."""

    def __init__(self, filename_):
        super().__init__(filename_ + "_Thirds")

    def compute_color(self, ray):
        x, _ = image_point(ray, self.scene.camera)
        return GREY if x < 1.0 + 1.0 / 3.0 else BLACK


def test_adaptive_accuracy_file_and_report_hold_the_estimate_worked_out_by_hand(tmp_path,
                                                                                capsys):
    # 3 x 2 pixels. The centre rays are grey in column 0, black in columns 1 and 2, so
    # columns 0 and 1 are refined (4 of 6 pixels): after the centre ray, N = 9 rays, one in
    # each cell of a 3 x 3 grid. In column 1 the samples of the cells of the left
    # column (0, 3, 6) are grey, the others black: mean 0.5 / 3; of the pairs (0, 1),
    # (2, 3), (4, 5), (6, 7) three differ by 0.5, so the estimated squared error is
    # 3 * 0.25 / (sqrt(2) * 2 * 4 * 9) in each channel. Column 0 is all grey: no error;
    # the pixels of column 2 kept their centre ray and count as exact.
    image = render_image(GreyColumn0AndFirstThirdOfColumn1(str(tmp_path / "img")),
                         fov90_scene(3, 2), workers=1, samples_per_pixel=9, adaptive=True)
    assert image[:, 0] == pytest.approx(np.full((2, 3), 0.5), abs=1e-15)
    assert image[:, 1] == pytest.approx(np.full((2, 3), 0.5 / 3), abs=1e-15)
    assert (image[:, 2] == 0.0).all()
    text = (tmp_path / "img_Thirds_accuracy.json").read_text()
    accuracy = json.loads(text)
    assert text == json.dumps(accuracy, indent=2)  # readable: one entry a line, indented
    rmse = math.sqrt(2 * 3 * 0.25 / (math.sqrt(2) * 2 * 4 * 9) / 6)
    assert accuracy["estimated_rmse"] == pytest.approx(rmse, rel=1e-12)
    assert accuracy["estimated_rmse_rgb"] == pytest.approx([rmse] * 3, rel=1e-12)
    assert (accuracy["samples_per_pixel"], accuracy["adaptive"], accuracy["tolerance"]) == (
        9, True, 0.03)
    assert accuracy["image_range"] == 0.5
    assert (accuracy["pixels"], accuracy["pixels_with_n_samples"]) == (6, 4)
    assert (accuracy["rays"], accuracy["rays_per_pixel"]) == (4 * 10 + 2, pytest.approx(42 / 6))
    assert accuracy["method"] == (
        "the square root of the mean, over pixels and channels, of each pixel's estimated "
        "squared error sum(d^2) / (sqrt(2) * 2P * N), d the difference of the two samples of "
        "each of the P pairs of neighbouring strata; pixels that kept their centre ray count "
        "as exact")
    samples = tmp_path / "img_Thirds_samples.png"
    captured = capsys.readouterr()
    assert captured.err == ""
    assert captured.out.splitlines() == [
        f"Saved {tmp_path / 'img_Thirds.png'} (and .npy, .hdr)",
        f"Adaptive sampling: 4 of 6 pixels (66.7%) got 9 rays after their centre ray, the "
        f"others their centre ray only: 7.00 rays per pixel, where uniform sampling takes 9. "
        f"Map of the rays per pixel: {samples} (black: 1, pale yellow: 10)",
        f"Estimated error: RMSE {rmse:.2e} of the linear image, {rmse / 0.5:.2%} of its "
        f"range, from the spread of each pixel's samples; saved in "
        f"{tmp_path / 'img_Thirds_accuracy.json'}"]


class ThirdsWithANaNPixel(GreyColumn0AndFirstThirdOfColumn1):
    """GreyColumn0AndFirstThirdOfColumn1 with NaN in pixel (2, 1)."""

    def compute_color(self, ray):
        x, y = image_point(ray, self.scene.camera)
        if (math.floor(x), math.floor(y)) == (2, 1):
            return RGBColor(math.nan, math.nan, math.nan)
        return super().compute_color(ray)


def test_estimate_and_image_range_leave_out_the_pixels_that_are_not_numbers(tmp_path, capfd):
    # As above, but pixel (2, 1) is NaN, which the PNG shows as the darkest colour, as its
    # neighbours: it keeps its centre ray, and the mean is over the other 5 pixels.
    image = render_image(ThirdsWithANaNPixel(str(tmp_path / "img")), fov90_scene(3, 2),
                         workers=1, samples_per_pixel=9, adaptive=True)
    assert np.isnan(image[1, 2]).all()
    accuracy = json.loads((tmp_path / "img_Thirds_accuracy.json").read_text())
    rmse = math.sqrt(2 * 3 * 0.25 / (math.sqrt(2) * 2 * 4 * 9) / 5)
    assert accuracy["estimated_rmse"] == pytest.approx(rmse, rel=1e-12)
    assert accuracy["estimated_rmse_rgb"] == pytest.approx([rmse] * 3, rel=1e-12)
    assert accuracy["image_range"] == 0.5
    assert accuracy["pixels_with_n_samples"] == 4
    assert "1 pixel(s), the first at pixel (2, 1)" in capfd.readouterr().err


class NaNEverywhere(Integrator):
    def compute_color(self, ray):
        return RGBColor(math.nan, math.nan, math.nan)


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # the mean of no numbers
def test_image_without_a_single_number_still_gets_its_accuracy_file(tmp_path, capsys):
    image = render_image(NaNEverywhere(str(tmp_path / "img")), fov90_scene(3, 2), workers=1,
                         samples_per_pixel=2)
    assert np.isnan(image).all()
    accuracy = json.loads((tmp_path / "img_accuracy.json").read_text())
    assert accuracy["image_range"] == 0.0  # no numbers, no range
    assert math.isnan(accuracy["estimated_rmse"])
    assert capsys.readouterr().out.splitlines()[1].startswith(
        "Estimated error: RMSE nan of the linear image, from the spread")


def test_a_render_without_estimate_or_map_removes_those_of_an_earlier_render(tmp_path):
    scene = fov90_scene(5, 4)
    render_image(StepAt(str(tmp_path / "img"), 2.3), scene, workers=1, samples_per_pixel=4,
                 adaptive=True)
    assert (tmp_path / "img_Step_samples.png").exists()
    render_image(StepAt(str(tmp_path / "img"), 2.3), scene, workers=1, samples_per_pixel=4)
    assert not (tmp_path / "img_Step_samples.png").exists()
    assert (tmp_path / "img_Step_accuracy.json").exists()
    render_image(StepAt(str(tmp_path / "img"), 2.3), scene, workers=1)
    assert not (tmp_path / "img_Step_accuracy.json").exists()


def test_integrator_making_its_own_rows_renders_them_uniformly_and_says_why(tmp_path, capfd):
    image = render_image(LazyIntegrator(str(tmp_path / "img")), fov90_scene(4, 2),
                         workers=1, samples_per_pixel=4, adaptive=True)
    assert image[1, 3] == pytest.approx([3 / 4, 1 / 2, 0.0])
    captured = capfd.readouterr()
    assert captured.err == ("PyRT: LazyIntegrator renders its pixels itself (a render loop "
                            "of its own), so adaptive sampling cannot choose its rays: every "
                            "pixel gets 4\n")
    assert captured.out == saved(tmp_path / "img_Lazy.png") + NO_ESTIMATE
    assert not (tmp_path / "img_Lazy_accuracy.json").exists()


def saved(png):
    """The line render() prints once it has saved the image png."""
    return f"Saved {png} (and .npy, .hdr)\n"


NO_ESTIMATE = ("No error estimate: LazyIntegrator renders its pixels itself (a render loop "
               "of its own), so PyRT does not see its samples\n")


def test_integrator_making_its_own_rows_says_only_that_its_error_is_not_estimated(tmp_path,
                                                                                  capfd):
    render_image(LazyIntegrator(str(tmp_path / "img")), fov90_scene(4, 2), workers=1,
                 samples_per_pixel=2)
    assert capfd.readouterr() == (saved(tmp_path / "img_Lazy.png") + NO_ESTIMATE, "")
    render_image(LazyIntegrator(str(tmp_path / "img")), fov90_scene(4, 2), workers=1)
    # one sample per pixel: nothing to estimate
    assert capfd.readouterr() == (saved(tmp_path / "img_Lazy.png"), "")


def test_adaptive_with_one_sample_per_pixel_says_what_adaptive_needs(tmp_path):
    integrator = PhongIntegrator(str(tmp_path / "img"))
    integrator.add_scene(sphere_test_scene(width=4, height=4))
    with pytest.raises(ValueError) as error:
        integrator.render(progress=False, samples_per_pixel=1, adaptive=True)
    assert str(error.value) == (
        "render: adaptive=True needs samples_per_pixel >= 2, the rays the pixels at edges get; "
        "with 1 every pixel gets the ray through its centre")


def test_adaptive_render_with_tolerance_one_refines_nothing(tmp_path):
    # the PNG's colours lie in [0, 1]: no two differ by more than 1
    integrator = StepAt(str(tmp_path / "img"), 2.3)
    image = render_image(integrator, fov90_scene(5, 4), workers=1, samples_per_pixel=4,
                         adaptive=True, tolerance=1)
    assert len(integrator.points) == 20
    assert (image[:, :2] == 1.0).all() and (image[:, 2:] == 0.0).all()  # the centre rays


@pytest.mark.parametrize("options, named", [
    *[({"adaptive": True, "tolerance": value}, "tolerance")
      for value in (-0.01, 1.5, math.nan, math.inf, "0.1", True, None)],
    ({"adaptive": "yes"}, "adaptive"),
    ({"tolerance": -1.0}, "tolerance"),
    ({"adaptive": True, "samples_per_pixel": 1}, "samples_per_pixel")])
def test_bad_adaptive_option_raises_value_error_naming_it(tmp_path, options, named):
    integrator = PhongIntegrator(str(tmp_path / "out" / "img"))
    integrator.add_scene(sphere_test_scene(width=4, height=4))
    options.setdefault("samples_per_pixel", 4)
    with pytest.raises(ValueError, match=re.escape(named)):
        integrator.render(progress=False, **options)
    assert not (tmp_path / "out").exists()


