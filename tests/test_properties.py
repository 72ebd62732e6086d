"""Properties of the intersections on random geometry at every scale (Hypothesis): hits lie
on the objects, the nearest hit is that of testing every object, the length of a ray's
direction does not matter, and the whole range of double precision gives scaled answers."""
import math
import sys

import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from helpers import GOOD, INF, as_tuple, distance, make_ray
from PyRT_Common import Cross, Dot, Length, Normalize, Ray, Vector3D
from PyRT_Core import InfinitePlane, Parallelogram, Scene, Sphere


EPS = sys.float_info.epsilon

PROPERTY = settings(max_examples=200, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow])


def magnitude(*vectors):
    """The largest absolute coordinate among the vectors: the scale of their rounding."""
    return max(abs(c) for v in vectors for c in as_tuple(v))



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
