"""Unit tests for PyRT_Core's shadow rays: visible_lights, and any_hit from a hit point to a
light, against values computed by hand."""
import math

import pytest

import pyrt.acceleration.queries
from helpers import approx3, as_tuple, assert_hit, ray, rgb, visible_lights
from PyRT_Common import (EPSILON, HUGEVALUE, Cross, Dot, HitData, Length, Normalize, RGBColor,
                         Ray, Vector3D)
from PyRT_Core import (Camera, InfinitePlane, Lambertian, Parallelogram, PointLight, Primitive,
                       Scene, Sphere)


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
