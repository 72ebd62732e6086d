"""pyrt/array_intersections.py: each array test finds, for every ray of an array, the
distance its scalar test finds (or misses where it misses), bit for bit, whatever t_max
each ray has: from anywhere, from the primitive's own surface, parallel to a plane, with
t_max at a hit's very distance, and with squares that overflow."""
import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from helpers import primitives
from pyrt.acceleration.queries import _object_test
from pyrt.array_intersections import ARRAY_TESTS
from PyRT_Common import *
from PyRT_Core import *

PROPERTY = settings(max_examples=200, deadline=None)


def scalar_distances(test, constants, rays, t_min):
    """The scalar test's answer for each ray (o, d, u, t_max): its distance or None."""
    return [test(constants, *o, *d, *u, t_min, t_max) for o, d, u, t_max in rays]


def array_distances(test, constants, rays, t_min):
    """The array test's answer for each ray, as scalar_distances gives it."""
    columns = [np.array(column, dtype=float) for column in zip(*(
        (*o, *d, *u, t_max) for o, d, u, t_max in rays))]
    with np.errstate(all="ignore"):
        t, hit = ARRAY_TESTS[test](constants, *columns[:9], t_min, columns[9])
    return [distance if hit_here else None
            for distance, hit_here in zip(t.tolist(), hit.tolist())]


def unit(x, y, z):
    """The unit vector of (x, y, z) and that vector normalised once more, as tuples."""
    d = Normalize(Vector3D(x, y, z))
    u = Normalize(d)
    return (d.x, d.y, d.z), (u.x, u.y, u.z)


def some_rays(obj, test, constants, seed, count=64):
    """Rays from anywhere and from the object's own surface, each with t_max INFINITY,
    a random one, and the very distance the scalar test finds for it."""
    generator = np.random.default_rng(seed)
    rays = []
    for _ in range(count):
        origin = tuple(generator.uniform(-5.0, 5.0, 3).tolist())
        d, u = unit(*generator.normal(size=3).tolist())
        hit = test(constants, *origin, *d, *u, 0.0, INFINITY)
        if hit is not None:  # from where the ray meets the object: a sample ray's start
            point = tuple(o + di * hit for o, di in zip(origin, d))
            d_out, u_out = unit(*generator.normal(size=3).tolist())
            rays.append((point, d_out, u_out, INFINITY))
            rays.append((origin, d, u, hit))  # t_max at the hit itself
            rays.append((origin, d, u, math.nextafter(hit, 0.0)))  # just short of it
        rays.append((origin, d, u, INFINITY))
        rays.append((origin, d, u, float(generator.uniform(0.0, 10.0))))
    return rays


@PROPERTY
@given(primitives, st.integers(0, 2 ** 32 - 1), st.sampled_from([EPSILON, 0.0, -3.0]))
def test_each_array_test_answers_as_its_scalar_test(obj, seed, t_min):
    test, constants = _object_test(obj)
    rays = some_rays(obj, test, constants, seed)
    assert array_distances(test, constants, rays, t_min) == scalar_distances(
        test, constants, rays, t_min)


def test_a_plane_whose_distance_overflows_is_missed_in_both_tests():
    # d . n is subnormal: t = n . (p - o) / (d . n) is infinite, which no test takes
    plane = InfinitePlane(Vector3D(0.0, 0.0, -1.0), Vector3D(0.0, 0.0, 1.0))
    test, constants = _object_test(plane)
    d = (math.sqrt(0.5), math.sqrt(0.5), -1e-310)
    rays = [((0.0, 0.0, 0.0), d, d, INFINITY), ((0.0, 0.0, 0.0), (0.0, 0.0, -1.0),
                                                 (0.0, 0.0, -1.0), INFINITY)]
    assert array_distances(test, constants, rays, EPSILON) == [None, 1.0]
    assert scalar_distances(test, constants, rays, EPSILON) == [None, 1.0]


def test_a_ray_parallel_to_a_plane_misses_in_both_tests():
    for obj in (InfinitePlane(Vector3D(0.0, -1.0, 0.0), Vector3D(0.0, 1.0, 0.0)),
                Parallelogram(Vector3D(-1.0, -1.0, -3.0), Vector3D(2.0, 0.0, 0.0),
                              Vector3D(0.0, 0.0, 2.0))):
        test, constants = _object_test(obj)
        rays = [((0.0, -1.0, -2.0), (1.0, 0.0, 0.0), (1.0, 0.0, 0.0), INFINITY),
                ((0.0, 0.0, 0.0), (0.0, 0.0, -1.0), (0.0, 0.0, -1.0), INFINITY),
                ((0.0, 0.0, -2.0), (0.0, -1.0, 0.0), (0.0, -1.0, 0.0), INFINITY)]
        answers = array_distances(test, constants, rays, EPSILON)
        assert answers == scalar_distances(test, constants, rays, EPSILON)
        assert answers[:2] == [None, None] and answers[2] == 1.0


def test_a_sphere_far_away_rescales_its_squares_as_the_scalar_test():
    # (o - c) / r with components near 1e200: their squares overflow
    sphere = Sphere(Vector3D(1e200, 0.0, 0.0), 1.0)
    test, constants = _object_test(sphere)
    rays = [((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 0.0, 0.0), INFINITY),
            ((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 1.0, 0.0), INFINITY),
            ((1e200 - 0.5, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 0.0, 0.0), INFINITY)]
    answers = array_distances(test, constants, rays, EPSILON)
    assert answers == scalar_distances(test, constants, rays, EPSILON)
    assert answers[1] is None and answers[0] is not None


def test_a_ray_that_starts_on_a_sphere_and_leaves_it_touching_finds_the_scalar_tests_root():
    # from the surface, along the tangent: the discriminant is about zero, q about zero
    sphere = Sphere(Vector3D(0.0, 0.0, 0.0), 1.0)
    test, constants = _object_test(sphere)
    rays = [((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 1.0, 0.0), INFINITY),
            ((1.0, 0.0, 0.0), (-1.0, 0.0, 0.0), (-1.0, 0.0, 0.0), INFINITY),
            ((1.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 0.0, 0.0), INFINITY)]
    for t_min in (EPSILON, 0.0):
        answers = array_distances(test, constants, rays, t_min)
        assert answers == scalar_distances(test, constants, rays, t_min)
    assert array_distances(test, constants, rays, EPSILON)[1] == 2.0  # through it
