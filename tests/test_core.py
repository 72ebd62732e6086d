"""Unit tests for PyRT_Core, against values computed by hand."""
import math

import cv2
import numpy as np
import pytest

import pyrt.acceleration.queries
import PyRT_Core
from helpers import as_tuple, rgb, visible_lights
from PyRT_Common import (BLACK, EPSILON, HUGEVALUE, Cross, Dot, HitData, Length, Normalize,
                         RGBColor, Ray, Vector3D)
from PyRT_Core import (Camera, InfinitePlane, Lambertian, Parallelogram, PointLight,
                       Primitive, Scene, Sphere)

TIGHT = 1e-12


def approx3(values, tol=TIGHT):
    return pytest.approx(values, abs=tol)


def ray(origin, direction, **limits):
    r = Ray(Vector3D(*origin), Vector3D(*direction))
    for name, value in limits.items():
        setattr(r, name, value)
    return r


def assert_hit(hit, point, normal, distance, tol=TIGHT):
    assert hit.has_hit is True
    assert as_tuple(hit.hit_point) == approx3(point, tol)
    assert as_tuple(hit.normal) == approx3(normal, tol)
    assert hit.hit_distance == pytest.approx(distance, abs=tol)


# ------------------------------------------------------------------------------------------
# Camera
# ------------------------------------------------------------------------------------------
def test_camera_attributes():
    camera = Camera(4, 3, 90)
    assert (camera.width, camera.height) == (4, 3)
    assert camera.vertical_fov == pytest.approx(math.pi / 2, rel=1e-15)  # 90 degrees
    assert camera.aspect_ratio == pytest.approx(4 / 3, rel=1e-15)


@pytest.mark.parametrize("width, height, x, y", [(5, 3, 2, 1), (1, 1, 0, 0), (7, 9, 3, 4)])
def test_camera_centre_pixel_of_odd_image_looks_straight_ahead(width, height, x, y):
    # x_s = 2(x + 0.5)/width - 1 = 0 and y_s = 1 - 2(y + 0.5)/height = 0
    d = Camera(width, height, 60).get_direction(x, y)
    assert as_tuple(d) == approx3((0.0, 0.0, -1.0))


R15 = 1 / math.sqrt(1.5)
R22 = 1 / math.sqrt(22)


@pytest.mark.parametrize("x, y, expected", [
    # 2 x 2, tan(45) = 1, aspect 1: x_s, y_s = +-0.5, point (+-0.5, +-0.5, -1) / sqrt(1.5)
    (0, 0, (-0.5 * R15, 0.5 * R15, -R15)),
    (1, 0, (0.5 * R15, 0.5 * R15, -R15)),
    (0, 1, (-0.5 * R15, -0.5 * R15, -R15)),
    (1, 1, (0.5 * R15, -0.5 * R15, -R15)),
])
def test_camera_direction_at_corners_of_2x2_image(x, y, expected):
    assert as_tuple(Camera(2, 2, 90).get_direction(x, y)) == approx3(expected)


@pytest.mark.parametrize("x, y, expected", [
    # 4 x 3, tan(45) = 1, aspect 4/3: pixel (0, 0) has x_s = 1/4 - 1 = -3/4, y_s = 1 - 1/3 =
    # 2/3, point (-3/4 * 4/3, 2/3, -1) = (-1, 2/3, -1), length sqrt(22)/3: (-3, 2, -3)/sqrt(22)
    (0, 0, (-3 * R22, 2 * R22, -3 * R22)),
    (3, 0, (3 * R22, 2 * R22, -3 * R22)),
    (0, 2, (-3 * R22, -2 * R22, -3 * R22)),
    (3, 2, (3 * R22, -2 * R22, -3 * R22)),
    # pixel (1, 1): x_s = 3/4 - 1 = -1/4, y_s = 0: point (-1/3, 0, -1) -> (-1, 0, -3)/sqrt(10)
    (1, 1, (-1 / math.sqrt(10), 0.0, -3 / math.sqrt(10))),
])
def test_camera_direction_of_4x3_image(x, y, expected):
    assert as_tuple(Camera(4, 3, 90).get_direction(x, y)) == approx3(expected)


def test_camera_direction_uses_the_vertical_fov():
    # fov 60: tan(30) = 1/sqrt(3); 1 x 2 pixel (0, 0): y_s = 1/2, point (0, 1/(2 sqrt 3), -1)
    y = 0.5 / math.sqrt(3)
    length = math.sqrt(1 + y * y)
    d = Camera(1, 2, 60).get_direction(0, 0)
    assert as_tuple(d) == approx3((0.0, y / length, -1.0 / length))


@pytest.mark.parametrize("x, y, u, v, point", [
    # 4 x 2, tan(45) = 1, aspect 2: the point (u, v) of pixel (x, y) has
    # x_s = 2(x + u)/4 - 1 and y_s = 1 - 2(y + v)/2, and lies at (2 x_s, y_s, -1)
    (0, 0, 0.0, 0.0, (-2.0, 1.0, -1.0)),     # the image's top left corner
    (1, 0, 0.0, 1.0, (-1.0, 0.0, -1.0)),     # x_s = -1/2, y_s = 0
    (1, 0, 1.0, 0.0, (0.0, 1.0, -1.0)),      # x_s = 0, y_s = 1
    (2, 1, 0.25, 0.75, (0.25, -0.75, -1.0)),  # x_s = 1/8, y_s = -3/4
    (3, 1, 0.75, 0.25, (1.75, -0.25, -1.0)),  # x_s = 7/8, y_s = -1/4
])
def test_camera_direction_through_a_point_inside_the_pixel(x, y, u, v, point):
    length = math.sqrt(sum(c * c for c in point))
    d = Camera(4, 2, 90).get_direction(x, y, u, v)
    assert as_tuple(d) == approx3(tuple(c / length for c in point))


def test_camera_direction_through_the_pixel_centre_is_the_default():
    camera = Camera(4, 2, 90)
    assert as_tuple(camera.get_direction(2, 1, 0.5, 0.5)) == as_tuple(camera.get_direction(2, 1))


def test_camera_directions_are_unit_length():
    camera = Camera(7, 5, 75)
    for y in range(5):
        for x in range(7):
            d = camera.get_direction(x, y)
            assert math.sqrt(d.x ** 2 + d.y ** 2 + d.z ** 2) == pytest.approx(1.0, abs=1e-15)


# ------------------------------------------------------------------------------------------
# Sphere
# ------------------------------------------------------------------------------------------
def test_sphere_attributes():
    sphere = Sphere(Vector3D(0.0, 0.0, -5.0), 2.0)
    assert as_tuple(sphere.origin) == (0.0, 0.0, -5.0)
    assert sphere.radius == 2.0
    assert sphere.radius_squared == 4.0
    assert rgb(sphere.emission) == (0.0, 0.0, 0.0)
    assert sphere.BRDF is None


def test_sphere_hit_from_outside_gives_near_point_and_outward_normal():
    # centre (0, 0, -5), radius 2: the ray down -z enters at z = -3, distance 3
    hit = Sphere(Vector3D(0.0, 0.0, -5.0), 2.0).intersect(ray((0, 0, 0), (0, 0, -1)))
    assert_hit(hit, (0.0, 0.0, -3.0), (0.0, 0.0, 1.0), 3.0)


def test_sphere_hit_off_axis():
    # unit sphere at the origin, ray x = 0.6 down -z from z = 5: z = sqrt(1 - 0.36) = 0.8,
    # distance 5 - 0.8 = 4.2, normal = the point itself
    hit = Sphere(Vector3D(0.0, 0.0, 0.0), 1.0).intersect(ray((0.6, 0, 5), (0, 0, -1)))
    assert_hit(hit, (0.6, 0.0, 0.8), (0.6, 0.0, 0.8), 4.2)


def test_sphere_normal_points_outward_when_ray_starts_at_centre():
    # from the centre (0, 0, -5) down -z: far side at z = -7, normal (0, 0, -1)
    hit = Sphere(Vector3D(0.0, 0.0, -5.0), 2.0).intersect(ray((0, 0, -5), (0, 0, -1)))
    assert_hit(hit, (0.0, 0.0, -7.0), (0.0, 0.0, -1.0), 2.0)


def test_sphere_normal_points_outward_when_ray_starts_inside():
    # from (0, 0, -4) towards +z: leaves the sphere at z = -3 after 1, normal (0, 0, 1)
    hit = Sphere(Vector3D(0.0, 0.0, -5.0), 2.0).intersect(ray((0, 0, -4), (0, 0, 1)))
    assert_hit(hit, (0.0, 0.0, -3.0), (0.0, 0.0, 1.0), 1.0)


@pytest.mark.parametrize("origin, direction", [
    ((0, 0, 0), (0, 1, 0)),    # points away sideways
    ((0, 2.5, 0), (0, 0, -1)),  # passes above: closest approach 2.5 > 2
    ((0, 0, 0), (0, 0, 1)),    # the sphere lies behind the origin
])
def test_sphere_miss(origin, direction):
    assert Sphere(Vector3D(0.0, 0.0, -5.0), 2.0).intersect(ray(origin, direction)).has_hit is False


def test_sphere_hit_beyond_t_max_is_a_miss():
    sphere = Sphere(Vector3D(0.0, 0.0, -5.0), 2.0)
    assert sphere.intersect(ray((0, 0, 0), (0, 0, -1), t_max=2.5)).has_hit is False


def test_sphere_hit_at_exactly_t_max_counts():
    # the near hit is at 3 exactly: (25 - 4) / (5 + 2)
    sphere = Sphere(Vector3D(0.0, 0.0, -5.0), 2.0)
    hit = sphere.intersect(ray((0, 0, 0), (0, 0, -1), t_max=3.0))
    assert_hit(hit, (0.0, 0.0, -3.0), (0.0, 0.0, 1.0), 3.0)


def test_sphere_t_min_past_the_near_hit_gives_the_far_hit():
    # near hit at 3 < t_min = 4, far hit at 7: point (0, 0, -7), normal outward (0, 0, -1)
    sphere = Sphere(Vector3D(0.0, 0.0, -5.0), 2.0)
    hit = sphere.intersect(ray((0, 0, 0), (0, 0, -1), t_min=4.0))
    assert_hit(hit, (0.0, 0.0, -7.0), (0.0, 0.0, -1.0), 7.0)


def test_sphere_both_hits_outside_t_range_is_a_miss():
    sphere = Sphere(Vector3D(0.0, 0.0, -5.0), 2.0)
    assert sphere.intersect(ray((0, 0, 0), (0, 0, -1), t_min=3.5, t_max=6.5)).has_hit is False


@pytest.mark.parametrize("origin, t_min, expected", [
    # From the origin down -z the sphere at (0, 0, -5) of radius 2 is entered at 3
    # (z = -3, normal (0, 0, 1)) and left at 7 (z = -7, normal (0, 0, -1)).
    ((0, 0, 0), 3.0, (3.0, -3.0, 1.0)),   # [t_min, t_max] is closed: the near hit counts
    ((0, 0, 0), 7.0, (7.0, -7.0, -1.0)),  # past the near hit, exactly at the far one
    ((0, 0, 0), 7.5, None),               # past both
    ((0, 0, 0), 1e6, None),
    # From the centre the sphere is met 2 behind (never a hit) and 2 ahead, at z = -7.
    ((0, 0, -5), 0.0, (2.0, -7.0, -1.0)),
    ((0, 0, -5), 2.0, (2.0, -7.0, -1.0)),
    ((0, 0, -5), 2.5, None),
])
def test_sphere_hit_is_the_first_one_at_or_beyond_t_min(origin, t_min, expected):
    scene = Scene()
    scene.add_object(Sphere(Vector3D(0.0, 0.0, -5.0), 2.0))
    r = ray(origin, (0, 0, -1), t_min=t_min, t_max=1e7)
    hits = (scene.object_list[0].intersect(r), scene.closest_hit(r))
    if expected is None:
        assert [hit.has_hit for hit in hits] == [False, False]
        assert scene.any_hit(r) is False
        return
    distance, z, normal_z = expected
    for hit in hits:
        assert_hit(hit, (0.0, 0.0, z), (0.0, 0.0, normal_z), distance)
    assert scene.any_hit(r) is True


def test_sphere_hit_exactly_at_t_max_from_inside_counts():
    # from the centre the sphere is left exactly 2 ahead: [t_min, t_max] is closed
    sphere = Sphere(Vector3D(0.0, 0.0, -5.0), 2.0)
    hit = sphere.intersect(ray((0, 0, -5), (0, 0, -1), t_min=0.0, t_max=2.0))
    assert_hit(hit, (0.0, 0.0, -7.0), (0.0, 0.0, -1.0), 2.0)


def test_sphere_with_a_negative_t_min_is_hit_behind_the_origin_at_its_distance():
    # [t_min, t_max] = [-10, inf): the sphere around (0, 0, 5) of radius 2, behind the
    # origin of a ray down -z, is met first at t = -7 (z = 7), then at -3 (z = 3)
    sphere = Sphere(Vector3D(0.0, 0.0, 5.0), 2.0)
    hit = sphere.intersect(ray((0, 0, 0), (0, 0, -1), t_min=-10.0))
    assert_hit(hit, (0.0, 0.0, 7.0), (0.0, 0.0, 1.0), -7.0)


def test_rays_leaving_a_sphere_outwards_never_meet_it_again():
    # From 5000 points of the sphere's surface, each in a direction of its outer side:
    # a sphere is convex, so none of them meets it again (here, as a student's shadow
    # rays do, from t_min = EPSILON on).
    rng = np.random.default_rng(7)
    sphere = Sphere(Vector3D(0.3, -0.2, -5.0), 1.3)
    for v, w in rng.normal(size=(5000, 2, 3)):
        n = Normalize(Vector3D(*v))
        d = Normalize(Vector3D(*w))
        if Dot(d, n) < 0.0:
            d = d * -1.0
        assert not sphere.intersect(Ray(sphere.origin + n * sphere.radius, d)).has_hit


def test_ray_exactly_tangent_to_a_sphere_touches_it():
    # x = 1 is tangent to the unit sphere around (0, 0, -5): the ray touches it at
    # (1, 0, -5), 5 along, where the normal is (1, 0, 0)
    sphere = Sphere(Vector3D(0.0, 0.0, -5.0), 1.0)
    hit = sphere.intersect(ray((1, 0, 0), (0, 0, -1)))
    assert_hit(hit, (1.0, 0.0, -5.0), (1.0, 0.0, 0.0), 5.0)


def test_ray_from_a_sphere_along_its_tangent_touches_it_only_at_its_origin():
    sphere = Sphere(Vector3D(0.0, 0.0, -5.0), 1.0)
    hit = sphere.intersect(ray((1, 0, -5), (0, 0, -1), t_min=0.0))
    assert_hit(hit, (1.0, 0.0, -5.0), (1.0, 0.0, 0.0), 0.0)
    assert not sphere.intersect(ray((1, 0, -5), (0, 0, -1))).has_hit  # t_min = EPSILON


def test_ray_starting_on_sphere_surface_does_not_hit_it_within_epsilon():
    # leaving the surface at z = -3 outwards: the only root is t = 0 < t_min = EPSILON
    sphere = Sphere(Vector3D(0.0, 0.0, -5.0), 2.0)
    assert sphere.intersect(ray((0, 0, -3), (0, 0, 1))).has_hit is False


# ------------------------------------------------------------------------------------------
# InfinitePlane
# ------------------------------------------------------------------------------------------
def floor_plane():
    return InfinitePlane(Vector3D(0.0, -1.0, 0.0), Vector3D(0.0, 2.0, 0.0))


def test_plane_normal_attribute_is_normalised():
    # (0, 3, 4) / 5
    plane = InfinitePlane(Vector3D(0.0, 0.0, 0.0), Vector3D(0.0, 3.0, 4.0))
    assert as_tuple(plane.normal) == approx3((0.0, 0.6, 0.8))


def test_plane_hit_straight_down():
    assert_hit(floor_plane().intersect(ray((0, 0, 0), (0, -1, 0))),
               (0.0, -1.0, 0.0), (0.0, 1.0, 0.0), 1.0)


def test_plane_hit_oblique():
    # direction (1, -1, 0)/sqrt(2) reaches y = -1 at x = 1 after sqrt(2)
    s = 1 / math.sqrt(2)
    assert_hit(floor_plane().intersect(ray((0, 0, 0), (s, -s, 0))),
               (1.0, -1.0, 0.0), (0.0, 1.0, 0.0), math.sqrt(2))


def test_plane_normal_is_returned_as_given_from_behind():
    # from y = -3 upwards: distance 2, the normal stays (0, 1, 0)
    assert_hit(floor_plane().intersect(ray((0, -3, 0), (0, 1, 0))),
               (0.0, -1.0, 0.0), (0.0, 1.0, 0.0), 2.0)


@pytest.mark.parametrize("origin, direction", [
    ((0, 0, 0), (1, 0, 0)),    # parallel above the plane
    ((0, -1, 0), (0, 0, 1)),   # parallel inside the plane
    ((0, 0, 0), (0, 1, 0)),    # the plane lies behind
])
def test_plane_miss(origin, direction):
    assert floor_plane().intersect(ray(origin, direction)).has_hit is False


def test_plane_respects_t_max():
    assert floor_plane().intersect(ray((0, 0, 0), (0, -1, 0), t_max=0.5)).has_hit is False


def test_plane_hit_at_exactly_t_max_counts():
    hit = floor_plane().intersect(ray((0, 0, 0), (0, -1, 0), t_max=1.0))
    assert_hit(hit, (0.0, -1.0, 0.0), (0.0, 1.0, 0.0), 1.0)


def test_plane_hit_from_a_point_off_every_axis():
    # The plane through (0, 0, -4) with normal n = (2, -1, 2)/3, from o = (1, 1, 1) down -z:
    # t = (p - o).n / d.n = ((-1, -1, -5).(2, -1, 2)/3) / (-2/3) = (-11/3) / (-2/3) = 5.5
    plane = InfinitePlane(Vector3D(0.0, 0.0, -4.0), Vector3D(2.0, -1.0, 2.0))
    assert_hit(plane.intersect(ray((1, 1, 1), (0, 0, -1))),
               (1.0, 1.0, -4.5), (2 / 3, -1 / 3, 2 / 3), 5.5)


# Squared lengths at the two ends of the range that is taken as unit length, 1 -+ 1e-12:
# 0.5^2 + 0.8660254037838613^2 and 1.0000000000005^2 round to exactly 1 - 1e-12 and 1 + 1e-12.
EDGES_OF_UNIT_LENGTH = [(0.0, 0.5, -0.8660254037838613), (0.0, 0.0, -1.0000000000005)]


@pytest.mark.parametrize("direction", EDGES_OF_UNIT_LENGTH, ids=["shortest", "longest"])
def test_a_direction_at_either_end_of_the_unit_tolerance_is_taken_as_it_is(direction):
    # The plane z = -1 lies (-1 - 0) / d.z = 1 / |d.z| along d itself; normalising d first
    # would move the hit by about 5e-13.
    assert direction[0] ** 2 + direction[1] ** 2 + direction[2] ** 2 in (1 - 1e-12, 1 + 1e-12)
    plane = InfinitePlane(Vector3D(0.0, 0.0, -1.0), Vector3D(0.0, 0.0, 1.0))
    scene = Scene()
    scene.add_object(plane)
    along_d = 1.0 / -direction[2]
    normalised = along_d * math.hypot(*direction)
    for hit in (plane.intersect(ray((0, 0, 0), direction)),
                scene.closest_hit(ray((0, 0, 0), direction))):
        assert hit.hit_distance == pytest.approx(along_d, rel=1e-15, abs=0.0)
    # any_hit agrees: the hit lies beyond a t_max halfway between the two distances when
    # d is shorter than unit length, before it when d is longer
    halfway = (along_d + normalised) / 2
    assert scene.any_hit(ray((0, 0, 0), direction, t_max=halfway)) is (along_d < halfway)


# ------------------------------------------------------------------------------------------
# Parallelogram
# ------------------------------------------------------------------------------------------
def square():
    """The square x, y in [-1, 1] at z = -3; normal Normalize((2,0,0) x (0,2,0)) = (0,0,1)."""
    return Parallelogram(Vector3D(-1.0, -1.0, -3.0), Vector3D(2.0, 0.0, 0.0),
                         Vector3D(0.0, 2.0, 0.0))


def skewed():
    """Corner (0, 0, -1), sides (1, 0, 0) and (1, 1, 0): the region with vertices (0, 0),
    (1, 0), (2, 1), (1, 1) at z = -1; a point (x, y) has b = y and a = x - y."""
    return Parallelogram(Vector3D(0.0, 0.0, -1.0), Vector3D(1.0, 0.0, 0.0),
                         Vector3D(1.0, 1.0, 0.0))


def down_at(x, y):
    """The ray from (x, y, 0) straight down -z."""
    return ray((x, y, 0), (0, 0, -1))


def test_parallelogram_hit_inside():
    assert_hit(square().intersect(ray((0, 0, 0), (0, 0, -1))),
               (0.0, 0.0, -3.0), (0.0, 0.0, 1.0), 3.0)


def test_parallelogram_hit_oblique():
    # towards (0.5, 0.25, -3): direction (0.5, 0.25, -3)/|.|, distance sqrt(0.25 + 0.0625 + 9)
    target = (0.5, 0.25, -3.0)
    length = math.sqrt(9.3125)
    hit = square().intersect(ray((0, 0, 0), tuple(c / length for c in target)))
    assert_hit(hit, target, (0.0, 0.0, 1.0), length)


def test_parallelogram_normal_faces_the_ray_from_behind():
    # from z = -5 towards +z: the normal is flipped to (0, 0, -1)
    assert_hit(square().intersect(ray((0, 0, -5), (0, 0, 1))),
               (0.0, 0.0, -3.0), (0.0, 0.0, -1.0), 2.0)


def test_parallelogram_normal_follows_the_order_of_the_sides():
    # s1 = (0,2,0), s2 = (2,0,0): Cross = (0,0,-4), which already faces a ray coming from z=0
    flipped = Parallelogram(Vector3D(-1.0, -1.0, -3.0), Vector3D(0.0, 2.0, 0.0),
                            Vector3D(2.0, 0.0, 0.0))
    assert as_tuple(flipped.intersect(ray((0, 0, 0), (0, 0, -1))).normal) == (0.0, 0.0, 1.0)
    assert as_tuple(flipped.intersect(ray((0, 0, -5), (0, 0, 1))).normal) == (0.0, 0.0, -1.0)


@pytest.mark.parametrize("x, y", [(1.5, 0.0), (0.0, 1.01), (-1.2, -1.2), (5.0, 5.0)])
def test_parallelogram_miss_outside(x, y):
    assert square().intersect(ray((x, y, 0), (0, 0, -1))).has_hit is False


def test_parallelogram_parallel_ray_misses():
    assert square().intersect(ray((0, 0, 0), (1, 0, 0))).has_hit is False


def test_parallelogram_behind_the_ray_misses():
    assert square().intersect(ray((0, 0, 0), (0, 0, 1))).has_hit is False


@pytest.mark.parametrize("x, y", [
    (1.5, 0.8),   # b = 0.8, a = 0.7
    (1.0, 0.5),   # b = 0.5, a = 0.5
    (1.9, 0.95),  # b = 0.95, a = 0.95
])
def test_skewed_parallelogram_hits_inside_the_skewed_region(x, y):
    assert_hit(skewed().intersect(down_at(x, y)), (x, y, -1.0), (0.0, 0.0, 1.0), 1.0)


@pytest.mark.parametrize("x, y", [
    (0.2, 0.8),   # inside the bounding box [0, 2] x [0, 1], but a = -0.6
    (1.8, 0.2),   # a = 1.6
    (0.05, 0.5),  # a = -0.45
    (2.5, 1.5),   # a = 1, b = 1.5
])
def test_skewed_parallelogram_misses_in_bounding_box_outside_the_skew(x, y):
    assert skewed().intersect(down_at(x, y)).has_hit is False


def test_parallelogram_hit_at_exactly_t_max_counts():
    assert_hit(square().intersect(ray((0, 0, 0), (0, 0, -1), t_max=3.0)), (0.0, 0.0, -3.0),
               (0.0, 0.0, 1.0), 3.0)
    assert not square().intersect(ray((0, 0, 0), (0, 0, -1), t_max=2.999)).has_hit


@pytest.mark.parametrize("x, y", [
    (0.0, 0.0), (1.0, 0.0), (2.0, 1.0), (1.0, 1.0),  # the corners
    (0.5, 0.0), (1.5, 0.5), (1.5, 1.0), (0.5, 0.5),  # the middle of each edge
])
def test_skewed_parallelogram_edges_and_corners_are_hits(x, y):
    assert_hit(skewed().intersect(down_at(x, y)), (x, y, -1.0), (0.0, 0.0, 1.0), 1.0)


@pytest.mark.parametrize("x, y", [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0),
                                  (0.0, 1.0), (-1.0, 0.3)])
def test_square_edges_and_corners_are_hits(x, y):
    assert_hit(square().intersect(ray((x, y, 0), (0, 0, -1))), (x, y, -3.0), (0.0, 0.0, 1.0), 3.0)


# ------------------------------------------------------------------------------------------
# Materials, lights, primitives
# ------------------------------------------------------------------------------------------
def test_lambertian_kd_is_colour_over_pi():
    kd = Lambertian(RGBColor(0.5, 0.25, 1.0)).kd
    assert rgb(kd) == pytest.approx((0.5 / math.pi, 0.25 / math.pi, 1 / math.pi), rel=1e-15)


@pytest.mark.parametrize("wi, cosine", [
    ((0.0, 0.0, 1.0), 1.0),
    ((1 / math.sqrt(2), 0.0, 1 / math.sqrt(2)), 1 / math.sqrt(2)),
    ((0.6, 0.0, 0.8), 0.8),
])
def test_lambertian_value_is_kd_times_cosine(wi, cosine):
    brdf = Lambertian(RGBColor(0.5, 0.25, 1.0))
    value = brdf.get_value(Vector3D(*wi), Vector3D(0.0, 0.0, 1.0), Vector3D(0.0, 0.0, 1.0))
    assert type(value) == RGBColor
    assert rgb(value) == pytest.approx(
        (0.5 / math.pi * cosine, 0.25 / math.pi * cosine, cosine / math.pi), rel=1e-12)


@pytest.mark.parametrize("wi", [(0.0, 0.0, -1.0), (1.0, 0.0, 0.0), (0.6, 0.0, -0.8)])
def test_lambertian_value_is_black_when_light_is_not_above(wi):
    brdf = Lambertian(RGBColor(0.5, 0.25, 1.0))
    value = brdf.get_value(Vector3D(*wi), Vector3D(0.0, 0.0, 1.0), Vector3D(0.0, 0.0, 1.0))
    assert type(value) == RGBColor
    assert value == BLACK and rgb(value) == (0.0, 0.0, 0.0)
    assert value is BLACK  # "else BLACK", as the docstring says, grazing light (n.wi = 0) too


def test_point_light_attributes():
    light = PointLight(Vector3D(1.0, 2.0, 3.0), RGBColor(4.0, 5.0, 6.0))
    assert as_tuple(light.pos) == (1.0, 2.0, 3.0)
    assert rgb(light.intensity) == (4.0, 5.0, 6.0)


def test_primitive_brdf_and_emission():
    brdf = Lambertian(RGBColor(0.8, 0.8, 0.8))
    sphere = Sphere(Vector3D(0.0, 0.0, 0.0), 1.0, emission=RGBColor(1.0, 2.0, 3.0))
    sphere.set_BRDF(brdf)
    assert sphere.get_BRDF() is brdf and sphere.BRDF is brdf
    assert rgb(sphere.emission) == (1.0, 2.0, 3.0)


def test_primitive_is_abstract():
    with pytest.raises(TypeError):
        Primitive()


# ------------------------------------------------------------------------------------------
# Scene
# ------------------------------------------------------------------------------------------
def test_new_scene_is_empty():
    scene = Scene()
    assert (scene.camera, scene.env_map, scene.rendered_image) == (None, None, None)
    assert scene.object_list == [] and scene.pointLights == []
    # no ambient light until set_ambient: black
    assert (scene.i_a.r, scene.i_a.g, scene.i_a.b) == (0.0, 0.0, 0.0)


def test_set_camera_allocates_image_of_height_width_3():
    scene = Scene()
    camera = Camera(4, 3, 60)
    scene.set_camera(camera)
    assert scene.camera is camera
    assert scene.rendered_image.shape == (3, 4, 3)
    assert scene.rendered_image.dtype.kind == "f"
    assert not scene.rendered_image.any()


def test_scene_collects_objects_lights_and_ambient():
    scene = Scene()
    sphere = Sphere(Vector3D(0.0, 0.0, -5.0), 1.0)
    light = PointLight(Vector3D(0.0, 5.0, 0.0), RGBColor(1.0, 1.0, 1.0))
    scene.add_object(sphere)
    scene.add_point_light_sources(light)
    scene.set_ambient(RGBColor(0.1, 0.2, 0.3))
    assert scene.object_list == [sphere]
    assert scene.pointLights == [light]
    assert rgb(scene.i_a) == (0.1, 0.2, 0.3)


def overlapping(order):
    """Objects on the -z axis: sphere hit at 9 (far), sphere hit at 4, square hit at 3 but
    placed at x = 10 (off the axis), plane hit at 20."""
    objects = {
        "far": Sphere(Vector3D(0.0, 0.0, -10.0), 1.0),
        "near": Sphere(Vector3D(0.0, 0.0, -5.0), 1.0),
        "aside": Parallelogram(Vector3D(9.0, -1.0, -3.0), Vector3D(2.0, 0.0, 0.0),
                               Vector3D(0.0, 2.0, 0.0)),
        "wall": InfinitePlane(Vector3D(0.0, 0.0, -20.0), Vector3D(0.0, 0.0, 1.0)),
    }
    scene = Scene()
    for name in order:
        scene.add_object(objects[name])
    return scene


@pytest.mark.parametrize("order", [
    ("far", "near", "aside", "wall"), ("wall", "aside", "near", "far"),
    ("near", "wall", "far", "aside"), ("aside", "far", "wall", "near"),
])
def test_closest_hit_picks_the_nearest_and_reports_its_index(order):
    scene = overlapping(order)
    hit = scene.closest_hit(ray((0, 0, 0), (0, 0, -1)))
    assert_hit(hit, (0.0, 0.0, -4.0), (0.0, 0.0, 1.0), 4.0)
    assert hit.primitive_index == order.index("near")


def test_closest_hit_beyond_t_max_of_nearer_objects():
    # t_min = 5 skips the near sphere's front (4), takes its back at 6
    scene = overlapping(("far", "near", "wall"))
    hit = scene.closest_hit(ray((0, 0, 0), (0, 0, -1), t_min=5.0))
    assert_hit(hit, (0.0, 0.0, -6.0), (0.0, 0.0, -1.0), 6.0)
    assert hit.primitive_index == 1


@pytest.mark.parametrize("axis", range(3), ids=["x", "y", "z"])
def test_rays_from_points_on_an_axis_hit_what_the_camera_cannot_see_there(axis):
    # From 5 along an axis, down the next axis, to the ball of radius 1 at 5 along the first
    # and -5 along the next: 4 away. From the camera, at the origin, that direction misses
    # the ball; from a point on an axis it does not.
    nxt = (axis + 1) % 3
    scene = Scene()
    scene.add_object(Sphere(Vector3D(0.0, 0.0, 50.0), 1.0))  # out of the way
    centre = [0.0] * 3
    centre[axis], centre[nxt] = 5.0, -5.0
    scene.add_object(Sphere(Vector3D(*centre), 1.0))
    origin, direction = [0.0] * 3, [0.0] * 3
    origin[axis], direction[nxt] = 5.0, -1.0
    hit = scene.closest_hit(ray(origin, direction))
    assert (hit.primitive_index, hit.hit_distance) == (1, pytest.approx(4.0))
    assert scene.any_hit(ray(origin, direction)) is True
    assert scene.closest_hit(ray((0, 0, 0), direction)).has_hit is False


@pytest.mark.parametrize("second, winner", [(-4.0, 0), (math.nextafter(-4.0, 0.0), 1),
                                            (math.nextafter(-4.0, -8.0), 0)],
                         ids=["tie", "nearer-by-one-ulp", "farther-by-one-ulp"])
def test_closest_hit_keeps_the_first_of_two_surfaces_at_the_same_distance(second, winner):
    # Two planes 4 away, the second at z = second: as in the course, a later object must be
    # strictly nearer, so of two at the same distance the first one added stays, and one
    # nearer by the least amount a double can hold replaces it.
    scene = Scene()
    for z in (-4.0, second):
        scene.add_object(InfinitePlane(Vector3D(0.0, 0.0, z), Vector3D(0.0, 0.0, 1.0)))
    assert scene.closest_hit(ray((0, 0, 0), (0, 0, -1))).primitive_index == winner


def test_closest_hit_miss_has_no_hit():
    scene = overlapping(("far", "near", "aside"))
    assert scene.closest_hit(ray((0, 0, 0), (0, 1, 0))).has_hit is False


def test_a_miss_is_a_new_hitdata_whose_fields_students_may_assign():
    # The course's own closest_hit sets primitive_index on every result of intersect().
    scene = overlapping(("far", "near", "aside"))
    first = scene.closest_hit(ray((0, 0, 0), (0, 1, 0)))
    second = scene.object_list[0].intersect(ray((0, 0, 0), (0, 1, 0)))
    first.primitive_index = 3
    second.hit_distance = 1.0
    assert first is not second
    assert scene.closest_hit(ray((0, 0, 0), (0, 1, 0))).primitive_index == -1


# Each primitive seen by the ray (0, 0, 0) -> (0, 0, -1) at (0, 0, -4) with normal (0, 0, 1).
FACING_THE_CAMERA = {
    "sphere": lambda: Sphere(Vector3D(0.0, 0.0, -5.0), 1.0),
    "plane": lambda: InfinitePlane(Vector3D(0.0, 0.0, -4.0), Vector3D(0.0, 0.0, 1.0)),
    "parallelogram": lambda: Parallelogram(Vector3D(-1.0, -1.0, -4.0), Vector3D(2.0, 0.0, 0.0),
                                           Vector3D(0.0, 2.0, 0.0)),
}


def hits_of(obj):
    """The hit of the ray down -z as intersect() and as closest_hit() return it."""
    scene = Scene()
    scene.add_object(obj)
    return [obj.intersect(ray((0, 0, 0), (0, 0, -1))),
            scene.closest_hit(ray((0, 0, 0), (0, 0, -1)))]


@pytest.mark.parametrize("kind", FACING_THE_CAMERA)
def test_hits_hold_plain_course_vectors(kind):
    # Real student code branches on `type(hit.normal) == Vector3D`.
    for hit in hits_of(FACING_THE_CAMERA[kind]()):
        assert type(hit.normal) == Vector3D and type(hit.hit_point) == Vector3D
        assert isinstance(hit.normal, Vector3D)
        assert_hit(hit, (0.0, 0.0, -4.0), (0.0, 0.0, 1.0), 4.0)


@pytest.mark.parametrize("kind", FACING_THE_CAMERA)
def test_a_hit_from_intersect_has_no_index_until_closest_hit_gives_it_one(kind):
    # -1, as in HitData(): only the scene knows where the object is in object_list
    from_intersect, from_scene = hits_of(FACING_THE_CAMERA[kind]())
    assert (from_intersect.primitive_index, from_scene.primitive_index) == (-1, 0)


@pytest.mark.parametrize("kind", FACING_THE_CAMERA)
def test_changing_a_returned_hit_changes_neither_the_scene_nor_another_hit(kind):
    obj = FACING_THE_CAMERA[kind]()
    first, second = hits_of(obj)
    assert first.normal is not second.normal and first.hit_point is not second.hit_point
    for hit in (first, second):
        hit.normal.x, hit.normal.z = 5.0, -1.0  # mutated, as students do
        hit.hit_point.y = 7.0
    assert as_tuple(second.normal) == (5.0, 0.0, -1.0)
    for later in hits_of(obj):
        assert_hit(later, (0.0, 0.0, -4.0), (0.0, 0.0, 1.0), 4.0)
    if kind != "sphere":
        assert as_tuple(obj.normal) == (0.0, 0.0, 1.0)


@pytest.mark.parametrize("origin", [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)])
def test_closest_hit_from_a_point_that_is_not_the_camera_sees_what_lies_ahead(origin):
    # A ray along d = (0.6, 0, -0.8) from a point 1 away from the camera meets the sphere
    # of radius 0.5 centred 5 along it, which the camera sees in a direction some 8 degrees
    # off d, beyond the 7 degrees the sphere fills.
    scene = Scene()
    d = Vector3D(0.6, 0.0, -0.8)
    scene.add_object(Sphere(Vector3D(*origin) + d * 5.0, 0.5))
    hit = scene.closest_hit(Ray(Vector3D(*origin), d))
    assert hit.has_hit and hit.hit_distance == pytest.approx(4.5, rel=1e-15)


@pytest.mark.parametrize("s2", [(3.6, 0.2, 0.0), (-3.6, 0.2, 0.0)], ids=["acute", "obtuse"])
def test_camera_rays_near_every_corner_of_a_thin_skewed_parallelogram_hit_it(s2):
    # The parallelogram at z = -5 with sides (4, 0, 0) and s2 is long and thin: its corners
    # lie far from its centre along its long diagonal, s1 + s2 or s1 - s2.
    scene = Scene()
    point, s1, s2 = Vector3D(-2.0, -0.1, -5.0), Vector3D(4.0, 0.0, 0.0), Vector3D(*s2)
    scene.add_object(Parallelogram(point, s1, s2))
    for a, b in ((0.01, 0.5), (0.99, 0.5), (0.5, 0.01), (0.5, 0.99), (0.02, 0.98),
                 (0.98, 0.02), (0.02, 0.02), (0.98, 0.98)):
        target = point + s1 * a + s2 * b
        hit = scene.closest_hit(Ray(Vector3D(0.0, 0.0, 0.0), Normalize(target)))
        assert hit.has_hit, (a, b)
        assert as_tuple(hit.hit_point) == pytest.approx(as_tuple(target), abs=1e-12)


def test_camera_ray_grazing_an_infinite_floor_meets_it_far_away():
    # 1e-10 below the horizon, the ray from the camera (t_max infinite, as render() makes
    # camera rays) meets the floor 1 below at 1e10
    scene = Scene()
    scene.add_object(InfinitePlane(Vector3D(0.0, -1.0, 0.0), Vector3D(0.0, 1.0, 0.0)))
    d = Normalize(Vector3D(0.0, -1e-10, -1.0))
    hit = scene.closest_hit(Ray(Vector3D(0.0, 0.0, 0.0), d, float("inf"), 0.0))
    assert hit.has_hit and hit.hit_distance == pytest.approx(1e10, rel=1e-12)


def test_closest_hit_on_empty_scene_is_a_miss():
    assert Scene().closest_hit(ray((0, 0, 0), (0, 0, -1))).has_hit is False


def test_any_hit_true_when_something_is_hit():
    assert overlapping(("far", "near")).any_hit(ray((0, 0, 0), (0, 0, -1))) is True


@pytest.mark.parametrize("direction, t_max", [((0, 1, 0), 1e6), ((0, 0, -1), 3.5)])
def test_any_hit_false_on_a_miss_or_beyond_t_max(direction, t_max):
    assert overlapping(("far", "near")).any_hit(ray((0, 0, 0), direction, t_max=t_max)) is False


def test_any_hit_measures_t_max_as_a_distance_along_a_direction_not_of_unit_length():
    # (1, 1, -1) reaches the plane z = -2 after a distance of 2 sqrt(3) = 3.46
    scene = Scene()
    scene.add_object(InfinitePlane(Vector3D(0.0, 0.0, -2.0), Vector3D(0.0, 0.0, 1.0)))
    assert scene.closest_hit(ray((0, 0, 0), (1, 1, -1))).hit_distance == pytest.approx(
        2 * math.sqrt(3), rel=1e-15)
    assert scene.any_hit(ray((0, 0, 0), (1, 1, -1), t_max=3.4)) is False
    assert scene.any_hit(ray((0, 0, 0), (1, 1, -1), t_max=3.5)) is True


def test_an_object_added_after_a_query_is_seen_by_the_next_one():
    scene = overlapping(("far",))
    assert scene.closest_hit(ray((0, 0, 0), (0, 0, -1))).hit_distance == pytest.approx(9.0)
    scene.add_object(Sphere(Vector3D(0.0, 0.0, -5.0), 1.0))
    hit = scene.closest_hit(ray((0, 0, 0), (0, 0, -1)))
    assert (hit.primitive_index, hit.hit_distance) == (1, pytest.approx(4.0))
    assert scene.any_hit(ray((0, 0, 0), (0, 0, -1), t_max=5.0)) is True


def test_a_sphere_moved_again_and_again_is_hit_where_it_is_now():
    sphere = Sphere(Vector3D(0.0, 0.0, -5.0), 1.0)
    scene = Scene()
    scene.add_object(sphere)
    for x in (5.0, -5.0, 5.0):
        sphere.origin = Vector3D(x, 0.0, -5.0)
        # straight at the centre, sqrt(50) away: the surface is one radius nearer
        towards = ray((0, 0, 0), (x, 0.0, -5.0))
        assert scene.closest_hit(towards).hit_distance == pytest.approx(math.sqrt(50) - 1)
        assert scene.any_hit(towards) is True


def test_a_geometric_attribute_lives_in_the_underscore_slot_and_rederives_its_owner():
    # What Sphere.radius, Camera.width and the like are made of: the constructor fills
    # _radius, reading radius gives it back, assigning it works the constants out again.
    class Disc:
        radius = PyRT_Core._GeometricAttribute()

        def __init__(self, radius):
            self._radius = radius
            self._derive()

        def _derive(self):
            self.area = math.pi * self._radius ** 2

    disc = Disc(1.0)
    assert (disc.radius, disc.area) == (1.0, math.pi)
    disc.radius = 2.0
    assert (disc.radius, disc._radius, disc.area) == (2.0, 2.0, 4 * math.pi)
    assert isinstance(Disc.radius, PyRT_Core._GeometricAttribute)


def test_set_environment_map_loads_the_map_of_the_scene(tmp_path):
    # a 2 x 1 map: left half RGB (1, 2, 4), right half (8, 16, 0.5); straight ahead (u = 0.5)
    # reads the texel under floor(0.5 * (2 - 1)) = 0, the left one
    path = tmp_path / "sky.hdr"
    image_rgb = np.array([[[1.0, 2.0, 4.0], [8.0, 16.0, 0.5]]], np.float32)
    assert cv2.imwrite(str(path), image_rgb[:, :, ::-1])
    scene = Scene()
    scene.set_environment_map(str(path))
    assert isinstance(scene.env_map, PyRT_Core.EnvironmentMap)
    assert scene.env_map.image.shape == (1, 2, 3)
    assert rgb(scene.env_map.getValue(Vector3D(0.0, 0.0, -1.0))) == (1.0, 2.0, 4.0)
    assert rgb(scene.env_map.getValue(Vector3D(0.0, 0.0, 1.0))) == (8.0, 16.0, 0.5)


def test_set_pixel_before_set_camera_says_to_set_the_camera_first():
    with pytest.raises(RuntimeError, match=r"^Scene\.set_pixel: the scene has no image yet; "
                                           r"call scene\.set_camera\(camera\) first$"):
        Scene().set_pixel(RGBColor(1.0, 1.0, 1.0), 0, 0)


def test_set_pixel_writes_row_y_column_x():
    scene = Scene()
    scene.set_camera(Camera(3, 2, 60))
    scene.set_pixel(RGBColor(0.25, 0.5, 0.75), 2, 1)
    expected = np.zeros((2, 3, 3))
    expected[1, 2] = (0.25, 0.5, 0.75)
    np.testing.assert_array_equal(scene.rendered_image, expected)


# ------------------------------------------------------------------------------------------
# Shadow rays: visible_lights, and any_hit from a hit point to a light
# ------------------------------------------------------------------------------------------
RIGHT, LEFT = Vector3D(1.0, 1.0, 0.0), Vector3D(-1.0, 1.0, 0.0)
WHITE_LIGHT = RGBColor(1.0, 1.0, 1.0)


def floor_and_wall():
    """A floor y = 0 (x, z in [-2, 2]) with a wall x = 0 standing on it (y in [0, 2]), a
    light on either side of the wall, 1 above the floor."""
    scene = Scene()
    scene.add_object(Parallelogram(Vector3D(-2.0, 0.0, 2.0), Vector3D(4.0, 0.0, 0.0),
                                   Vector3D(0.0, 0.0, -4.0)))
    scene.add_object(Parallelogram(Vector3D(0.0, 0.0, -2.0), Vector3D(0.0, 2.0, 0.0),
                                   Vector3D(0.0, 0.0, 4.0)))
    for position in (RIGHT, LEFT):
        scene.add_point_light_sources(PointLight(position, RGBColor(1.0, 1.0, 1.0)))
    return scene


def floor_hit(scene):
    """The floor seen at (0.5, 0, 0), right of the wall, from (0.5, 3, 0) above it."""
    hit = scene.closest_hit(ray((0.5, 3.0, 0.0), (0.0, -1.0, 0.0)))
    assert (hit.primitive_index, as_tuple(hit.hit_point)) == (0, (0.5, 0.0, 0.0))
    return hit


def student_shadow_ray(hit, light):
    """A shadow ray as the course's students write it: from the hit point to the light."""
    to_light = light.pos - hit.hit_point
    return Ray(hit.hit_point, Normalize(to_light), Length(to_light))


def test_visible_lights_are_those_in_front_with_nothing_in_between():
    # From (0.5, 0, 0) the right light is (0.5, 1, 0) away: r2 = 1.25, wi = (0.5, 1, 0)/r.
    # The segment to the left light, (0.5, 0, 0) + s (-1.5, 1, 0), crosses the wall x = 0 at
    # s = 1/3, at height 1/3: the wall hides it.
    scene = floor_and_wall()
    [(light, wi, r2)] = visible_lights(scene, floor_hit(scene))
    assert light is scene.pointLights[0]
    assert type(wi) == Vector3D
    assert as_tuple(wi) == approx3((0.5 / math.sqrt(1.25), 1.0 / math.sqrt(1.25), 0.0))
    assert r2 == pytest.approx(1.25, rel=1e-15)


def assert_the_light_is_hidden(scene, hit):
    """The scene's only light lights nothing at the hit's point: visible_lights finds no
    light, and a student's shadow ray meets something, as testing every object finds."""
    assert visible_lights(scene, hit) == []
    r = student_shadow_ray(hit, scene.pointLights[0])
    assert scene.any_hit(r) is hits_anything(scene, r) is True


@pytest.mark.parametrize("axis", [0, 1, 2])
@pytest.mark.parametrize("flat", ["plane", "parallelogram"])
def test_a_wall_between_a_sphere_and_the_light_shadows_it_along_every_axis(axis, flat):
    # The wall is the plane u = -2 of axis u (a 20 x 20 parallelogram, or infinite), the
    # light at u = 1 on one side of it, a sphere of radius 1 around u = -5 on the other.
    # The sphere's point u = -4 faces the light, and the wall hides it.
    def along(u, rest=0.0):
        xyz = [rest] * 3
        xyz[axis] = u
        return Vector3D(*xyz)

    scene = Scene()
    if flat == "plane":
        scene.add_object(InfinitePlane(along(-2.0), along(1.0)))
    else:
        s1, s2 = [0.0] * 3, [0.0] * 3
        s1[(axis + 1) % 3] = s2[(axis + 2) % 3] = 20.0
        scene.add_object(Parallelogram(along(-2.0, -10.0), Vector3D(*s1), Vector3D(*s2)))
    scene.add_object(Sphere(along(-5.0), 1.0))
    scene.add_point_light_sources(PointLight(along(1.0), WHITE_LIGHT))
    hit = scene.closest_hit(Ray(along(-3.0), along(-1.0)))
    assert (hit.primitive_index, as_tuple(hit.hit_point)) == (1, as_tuple(along(-4.0)))
    assert_the_light_is_hidden(scene, hit)


def test_a_sphere_cut_by_a_wall_is_shadowed_behind_it():
    # The wall x = -2 (y, z in [-10, 10]) cuts the sphere of radius 1 around (-1.5, 0, 0);
    # the light is at (1, 5, 0). The sphere's point p = (-2.2, sqrt(0.51), 0), behind the
    # wall, faces the light (n.(light - p) = 0.82 > 0), and its way there crosses the wall
    # at y = 0.98.
    scene = Scene()
    scene.add_object(Parallelogram(Vector3D(-2.0, -10.0, -10.0), Vector3D(0.0, 20.0, 0.0),
                                   Vector3D(0.0, 0.0, 20.0)))
    scene.add_object(Sphere(Vector3D(-1.5, 0.0, 0.0), 1.0))
    scene.add_point_light_sources(PointLight(Vector3D(1.0, 5.0, 0.0), WHITE_LIGHT))
    n = Vector3D(-0.7, math.sqrt(0.51), 0.0)
    hit = scene.closest_hit(Ray(Vector3D(-1.5, 0.0, 0.0) + n * 1.5, n * -1.0))
    assert hit.primitive_index == 1
    assert as_tuple(hit.hit_point) == pytest.approx((-2.2, math.sqrt(0.51), 0.0), abs=1e-12)
    assert_the_light_is_hidden(scene, hit)


# A tile with one corner across the wall x = 1, from the near side (x < 1): its point p
# and its sides s1, s2, and (a, b), where p + a s1 + b s2 is that corner.
CORNER_ACROSS = [
    ((0.0, 0.0, 0.0), (0.8, 1.0, 0.0), (0.8, 0.0, 1.0), (1, 1)),
    ((1.6, 0.0, 0.0), (-0.8, 1.0, 0.0), (-0.8, 0.0, 1.0), (0, 0)),
    ((0.8, 0.0, 0.0), (0.8, 1.0, 0.0), (-0.8, 0.0, 1.0), (1, 0)),
    ((0.8, 0.0, 0.0), (-0.8, 1.0, 0.0), (0.8, 0.0, 1.0), (0, 1)),
]


@pytest.mark.parametrize("axis", [0, 1, 2], ids=["x", "y", "z"])
@pytest.mark.parametrize("p, s1, s2, corner", CORNER_ACROSS,
                         ids=["far corner", "point", "point + s1", "point + s2"])
def test_a_tile_with_a_corner_across_a_wall_is_shadowed_beyond_it(axis, p, s1, s2, corner):
    # The scene with x turned into the axis given: the wall u = 1 (10 x 10, centred on the
    # axis), the light at u = -3, the tile reaching across the wall with one corner only.
    # The tile's point near that corner, at u = 1.44, faces the light, which the wall hides.
    def turned(v):
        w = [0.0] * 3
        for i, c in enumerate(v):
            w[(axis + i) % 3] = c
        return Vector3D(*w)

    p, s1, s2 = turned(p), turned(s1), turned(s2)
    scene = Scene()
    scene.add_object(Parallelogram(p, s1, s2))
    scene.add_object(Parallelogram(turned((1.0, -5.0, -5.0)), turned((0.0, 10.0, 0.0)),
                                   turned((0.0, 0.0, 10.0))))
    light = turned((-3.0, 0.5, 0.5))
    scene.add_point_light_sources(PointLight(light, WHITE_LIGHT))
    a, b = (0.9 if k else 0.1 for k in corner)
    point = p + s1 * a + s2 * b
    assert Dot(point, turned((1.0, 0.0, 0.0))) == pytest.approx(1.44, abs=1e-12)
    n = Normalize(Cross(s1, s2))
    if Dot(n, light - point) < 0.0:
        n = n * -1.0  # the tile's side that faces the light
    hit = scene.closest_hit(Ray(point + n * 0.1, n * -1.0))
    assert hit.primitive_index == 0
    assert as_tuple(hit.hit_point) == pytest.approx(as_tuple(point), abs=1e-12)
    assert_the_light_is_hidden(scene, hit)


def test_a_wall_on_an_infinite_floor_shadows_the_floor_behind_it():
    # floor_and_wall with an infinite floor: its point (-0.5, 0, 0), left of the wall x = 0,
    # does not see the light at (1, 1, 0), its way crossing the wall at height 1/3.
    scene = floor_and_wall()
    scene.object_list[0] = InfinitePlane(Vector3D(0.0, 0.0, 0.0), Vector3D(0.0, 1.0, 0.0))
    hit = scene.closest_hit(ray((-0.5, 3.0, 0.0), (0.0, -1.0, 0.0)))
    assert (hit.primitive_index, as_tuple(hit.hit_point)) == (0, (-0.5, 0.0, 0.0))
    assert [light.pos for light, _, _ in visible_lights(scene, hit)] == [LEFT]
    r = student_shadow_ray(hit, scene.pointLights[0])
    assert scene.any_hit(r) is hits_anything(scene, r) is True


def test_student_shadow_rays_from_a_hit_point_see_the_same_lights():
    scene = floor_and_wall()
    hit = floor_hit(scene)
    assert [scene.any_hit(student_shadow_ray(hit, light)) for light in scene.pointLights] == [
        False, True]


def test_visible_lights_of_a_hit_made_by_intersect_tests_every_object():
    # A hit of the floor's own intersect() has no index in object_list (-1): the wall,
    # which closest_hit's hits know to test, still hides the left light.
    scene = floor_and_wall()
    hit = scene.object_list[0].intersect(ray((0.5, 3.0, 0.0), (0.0, -1.0, 0.0)))
    assert (hit.primitive_index, as_tuple(hit.hit_point)) == (-1, (0.5, 0.0, 0.0))
    assert [light for light, _, _ in visible_lights(scene, hit)] == scene.pointLights[:1]


def test_visible_lights_sees_an_object_added_after_the_hit():
    # A ball added on the way from (0.5, 0, 0) to the right light (0.5 + 0.5 s, s, 0)
    scene = floor_and_wall()
    hit = floor_hit(scene)
    scene.add_object(Sphere(Vector3D(0.75, 0.5, 0.0), 0.2))
    assert visible_lights(scene, hit) == []


def test_a_light_moved_in_place_is_seen_from_its_new_position():
    scene = floor_and_wall()
    assert len(visible_lights(scene, floor_hit(scene))) == 1
    scene.pointLights[1].pos.x = 0.75  # the left light moves right of the wall
    hit = floor_hit(scene)
    assert [light for light, _, _ in visible_lights(scene, hit)] == scene.pointLights
    assert not scene.any_hit(student_shadow_ray(hit, scene.pointLights[1]))


def test_objects_added_or_reshaped_after_a_query_cast_their_shadows():
    # A ball at c = (1.05, 0.5, 0) passes the segment from (0.5, 0, 0) to the right light,
    # direction (0.5, 1, 0)/sqrt(1.25), at sqrt(|c - p|^2 - ((c - p).u)^2) = sqrt(0.5525 -
    # 0.775^2/1.25) = 0.268: a radius of 0.1 leaves the light in view, one of 0.3 hides it.
    scene = floor_and_wall()
    assert len(visible_lights(scene, floor_hit(scene))) == 1
    ball = Sphere(Vector3D(1.05, 0.5, 0.0), 0.1)
    scene.object_list.append(ball)
    hit = floor_hit(scene)
    assert len(visible_lights(scene, hit)) == 1
    assert not scene.any_hit(student_shadow_ray(hit, scene.pointLights[0]))
    ball.radius = 0.3
    hit = floor_hit(scene)
    assert visible_lights(scene, hit) == []
    assert scene.any_hit(student_shadow_ray(hit, scene.pointLights[0]))


def cube_around_a_tile():
    """A floor tile y = 0 (x, z in [-0.25, 0.25]) in a closed cube of six 2 x 2 walls at
    x, y, z = -1 and 1, with lights on each axis: at +-2, outside the cube, and at +-0.5,
    inside it. The hit returned is the tile's at the origin, seen from above."""
    scene = Scene()
    scene.add_object(Parallelogram(Vector3D(-0.25, 0.0, 0.25), Vector3D(0.5, 0.0, 0.0),
                                   Vector3D(0.0, 0.0, -0.5)))
    for axis in range(3):
        for side in (-1.0, 1.0):
            corner, s1, s2 = [-1.0] * 3, [0.0] * 3, [0.0] * 3
            corner[axis] = side
            s1[(axis + 1) % 3] = s2[(axis + 2) % 3] = 2.0
            scene.add_object(Parallelogram(Vector3D(*corner), Vector3D(*s1), Vector3D(*s2)))
    for axis in range(3):
        for position in (2.0, -2.0, 0.5, -0.5):
            xyz = [0.0] * 3
            xyz[axis] = position
            scene.add_point_light_sources(PointLight(Vector3D(*xyz), WHITE_LIGHT))
    return scene


def tile_hit(scene):
    hit = scene.closest_hit(ray((0.0, 0.5, 0.0), (0.0, -1.0, 0.0)))
    assert (hit.primitive_index, as_tuple(hit.hit_point)) == (0, (0.0, 0.0, 0.0))
    return hit


def hits_anything(scene, r):
    """any_hit as testing every object gives it, which pyrt.acceleration's any_hit must
    give too."""
    expected = any(obj.intersect(r).has_hit for obj in scene.object_list)
    assert pyrt.acceleration.queries.AcceleratedQueries(scene).any_hit(r) is expected
    return expected


def to_point(hit, target, **limits):
    """The ray from the hit point to target, stopping there, as students write them."""
    r = student_shadow_ray(hit, PointLight(Vector3D(*target), WHITE_LIGHT))
    for name, value in limits.items():
        setattr(r, name, value)
    return r


def test_shadow_rays_from_a_hit_point_to_every_light_find_the_walls_in_between():
    # The lights outside the cube are hidden by a wall, those inside it are not (the one
    # below the tile is not hidden by the tile: the ray leaves it).
    scene = cube_around_a_tile()
    hit = tile_hit(scene)
    expected = [True, True, False, False] * 3
    for _ in range(2):  # twice, the second time with the lights in reverse order
        rays = [student_shadow_ray(hit, light) for light in scene.pointLights]
        assert [scene.any_hit(r) for r in rays] == [hits_anything(scene, r) for r in rays]
        assert [scene.any_hit(r) for r in rays] == expected
        scene.pointLights.reverse()
        expected.reverse()
        hit = tile_hit(scene)


@pytest.mark.parametrize("target, expected", [
    ((0.0, 3.0, 0.0), True), ((0.0, -3.0, 0.0), True), ((0.3, 0.3, 0.3), False),
    ((0.0, 1.0 - 1e-6, 0.0), False), ((2.5, 0.0, 0.0), True),
])
def test_rays_from_a_hit_point_to_points_that_are_no_lights_see_what_is_there(target, expected):
    scene = cube_around_a_tile()
    r = to_point(tile_hit(scene), target)
    assert scene.any_hit(r) is hits_anything(scene, r) is expected


@pytest.mark.parametrize("axis", range(3))
def test_rays_from_a_hit_point_moved_in_place_see_what_is_there_now(axis):
    # Moved out of the cube, 3 along an axis, the point sees the light inside the cube on
    # that axis through the wall.
    scene = cube_around_a_tile()
    hit = tile_hit(scene)
    light = [0.0] * 3
    light[axis] = 0.5
    setattr(hit.hit_point, "xyz"[axis], 3.0)
    r = to_point(hit, light)
    assert scene.any_hit(r) is hits_anything(scene, r) is True


def tile_under_a_light_beside_a_wall():
    """A tile y = 3 (x, z in [-0.5, 0.5]) under a light at (0, 5, 0), a wall x = 1.5 (y in
    [0, 6], z in [-2, 2]) beside them, and the tile's hit at (0.2, 3, -0.1), seen from
    above: neither the tile nor the wall can hide the light from a point of the tile."""
    scene = Scene()
    scene.add_object(Parallelogram(Vector3D(-0.5, 3.0, 0.5), Vector3D(1.0, 0.0, 0.0),
                                   Vector3D(0.0, 0.0, -1.0)))
    scene.add_object(Parallelogram(Vector3D(1.5, 0.0, -2.0), Vector3D(0.0, 6.0, 0.0),
                                   Vector3D(0.0, 0.0, 4.0)))
    scene.add_point_light_sources(PointLight(Vector3D(0.0, 5.0, 0.0), WHITE_LIGHT))
    hit = scene.closest_hit(ray((0.2, 4.0, -0.1), (0.0, -1.0, 0.0)))
    assert (hit.primitive_index, as_tuple(hit.hit_point)) == (0, (0.2, 3.0, -0.1))
    return scene, hit


@pytest.mark.parametrize("axis, value", [
    (0, 3.0),    # to (3, 3, -0.1), beyond the wall, which hides the light
    (1, -0.1),   # to (0.2, -0.1, -0.1), under the tile, which hides the light
])
def test_a_hit_point_moved_to_a_value_another_coordinate_had_sees_what_is_there_now(axis,
                                                                                   value):
    # A moved coordinate can take any value, the one another coordinate had too: the point
    # is a new one all the same.
    scene, hit = tile_under_a_light_beside_a_wall()
    setattr(hit.hit_point, "xyz"[axis], value)
    r = student_shadow_ray(hit, scene.pointLights[0])
    assert scene.any_hit(r) is hits_anything(scene, r) is True


def test_shadow_rays_after_an_object_is_removed_see_the_scene_as_it_is_now():
    # The wall of floor_and_wall is hit (object 1), then the floor is taken out of the
    # list: the wall is object 0, the only one, and nothing lies between its hit point and
    # the light on its right.
    scene = floor_and_wall()
    hit = scene.closest_hit(ray((1.0, 0.5, 0.0), (-1.0, 0.0, 0.0)))
    assert (hit.primitive_index, as_tuple(hit.hit_point)) == (1, (0.0, 0.5, 0.0))
    del scene.object_list[0]
    r = student_shadow_ray(hit, scene.pointLights[0])
    assert scene.any_hit(r) is hits_anything(scene, r) is False


def test_rays_from_a_hit_point_that_start_on_its_surface_see_that_surface():
    # With t_min = 0 the ray from the tile to the light above it meets the tile at t = 0.
    scene = cube_around_a_tile()
    r = to_point(tile_hit(scene), (0.0, 0.5, 0.0), t_min=0.0)
    assert scene.any_hit(r) is hits_anything(scene, r) is True


def test_rays_from_a_hit_point_far_away_that_skip_less_than_its_rounding_see_its_surface():
    # A million from the origin the hit point lies off its tilted tile by rounding, some
    # 1e-10. A ray from it with t_min = 1e-12 towards the light above the tile can meet the
    # tile right away; this one does, as testing every object finds.
    scene = Scene()
    tile = Parallelogram(Vector3D(1e6, 1e6, -1e6), Vector3D(300.0, 100.0, 0.0),
                         Vector3D(0.0, 100.0, -300.0))
    scene.add_object(tile)
    n = tile.normal
    light = PointLight(Vector3D(1e6 + 150.0, 1e6 + 100.0, -1e6 - 150.0) + n * 500.0,
                       WHITE_LIGHT)
    scene.add_point_light_sources(light)
    eye = Vector3D(1000236.4162440295, 1000172.0820249226, -1000114.3091659487)
    seen = Vector3D(1000250.7295311759, 1000126.8532171826, -1000129.8301203715)
    hit = scene.closest_hit(Ray(eye, Normalize(seen - eye)))
    assert hit.has_hit
    r = to_point(hit, as_tuple(light.pos), t_min=1e-12)
    assert scene.any_hit(r) is hits_anything(scene, r) is True


def test_rays_from_a_hit_point_in_a_tiny_scene_to_just_past_a_light_see_what_is_there():
    # A scene 1e-4 across: a tile at the origin, a light 1e-4 along x and a wall 1e-7
    # beyond the light. The ray to the point 1e-6 beyond the light crosses the wall.
    scene = Scene()
    scene.add_object(Parallelogram(Vector3D(-2.5e-5, 0.0, 2.5e-5), Vector3D(5e-5, 0.0, 0.0),
                                   Vector3D(0.0, 0.0, -5e-5)))
    scene.add_object(Parallelogram(Vector3D(1e-4 + 1e-7, -1e-4, -1e-4),
                                   Vector3D(0.0, 2e-4, 0.0), Vector3D(0.0, 0.0, 2e-4)))
    scene.add_point_light_sources(PointLight(Vector3D(1e-4, 0.0, 0.0), WHITE_LIGHT))
    hit = scene.closest_hit(ray((0.0, 1e-5, 0.0), (0.0, -1.0, 0.0), t_min=1e-9))
    assert (hit.primitive_index, as_tuple(hit.hit_point)) == (0, (0.0, 0.0, 0.0))
    r = to_point(hit, (1e-4 + 1e-6, 0.0, 0.0), t_min=1e-9)
    assert scene.any_hit(r) is hits_anything(scene, r) is True


def test_rays_from_a_hit_point_see_an_object_added_after_the_hit():
    scene = cube_around_a_tile()
    hit = tile_hit(scene)
    scene.add_object(Parallelogram(Vector3D(-0.1, 0.25, 0.1), Vector3D(0.2, 0.0, 0.0),
                                   Vector3D(0.0, 0.0, -0.2)))
    r = to_point(hit, (0.0, 0.5, 0.0))
    assert scene.any_hit(r) is hits_anything(scene, r) is True


AXES = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]


def along(*pairs):
    """The vector sum of factor * AXES[a] over the (factor, a) pairs, as a tuple."""
    v = [0.0] * 3
    for factor, a in pairs:
        v[a] += factor
    return tuple(v)


@pytest.mark.parametrize("far, normal, point, eye", [
    (0, 1, 1000.0, 1.0), (1, 2, 1000.0, 1.0), (2, 0, 1000.0, 1.0), (0, 1, 0.0, 1000.0),
], ids=["x", "y", "z", "distance"])
def test_a_light_above_the_surface_lights_it_however_close_and_one_on_it_does_not(
        far, normal, point, eye):
    # The point P, `point` along one axis, on the plane through the origin normal to
    # another, seen from `eye` away: shadow rays start lift = 2^-32 (1000 + 1) = 2.3e-7 (or
    # 2^-32 1000) above it. A light on the surface (height 0) is not in front of it and
    # lights nothing; lights 1e-7 above P, below the lift, exactly the lift above it and
    # 1e-6 above it are in front, and nothing lies between them and P.
    lift = (point + eye) * 2.0 ** -32
    scene = Scene()
    scene.add_object(InfinitePlane(Vector3D(0.0, 0.0, 0.0), Vector3D(*AXES[normal])))
    for height in (0.0, 1e-7, lift, 1e-6):
        scene.add_point_light_sources(PointLight(
            Vector3D(*along((point, far), (height, normal))), WHITE_LIGHT))
    hit = scene.closest_hit(ray(along((point, far), (eye, normal)), along((-1.0, normal))))
    assert as_tuple(hit.hit_point) == along((point, far))
    assert [light for light, _, _ in visible_lights(scene, hit)] == scene.pointLights[1:]


def test_a_lamp_on_the_ceiling_lights_the_floor_below_it_far_from_the_origin():
    # Floor y = 0 and ceiling y = 0.1, 1000 from the origin; the lamp lies on the ceiling,
    # 0.1 above the point seen. The shadow ray stops short of the lamp, so the ceiling the
    # lamp lies on does not hide it, although the ray starts 2.3e-7 above the floor, more
    # than 1e-6 of the way to the lamp.
    scene = Scene()
    scene.add_object(InfinitePlane(Vector3D(0.0, 0.0, 0.0), Vector3D(0.0, 1.0, 0.0)))
    scene.add_object(InfinitePlane(Vector3D(0.0, 0.1, 0.0), Vector3D(0.0, -1.0, 0.0)))
    scene.add_point_light_sources(PointLight(Vector3D(1000.0, 0.1, 0.0), WHITE_LIGHT))
    hit = scene.closest_hit(ray((1000.0, 0.05, 0.0), (0.0, -1.0, 0.0)))
    assert (hit.primitive_index, as_tuple(hit.hit_point)) == (0, (1000.0, 0.0, 0.0))
    assert [light for light, _, _ in visible_lights(scene, hit)] == scene.pointLights


@pytest.mark.parametrize("axis", range(3), ids=["x", "y", "z"])
def test_a_ball_between_a_surface_and_a_light_shades_it_whichever_way_the_surface_faces(axis):
    # In the plane of `axis` (a) and the next one (b): the wall a = -2 faces +a, seen at
    # P = (-2, 2) from (-1, 2). A ball of radius 0.5 at (-1, 1), halfway from P to the light
    # at the origin, hides that light; the ray to the light at (0, 4) passes its centre at
    # sqrt(2).
    b = (axis + 1) % 3
    scene = Scene()
    scene.add_object(InfinitePlane(Vector3D(*along((-2.0, axis))), Vector3D(*AXES[axis])))
    scene.add_object(Sphere(Vector3D(*along((-1.0, axis), (1.0, b))), 0.5))
    for position in ((0.0, 0.0, 0.0), along((4.0, b))):
        scene.add_point_light_sources(PointLight(Vector3D(*position), WHITE_LIGHT))
    hit = scene.closest_hit(ray(along((-1.0, axis), (2.0, b)), along((-1.0, axis))))
    assert (hit.primitive_index, as_tuple(hit.hit_point)) == (0, along((-2.0, axis), (2.0, b)))
    assert [light for light, _, _ in visible_lights(scene, hit)] == scene.pointLights[1:]
    assert [scene.any_hit(student_shadow_ray(hit, light)) for light in scene.pointLights] == [
        True, False]


class StudentFloor(Primitive):
    """A primitive of a student's own, with only intersect(): the plane y = height, normal
    (0, 1, 0), hit between the ray's t_min and t_max."""

    def __init__(self, height):
        super().__init__()
        self.height = height
        self.rays = []

    def intersect(self, r):
        self.rays.append(r)
        if r.d.y == 0.0:
            return HitData()
        t = (self.height - r.o.y) / r.d.y
        if not r.t_min <= t <= r.t_max:
            return HitData()
        return HitData(True, r.get_hitpoint(t), Vector3D(0.0, 1.0, 0.0), t)


def test_a_primitive_of_ones_own_is_hit_through_its_intersect():
    # From (1, 2, 3) along (2, -2, 1)/3 the plane y = -1 is (-1 - 2)/(-2/3) = 4.5 away, at
    # (1 + 3, 2 - 3, 3 + 1.5).
    floor = StudentFloor(-1.0)
    scene = Scene()
    scene.add_object(Sphere(Vector3D(0.0, 10.0, 0.0), 1.0))
    scene.add_object(floor)
    d = (2 / 3, -2 / 3, 1 / 3)
    hit = scene.closest_hit(ray((1, 2, 3), d))
    assert_hit(hit, (4.0, -1.0, 4.5), (0.0, 1.0, 0.0), 4.5)
    assert hit.primitive_index == 1
    seen = floor.rays[-1]
    assert (type(seen), as_tuple(seen.o), as_tuple(seen.d), seen.t_min, seen.t_max) == (
        Ray, (1.0, 2.0, 3.0), d, EPSILON, HUGEVALUE)
    assert scene.closest_hit(ray((1, 2, 3), d, t_min=5.0)).has_hit is False
    assert scene.closest_hit(ray((1, 2, 3), d, t_max=4.0)).has_hit is False
    assert scene.any_hit(ray((1, 2, 3), d, t_max=4.0)) is False
    assert scene.any_hit(ray((1, 2, 3), d, t_max=5.0)) is True
    assert scene.any_hit(ray((1, 2, 3), (0, 1, 0), t_max=5.0)) is False


def test_a_primitive_of_ones_own_casts_shadows():
    # A floor tile seen at the origin, under a student's plane y = 1: it hides the light
    # above it, not the one below it.
    scene = Scene()
    scene.add_object(Parallelogram(Vector3D(-1.0, 0.0, 1.0), Vector3D(2.0, 0.0, 0.0),
                                   Vector3D(0.0, 0.0, -2.0)))
    scene.add_object(StudentFloor(1.0))
    for height in (2.0, 0.5):
        scene.add_point_light_sources(PointLight(Vector3D(0.0, height, 0.0), WHITE_LIGHT))
    hit = scene.closest_hit(ray((0.0, 0.75, 0.0), (0.0, -1.0, 0.0)))
    assert (hit.primitive_index, as_tuple(hit.hit_point)) == (0, (0.0, 0.0, 0.0))
    assert [light for light, _, _ in visible_lights(scene, hit)] == scene.pointLights[1:]
    assert [scene.any_hit(student_shadow_ray(hit, light)) for light in scene.pointLights] == [
        True, False]


def test_a_scene_sent_to_a_worker_process_arrives_whole():
    # Worker processes get the scene pickled: it must answer every query as the original.
    import pickle
    scene = floor_and_wall()
    scene.set_ambient(RGBColor(0.1, 0.2, 0.3))
    scene.object_list[0].set_BRDF(Lambertian(RGBColor(0.5, 0.25, 1.0)))
    scene.set_camera(Camera(4, 3, 60))
    copy = pickle.loads(pickle.dumps(scene))
    assert (rgb(copy.i_a), copy.camera.width, copy.camera.height) == ((0.1, 0.2, 0.3), 4, 3)
    assert copy.camera.get_direction(1, 2) == scene.camera.get_direction(1, 2)
    assert [as_tuple(light.pos) for light in copy.pointLights] == [as_tuple(RIGHT),
                                                                   as_tuple(LEFT)]
    assert rgb(copy.object_list[0].get_BRDF().kd) == rgb(scene.object_list[0].BRDF.kd)
    hit = floor_hit(copy)
    assert [copy.pointLights.index(light) for light, _, _ in visible_lights(copy, hit)] == [0]
