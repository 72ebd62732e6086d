"""Bad input: the exception type, and a clear message naming the argument, for every bad
argument of the course's classes."""
import math

import pytest

from helpers import GOOD, INF, as_tuple
from PyRT_Common import BLACK, Normalize, RGBColor, Ray, Vector3D
from PyRT_Core import (Camera, InfinitePlane, Lambertian, Parallelogram, PointLight, Scene,
                       Sphere)
from PyRT_Integrators import DepthIntegrator


NAN = float("nan")


# ------------------------------------------------------------------------------------------
# Bad input: the exception type, and a message naming the argument
# ------------------------------------------------------------------------------------------
# A number that is not a whole positive number is a ValueError; something that is not a
# number at all (a string; a bool, which the framework refuses as a number) is a TypeError,
# as for the field of view and the sphere radius.
PIXEL_COUNTS = [(0, ValueError), (-1, ValueError), (2.5, ValueError), (True, TypeError),
                ("500", TypeError)]


@pytest.mark.parametrize("width, exception", PIXEL_COUNTS)
def test_camera_width_must_be_a_positive_integer(width, exception):
    with pytest.raises(exception, match=r"^Camera: width must be a "):
        Camera(width, 10, 60)


@pytest.mark.parametrize("height, exception", PIXEL_COUNTS)
def test_camera_height_must_be_a_positive_integer(height, exception):
    with pytest.raises(exception, match=r"^Camera: height must be a "):
        Camera(10, height, 60)


@pytest.mark.parametrize("fov", [0, 180, -5, 200, NAN, INF])
def test_camera_fov_must_lie_strictly_between_0_and_180(fov):
    with pytest.raises(ValueError, match=r"^Camera: vertical_fov_ "):
        Camera(10, 10, fov)


@pytest.mark.parametrize("fov", ["60", True, None])
def test_camera_fov_must_be_a_number(fov):
    with pytest.raises(TypeError, match=r"^Camera: vertical_fov_ must be a number, got "):
        Camera(10, 10, fov)


@pytest.mark.parametrize("fov", [0.0, math.pi, -1.0, NAN])
def test_camera_fov_set_later_in_radians_must_lie_strictly_between_0_and_pi(fov):
    camera = Camera(10, 10, 60)
    with pytest.raises(ValueError) as error:
        camera.vertical_fov = fov
    assert str(error.value) == ("Camera: vertical_fov is in radians once the camera exists "
                                f"and must lie strictly between 0 and pi, got {fov!r}")


def test_camera_fov_set_later_just_inside_0_to_pi_is_taken():
    camera = Camera(10, 10, 60)
    for fov in (1e-9, math.pi - 1e-9):
        camera.vertical_fov = fov
        assert camera.vertical_fov == fov


def test_camera_size_given_as_whole_floats_becomes_whole_numbers():
    camera = Camera(500.0, 400.0, 60)
    assert (camera.width, camera.height) == (500, 400)
    assert type(camera.width) is int and type(camera.height) is int


@pytest.mark.parametrize("radius", [0, -1, INF, NAN])
def test_sphere_radius_must_be_positive_and_finite(radius):
    with pytest.raises(ValueError, match=r"^Sphere: sphere_radius must be positive and finite"):
        Sphere(GOOD, radius)


def test_sphere_radius_must_be_a_number():
    with pytest.raises(TypeError, match=r"^Sphere: sphere_radius must be a number, got "):
        Sphere(GOOD, "2")


BAD_VECTORS = [Vector3D(NAN, 0.0, 0.0), Vector3D(0.0, INF, 0.0), Vector3D(0.0, 0.0, -INF)]


@pytest.mark.parametrize("bad", BAD_VECTORS)
def test_sphere_origin_must_be_finite(bad):
    with pytest.raises(ValueError, match=r"^Sphere: sphere_origin must have finite components"):
        Sphere(bad, 1.0)


@pytest.mark.parametrize("bad", BAD_VECTORS)
def test_point_light_position_must_be_finite(bad):
    with pytest.raises(ValueError, match=r"^PointLight: pos_ must have finite components"):
        PointLight(bad, RGBColor(1.0, 1.0, 1.0))


@pytest.mark.parametrize("bad", BAD_VECTORS)
def test_parallelogram_point_must_be_finite(bad):
    with pytest.raises(ValueError, match=r"^Parallelogram: point must have finite components"):
        Parallelogram(bad, Vector3D(1.0, 0.0, 0.0), Vector3D(0.0, 1.0, 0.0))


@pytest.mark.parametrize("make, name", [
    (lambda v: Parallelogram(GOOD, v, Vector3D(0.0, 1.0, 0.0)), "Parallelogram: s1"),
    (lambda v: Parallelogram(GOOD, Vector3D(1.0, 0.0, 0.0), v), "Parallelogram: s2"),
    (lambda v: InfinitePlane(GOOD, v), "InfinitePlane: plane_normal"),
], ids=["s1", "s2", "plane_normal"])
def test_directions_that_are_not_finite_vectors_are_refused_naming_them(make, name):
    bad = Vector3D(NAN, 0.0, 1.0)
    with pytest.raises(ValueError) as error:
        make(bad)
    assert str(error.value) == f"{name} must have finite components, got {bad!r}"
    with pytest.raises(TypeError) as error:
        make((1.0, 0.0, 0.0))
    assert str(error.value) == f"{name} must be a Vector3D, got (1.0, 0.0, 0.0)"


@pytest.mark.parametrize("bad", BAD_VECTORS)
def test_plane_origin_must_be_finite(bad):
    with pytest.raises(ValueError, match=r"^InfinitePlane: plane_origin must have finite "):
        InfinitePlane(bad, Vector3D(0.0, 1.0, 0.0))


def test_vectors_and_colours_must_hold_numbers():
    with pytest.raises(TypeError) as error:
        Sphere(Vector3D("x", 0.0, -5.0), 1.0)
    assert str(error.value) == ("Sphere: sphere_origin must hold numbers, got "
                                f"{Vector3D('x', 0.0, -5.0)!r}")
    with pytest.raises(TypeError) as error:
        PointLight(GOOD, RGBColor(None, 1.0, 1.0))
    assert str(error.value) == ("PointLight: intensity_ must hold numbers, got "
                                f"{RGBColor(None, 1.0, 1.0)!r}")


def test_sphere_origin_must_be_a_vector():
    with pytest.raises(TypeError, match=r"^Sphere: sphere_origin must be a Vector3D, got "):
        Sphere((0.0, 0.0, -5.0), 1.0)


@pytest.mark.parametrize("name", ["s1", "s2"])
def test_parallelogram_sides_must_be_non_zero(name):
    sides = {"s1": Vector3D(1.0, 0.0, 0.0), "s2": Vector3D(0.0, 1.0, 0.0)}
    sides[name] = Vector3D(0.0, 0.0, 0.0)
    with pytest.raises(ValueError, match=rf"^Parallelogram: {name} must not be the zero vector"):
        Parallelogram(GOOD, sides["s1"], sides["s2"])


@pytest.mark.parametrize("s2", [
    Vector3D(2.0, 4.0, 6.0),         # 2 * s1
    Vector3D(-1.0, -2.0, -3.0),      # -s1
    Vector3D(1e-9, 2e-9, 3e-9),      # a tiny multiple of s1
])
def test_parallelogram_sides_must_not_be_parallel(s2):
    with pytest.raises(ValueError, match="parallel") as error:
        Parallelogram(GOOD, Vector3D(1.0, 2.0, 3.0), s2)
    assert "s1" in str(error.value) and "s2" in str(error.value)
    assert str(error.value).startswith("Parallelogram: s1 ")
    assert str(error.value).endswith(", so they span no area; give two sides that point in "
                                     "different directions")


@pytest.mark.parametrize("make, message", [
    (lambda: Scene().set_ambient((0.1, 0.2, 0.3)), r"^Scene\.set_ambient: i_a must be a RGBColor"),
    (lambda: Sphere(GOOD, 1.0, emission=(1.0, 1.0, 1.0)), r"^Sphere: emission must be a RGBColor"),
    (lambda: PointLight(GOOD, 80.0), r"^PointLight: intensity_ must be a RGBColor"),
], ids=["ambient", "emission", "intensity"])
def test_colours_that_are_not_rgb_colours_are_refused_naming_the_argument(make, message):
    with pytest.raises(TypeError, match=message):
        make()


def test_set_camera_needs_a_camera():
    with pytest.raises(TypeError, match=r"^Scene\.set_camera: camera must be a Camera, got "):
        Scene().set_camera((500, 500, 60))


def test_add_point_light_sources_needs_a_point_light():
    with pytest.raises(TypeError) as error:
        Scene().add_point_light_sources((0.0, 1.0, 0.0))
    assert str(error.value) == ("Scene.add_point_light_sources: point_light must be a "
                                "PointLight, got (0.0, 1.0, 0.0)")


def test_set_brdf_needs_a_brdf_and_names_the_class():
    with pytest.raises(TypeError, match=r"^Sphere\.set_BRDF: BRDF must be a BRDF such as "
                                        r"Lambertian\(RGBColor\(\.\.\.\)\), got "):
        Sphere(GOOD, 1.0).set_BRDF(RGBColor(0.5, 0.5, 0.5))


@pytest.mark.parametrize("direction", [Vector3D(0.0, 0.0, 0.0), Vector3D(NAN, 0.0, 1.0),
                                       Vector3D(INF, 0.0, 0.0)], ids=["zero", "nan", "infinite"])
def test_a_ray_with_no_direction_is_refused_with_what_to_do(direction):
    with pytest.raises(ValueError, match=r"^the ray direction must be a non-zero finite vector, "
                                         r"got .*; set ray\.d before tracing the ray$"):
        Sphere(GOOD, 1.0).intersect(Ray(Vector3D(0.0, 0.0, 0.0), direction))


def test_plane_normal_must_be_non_zero():
    with pytest.raises(ValueError, match=r"^InfinitePlane: plane_normal must not be the zero "):
        InfinitePlane(GOOD, Vector3D(0.0, 0.0, 0.0))


@pytest.mark.parametrize("zero", [Vector3D(0.0, 0.0, 0.0), Vector3D(-0.0, 0.0, -0.0)])
def test_normalize_zero_vector_raises_value_error(zero):
    with pytest.raises(ValueError, match="zero vector"):
        Normalize(zero)


@pytest.mark.parametrize("components, expected", [
    ((1e-200, 0.0, 0.0), (1.0, 0.0, 0.0)),      # its square underflows to 0
    ((3e-170, 4e-170, 0.0), (0.6, 0.8, 0.0)),   # a 3-4-5 triangle
    ((1e200, 1e200, 0.0), (2 ** -0.5, 2 ** -0.5, 0.0)),  # its square overflows
])
def test_normalize_tiny_and_huge_non_zero_vectors_gives_unit_vectors(components, expected):
    assert as_tuple(Normalize(Vector3D(*components))) == pytest.approx(expected, abs=1e-15)


@pytest.mark.parametrize("max_depth", [0, -1, INF, NAN])
def test_depth_integrator_max_depth_must_be_positive(max_depth):
    with pytest.raises(ValueError, match="max_depth_"):
        DepthIntegrator("unused", max_depth)


@pytest.mark.parametrize("colour", [(0.5, 0.5, 0.5), Vector3D(0.5, 0.5, 0.5), 0.5, None])
def test_lambertian_needs_an_rgb_colour(colour):
    with pytest.raises(TypeError, match=r"^Lambertian: diffuse_colour must be a RGBColor, got "):
        Lambertian(colour)


@pytest.mark.parametrize("obj", [Lambertian(BLACK), Vector3D(0.0, 0.0, 0.0), "sphere", None])
def test_add_object_needs_a_primitive(obj):
    scene = Scene()
    with pytest.raises(TypeError, match=r"^Scene\.add_object: new_object must be a Primitive "
                       r"\(Sphere, InfinitePlane, Parallelogram or your own subclass\), got "):
        scene.add_object(obj)
    assert scene.object_list == []


def small_scene():
    scene = Scene()
    scene.set_camera(Camera(4, 3, 60))
    return scene


@pytest.mark.parametrize("x, y", [(4, 0), (0, 3), (-1, 0), (0, -1), (10, 10)])
def test_set_pixel_out_of_bounds_raises_index_error(x, y):
    scene = small_scene()
    with pytest.raises(IndexError, match=r"\({}, {}\)".format(x, y)):
        scene.set_pixel(RGBColor(1.0, 1.0, 1.0), x, y)
    assert not scene.rendered_image.any()


@pytest.mark.parametrize("value", [(1.0, 0.0, 0.0), 0.5, None, Vector3D(1.0, 0.0, 0.0)])
def test_set_pixel_needs_a_colour(value):
    with pytest.raises(TypeError, match="pixel_val"):
        small_scene().set_pixel(value, 1, 1)
