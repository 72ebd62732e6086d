"""Numerical extremes and bad input: random geometry at every scale, scaled scenes,
degenerate cameras and lights, and a clear error for every bad argument."""
import math
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from AppRenderer import cornell_box_scene, sphere_test_scene
from helpers import as_tuple
from PyRT_Common import BLACK, HUGEVALUE, Cross, Dot, Length, Normalize, RGBColor, Ray, Vector3D
from PyRT_Core import (Camera, InfinitePlane, Lambertian, Parallelogram, PointLight, Scene,
                       Sphere)
from PyRT_Integrators import DepthIntegrator, NormalIntegrator, PhongIntegrator

EPS = sys.float_info.epsilon
INF = float("inf")
NAN = float("nan")

PROPERTY = settings(max_examples=200, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow])


def is_finite(v):
    return all(math.isfinite(c) for c in as_tuple(v))


def magnitude(*vectors):
    """The largest absolute coordinate among the vectors: the scale of their rounding."""
    return max(abs(c) for v in vectors for c in as_tuple(v))


def distance(a, b):
    return Length(a - b)


def make_ray(origin, direction, t_max=HUGEVALUE, t_min=0.0):
    """A ray with both limits chosen: t_min 0 keeps hits closer than EPSILON."""
    ray = Ray(origin, direction, t_max)
    ray.t_min = t_min
    return ray


# ------------------------------------------------------------------------------------------
# Strategies
# ------------------------------------------------------------------------------------------
def log_uniform(lo_exponent, hi_exponent):
    return st.floats(lo_exponent, hi_exponent).map(lambda e: 10.0 ** e)


components = st.tuples(*[st.floats(-1.0, 1.0)] * 3)
unit_vectors = components.filter(lambda c: sum(x * x for x in c) > 0.01).map(
    lambda c: Normalize(Vector3D(*c)))


@st.composite
def sphere_and_ray_from_outside(draw):
    """A sphere 1.5 to 1e6 radii (and at most 1e8) away from the ray origin, and a ray
    aimed at a point at most 0.9 radii from its centre: it enters the sphere, not grazing."""
    radius = draw(log_uniform(-7, 7))
    away = min(radius * draw(log_uniform(math.log10(1.5), 6)), 1e8)
    origin = Vector3D(*draw(components)) * away
    centre = origin + draw(unit_vectors) * away
    target = centre + draw(unit_vectors) * (radius * draw(st.floats(0.0, 0.9)))
    return Sphere(centre, radius), make_ray(origin, Normalize(target - origin), 2.0 * away)


@st.composite
def sphere_and_ray_from_inside(draw):
    """A sphere up to 1e8 from the world origin (at most 1e6 radii) and a ray starting at
    most 0.9 radii from its centre, in any direction."""
    radius = draw(log_uniform(-7, 7))
    away = min(radius * draw(log_uniform(0, 6)), 1e8)
    centre = Vector3D(*draw(components)) * away
    origin = centre + draw(unit_vectors) * (radius * draw(st.floats(0.0, 0.9)))
    return Sphere(centre, radius), make_ray(origin, draw(unit_vectors), 2.0 * radius)


@st.composite
def parallelogram_and_ray(draw):
    """A parallelogram of size ~L (1e-3 .. 1e3) with sides at any angle of at least ~6
    degrees, a point p0 + a*s1 + b*s2 of it (a, b in [0, 1], edges included) and a ray
    towards that point from 0.1 L to 100 L away, at least ~12 degrees off the plane."""
    size = draw(log_uniform(-3, 3))
    point = Vector3D(*draw(components)) * (10.0 * size)
    s1 = Vector3D(*draw(components)) * size
    s2 = Vector3D(*draw(components)) * size
    cross = Cross(s1, s2)
    sides = Length(s1) * Length(s2)
    if not (Length(s1) > 0.1 * size and Length(s2) > 0.1 * size
            and Length(cross) > 0.1 * sides):
        s1, s2 = Vector3D(size, 0.0, 0.0), Vector3D(0.3 * size, 0.0, size)  # skewed default
        cross = Cross(s1, s2)
    normal = Normalize(cross)
    a, b = draw(st.floats(0.0, 1.0)), draw(st.floats(0.0, 1.0))
    target = point + s1 * a + s2 * b
    w = draw(unit_vectors)
    if abs(Dot(w, normal)) < 0.2:
        w = Normalize(w + normal)
    origin = target + w * (size * draw(log_uniform(-1, 2)))
    return Parallelogram(point, s1, s2), make_ray(origin, Normalize(target - origin)), target


# ------------------------------------------------------------------------------------------
# Property-based: spheres
# ------------------------------------------------------------------------------------------
def assert_on_sphere(hit, sphere, ray):
    c, r = sphere.origin, sphere.radius
    p, n, t = hit.hit_point, hit.normal, hit.hit_distance
    scale = magnitude(c, ray.o) + r
    assert ray.t_min <= t <= ray.t_max
    assert abs(distance(p, c) - r) <= 64 * EPS * scale          # on the surface
    assert abs(distance(p, ray.o) - t) <= 64 * EPS * scale      # t is the distance
    assert distance(ray.get_hitpoint(t), p) <= 1e3 * EPS * scale  # on the ray
    assert abs(Length(n) - 1.0) <= 1e-12
    outward = (p - c) / r
    assert distance(n, outward) <= 1e3 * EPS * scale / r


@PROPERTY
@given(sphere_and_ray_from_outside())
def test_random_sphere_hit_from_outside_lies_on_surface_with_outward_normal(case):
    sphere, ray = case
    hit = sphere.intersect(ray)
    assert hit.has_hit
    assert_on_sphere(hit, sphere, ray)
    assert Dot(hit.normal, ray.d) < 0  # the near side: the ray enters there
    assert hit.hit_distance < distance(ray.o, sphere.origin)


@PROPERTY
@given(sphere_and_ray_from_inside())
def test_random_sphere_hit_from_inside_is_far_side_with_outward_normal(case):
    sphere, ray = case
    hit = sphere.intersect(ray)
    assert hit.has_hit
    assert_on_sphere(hit, sphere, ray)
    assert Dot(hit.normal, ray.d) > 0  # the ray leaves through the far side
    # starting at most 0.9 r from the centre, the exit is 0.1 r to 1.9 r away
    assert 0.1 * sphere.radius * (1 - 1e-9) <= hit.hit_distance <= 1.9 * sphere.radius * (1 + 1e-9)


# ------------------------------------------------------------------------------------------
# Property-based: parallelograms
# ------------------------------------------------------------------------------------------
@PROPERTY
@given(parallelogram_and_ray())
def test_random_parallelogram_is_hit_at_the_aimed_point(case):
    parallelogram, ray, target = case
    hit = parallelogram.intersect(ray)
    assert hit.has_hit
    scale = magnitude(ray.o, target, parallelogram.s1, parallelogram.s2)
    assert distance(hit.hit_point, target) <= 1e3 * EPS * scale
    assert hit.hit_distance == pytest.approx(distance(ray.o, target), abs=1e3 * EPS * scale)
    expected = Normalize(Cross(parallelogram.s1, parallelogram.s2))
    assert abs(abs(Dot(hit.normal, expected)) - 1.0) <= 1e-12
    assert Dot(hit.normal, ray.d) < 0  # faces the incoming ray


# ------------------------------------------------------------------------------------------
# Property-based: Scene.closest_hit against brute force
# ------------------------------------------------------------------------------------------
coordinates = st.floats(-10.0, 10.0)
points = st.builds(Vector3D, coordinates, coordinates, coordinates)
sides = st.builds(Vector3D, *[st.floats(-4.0, 4.0)] * 3).filter(lambda v: Length(v) > 0.1)
spheres = st.builds(Sphere, points, st.floats(0.1, 3.0))
planes = st.builds(InfinitePlane, points, unit_vectors)
parallelograms = st.tuples(points, sides, sides).filter(
    lambda p: Length(Cross(p[1], p[2])) > 0.05 * Length(p[1]) * Length(p[2])).map(
    lambda p: Parallelogram(*p))
objects = st.lists(st.one_of(spheres, spheres, parallelograms, parallelograms, planes),
                   min_size=0, max_size=6)
directions = components.filter(lambda c: sum(x * x for x in c) > 0.01).map(
    lambda c: Vector3D(*c))


@PROPERTY
@given(objects, points, directions)
def test_closest_hit_equals_brute_force_minimum(object_list, origin, direction):
    scene = Scene()
    for obj in object_list:
        scene.add_object(obj)
    ray = Ray(origin, direction)
    distances = [hit.hit_distance for hit in (obj.intersect(ray) for obj in object_list)
                 if hit.has_hit]
    closest = scene.closest_hit(ray)
    if not distances:
        assert not closest.has_hit
        assert not scene.any_hit(ray)
        return
    assert closest.has_hit and scene.any_hit(ray)
    # objects hit at the same distance (coplanar ones, say) may differ by rounding
    assert closest.hit_distance == pytest.approx(min(distances), rel=1e-9, abs=1e-12)
    own = object_list[closest.primitive_index].intersect(ray)
    assert own.has_hit
    assert own.hit_distance == pytest.approx(closest.hit_distance, rel=1e-12, abs=1e-12)
    assert as_tuple(own.normal) == pytest.approx(as_tuple(closest.normal), abs=1e-9)


def test_a_sphere_smaller_than_the_rounding_of_its_position_faces_the_ray():
    # 3e17 away, neighbouring coordinates are 16 to 32 apart: the unit sphere is a single
    # point there, and its normal at the hit is the one facing the ray, -d = -(1, 2, -2)/3.
    sphere = Sphere(Vector3D(1e17, 2e17, -2e17), 1.0)
    hit = sphere.intersect(Ray(Vector3D(0.0, 0.0, 0.0), Vector3D(1.0, 2.0, -2.0), 1e18))
    assert hit.has_hit
    assert as_tuple(hit.normal) == pytest.approx((-1 / 3, -2 / 3, 2 / 3), abs=1e-15)
    assert as_tuple(hit.hit_point) == pytest.approx((1e17, 2e17, -2e17), rel=1e-15)
    assert hit.hit_distance == pytest.approx(3e17, rel=1e-15)


# ------------------------------------------------------------------------------------------
# Property-based: the length of the direction vector does not matter
# ------------------------------------------------------------------------------------------
aimed_rays = st.one_of(sphere_and_ray_from_outside(), sphere_and_ray_from_inside(),
                       parallelogram_and_ray().map(lambda case: case[:2]))


@PROPERTY
@given(aimed_rays, log_uniform(-3, 3))
def test_non_unit_direction_gives_the_same_hit(case, factor):
    obj, unit_ray = case
    scaled_ray = make_ray(unit_ray.o, unit_ray.d * factor, unit_ray.t_max, unit_ray.t_min)
    scene = Scene()
    scene.add_object(obj)
    size = obj.radius if isinstance(obj, Sphere) else Length(obj.s1)
    scale = magnitude(unit_ray.o, obj.origin if isinstance(obj, Sphere) else obj.point) + size
    # a direction that is unit length to within ~1e-12 may be used as it is, so the two
    # hits agree to a few 1e-12 of the scene's scale, not to the last bit
    tolerance = 4e-12 * scale
    for expected, hit in ((obj.intersect(unit_ray), obj.intersect(scaled_ray)),
                          (scene.closest_hit(unit_ray), scene.closest_hit(scaled_ray))):
        assert expected.has_hit and hit.has_hit
        assert distance(hit.hit_point, expected.hit_point) <= tolerance
        assert hit.hit_distance == pytest.approx(expected.hit_distance, abs=tolerance)
        assert distance(hit.normal, expected.normal) <= tolerance / size


# ------------------------------------------------------------------------------------------
# Property-based: the whole range of double precision
# ------------------------------------------------------------------------------------------
def scaled_primitive(obj, s):
    """The primitive with every position and length times s."""
    if isinstance(obj, Sphere):
        return Sphere(obj.origin * s, obj.radius * s)
    return Parallelogram(obj.point * s, obj.s1 * s, obj.s2 * s)


def scaled_ray(ray, s):
    return make_ray(ray.o * s, ray.d, ray.t_max * s, ray.t_min * s)


# 2**-498 ~ 1.2e-150 to 2**498 ~ 8.2e149: multiplying by a power of two changes only the
# exponents, so a test free of over- and underflow gives exactly the scaled answer.
powers_of_two = st.integers(-498, 498).map(lambda k: 2.0 ** k)


def no_tiny_components(*vectors):
    """True when every component is 0 or at least 1e-100 in size: scaled by 2**-498, such a
    component stays a normal double. (A direction like (0, 1, 1e-272) has components whose
    products underflow at any scale; that is not what scaling tests.)"""
    return all(c == 0.0 or abs(c) >= 1e-100 for v in vectors for c in as_tuple(v))


@PROPERTY
@given(aimed_rays, powers_of_two)
def test_hits_scaled_by_a_power_of_two_are_exactly_the_scaled_hits(case, s):
    obj, ray = case
    expected = obj.intersect(ray)
    assume(no_tiny_components(ray.o, ray.d, expected.hit_point, expected.normal))
    scene = Scene()
    scene.add_object(scaled_primitive(obj, s))
    for hit in (scene.object_list[0].intersect(scaled_ray(ray, s)),
                scene.closest_hit(scaled_ray(ray, s))):
        assert hit.has_hit
        assert hit.hit_distance == expected.hit_distance * s
        assert as_tuple(hit.hit_point) == as_tuple(expected.hit_point * s)
        assert as_tuple(hit.normal) == as_tuple(expected.normal)


@PROPERTY
@given(aimed_rays, st.floats(-150.0, 150.0))
def test_hits_at_any_scale_from_1e_minus_150_to_1e150_are_the_scaled_hits(case, exponent):
    obj, ray = case
    s = 10.0 ** exponent
    expected = obj.intersect(ray)
    hit = scaled_primitive(obj, s).intersect(scaled_ray(ray, s))
    assert hit.has_hit
    # the inputs are rounded once when scaled: the answers agree to a few ulps of the scene
    scale = magnitude(ray.o, expected.hit_point) + expected.hit_distance
    assert hit.hit_distance / s == pytest.approx(expected.hit_distance, abs=1e-12 * scale)
    assert distance(hit.hit_point / s, expected.hit_point) <= 1e-12 * scale
    assert distance(hit.normal, expected.normal) <= 1e-9


@pytest.mark.parametrize("s", [1e-300, 1e-150, 1e150, 1e300])
def test_parallel_sides_are_refused_and_others_accepted_at_any_scale(s):
    with pytest.raises(ValueError, match="parallel"):
        Parallelogram(GOOD * s, Vector3D(1.0, 2.0, 3.0) * s, Vector3D(-2.0, -4.0, -6.0) * s)
    # sides 1e-12 radians apart are parallel as far as a double can tell, at every scale ...
    with pytest.raises(ValueError, match="parallel"):
        Parallelogram(GOOD * s, Vector3D(1.0, 0.0, 0.0) * s, Vector3D(1.0, 1e-13, 0.0) * s)
    # ... while a skewed, thin parallelogram of any size is a parallelogram
    thin = Parallelogram(Vector3D(0.0, 0.0, -1.0) * s, Vector3D(1.0, 0.0, 0.0) * s,
                         Vector3D(1.0, 1e-6, 0.0) * s)
    assert as_tuple(thin.normal) == (0.0, 0.0, 1.0)


@pytest.mark.parametrize("tiny", [1e-300, 5e-324])
def test_tiny_non_zero_vectors_are_sides_and_normals_not_zero_vectors(tiny):
    square = Parallelogram(Vector3D(0.0, 0.0, -tiny), Vector3D(tiny, 0.0, 0.0),
                           Vector3D(0.0, tiny, 0.0))
    assert as_tuple(square.normal) == (0.0, 0.0, 1.0)
    # Normalize rounds as the course's v * (1 / |v|) does: -c * (1 / c) for the mantissa c
    # of tiny, the same for tiny times any power of two, within one rounding of -1
    plane = InfinitePlane(Vector3D(0.0, 0.0, 0.0), Vector3D(0.0, -tiny, 0.0))
    mantissa = math.frexp(tiny)[0]
    assert as_tuple(plane.normal) == (0.0, -mantissa * (1.0 / mantissa), 0.0)
    assert as_tuple(plane.normal) == as_tuple(
        InfinitePlane(Vector3D(0.0, 0.0, 0.0), Vector3D(0.0, -mantissa, 0.0)).normal)
    assert plane.normal.y == pytest.approx(-1.0, abs=2.0 ** -52)


@pytest.mark.parametrize("s", [1e-300, 1e-150, 1e150, 1e300])
def test_spheres_of_any_size_are_hit_at_the_scaled_distance(s):
    # radius s, centre 3s down -z: the ray down -z enters at 2s, normal (0, 0, 1)
    hit = Sphere(Vector3D(0.0, 0.0, -3.0 * s), s).intersect(
        make_ray(Vector3D(0.0, 0.0, 0.0), Vector3D(0.0, 0.0, -1.0), INF))
    assert hit.has_hit
    assert hit.hit_distance == pytest.approx(2.0 * s, rel=1e-15)
    assert as_tuple(hit.normal) == (0.0, 0.0, 1.0)


def test_sphere_1e160_radii_away_is_hit_where_its_square_would_overflow():
    # |f|^2 = 1e320 overflows; (|f| - 1)(|f| + 1) does not: the near side is 1e160 - 1 away,
    # which rounds to 1e160
    hit = Sphere(Vector3D(0.0, 0.0, -1e160), 1.0).intersect(
        make_ray(Vector3D(0.0, 0.0, 0.0), Vector3D(0.0, 0.0, -1.0), INF))
    assert hit.has_hit
    assert hit.hit_distance == 1e160
    assert as_tuple(hit.normal) == (0.0, 0.0, 1.0)


# ------------------------------------------------------------------------------------------
# Specific numerical cases
# ------------------------------------------------------------------------------------------
def test_unit_sphere_1e8_away_is_hit_head_on():
    # the near side is at 1e8 - 1; b^2 - c = 1e16 - (1e16 - 1) would lose the 1 entirely
    hit = Sphere(Vector3D(0.0, 0.0, -1e8), 1.0).intersect(
        Ray(Vector3D(0.0, 0.0, 0.0), Vector3D(0.0, 0.0, -1.0), INF))
    assert hit.has_hit
    assert hit.hit_distance == pytest.approx(1e8 - 1.0, abs=1e-6)
    assert as_tuple(hit.normal) == pytest.approx((0.0, 0.0, 1.0), abs=1e-9)


def test_unit_sphere_1e8_away_is_hit_off_centre():
    # aimed at the point 0.6 off the centre: the surface point is (0.6, 0, -1e8 + 0.8)
    centre = Vector3D(0.0, 0.0, -1e8)
    target = Vector3D(0.6, 0.0, -1e8 + 0.8)
    hit = Sphere(centre, 1.0).intersect(Ray(Vector3D(0.0, 0.0, 0.0), Normalize(target), INF))
    assert hit.has_hit
    assert abs(distance(hit.hit_point, centre) - 1.0) <= 1e-7
    assert as_tuple(hit.hit_point) == pytest.approx(as_tuple(target), abs=1e-6)
    assert as_tuple(hit.normal) == pytest.approx((0.6, 0.0, 0.8), abs=1e-6)


@pytest.mark.parametrize("radius", [1e-7, 1e7])
def test_smallest_and_largest_spheres_far_away_are_hit(radius):
    away = min(radius * 1e6, 1e8)  # 0.1 and 1e8: 1e6 and 10 radii away
    hit = Sphere(Vector3D(0.0, away, 0.0), radius).intersect(
        make_ray(Vector3D(0.0, 0.0, 0.0), Vector3D(0.0, 1.0, 0.0), INF))
    assert hit.has_hit
    assert hit.hit_distance == pytest.approx(away - radius, rel=1e-12)


SQUARE = (Vector3D(-1.0, -1.0, -3.0), Vector3D(2.0, 0.0, 0.0), Vector3D(0.0, 2.0, 0.0))
SKEWED = (Vector3D(0.1, 0.2, -3.0), Vector3D(0.7, 0.3, 0.0), Vector3D(-0.2, 0.9, 0.0))


@pytest.mark.parametrize("shape", [SQUARE, SKEWED])
@pytest.mark.parametrize("a, b", [(0, 0), (1, 0), (0, 1), (1, 1)])
def test_ray_through_exact_parallelogram_corner_is_a_hit(shape, a, b):
    point, s1, s2 = shape
    corner = point + s1 * a + s2 * b
    hit = Parallelogram(point, s1, s2).intersect(Ray(Vector3D(0.0, 0.0, 0.0), Normalize(corner)))
    assert hit.has_hit
    assert as_tuple(hit.hit_point) == pytest.approx(as_tuple(corner), abs=1e-12)


@pytest.mark.parametrize("shape", [SQUARE, SKEWED], ids=["square", "skewed"])
@pytest.mark.parametrize("side", ["s1", "s2", "diagonal"])
def test_ray_from_the_corner_along_the_plane_misses(shape, side):
    # The ray lies in the parallelogram's plane (z = -3), so d.n = 0: like any ray
    # parallel to the plane it misses, even where it runs across the parallelogram.
    point, s1, s2 = shape
    direction = {"s1": s1, "s2": s2, "diagonal": s1 + s2}[side]
    scene = Scene()
    scene.add_object(Parallelogram(point, s1, s2))
    ray = make_ray(point, Normalize(direction), INF)
    assert scene.object_list[0].intersect(ray).has_hit is False
    assert scene.closest_hit(ray).has_hit is False
    assert scene.any_hit(ray) is False


PLANAR = {
    "plane": lambda: InfinitePlane(Vector3D(0.0, 0.0, 0.0), Vector3D(0.0, 1.0, 0.0)),
    # x and z in [-1, 1], y = 0; Cross(s1, s2) = (0, 4, 0), the same normal as the plane
    "parallelogram": lambda: Parallelogram(Vector3D(-1.0, 0.0, -1.0),
                                           Vector3D(0.0, 0.0, 2.0), Vector3D(2.0, 0.0, 0.0)),
}
# The ray below starts at (-0.5, height, 0.25) and heads along (1, -tilt, 0), a unit
# vector to within rounding (1 + tilt^2 rounds to 1): it meets the plane y = 0 at the
# distance height / tilt. These crossings are positive and finite; all the others lie
# behind the ray (height and tilt of opposite signs) or overflow to infinity (height /
# 1e-320 > 1e308).
FAR_CROSSINGS = {(1.0, 1e-200): 1e200, (1.0, 1e-300): 1e300, (1e6, 1e-200): 1e206,
                 (1e6, 1e-300): 1e306, (-1.0, -1e-200): 1e200, (-1.0, -1e-300): 1e300}


def nearly_parallel_hit(kind, tilt, height, t_max):
    """The distance at which the ray of the test below hits the object, or None."""
    if tilt == 0.0:
        return None  # parallel, d.n = 0: a miss, also for the ray lying in the plane
    if height == 0.0:
        return 0.0  # starts on the plane (inside the parallelogram, at a = 0.625, b = 0.25)
    # the far crossings lie beyond t_max = 1e6 and beyond the parallelogram's edge x = 1
    return FAR_CROSSINGS.get((height, tilt)) if kind == "plane" and t_max == INF else None


@pytest.mark.parametrize("kind", PLANAR)
@pytest.mark.parametrize("tilt", [0.0, 1e-200, -1e-200, 1e-300, -1e-300, 1e-320])
@pytest.mark.parametrize("height", [1.0, 0.0, -1.0, 1e6])
@pytest.mark.parametrize("t_max", [HUGEVALUE, INF])
def test_parallel_and_nearly_parallel_rays_hit_only_where_they_cross_the_plane(
        kind, tilt, height, t_max):
    obj = PLANAR[kind]()
    scene = Scene()
    scene.add_object(obj)
    ray = make_ray(Vector3D(-0.5, height, 0.25), Vector3D(1.0, -tilt, 0.0), t_max)
    expected = nearly_parallel_hit(kind, tilt, height, t_max)
    assert scene.any_hit(ray) is (expected is not None)
    # the normal is (0, 1, 0); the parallelogram's faces the ray: flipped when it heads up
    normal = (0.0, -1.0, 0.0) if kind == "parallelogram" and tilt < 0 else (0.0, 1.0, 0.0)
    for hit in (obj.intersect(ray), scene.closest_hit(ray)):
        assert hit.has_hit is (expected is not None)
        if expected is not None:
            assert hit.hit_distance == pytest.approx(expected, rel=1e-15, abs=0.0)
            assert as_tuple(hit.hit_point) == pytest.approx(
                (expected - 0.5, 0.0, 0.25), rel=1e-15, abs=1e-9 * abs(height))
            assert as_tuple(hit.normal) == normal


# ------------------------------------------------------------------------------------------
# Scale invariance
# ------------------------------------------------------------------------------------------
SIZE = 40


def scaled_copy(scene, s):
    """The scene with every position and size times s and light intensities times s**2."""
    copy = Scene()
    copy.set_ambient(scene.i_a)
    for obj in scene.object_list:
        if isinstance(obj, Sphere):
            new = Sphere(obj.origin * s, obj.radius * s)
        else:
            new = Parallelogram(obj.point * s, obj.s1 * s, obj.s2 * s)
        new.set_BRDF(obj.get_BRDF())
        copy.add_object(new)
    for light in scene.pointLights:
        copy.add_point_light_sources(PointLight(light.pos * s, light.intensity * (s * s)))
    copy.set_camera(Camera(SIZE, SIZE, 70))
    return copy


INTEGRATORS = {
    "phong": lambda name, s: PhongIntegrator(name),
    "depth": lambda name, s: DepthIntegrator(name, 5.0 * s),
    "normal": lambda name, s: NormalIntegrator(name),
}


def render(integrator, scene):
    integrator.add_scene(scene)
    integrator.render(workers=1, progress=False)
    return scene.rendered_image.copy()


@pytest.fixture(scope="session")
def cornell_references(tmp_path_factory):
    folder = tmp_path_factory.mktemp("reference")
    base = cornell_box_scene(0.75, 2)
    return {name: render(make(str(folder / name), 1.0), scaled_copy(base, 1.0))
            for name, make in INTEGRATORS.items()}


def test_cornell_reference_images_are_not_trivial(cornell_references):
    phong, depth = cornell_references["phong"], cornell_references["depth"]
    assert np.all(np.isfinite(phong)) and np.all(phong > 0)  # the box fills the view
    # every ray enters the box; the nearest point seen is the sphere's front, 1.75 - 0.25 =
    # 1.5 away, the farthest the back wall's corners, sqrt(1 + 1 + 2.75^2) = 3.09 away:
    # grey 1 - d/5 lies in [1 - 3.09/5, 1 - 1.5/5] = [0.382, 0.7]
    assert np.all((depth >= 0.38) & (depth <= 0.7 + 1e-12))


def phong(point, normal, albedo, ambient, lights):
    """The course's Phong value kd (x) (i_a + sum of I cos / r^2) at a point with the given
    unit normal, kd = albedo / pi, for the (position, intensity) lights that reach it."""
    total = np.array(ambient, dtype=float)
    for position, intensity in lights:
        to_light = np.subtract(position, point)
        r2 = to_light @ to_light
        total = total + np.array(intensity) * (np.dot(normal, to_light) / math.sqrt(r2)) / r2
    return np.array(albedo) / math.pi * total


# The Cornell box of cornell_box_scene(0.75, 2)
CORNELL_AMBIENT = (1.0, 1.0, 0.3)
CORNELL_LIGHTS = [((x, 0.5, -1.75), (0.5, 0.5, 0.5)) for x in (0.0, -0.5, 0.5)]
WHITE_WALL, RED_WALL, GREEN_WALL = (0.8, 0.8, 0.8), (0.7, 0.2, 0.2), (0.2, 0.7, 0.2)


def cornell_seam_colours(k, side):
    """The Phong colours of the two surfaces that meet on the seam seen at pixel (k, k)
    (side "left": the left wall, then the ceiling) or (39 - k, k) ("right": the ceiling,
    then the right wall) of the 40 x 40 Cornell box, in the order of object_list.

    Pixel (k, k) has x_s = (2k + 1)/40 - 1 = -y_s: its ray (-a, a, -1), a = -x_s tan(35
    deg), meets x = -1 and y = 1 together, on the edge of the left wall and the ceiling,
    at z = -1/a (inside the box for k <= 9); pixel (39 - k, k) is its mirror image on the
    right. All three lights hang below the ceiling in front of both walls, and the sphere
    lies below them."""
    a = (1.0 - (2 * k + 1) / 40) * math.tan(math.radians(35))
    if side == "left":
        point = (-1.0, 1.0, -1.0 / a)
        surfaces = [((1.0, 0.0, 0.0), RED_WALL), ((0.0, -1.0, 0.0), WHITE_WALL)]
    else:
        point = (1.0, 1.0, -1.0 / a)
        surfaces = [((0.0, -1.0, 0.0), WHITE_WALL), ((-1.0, 0.0, 0.0), GREEN_WALL)]
    return [phong(point, normal, albedo, CORNELL_AMBIENT, CORNELL_LIGHTS)
            for normal, albedo in surfaces]


@pytest.mark.parametrize("k", range(10))
def test_where_the_left_wall_meets_the_ceiling_at_the_same_distance_the_wall_is_seen(
        cornell_references, k):
    # x_s and y_s of pixel (k, k) are exact opposites, so the ray's components a and -a
    # are too, and the two walls' distances 1/a are the same number: a tie, which keeps
    # the first of object_list (sphere, back, floor, left, ceiling, right): the left wall.
    wall, _ = cornell_seam_colours(k, "left")
    np.testing.assert_allclose(cornell_references["phong"][k, k], wall, rtol=1e-6, atol=0)


@pytest.mark.parametrize("k", range(10))
def test_where_the_ceiling_meets_the_right_wall_one_of_the_two_is_seen(cornell_references, k):
    # x_s of pixel 39 - k and y_s of row k are equal numbers rounded in two ways, so the
    # two distances may differ in their last digit, and the strictly nearer one is seen,
    # as in the course's images: either surface is right.
    pixel = cornell_references["phong"][k, 39 - k]
    assert any(np.allclose(pixel, colour, rtol=1e-6, atol=0)
               for colour in cornell_seam_colours(k, "right")), pixel


def cornell_seams(scene):
    """The (y, x) pixels of the scene's camera whose ray meets two objects at distances
    that agree to within a relative 1e-9: where surfaces meet, and rounding decides which
    of them is the nearest."""
    seams = set()
    camera = scene.camera
    for y in range(camera.height):
        for x in range(camera.width):
            ray = make_ray(Vector3D(0.0, 0.0, 0.0), camera.get_direction(x, y), INF)
            distances = sorted(hit.hit_distance for hit in map(lambda o: o.intersect(ray),
                                                                scene.object_list)
                               if hit.has_hit)
            if len(distances) > 1 and distances[1] - distances[0] <= 1e-9 * distances[0]:
                seams.add((y, x))
    return seams


@pytest.fixture(scope="session")
def cornell_seam_pixels():
    return cornell_seams(scaled_copy(cornell_box_scene(0.75, 2), 1.0))


def test_the_seams_of_the_cornell_box_are_its_edges_seen_on_the_diagonals(cornell_seam_pixels):
    # The box's four edges along z project onto the image's diagonals, x = y and
    # x = 39 - y; its front edges lie outside the 70 degree view. In each corner of the
    # image the diagonal runs through ten pixels before it reaches the back wall's corner.
    assert cornell_seam_pixels
    assert all(x == y or x == 39 - y for y, x in cornell_seam_pixels)
    assert len(cornell_seam_pixels) <= 4 * 10


@pytest.mark.parametrize("name", INTEGRATORS)
@pytest.mark.parametrize("s", [1e-150, 1e-100, 1e-6, 1e-3, 1e3, 1e6, 1e100, 1e150])
def test_scaled_cornell_box_renders_the_same_image_but_for_ties_on_its_seams(
        cornell_references, cornell_seam_pixels, tmp_path, name, s):
    # Scaling by s rounds every number anew: the image is the same to within rounding,
    # except where two walls meet at the same distance, which rounding decides either way
    image = render(INTEGRATORS[name](str(tmp_path / name), s),
                   scaled_copy(cornell_box_scene(0.75, 2), s))
    close = np.isclose(image, cornell_references[name], rtol=1e-6, atol=1e-12).all(axis=2)
    differing = {tuple(pixel) for pixel in np.argwhere(~close)}
    assert differing <= cornell_seam_pixels


@pytest.mark.parametrize("name", INTEGRATORS)
@pytest.mark.parametrize("s", [2.0 ** -498, 2.0 ** -300, 2.0 ** 300, 2.0 ** 498])
def test_cornell_box_scaled_by_a_power_of_two_renders_exactly_the_same_image(
        cornell_references, tmp_path, name, s):
    # 2**-498 ~ 1.2e-150, 2**498 ~ 8.2e149: only the exponents of every number change
    image = render(INTEGRATORS[name](str(tmp_path / name), s),
                   scaled_copy(cornell_box_scene(0.75, 2), s))
    assert np.array_equal(image, cornell_references[name])


# ------------------------------------------------------------------------------------------
# Defined results at the edges
# ------------------------------------------------------------------------------------------
def render_small(scene, integrator, camera):
    scene.set_camera(camera)
    image = render(integrator, scene)
    assert image.shape == (camera.height, camera.width, 3)
    assert np.all(np.isfinite(image))
    return image


# The sphere scene, sphere_test_scene(), seen by a 5 x 5 camera with a 90 degree field of
# view: pixel (2, y) looks along (0, y_s, -1), y_s = 1 - 2(y + 0.5)/5.
SPHERE_AMBIENT = (0.5, 0.5, 0.5)
SPHERE_SCENE_LIGHT = ((0.0, 5.0, 0.0), (80.0, 80.0, 80.0))
GREY_SPHERE, GREEN_FLOOR = (0.8, 0.8, 0.8), (0.2, 0.8, 0.2)
SPHERE_SCENE_PIXELS = {  # pixel: point seen, its normal, albedo, lit by the scene's light
    # y_s = 0: the sphere's front
    (2, 2): ((0.0, 0.0, -3.0), (0.0, 0.0, 1.0), GREY_SPHERE, True),
    # y_s = -0.4: 1.16 t^2 - 10 t + 21 = 0 at t = 105/29, P = (0, -42, -105)/29, normal
    # (P - (0, 0, -5))/2 = (0, -21, 20)/29; the light at (0, 5, 0) is behind the surface
    # there: n.(L - P) = (-21 * 187 + 20 * 105)/29^2 < 0
    (2, 3): ((0.0, -42 / 29, -105 / 29), (0.0, -21 / 29, 20 / 29), GREY_SPHERE, False),
    # y_s = -0.8: passes the sphere's centre 4/sqrt(1.64) = 3.1 away and meets the floor
    # y = -2 at t = 2.5
    (2, 4): ((0.0, -2.0, -2.5), (0.0, 1.0, 0.0), GREEN_FLOOR, True),
}


@pytest.mark.parametrize("position, lit", [
    # on the floor: it lights the sphere at (2, 3), n.(L - P) = (21*16 + 20*18)/29^2 > 0,
    # and not the floor; for (2, 2) it lies level with the surface (cos = 0)
    ((0.0, -2.0, -3.0), [(2, 3)]),
    # on the floor's corner: it lights the sphere at (2, 2), L - P = (-4, -2, 2), and at
    # (2, 3), n.(L - P) = (21*16 + 20*76)/29^2 > 0; not the floor
    ((-4.0, -2.0, -1.0), [(2, 2), (2, 3)]),
    # on the sphere, at the very point (2, 2) sees: it lights the floor, L - P = (0, 2,
    # -0.5), a segment that reaches the sphere only at the light; not the sphere
    ((0.0, 0.0, -3.0), [(2, 4)]),
])
def test_point_light_on_a_surface_of_the_sphere_scene_lights_only_the_others(
        tmp_path, position, lit):
    extra = (position, (5.0, 5.0, 5.0))
    scene = sphere_test_scene()
    scene.add_point_light_sources(PointLight(Vector3D(*position), RGBColor(*extra[1])))
    image = render_small(scene, PhongIntegrator(str(tmp_path / "img")), Camera(5, 5, 90))
    for (x, y), (point, normal, albedo, scene_light) in SPHERE_SCENE_PIXELS.items():
        lights = ([SPHERE_SCENE_LIGHT] if scene_light else []) + ([extra] if (x, y) in lit else [])
        expected = phong(point, normal, albedo, SPHERE_AMBIENT, lights)
        np.testing.assert_allclose(image[y, x], expected, rtol=1e-9, err_msg=f"{(x, y)}")


# The Cornell box seen by a 7 x 7 camera with a 90 degree field of view: pixel (x, y) looks
# along (x_s, y_s, -1) with x_s, y_s in {0, +-2/7, +-4/7, +-6/7}. The sphere hides none of
# these points, and all three lights reach them but the floor's, straight under the
# sphere: there the middle light is hidden, the side ones pass the sphere's centre
# sqrt(0.1) = 0.32 away.
CORNELL_PIXELS = {  # pixel: point seen, its normal, albedo, lights that reach it
    (3, 0): ((0.0, 1.0, -7 / 6), (0.0, -1.0, 0.0), WHITE_WALL, CORNELL_LIGHTS),  # ceiling
    (3, 2): ((0.0, 11 / 14, -2.75), (0.0, 0.0, 1.0), WHITE_WALL, CORNELL_LIGHTS),  # back
    (3, 5): ((0.0, -1.0, -1.75), (0.0, 1.0, 0.0), WHITE_WALL, CORNELL_LIGHTS[1:]),  # floor
    (1, 3): ((-1.0, 0.0, -1.75), (1.0, 0.0, 0.0), RED_WALL, CORNELL_LIGHTS),  # left
    (5, 3): ((1.0, 0.0, -1.75), (-1.0, 0.0, 0.0), GREEN_WALL, CORNELL_LIGHTS),  # right
}


@pytest.mark.parametrize("position, lit", [
    # the centre of the back wall: it lights the ceiling, floor and side walls (each
    # segment to it passes the sphere's centre at least 0.53 away), not the back wall
    ((0.0, 0.0, -2.75), [(3, 0), (3, 5), (1, 3), (5, 3)]),
    # the edge of the floor and the left wall: it lights the ceiling, back and right wall
    # (passing the sphere at least 0.45 away), not the floor or the left wall
    ((-1.0, -1.0, -1.5), [(3, 0), (3, 2), (5, 3)]),
    # the corner of the back wall, the ceiling and the right wall: it lights the floor and
    # the left wall (passing the sphere 1/sqrt(3) away), none of its three walls
    ((1.0, 1.0, -2.75), [(3, 5), (1, 3)]),
])
def test_point_light_on_a_cornell_wall_lights_only_the_others(tmp_path, position, lit):
    extra = (position, (0.5, 0.5, 0.5))
    scene = cornell_box_scene(0.75, 2)
    scene.add_point_light_sources(PointLight(Vector3D(*position), RGBColor(*extra[1])))
    image = render_small(scene, PhongIntegrator(str(tmp_path / "img")), Camera(7, 7, 90))
    for (x, y), (point, normal, albedo, lights) in CORNELL_PIXELS.items():
        expected = phong(point, normal, albedo, CORNELL_AMBIENT,
                         lights + ([extra] if (x, y) in lit else []))
        np.testing.assert_allclose(image[y, x], expected, rtol=1e-9, err_msg=f"{(x, y)}")


@pytest.mark.parametrize("width, height", [(1, 21), (21, 1), (1, 1)])
def test_one_pixel_wide_or_tall_image_looks_through_the_centre(tmp_path, width, height):
    # the middle pixel looks straight down -z at the sphere: distance 5 - 2 = 3, grey 1 - 3/5
    image = render_small(sphere_test_scene(), DepthIntegrator(str(tmp_path / "img"), 5),
                         Camera(width, height, 60))
    assert image[height // 2, width // 2] == pytest.approx([0.4, 0.4, 0.4], abs=1e-12)


# The middle pixel of an image with odd sides sees the sphere's front (0, 0, -3), normal
# (0, 0, 1); the light at (0, 5, 0) is (0, 5, 3) away: r^2 = 34, cos = 3/sqrt(34). Phong
# gives 0.8/pi (0.5 + 80 * 3/34^1.5) = 0.4356 in every channel.
SPHERE_FRONT_PHONG = phong((0.0, 0.0, -3.0), (0.0, 0.0, 1.0), GREY_SPHERE, SPHERE_AMBIENT,
                           [SPHERE_SCENE_LIGHT])


def test_phong_of_the_sphere_front_is_the_value_worked_out_by_hand():
    assert SPHERE_FRONT_PHONG == pytest.approx([0.4356] * 3, abs=1e-4)


@pytest.mark.parametrize("width, height", [(1, 9), (9, 1), (1, 1)])
def test_one_pixel_wide_or_tall_image_shades_the_centre_with_phong(tmp_path, width, height):
    image = render_small(sphere_test_scene(), PhongIntegrator(str(tmp_path / "img")),
                         Camera(width, height, 60))
    np.testing.assert_allclose(image[height // 2, width // 2], SPHERE_FRONT_PHONG, rtol=1e-9)


def test_tiny_field_of_view_sees_only_the_sphere_front(tmp_path):
    # every ray is within ~1e-8 radians of -z: the normal at (0, 0, -3) is (0, 0, 1),
    # coloured ((0, 0, 1) + 1) / 2 = (0.5, 0.5, 1)
    image = render_small(sphere_test_scene(), NormalIntegrator(str(tmp_path / "img")),
                         Camera(5, 5, 1e-6))
    assert image == pytest.approx(np.broadcast_to([0.5, 0.5, 1.0], image.shape), abs=1e-6)


@pytest.mark.parametrize("fov", [1e-6, 179.999])
def test_extreme_field_of_view_centre_pixel_sees_the_sphere_front(tmp_path, fov):
    # the centre of a 9 x 9 image looks straight down -z: normal (0, 0, 1) -> (0.5, 0.5, 1)
    image = render_small(sphere_test_scene(), NormalIntegrator(str(tmp_path / "img")),
                         Camera(9, 9, fov))
    assert image[4, 4] == pytest.approx([0.5, 0.5, 1.0], abs=1e-12)


@pytest.mark.parametrize("fov", [1e-6, 179.999])
def test_extreme_field_of_view_centre_pixel_shades_the_sphere_front(tmp_path, fov):
    image = render_small(sphere_test_scene(), PhongIntegrator(str(tmp_path / "img")),
                         Camera(9, 9, fov))
    np.testing.assert_allclose(image[4, 4], SPHERE_FRONT_PHONG, rtol=1e-9)


def test_field_of_view_close_to_180_degrees_has_finite_unit_directions():
    camera = Camera(4, 4, 179.999)
    for x, y in ((0, 0), (3, 3), (0, 3), (2, 1)):
        d = camera.get_direction(x, y)
        assert is_finite(d) and Length(d) == pytest.approx(1.0, abs=1e-12)


# ------------------------------------------------------------------------------------------
# Bad input: the exception type, and a message naming the argument
# ------------------------------------------------------------------------------------------
GOOD = Vector3D(0.0, 0.0, -5.0)


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
    assert str(error.value) == ("Scene.add_point_light_sources: light must be a PointLight, "
                                "got (0.0, 1.0, 0.0)")


def test_set_brdf_needs_a_brdf_and_names_the_class():
    with pytest.raises(TypeError, match=r"^Sphere\.set_BRDF: brdf must be a BRDF such as "
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
    with pytest.raises(TypeError, match=r"^Scene\.add_object: obj must be a Primitive \(Sphere, "
                       r"InfinitePlane, Parallelogram or your own subclass\), got "):
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
