"""pyrt/scalar_intersections.py: each scalar test finds the distance, hit point and normal
that its primitive's intersect finds, bit for bit, and the shorter test of walls along the
axes finds, for camera rays, what the general parallelogram test finds."""
import math

from hypothesis import assume, given, settings
from hypothesis import strategies as st

from helpers import directions, primitives, vectors
from pyrt.acceleration.queries import _object_test
from PyRT_Common import *
from PyRT_Core import *
from pyrt.scalar_intersections import (POINT_AND_NORMAL, aligned_wall_distance, camera_test,
                                      parallelogram_distance)

PROPERTY = settings(max_examples=300, deadline=None)
lengths = st.floats(0.25, 3.0) | st.floats(-3.0, -0.25)


def scalar_answer(test, constants, ray):
    """(distance, hit point, normal) of a scalar test for ray, or None on a miss."""
    o, d = ray.o, ray.d
    u = Normalize(d)  # the direction the plane tests measure t along
    t = test(constants, o.x, o.y, o.z, d.x, d.y, d.z, u.x, u.y, u.z, ray.t_min, ray.t_max)
    if t is None:
        return None
    point_and_normal = POINT_AND_NORMAL[test](constants, o.x, o.y, o.z, d.x, d.y, d.z, u.x,
                                              u.y, u.z, t)
    return t, point_and_normal[:3], point_and_normal[3:]


def intersect_answer(obj, ray):
    """(distance, hit point, normal) of obj.intersect(ray), or None on a miss."""
    hit = obj.intersect(ray)
    if not hit.has_hit:
        return None
    p, n = hit.hit_point, hit.normal
    return hit.hit_distance, (p.x, p.y, p.z), (n.x, n.y, n.z)


@PROPERTY
@given(primitives, vectors, directions, st.floats(-6.0, 1.0), st.floats(0.0, 20.0))
def test_each_scalar_test_answers_as_its_primitives_intersect(obj, origin, direction,
                                                              t_min, length):
    # t_min down to -6: the hits behind a ray's origin count too, as for a ray that
    # starts inside a sphere or past it
    test, constants = _object_test(obj)
    for t_max in (t_min + length, INFINITY):
        ray = Ray(origin, direction, t_max, t_min)
        assert scalar_answer(test, constants, ray) == intersect_answer(obj, ray), ray


@st.composite
def walls_along_the_axes(draw):
    """A parallelogram with its sides along two different axes, at any place."""
    first, second = draw(st.permutations([0, 1, 2]))[:2]
    s1, s2 = [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
    s1[first], s2[second] = draw(lengths), draw(lengths)
    return Parallelogram(draw(vectors), Vector3D(*s1), Vector3D(*s2))


@PROPERTY
@given(walls_along_the_axes(), directions)
def test_a_wall_along_the_axes_gets_the_shorter_camera_test_with_the_same_answers(wall,
                                                                                   direction):
    test, constants = _object_test(wall)
    camera, camera_constants = camera_test(test, constants)
    assume(camera is aligned_wall_distance)  # not when the wall's plane holds the camera
    ray = Ray(Vector3D(0.0, 0.0, 0.0), direction, INFINITY, 0.0)
    assert scalar_answer(camera, camera_constants, ray) == intersect_answer(wall, ray), ray


def test_walls_askew_or_through_the_camera_keep_the_general_test():
    askew = Parallelogram(Vector3D(0.0, 0.0, -2.0), Vector3D(1.0, 0.0, 0.0),
                          Vector3D(1.0, 1.0, 0.0))  # normal along z, one side askew
    through_camera = Parallelogram(Vector3D(0.0, -1.0, -3.0), Vector3D(0.0, 2.0, 0.0),
                                   Vector3D(0.0, 0.0, 2.0))  # in the plane x = 0
    for wall in (askew, through_camera):
        assert camera_test(*_object_test(wall))[0] is parallelogram_distance


def test_a_camera_ray_whose_distance_overflows_misses_the_wall_in_both_tests():
    # d_z * n_z is subnormal: t = n_z p_z / (d_z n_z) is infinite; both tests miss
    wall = Parallelogram(Vector3D(-1.0, -1.0, -1.0), Vector3D(2.0, 0.0, 0.0),
                         Vector3D(0.0, 2.0, 0.0))
    ray = Ray(Vector3D(0.0, 0.0, 0.0), Vector3D(math.sqrt(0.5), math.sqrt(0.5), -1e-310),
              INFINITY, 0.0)
    test, constants = _object_test(wall)
    assert camera_test(test, constants)[0] is aligned_wall_distance
    assert scalar_answer(*camera_test(test, constants), ray) is None
    assert scalar_answer(test, constants, ray) is None
    assert not wall.intersect(ray).has_hit
