"""Unit tests for PyRT_Core's Scene: its objects, lights, queries and image, against values
computed by hand."""
import math

import cv2
import numpy as np
import pytest

import PyRT_Core
from helpers import as_tuple, assert_hit, ray, rgb
from PyRT_Common import Normalize, RGBColor, Ray, Vector3D
from PyRT_Core import Camera, InfinitePlane, Parallelogram, PointLight, Scene, Sphere


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


def test_set_environment_map_loads_the_map_of_the_scene_in_grey(tmp_path):
    # a 2 x 1 map: left half RGB (1, 2, 4), right half (8, 16, 0.5); straight ahead (u = 0.5)
    # reads the texel under floor(0.5 * (2 - 1)) = 0, the left one; read in grey as the
    # course reads it, 0.299 R + 0.587 G + 0.114 B in every channel
    path = tmp_path / "sky.hdr"
    image_rgb = np.array([[[1.0, 2.0, 4.0], [8.0, 16.0, 0.5]]], np.float32)
    assert cv2.imwrite(str(path), image_rgb[:, :, ::-1])
    scene = Scene()
    scene.set_environment_map(env_map_path=str(path))
    assert isinstance(scene.env_map, PyRT_Core.EnvironmentMap)
    assert scene.env_map.env_map_hdr.shape == (1, 2, 3)
    ahead, behind = (rgb(scene.env_map.getValue(Vector3D(0.0, 0.0, z))) for z in (-1.0, 1.0))
    assert ahead == pytest.approx((0.299 + 1.174 + 0.456,) * 3, rel=1e-2)
    assert behind == pytest.approx((2.392 + 9.392 + 0.057,) * 3, rel=1e-2)


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
