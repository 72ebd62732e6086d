"""The integrators of PyRT_Integrators.py: their file names, the value they give each
pixel (worked out by hand on tiny scenes), integrators written the way students write
them, parallel and anti-aliased rendering, and the errors a student runs into.

Most scenes use a camera with a vertical field of view of 90 degrees, so tan(fov/2) = 1:
pixel (x, y) of a width x height image looks along (x_s * width/height, y_s, -1) with
x_s = 2(x + 0.5)/width - 1 and y_s = 1 - 2(y + 0.5)/height. The centre pixel of an image
with odd sides looks straight down -z."""
import math
import multiprocessing
import os
import sys
import time

import numpy as np
import pytest
from tqdm import tqdm

from AppRenderer import cornell_box_scene, sphere_test_scene
from benchmark import StudentPhongIntegrator
from helpers import PNG_TOLERANCE, read_png, render_image, run_python
from PyRT_Core import *
from PyRT_Integrators import *

GREY = RGBColor(0.5, 0.5, 0.5)


def fov90_scene(width, height, objects=(), lights=(), ambient=BLACK):
    """A scene seen by a width x height camera with a 90 degree field of view; objects are
    (primitive, albedo) pairs and get a Lambertian BRDF of that albedo."""
    scene = Scene()
    scene.set_ambient(ambient)
    for primitive, albedo in objects:
        primitive.set_BRDF(Lambertian(albedo))
        scene.add_object(primitive)
    for position, intensity in lights:
        scene.add_point_light_sources(PointLight(position, intensity))
    scene.set_camera(Camera(width, height, 90))
    return scene


def direction_through(x, y, width, height):
    """The (unnormalised) direction of the ray through the centre of pixel (x, y) of a
    90 degree camera, from the formula in the module docstring."""
    return ((2 * (x + 0.5) / width - 1) * width / height, 1 - 2 * (y + 0.5) / height, -1.0)


def pixel_of(ray, camera):
    """The pixel whose centre ray is `ray`: get_direction inverted, so that a test
    integrator can give chosen pixels chosen colours."""
    d = ray.d
    scale_y = math.tan(camera.vertical_fov / 2)
    x_s = d.x / -d.z / (scale_y * camera.aspect_ratio)
    y_s = d.y / -d.z / scale_y
    return (round((x_s + 1) * camera.width / 2 - 0.5),
            round((1 - y_s) * camera.height / 2 - 0.5))


def kd_of(albedo):
    """The Lambertian kd of an albedo: albedo / pi."""
    return np.array(albedo) / math.pi


def small_cornell_box(size):
    return cornell_box_scene(0.75, 2, width=size, height=size)


class PixelGrey(Integrator):
    """Grey (x + 10 y) / 100 at pixel (x, y), found from the ray's direction."""

    def __init__(self, filename_):
        super().__init__(filename_ + "_PixelGrey")
        self.calls = 0

    def grey(self, x, y):
        return (x + 10 * y) / 100

    def compute_color(self, ray):
        self.calls += 1
        g = self.grey(*pixel_of(ray, self.scene.camera))
        return RGBColor(g, g, g)


# ------------------------------------------------------------------------------------------
# File names
# ------------------------------------------------------------------------------------------
INTEGRATOR_SUFFIXES = [
    (LazyIntegrator, "_Lazy"),
    (IntersectionIntegrator, "_Intersection"),
    (DepthIntegrator, "_Depth"),
    (NormalIntegrator, "_Normal"),
    (PhongIntegrator, "_Phong"),
]


@pytest.mark.parametrize("integrator_class, suffix", INTEGRATOR_SUFFIXES)
def test_integrator_appends_its_name_to_the_file_name(integrator_class, suffix):
    integrator = integrator_class("out/rendered_image")
    assert integrator.filename == "out/rendered_image" + suffix
    assert integrator.get_filename() == "out/rendered_image" + suffix


@pytest.mark.parametrize("integrator_class, suffix", INTEGRATOR_SUFFIXES)
def test_experiment_name_comes_after_the_integrator_name(integrator_class, suffix):
    integrator = integrator_class("out/img", experiment_name="_run2")
    assert integrator.get_filename() == "out/img" + suffix + "_run2"


def test_depth_integrator_max_depth_defaults_to_10():
    assert DepthIntegrator("img").max_depth == 10
    assert DepthIntegrator("img", 5).max_depth == 5
    assert DepthIntegrator("img", 5, "_far").get_filename() == "img_Depth_far"


def test_own_integrator_file_name_is_filename_plus_experiment_name():
    class Plain(Integrator):
        def compute_color(self, ray):
            return BLACK

    assert Plain("base").get_filename() == "base"
    assert Plain("base", "_exp").get_filename() == "base_exp"
    integrator = Plain("base")
    assert integrator.scene is None
    scene = Scene()
    integrator.add_scene(scene)
    assert integrator.scene is scene


def test_render_saves_png_npy_and_hdr_under_get_filename(tmp_path):
    integrator = PixelGrey(str(tmp_path / "img"))
    image = render_image(integrator, fov90_scene(4, 3))
    for suffix in (".png", ".npy", ".hdr"):
        assert (tmp_path / ("img_PixelGrey" + suffix)).is_file()
    assert read_png(tmp_path / "img_PixelGrey.png").shape == (3, 4, 3)
    # Rows are y, columns x: image[y, x] = (x + 10 y) / 100.
    expected = np.array([[[(x + 10 * y) / 100] * 3 for x in range(4)] for y in range(3)])
    assert np.array_equal(image, expected)


# ------------------------------------------------------------------------------------------
# Pixel values worked out by hand
# ------------------------------------------------------------------------------------------
def test_lazy_pixel_is_x_over_width_and_y_over_height_exactly(tmp_path):
    width, height = 5, 4
    integrator = LazyIntegrator(str(tmp_path / "img"))
    image = render_image(integrator, fov90_scene(width, height), workers=1)
    expected = np.zeros((height, width, 3))
    for y in range(height):
        for x in range(width):
            expected[y, x] = (x / width, y / height, 0.0)
    assert np.array_equal(image, expected)
    assert np.array_equal(integrator.scene.rendered_image, expected)


def test_lazy_png_shows_the_linear_values_without_tonemapping(tmp_path):
    # Tonemapped, pixel (1, 0) = (0.2, 0, 0) would be (0.2 / 0.8) ** (1 / 2.5) = 0.574
    # (0.8 = the image's largest value); untonemapped it stays 0.2.
    width, height = 5, 4
    integrator = LazyIntegrator(str(tmp_path / "img"))
    image = render_image(integrator, fov90_scene(width, height))
    png = read_png(tmp_path / "img_Lazy.png")
    assert np.abs(png - image).max() <= PNG_TOLERANCE


def test_intersection_is_red_on_a_hit_and_black_on_a_miss(tmp_path):
    # Only the centre ray, (0, 0, -1), meets the sphere of radius 1 at distance 5. The
    # others pass it at 5 sin(angle to the axis) >= 5 * (2/3) / sqrt(13/9) = 2.77 > 1.
    scene = fov90_scene(3, 3, [(Sphere(Vector3D(0, 0, -5), 1), GREY)])
    image = render_image(IntersectionIntegrator(str(tmp_path / "img")), scene)
    expected = np.zeros((3, 3, 3))
    expected[1, 1] = (1, 0, 0)
    assert np.array_equal(image, expected)


@pytest.mark.parametrize("max_depth", [None, 5, 4.5])
def test_depth_is_one_minus_distance_over_max_depth_clamped_at_zero(tmp_path, max_depth):
    # A wall at z = -4 facing the camera: pixel (x, y) meets it at the distance
    # d = 4 |direction_through(x, y)| = 4 sqrt(x_s^2 + y_s^2 + 1): 4 at the centre,
    # 4 sqrt(13)/3 = 4.81 at the edges and 4 sqrt(17)/3 = 5.50 in the corners, so with
    # max_depth 5 and 4.5 some pixels are clamped to 0.
    wall = InfinitePlane(Vector3D(0, 0, -4), Vector3D(0, 0, 1))
    scene = fov90_scene(3, 3, [(wall, GREY)])
    if max_depth is None:
        integrator, max_depth = DepthIntegrator(str(tmp_path / "img")), 10
    else:
        integrator = DepthIntegrator(str(tmp_path / "img"), max_depth)
    image = render_image(integrator, scene)
    for y in range(3):
        for x in range(3):
            d = 4 * math.sqrt(sum(c * c for c in direction_through(x, y, 3, 3)))
            c = max(1 - d / max_depth, 0)
            assert image[y, x] == pytest.approx([c, c, c], abs=1e-12), (x, y)


def test_depth_of_a_sphere_at_the_centre_pixel(tmp_path):
    # The sphere of radius 1.5 centred at distance 7 is met by the centre ray at
    # d = 7 - 1.5 = 5.5: grey 1 - 5.5/10 = 0.45. Every other ray misses it (it passes the
    # centre at >= 7 * 0.555 = 3.88 > 1.5) and is black.
    scene = fov90_scene(3, 3, [(Sphere(Vector3D(0, 0, -7), 1.5), GREY)])
    image = render_image(DepthIntegrator(str(tmp_path / "img")), scene)
    assert image[1, 1] == pytest.approx([0.45] * 3, abs=1e-12)
    image[1, 1] = 0
    assert not image.any()


@pytest.mark.parametrize("surface, colour", [
    # Sphere: the centre ray meets it at (0, 0, -3), where n = (0, 0, 1).
    (Sphere(Vector3D(0, 0, -5), 2), (0.5, 0.5, 1.0)),
    # Plane normals are used as given: (2, -1, 2)/3 -> ((1 + 2/3)/2, (1 - 1/3)/2, ...).
    (InfinitePlane(Vector3D(0, 0, -4), Vector3D(2, -1, 2)), (5 / 6, 1 / 3, 5 / 6)),
    # ... also when they face away from the camera: n = (0, 0, -1).
    (InfinitePlane(Vector3D(0, 0, -4), Vector3D(0, 0, -1)), (0.5, 0.5, 0.0)),
    # A parallelogram's Cross(s1, s2) = (0, 0, -4) faces away; it is flipped to (0, 0, 1).
    (Parallelogram(Vector3D(-1, -1, -4), Vector3D(0, 2, 0), Vector3D(2, 0, 0)),
     (0.5, 0.5, 1.0)),
], ids=["sphere", "tilted-plane", "plane-facing-away", "parallelogram"])
def test_normal_colour_is_half_of_n_plus_one(tmp_path, surface, colour):
    scene = fov90_scene(3, 3, [(surface, GREY)])
    image = render_image(NormalIntegrator(str(tmp_path / "img")), scene)
    assert image[1, 1] == pytest.approx(colour, abs=1e-12)


def test_normal_and_depth_are_black_on_a_miss(tmp_path):
    scene = fov90_scene(3, 3, [(Sphere(Vector3D(0, 0, 5), 1), GREY)])  # behind the camera
    assert not render_image(NormalIntegrator(str(tmp_path / "n")), scene).any()
    assert not render_image(DepthIntegrator(str(tmp_path / "d")), scene).any()


# Phong: pixel (1, 2) of a 3 x 3 camera looks along (0, -2/3, -1) and meets the floor
# y = -1 at P = (0, -1, -1.5) (1.5 times that direction). The floor's normal there is
# n = (0, 1, 0), and with kd = albedo/pi the course's model gives
#     colour = kd (x) i_a + sum of I (x) kd * cos / r^2 over the lights seen from P.
ALBEDO = (0.6, 0.3, 0.9)
AMBIENT = (0.2, 0.1, 0.4)
ABOVE = (Vector3D(0, 1, -1.5), (4.0, 8.0, 2.0))  # straight above P: r = 2, cos = 1
SLANTED = (Vector3D(0, 3, -4.5), (50.0, 25.0, 75.0))  # P + (0, 4, -3): r = 5, cos = 4/5
BELOW = (Vector3D(0, -3, -1.5), (9.0, 9.0, 9.0))  # under the floor: cos < 0


def floor_pixel(tmp_path, kind, lights, occluders=()):
    """The Phong colour of pixel (1, 2), which sees P on a floor of the given kind."""
    if kind == "parallelogram":
        floor = Parallelogram(Vector3D(-2, -1, 0), Vector3D(4, 0, 0), Vector3D(0, 0, -4))
    else:
        floor = InfinitePlane(Vector3D(0, -1, 0), Vector3D(0, 1, 0))
    objects = [(floor, RGBColor(*ALBEDO))] + [(o, GREY) for o in occluders]
    scene = fov90_scene(3, 3, objects, [(pos, RGBColor(*i)) for pos, i in lights],
                        RGBColor(*AMBIENT))
    return render_image(PhongIntegrator(str(tmp_path / "img")), scene)[2, 1]


FLOORS = ["parallelogram", "infinite-plane"]


@pytest.mark.parametrize("kind", FLOORS)
def test_phong_floor_lit_by_a_light_straight_above(tmp_path, kind):
    kd = kd_of(ALBEDO)
    expected = kd * AMBIENT + np.array(ABOVE[1]) * kd * 1.0 / 2 ** 2
    assert floor_pixel(tmp_path, kind, [ABOVE]) == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("kind", FLOORS)
def test_phong_light_at_an_angle_is_weighted_by_cosine_over_r_squared(tmp_path, kind):
    kd = kd_of(ALBEDO)
    expected = kd * AMBIENT + np.array(SLANTED[1]) * kd * 0.8 / 5 ** 2
    assert floor_pixel(tmp_path, kind, [SLANTED]) == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("kind", FLOORS)
def test_phong_shadowed_point_gets_only_the_ambient_term(tmp_path, kind):
    # A ball of radius 0.3 half-way between P and the light above it. The camera ray to P
    # passes its centre c = (0, -0.5, -1.5) at |c x (0, -2, -3)| / sqrt(13) = 1.5 / sqrt(13)
    # = 0.42 > 0.3, so P itself stays in view.
    ball = Sphere(Vector3D(0, -0.5, -1.5), 0.3)
    expected = kd_of(ALBEDO) * AMBIENT
    assert floor_pixel(tmp_path, kind, [ABOVE], [ball]) == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("kind", FLOORS)
def test_phong_light_behind_the_surface_adds_nothing(tmp_path, kind):
    expected = kd_of(ALBEDO) * AMBIENT
    assert floor_pixel(tmp_path, kind, [BELOW]) == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("kind", FLOORS)
def test_phong_sums_the_lights(tmp_path, kind):
    kd = kd_of(ALBEDO)
    expected = (kd * AMBIENT + np.array(ABOVE[1]) * kd / 4
                + np.array(SLANTED[1]) * kd * 0.8 / 25)
    pixel = floor_pixel(tmp_path, kind, [ABOVE, BELOW, SLANTED])
    assert pixel == pytest.approx(expected, rel=1e-9)


def test_phong_centre_pixel_of_a_wall_lit_from_the_side(tmp_path):
    # The centre ray meets the wall z = -4 at (0, 0, -4), n = (0, 0, 1); the light at
    # (0, 3, 0) is (0, 3, 4) away: r = 5, cos = 4/5.
    wall = Parallelogram(Vector3D(-2, -2, -4), Vector3D(4, 0, 0), Vector3D(0, 4, 0))
    scene = fov90_scene(3, 3, [(wall, RGBColor(*ALBEDO))],
                        [(Vector3D(0, 3, 0), RGBColor(25, 50, 100))], RGBColor(*AMBIENT))
    kd = kd_of(ALBEDO)
    expected = kd * AMBIENT + np.array([25, 50, 100]) * kd * 0.8 / 25
    image = render_image(PhongIntegrator(str(tmp_path / "img")), scene)
    assert image[1, 1] == pytest.approx(expected, rel=1e-9)


def test_phong_miss_is_black_not_ambient(tmp_path):
    scene = fov90_scene(3, 3, [(Sphere(Vector3D(0, 0, -5), 1), GREY)],
                        [(Vector3D(0, 0, 0), WHITE)], RGBColor(1, 1, 1))
    image = render_image(PhongIntegrator(str(tmp_path / "img")), scene)
    image[1, 1] = 0  # the only pixel that sees the sphere
    assert not image.any()


# A light far away, low over a tilted surface. The centre ray of a 3 x 3 camera meets the
# surface at P = (0, 0, -4), where its unit normal is n and t is a unit vector along it.
# The light hangs at P + 12480 t + 1000 n: r = 12520 and cos = n.wi = 1000/12520 = 25/313
# (the 312-25-313 right triangle, times 40), 4.6 degrees above the surface. Nothing lies
# between P and the light, so Phong is the plain Lambertian kd (x) (i_a + I cos / r^2),
# with I chosen so that I cos / r^2 = GRAZING_IRRADIANCE. A shadow ray that started below
# the surface would cross it again after 313/25 = 12.5 times its depth, beyond the
# stretch it skips, and find the light hidden: only the ambient term would be left. The
# second normal has components of both signs, all different, so that a start point with
# two components of n swapped (height (2 nx ny + nz^2) < 0) or the sign of ny wrong
# (height 1 - 2 ny^2 < 0) lies below the surface too.
GRAZING_IRRADIANCE = np.array([1.0, 2.0, 3.0])
TILTS = {  # n, t
    "normal-(0,1,1)": (Vector3D(0, 1, 1) / math.sqrt(2), Vector3D(1, 0, 0)),
    "normal-(-2,6,3)": (Vector3D(-2, 6, 3) / 7, Vector3D(3, 0, 2) / math.sqrt(13)),
}


def tilted_surface(kind, n, t):
    """The plane through P = (0, 0, -4) with normal n, or the 4 x 4 square of it centred
    on P with sides along t and n x t (Cross(4 t, 4 n x t) = 16 n: its normal is n)."""
    p = Vector3D(0, 0, -4)
    if kind == "infinite-plane":
        return InfinitePlane(p, n)
    s1, s2 = t * 4, Cross(n, t) * 4
    return Parallelogram(p - s1 / 2 - s2 / 2, s1, s2)


@pytest.mark.parametrize("tilt", TILTS)
@pytest.mark.parametrize("kind", FLOORS)
def test_phong_far_light_grazing_a_tilted_surface_gives_the_lambertian_value(
        tmp_path, kind, tilt):
    n, t = TILTS[tilt]
    light = Vector3D(0, 0, -4) + t * 12480 + n * 1000
    intensity = RGBColor(*(GRAZING_IRRADIANCE * 12520 ** 2 / (25 / 313)))
    scene = fov90_scene(3, 3, [(tilted_surface(kind, n, t), RGBColor(*ALBEDO))],
                        [(light, intensity)], RGBColor(*AMBIENT))
    expected = kd_of(ALBEDO) * (np.array(AMBIENT) + GRAZING_IRRADIANCE)
    image = render_image(PhongIntegrator(str(tmp_path / "img")), scene)
    assert image[1, 1] == pytest.approx(expected, rel=1e-9)


# ------------------------------------------------------------------------------------------
# Integrators written the way students write them
# ------------------------------------------------------------------------------------------
class StudentLoop(PhongIntegrator):
    """Phong with the rendering loop of Assignment 1.1 written out by hand."""

    def render(self):
        cam = self.scene.camera
        for y in range(cam.height):
            for x in range(cam.width):
                ray = Ray()
                ray.o = Vector3D(0.0, 0.0, 0.0)
                ray.d = cam.get_direction(x, y)
                self.scene.set_pixel(self.compute_color(ray), x, y)
        self.scene.save_image(self.get_filename())


def test_student_phong_agrees_with_phong_integrator_on_the_cornell_box(tmp_path):
    student = render_image(StudentPhongIntegrator(str(tmp_path / "a")), small_cornell_box(60),
                           workers=1)
    built_in = render_image(PhongIntegrator(str(tmp_path / "b")), small_cornell_box(60),
                            workers=1)
    assert student.any()
    np.testing.assert_allclose(student, built_in, rtol=0, atol=1e-9)


def test_student_render_loop_saves_what_the_built_in_render_saves(tmp_path):
    student = StudentLoop(str(tmp_path / "student"))
    student.add_scene(small_cornell_box(40))
    student.render()
    saved = np.load(tmp_path / "student_Phong.npy")
    built_in = render_image(PhongIntegrator(str(tmp_path / "built_in")),
                            small_cornell_box(40), workers=1)
    assert np.array_equal(saved, built_in)
    assert (tmp_path / "student_Phong.png").is_file()


# ------------------------------------------------------------------------------------------
# Parallel rendering
# ------------------------------------------------------------------------------------------
class WorkerRendersFirst(PhongIntegrator):
    """Phong whose main process holds back its first block until a worker process has
    rendered one (it leaves a marker file), so that both surely render part of the image.
    With raise_in_worker = (exception class, arguments), the worker raises that exception
    instead, after leaving the marker."""

    def __init__(self, filename_, marker, raise_in_worker=None):
        super().__init__(filename_)
        self.marker = str(marker)
        self.raise_in_worker = raise_in_worker

    def render_rows(self, y0, y1, samples_per_pixel=1):
        if multiprocessing.parent_process() is not None:  # a worker process
            rows = super().render_rows(y0, y1, samples_per_pixel)
            open(self.marker, "a").close()
            if self.raise_in_worker:
                error_class, arguments = self.raise_in_worker
                raise error_class(*arguments)
            return rows
        wait_for_file(self.marker)
        return super().render_rows(y0, y1, samples_per_pixel)


def wait_for_file(path, seconds=60):
    deadline = time.monotonic() + seconds
    while not os.path.exists(path) and time.monotonic() < deadline:
        time.sleep(0.005)


@pytest.mark.parametrize("samples", [1, 4])
def test_one_and_two_workers_give_identical_images(tmp_path, capfd, samples):
    one = render_image(PhongIntegrator(str(tmp_path / "one")), small_cornell_box(64),
                       workers=1, samples_per_pixel=samples)
    marker = tmp_path / "worker_rendered"
    two = render_image(WorkerRendersFirst(str(tmp_path / "two"), marker),
                       small_cornell_box(64), workers=2, samples_per_pixel=samples)
    assert marker.exists(), "no worker process rendered a block"
    assert "one process" not in capfd.readouterr().err
    assert one.any()
    assert np.array_equal(one, two)


def test_error_in_a_worker_process_is_raised_with_the_worker_traceback(tmp_path):
    integrator = WorkerRendersFirst(str(tmp_path / "bad"), tmp_path / "marker",
                                    raise_in_worker=(ZeroDivisionError, ["raised in a worker"]))
    integrator.add_scene(small_cornell_box(32))
    with pytest.raises(ZeroDivisionError, match="raised in a worker") as raised:
        integrator.render(workers=2, progress=False)
    assert "render_rows" in str(raised.value.__cause__)  # where the worker raised it


class NeedsTwoArguments(Exception):
    """An exception that pickle cannot rebuild: its __init__ wants two arguments."""

    def __init__(self, reason, code):
        super().__init__(f"{reason} ({code})")


def test_error_that_cannot_leave_a_worker_is_raised_as_its_text(tmp_path):
    integrator = WorkerRendersFirst(str(tmp_path / "bad"), tmp_path / "marker",
                                    raise_in_worker=(NeedsTwoArguments, ["odd failure", 7]))
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
# Its main process holds back its rendering until a worker process has rendered a block
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

    def render_rows(self, y0, y1, samples_per_pixel=1):
        rows = super().render_rows(y0, y1, samples_per_pixel)
        if multiprocessing.parent_process() is not None:  # a worker process
            open("worker_rendered", "a").close()
        else:
            deadline = time.monotonic() + 60
            while (multiprocessing.active_children() and not os.path.exists("worker_rendered")
                   and time.monotonic() < deadline):
                time.sleep(0.005)
        return rows
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


class InterruptedAfterAWorkerBlock(WorkerRendersFirst):
    """Stopped with Ctrl+C in the main process, once a worker process has rendered a block."""

    def render_rows(self, y0, y1, samples_per_pixel=1):
        rows = super().render_rows(y0, y1, samples_per_pixel)
        if multiprocessing.parent_process() is None:
            raise KeyboardInterrupt
        return rows


def test_ctrl_c_with_workers_keeps_the_rows_the_workers_finished(tmp_path):
    full = render_image(PhongIntegrator(str(tmp_path / "full")), small_cornell_box(32),
                        workers=1)
    integrator = InterruptedAfterAWorkerBlock(str(tmp_path / "img"), tmp_path / "marker")
    integrator.add_scene(small_cornell_box(32))
    with pytest.raises(KeyboardInterrupt):
        integrator.render(workers=2, progress=False)
    partial = np.load(tmp_path / "img_Phong_partial.npy")
    rendered = partial.any(axis=(1, 2))
    assert rendered.any() and not rendered.all()
    assert np.array_equal(partial[rendered], full[rendered])


def test_ctrl_c_between_blocks_stops_the_worker_processes(tmp_path, monkeypatch):
    def interrupted(bar, n=1):  # Ctrl+C while render() updates the progress bar
        raise KeyboardInterrupt

    monkeypatch.setattr(tqdm, "update", interrupted)
    integrator = WorkerRendersFirst(str(tmp_path / "img"), tmp_path / "marker")
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
