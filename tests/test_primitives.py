"""Unit tests for PyRT_Core's primitives (Sphere, InfinitePlane, Parallelogram), materials
and lights, against values computed by hand."""
import math

import numpy as np
import pytest

from helpers import approx3, as_tuple, assert_hit, ray, rgb
from PyRT_Common import BLACK, Dot, Normalize, RGBColor, Ray, Vector3D
from PyRT_Core import (InfinitePlane, Lambertian, Parallelogram, PointLight, Primitive, Scene,
                       Sphere)


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
def test_a_plane_measures_t_along_the_direction_normalised_once_more(direction):
    # As the course's framework does (the spec's "How the course's framework computes a
    # hit"): d' = Normalize(d) = d * (1 / |d|), t = Dot(n, point - o) / Dot(d', n), which
    # for the plane z = -1 seen from the origin is -1 / d'.z, and the hit point is
    # o + d * t along the ray's own direction, of unit length to within 1e-12.
    assert direction[0] ** 2 + direction[1] ** 2 + direction[2] ** 2 in (1 - 1e-12, 1 + 1e-12)
    plane = InfinitePlane(Vector3D(0.0, 0.0, -1.0), Vector3D(0.0, 0.0, 1.0))
    scene = Scene()
    scene.add_object(plane)
    inverse = 1.0 / math.sqrt(direction[0] ** 2 + direction[1] ** 2 + direction[2] ** 2)
    t = -1.0 / (direction[2] * inverse)
    along_d = 1.0 / -direction[2]  # where d itself meets the plane, about 5e-13 away
    assert t != along_d
    for hit in (plane.intersect(ray((0, 0, 0), direction)),
                scene.closest_hit(ray((0, 0, 0), direction))):
        assert hit.hit_distance == t
        assert tuple(hit.hit_point) == (direction[0] * t, direction[1] * t, direction[2] * t)
    # any_hit agrees: the hit lies beyond a t_max halfway between the two distances when
    # it lies beyond along_d, before it otherwise
    halfway = (along_d + t) / 2
    assert scene.any_hit(ray((0, 0, 0), direction, t_max=halfway)) is (t < halfway)


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
