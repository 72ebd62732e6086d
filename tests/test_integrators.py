"""The integrators of PyRT_Integrators.py: their file names, the value they give each
pixel (worked out by hand on tiny scenes) and integrators written the way students write
them. Most scenes use the 90 degree camera of helpers.fov90_scene."""
import math
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

from AppRenderer import sphere_test_scene
from helpers import (GREY, PNG_TOLERANCE, PixelGrey, StudentPhongIntegrator,
                     direction_through, fov90_scene, read_png, render_image, run_python,
                     small_cornell_box)
from PyRT_Core import *
from PyRT_Integrators import *


def sphere_scene(size):
    return sphere_test_scene(width=size, height=size)


def kd_of(albedo):
    """The Lambertian kd of an albedo: albedo / pi."""
    return np.array(albedo) / math.pi


# ------------------------------------------------------------------------------------------
# What student scripts import
# ------------------------------------------------------------------------------------------
def test_star_import_gives_the_common_names_and_the_integrators():
    namespace = {}
    exec("from PyRT_Integrators import *", namespace)
    common = {}
    exec("from PyRT_Common import *", common)
    names = set(namespace) - {"__builtins__"}
    assert names == set(common) - {"__builtins__"} | {
        "Integrator", "LazyIntegrator", "IntersectionIntegrator", "DepthIntegrator",
        "NormalIntegrator", "PhongIntegrator", "CMCIntegrator", "BayesianMonteCarloIntegrator",
        "CMCISIntegrator", "BMCISIntegrator"}
    assert all(namespace[name] is common[name] for name in common if name != "__builtins__")


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


@pytest.mark.parametrize("max_depth", ["10", None, True, Vector3D(0.0, 0.0, 10.0)],
                         ids=["str", "None", "bool", "Vector3D"])
def test_depth_integrator_max_depth_must_be_a_number(max_depth):
    with pytest.raises(ValueError, match="max_depth_ must be a positive finite distance"):
        DepthIntegrator("unused", max_depth)


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


class RecordingLambertian(Lambertian):
    """Lambertian that records the directions and normal each call gets."""

    def __init__(self, diffuse_colour):
        super().__init__(diffuse_colour)
        self.calls = []

    def get_value(self, wi, wo, normal):
        self.calls.append((wi, wo, normal))
        return super().get_value(wi, wo, normal)


def test_phong_gives_the_brdf_the_light_direction_the_way_back_along_the_ray_and_normal():
    # the centre ray of a 3 x 3 camera, (0, 0, -1), meets the sphere at (0, 0, -4), normal
    # (0, 0, 1); the light at (0, 3, 0) lies along (0, 3, 4) from there
    sphere = Sphere(Vector3D(0, 0, -5), 1)
    scene = fov90_scene(3, 3, [(sphere, GREY)], [(Vector3D(0, 3, 0), WHITE)])
    brdf = RecordingLambertian(GREY)
    sphere.set_BRDF(brdf)
    integrator = PhongIntegrator("unused")
    integrator.add_scene(scene)
    integrator.compute_color(Ray(Vector3D(0, 0, 0), Vector3D(0, 0, -1)))
    [(wi, wo, normal)] = brdf.calls
    assert (wi.x, wi.y, wi.z) == pytest.approx((0.0, 0.6, 0.8), abs=1e-15)
    assert (wo.x, wo.y, wo.z) == (0.0, 0.0, 1.0)
    assert (normal.x, normal.y, normal.z) == (0.0, 0.0, 1.0)


def test_phong_hitting_an_object_without_brdf_names_it_and_says_how_to_give_it_one(tmp_path):
    scene = fov90_scene(3, 3, [(Sphere(Vector3D(5, 0, -5), 1), GREY)])
    scene.add_object(Sphere(Vector3D(0, 0, -5), 1))  # object 1, without set_BRDF
    integrator = PhongIntegrator(str(tmp_path / "img"))
    integrator.add_scene(scene)
    with pytest.raises(RuntimeError) as error:
        integrator.render(workers=1, progress=False)
    assert str(error.value) == ("Sphere(Vector3D(0.0, 0.0, -5.0), 1.0) has no BRDF; call "
                                "obj.set_BRDF(Lambertian(RGBColor(...))) on it before "
                                "rendering")


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


class TypeCheckingNormal(Integrator):
    """The Normal integrator as a real student solution writes it: it checks the type of the
    normal and otherwise treats it as a numpy array."""

    def __init__(self, filename_):
        super().__init__(filename_ + "_Normal")

    def compute_color(self, ray):
        hit = self.scene.closest_hit(ray)
        if hit.has_hit == False:  # noqa: E712 (as written)
            return BLACK
        if type(hit.normal) == Vector3D:
            n = np.array([hit.normal.x, hit.normal.y, hit.normal.z])
        else:
            n = hit.normal
        c = (n + 1) / 2
        return RGBColor(c[0], c[1], c[2])


def test_student_code_that_checks_the_normal_type_gives_the_normal_image(tmp_path):
    student = render_image(TypeCheckingNormal(str(tmp_path / "student")),
                           small_cornell_box(24), workers=1)
    built_in = render_image(NormalIntegrator(str(tmp_path / "built_in")),
                            small_cornell_box(24), workers=1)
    assert np.array_equal(student, built_in)


class RayInspector(Integrator):
    """Records the types of the ray's vectors, then moves the ray's origin in place, as a
    student building a secondary ray might."""

    def __init__(self, filename_):
        super().__init__(filename_)
        self.seen = set()

    def compute_color(self, ray):
        self.seen.add((type(ray.o), type(ray.d), (ray.o.x, ray.o.y, ray.o.z)))
        ray.o.x += 1.0
        return BLACK


def test_every_camera_ray_has_plain_vectors_and_an_origin_of_its_own(tmp_path):
    integrator = RayInspector(str(tmp_path / "img"))
    render_image(integrator, fov90_scene(4, 3), workers=1)
    assert integrator.seen == {(Vector3D, Vector3D, (0.0, 0.0, 0.0))}


@pytest.mark.parametrize("name", ["lazy", "intersection", "depth", "normal", "phong"])
def test_colours_the_integrators_return_are_plain_rgbcolors(tmp_path, name):
    integrator = {"lazy": LazyIntegrator, "intersection": IntersectionIntegrator,
                  "depth": DepthIntegrator, "normal": NormalIntegrator,
                  "phong": PhongIntegrator}[name](str(tmp_path / "img"))
    integrator.add_scene(sphere_test_scene(width=8, height=8))
    for direction in (Vector3D(0.0, 0.0, -1.0), Vector3D(0.0, 1.0, 0.0)):  # a hit, a miss
        color = integrator.compute_color(Ray(Vector3D(0.0, 0.0, 0.0), direction))
        assert type(color) == RGBColor


class ChangesBlackInPlace(NormalIntegrator):
    """Brightens misses by changing BLACK itself: `color = BLACK; color.r += 0.5`."""

    def compute_color(self, ray):
        color = super().compute_color(ray)
        if color == BLACK:
            color.r += 0.5
        return color


@pytest.mark.parametrize("workers", [1, 2])
def test_changing_black_in_place_stops_the_render_with_the_fix(tmp_path, workers):
    integrator = ChangesBlackInPlace(str(tmp_path / "img"))
    integrator.add_scene(sphere_test_scene(width=16, height=16))
    with pytest.raises(RuntimeError, match=r"BLACK was changed in place") as error:
        integrator.render(workers=workers, progress=False)
    assert "color = RGBColor(0.0, 0.0, 0.0)" in str(error.value)
    assert (BLACK.r, BLACK.g, BLACK.b) == (0.0, 0.0, 0.0)
    assert not (tmp_path / "img_Normal.png").exists()


def test_an_own_render_loop_that_changed_a_constant_is_told_when_it_saves(tmp_path):
    scene = fov90_scene(2, 2)
    red = RED
    red.g = 1.0  # RED is now yellow, for every later use
    scene.set_pixel(red, 0, 0)
    with pytest.raises(RuntimeError, match=r"^" + re.escape("Scene.save_image: the shared "
                                                           "colour RED was changed in place")):
        scene.save_image(str(tmp_path / "img"))
    assert (RED.r, RED.g, RED.b) == (1.0, 0.0, 0.0)


STUDENT = Path(__file__).resolve().parent / "student"


def test_a_course_style_student_solution_runs_unchanged_and_gives_pyrt_images(tmp_path):
    # The student's own PyRT_Integrators.py (tests/student/student_integrators.py, copied
    # in under the course's name) shadows PyRT's, as in their project; their Scene.any_hit
    # and closest_hit replace PyRT's, so that none of PyRT's fast paths stands in for them.
    # The images are PyRT's to rounding, the seams where two walls of the Cornell box
    # meet included: both keep the strictly nearest hit.
    shutil.copy(STUDENT / "student_integrators.py", tmp_path / "PyRT_Integrators.py")
    for name in ("student_scene.py", "render_all.py"):
        shutil.copy(STUDENT / name, tmp_path / name)
    result = run_python(["render_all.py", tmp_path / "student", 40], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    for name, scene, integrator in [
            ("cornell_Phong", small_cornell_box, PhongIntegrator),
            ("sphere_Lazy", sphere_scene, LazyIntegrator),
            ("sphere_Intersection", sphere_scene, IntersectionIntegrator),
            ("sphere_Depth", sphere_scene, lambda f: DepthIntegrator(f, 5)),
            ("sphere_Normal", sphere_scene, NormalIntegrator),
            ("sphere_Phong", sphere_scene, PhongIntegrator)]:
        own = render_image(integrator(str(tmp_path / "pyrt")), scene(40), workers=1)
        student = np.load(tmp_path / "student" / f"{name}.npy")
        assert own.any(), name
        np.testing.assert_allclose(student, own, rtol=1e-12, atol=1e-15, err_msg=name)


@pytest.mark.parametrize("height, lit", [(1e-170, False), (1e-150, True)])
def test_phong_with_a_light_at_the_point_seen_neither_crashes_nor_gives_infinity(
        tmp_path, height, lit):
    # The camera's ray meets the floor z = 0 where it starts, at the origin, and a light
    # hangs `height` above that point. At 1e-170 the square of its distance is below the
    # smallest double: the light is at the point, and lights nothing; at 1e-150 it lights
    # the point with I kd / r^2 = kd 1e300, large but finite.
    scene = fov90_scene(1, 1, [(InfinitePlane(Vector3D(0, 0, 0), Vector3D(0, 0, 1)), GREY)],
                        lights=[(Vector3D(0.0, 0.0, height), RGBColor(1.0, 1.0, 1.0))],
                        ambient=RGBColor(1.0, 1.0, 1.0))
    image = render_image(PhongIntegrator(str(tmp_path / "img")), scene, workers=1)
    kd = 0.5 / math.pi
    expected = kd + (kd / height ** 2 if lit else 0.0)
    np.testing.assert_allclose(image[0, 0], [expected] * 3, rtol=1e-12)
