"""A pixel's history (pyrt/explain.py): the stories of pixels worked out by hand from the
scenes' numbers in AppRenderer.py (the course's) and from small scenes built here.

The Cornell box of Figure 1 (dist 0.75, side 2): the sphere, object 0, has its centre at
(0, 0, -1.75) and radius 0.25; the floor, object 2, is y = -1 for x in [-1, 1] and z in
[-2.75, -0.75]; lights 0, 1 and 2 hang at y = 0.5, z = -1.75 and x = 0, -0.5, 0.5.
A floor point P = (px, -1, pz) near (0, -1, -1.75), straight below the sphere, sees light
0 through the sphere, which it meets 0.75 up, at y = -0.25. Light 1 it sees past the
sphere: in the plane z = -1.75 the line from (0, -1) to (-0.5, 0.5) passes the sphere's
centre (0, 0) at a distance |(-0.5)(1) - (1.5)(0)| / sqrt(0.5^2 + 1.5^2) = 0.316, more
than the radius; light 2 likewise, mirrored.
"""
import math
import sys

import numpy as np
import pytest

import pyrt.acceleration.accelerated
from AppRenderer import cornell_box_scene, sphere_test_scene
from helpers import (ShadowRayFrom, StudentPhongIntegrator, fov90_scene, read_png,
                     render_image)
from PyRT_Core import *
from pyrt.explain import explain_pixel, vector
from pyrt.explain_picture import merged_labels, save_picture
from PyRT_Integrators import *

FLOOR_PIXEL = (250, 453)  # of Figure 1, 500 x 500: the floor straight below the sphere


def figure1_floor_point():
    """Where the camera ray of FLOOR_PIXEL meets the floor y = -1, from the camera's
    formula (x_s = 2(x + 0.5)/500 - 1, y_s = 1 - 2(y + 0.5)/500, field of view 70)."""
    x, y = FLOOR_PIXEL
    scale = math.tan(math.radians(35))
    direction = ((2 * (x + 0.5) / 500 - 1) * scale, (1 - 2 * (y + 0.5) / 500) * scale, -1.0)
    s = -1.0 / direction[1]
    return tuple(c * s for c in direction)


def sphere_entry(start, target, centre, radius):
    """The distance from start, towards target, to where the segment enters the sphere."""
    length = math.dist(start, target)
    d = [(t - s) / length for s, t in zip(start, target)]
    f = [s - c for s, c in zip(start, centre)]
    b = sum(a * c for a, c in zip(f, d))
    c = sum(a * a for a in f) - radius * radius
    return -b - math.sqrt(b * b - c)


def test_a_floor_pixel_of_figure_1_below_the_sphere_is_in_the_shadow_of_light_0_only():
    integrator = PhongIntegrator("unused")
    integrator.add_scene(cornell_box_scene(0.75, 2))
    history = integrator.explain_pixel(*FLOOR_PIXEL)
    point = figure1_floor_point()

    camera = history.camera_hit
    assert camera.role == "camera ray" and camera.method == "closest_hit"
    assert camera.hit.index == 2 and camera.hit.normal == (0.0, 1.0, 0.0)
    assert camera.hit.distance == pytest.approx(math.dist((0, 0, 0), point), rel=1e-9)
    assert [(q.light, q.method, q.blocked) for q in history.shadow_rays()] == [
        (0, "any_hit", True), (1, "any_hit", False), (2, "any_hit", False)]
    blocker = history.shadow_rays()[0].blocker
    assert (blocker.index, blocker.kind) == (0, "Sphere")
    entry = sphere_entry(point, (0.0, 0.5, -1.75), (0.0, 0.0, -1.75), 0.25)
    assert entry == pytest.approx(0.75, abs=1e-3)  # the point is a hair off (0, -1, -1.75)
    # shadow_ray starts 2^-32 (|coordinates| + distance), about 1e-9, above the floor
    assert blocker.answer.distance == pytest.approx(entry, abs=1e-8)

    # The colour: kd (x) i_a + light 1 + light 2, kd = 0.8/pi, each visible light adding
    # 0.5 kd cos / r^2 with cos = 1.5 / r (the floor's normal is +y)
    kd = 0.8 / math.pi
    lit = sum(0.5 * kd * 1.5 / math.dist(point, light) ** 3
              for light in ((-0.5, 0.5, -1.75), (0.5, 0.5, -1.75)))
    assert history.color == pytest.approx((kd + lit, kd + lit, 0.3 * kd + lit), rel=1e-9)
    story = str(history)
    assert "shadow ray to light 0 -> any_hit True: blocked by object 0 (Sphere) at 0.75" in story
    assert "shadow ray to light 1 -> any_hit False: visible" in story
    assert history.notes == []


def test_a_background_pixel_tells_that_every_object_missed():
    # Pixel (0, 0) of the sphere scene looks up and left, along (-1, 1, -sqrt 3)/sqrt 5
    # (x_s = y_s = 0.998 with tan 30 = 1/sqrt 3): upwards it cannot meet the floor below
    # the camera (y = -2), and it passes the sphere (centre 5 away, radius 2, seen within
    # asin(2/5) = 23.6 degrees of -z) at acos(sqrt(3/5)) = 39.2 degrees from -z.
    integrator = PhongIntegrator("unused")
    integrator.add_scene(sphere_test_scene())
    history = explain_pixel(integrator, 0, 0)
    [camera] = history.events
    assert camera.role == "camera ray" and not camera.hit.has_hit
    assert [(e.index, e.kind, e.answer.has_hit) for e in camera.intersects] == [
        (0, "Sphere", False), (1, "Parallelogram", False)]
    assert history.shadow_rays() == [] and history.color == (0.0, 0.0, 0.0)
    assert "camera ray -> closest_hit: no hit" in str(history)
    assert "every object missed (2 asked)" in str(history)


def wall_scene():
    """A 1 x 1 image looking straight down -z at a wall z = -2 (object 0), one light at
    (1, 0, -1) in front of it. The camera ray (0, 0, -1) meets the wall at t = 2 exactly,
    at the point (0, 0, -2), which lies exactly on the wall's plane."""
    wall = Parallelogram(Vector3D(-1.0, -1.0, -2.0), Vector3D(2.0, 0.0, 0.0),
                         Vector3D(0.0, 2.0, 0.0))
    return fov90_scene(1, 1, [(wall, RGBColor(0.5, 0.5, 0.5))],
                       [(Vector3D(1.0, 0.0, -1.0), RGBColor(1.0, 1.0, 1.0))],
                       ambient=RGBColor(0.1, 0.1, 0.1))


def test_a_shadow_ray_without_offset_hits_its_own_surface_and_is_called_shadow_acne():
    # Started on the plane with t_min 0, the shadow ray meets the wall at t = 0/(d.n) = 0
    integrator = ShadowRayFrom(0.0)
    integrator.add_scene(wall_scene())
    history = explain_pixel(integrator, 0, 0)
    [shadow] = history.shadow_rays()
    assert shadow.light == 0 and shadow.blocked and shadow.acne
    assert (shadow.blocker.index, shadow.blocker.answer.distance) == (0, 0.0)
    assert "blocked by object 0 (Parallelogram) at 0, its own surface: SHADOW ACNE" in str(
        history)
    [note] = history.notes
    assert note.startswith("shadow acne: the shadow ray to light 0 hits object 0")
    assert "EPSILON" in note
    # only the ambient term is left: 0.5/pi x 0.1
    assert history.color == pytest.approx((0.05 / math.pi,) * 3, rel=1e-12)


def test_the_same_shadow_ray_starting_epsilon_along_sees_its_light():
    integrator = ShadowRayFrom(EPSILON)
    integrator.add_scene(wall_scene())
    history = explain_pixel(integrator, 0, 0)
    [shadow] = history.shadow_rays()
    assert shadow.light == 0 and not shadow.blocked and not shadow.acne
    assert history.notes == [] and "visible" in str(history)


def test_an_any_hit_of_numpys_false_assigned_to_the_scene_leaves_the_light_visible():
    integrator = ShadowRayFrom(EPSILON)
    scene = wall_scene()
    scene.any_hit = lambda ray: np.bool_(Scene.any_hit(scene, ray))  # the student's own
    integrator.add_scene(scene)
    [shadow] = explain_pixel(integrator, 0, 0).shadow_rays()
    assert (shadow.answer, shadow.blocked) == (False, False)
    assert len(shadow.intersects) == 1  # the wall, asked by the student's any_hit


class AnyHitByClosestHit(Scene):
    """A student's Scene whose any_hit asks its closest_hit."""

    def any_hit(self, ray):
        return self.closest_hit(ray).has_hit


def test_a_students_own_any_hit_shows_the_closest_hit_it_asks_inside_it():
    # The camera ray meets the wall z = -4 (object 0) at (0, 0, -4); the shadow ray from
    # there to the light at (2, 0, -2) runs along (1, 0, 1)/sqrt 2 through the centre of
    # the sphere (1, 0, -3) of radius 0.25 (object 1), sqrt 2 away: it enters at
    # sqrt 2 - 0.25.
    scene = AnyHitByClosestHit()
    wall = Parallelogram(Vector3D(-2.0, -2.0, -4.0), Vector3D(4.0, 0.0, 0.0),
                         Vector3D(0.0, 4.0, 0.0))
    for obj in (wall, Sphere(Vector3D(1.0, 0.0, -3.0), 0.25)):
        obj.set_BRDF(Lambertian(RGBColor(0.5, 0.5, 0.5)))
        scene.add_object(obj)
    scene.add_point_light_sources(PointLight(Vector3D(2.0, 0.0, -2.0), RGBColor(1, 1, 1)))
    scene.set_camera(Camera(1, 1, 90))
    before = {name: value for name, value in vars(scene).items()}
    integrator = StudentPhongIntegrator("unused")
    integrator.add_scene(scene)

    history = explain_pixel(integrator, 0, 0)
    camera, shadow = history.events
    assert (camera.hit.index, camera.hit.distance) == (0, 4.0)
    assert shadow.method == "any_hit" and shadow.answer is True and shadow.light == 0
    assert shadow.intersects == []  # they belong to the closest_hit asked inside it
    [inner] = shadow.nested
    assert inner.method == "closest_hit" and inner.hit.index == 1
    assert inner.hit.distance == pytest.approx(math.sqrt(2) - 0.25, rel=1e-12)
    assert [(e.index, e.answer.has_hit) for e in inner.intersects] == [(0, False), (1, True)]
    assert (shadow.blocker.index, shadow.blocked, shadow.acne) == (1, True, False)
    story = str(history).splitlines()
    assert any(line.startswith("    shadow ray to light 0 -> closest_hit at 1.16")
               for line in story)  # nested, indented one step further

    # and nothing of the scene changed: no recorder left on it or its objects
    assert vars(scene) == before
    assert all("intersect" not in vars(obj) for obj in scene.object_list)
    assert not np.any(scene.rendered_image)


class Returns(Integrator):
    """compute_color returns `color` after asking the scene's closest_hit."""

    def __init__(self, color):
        super().__init__("unused")
        self.color = color

    def compute_color(self, ray):
        self.scene.closest_hit(ray)
        return self.color


@pytest.mark.parametrize("color, note", [
    ((0.5, 0.5, 0.5), "the colour (0.5, 0.5, 0.5) is not an RGBColor"),
    (None, "the colour None is not an RGBColor: compute_color must return one (a `pass` "
           "left in returns None)"),
    (RGBColor(float("nan"), 0.0, 0.0), "has NaN (not a number) in it"),
])
def test_a_colour_that_is_not_an_rgbcolor_or_has_nan_is_pointed_out(color, note):
    integrator = Returns(color)
    integrator.add_scene(wall_scene())
    [found] = explain_pixel(integrator, 0, 0).notes
    assert note in found


class LongNormals(Parallelogram):
    """A Parallelogram whose hits come with their normal doubled."""

    def intersect(self, ray):
        hit = super().intersect(ray)
        hit.normal = hit.normal * 2.0
        return hit


def test_a_normal_that_is_not_of_unit_length_is_pointed_out():
    wall = LongNormals(Vector3D(-1.0, -1.0, -2.0), Vector3D(2.0, 0.0, 0.0),
                       Vector3D(0.0, 2.0, 0.0))
    integrator = NormalIntegrator("unused")
    integrator.add_scene(fov90_scene(1, 1, [(wall, RGBColor(0.5, 0.5, 0.5))]))
    [note] = explain_pixel(integrator, 0, 0).notes
    assert note.startswith("the normal (0, 0, 2) of the camera ray's hit has length 2, not 1")


class Raises(Integrator):
    def compute_color(self, ray):
        self.scene.closest_hit(ray)
        return RGBColor(1.0, 0.0, 0.0) / 0


def test_an_error_of_compute_color_ends_the_story_after_what_was_asked_before_it():
    integrator = Raises("unused")
    integrator.add_scene(wall_scene())
    history = explain_pixel(integrator, 0, 0)
    assert history.error.startswith("ZeroDivisionError")
    lines = str(history).splitlines()
    assert lines[1].startswith("  camera ray -> closest_hit: object 0 (Parallelogram)")
    assert lines[-1].startswith("  -> compute_color raised ZeroDivisionError")
    assert "closest_hit" not in vars(integrator.scene)


def test_explain_runs_on_the_plain_queries_while_a_render_has_swapped_them():
    integrator = PhongIntegrator("unused")
    integrator.add_scene(cornell_box_scene(0.75, 2))
    plain = str(explain_pixel(integrator, *FLOOR_PIXEL))
    with pyrt.acceleration.accelerated.accelerated(integrator):
        fast = vars(integrator.scene)["closest_hit"]
        during = explain_pixel(integrator, *FLOOR_PIXEL)
        assert vars(integrator.scene)["closest_hit"] is fast  # put back as it was
    assert len(during.camera_hit.intersects) == 6  # every object asked, as the course's loop
    assert str(during) == plain


def test_the_colour_told_is_the_colour_that_render_gave_each_pixel(tmp_path):
    integrator = PhongIntegrator(str(tmp_path / "image"))
    scene = cornell_box_scene(0.75, 2, width=12, height=12)
    image = render_image(integrator, scene, workers=1)
    for y in range(12):
        for x in range(12):
            history = explain_pixel(integrator, x, y)
            assert history.image_color == tuple(image[y, x])
            assert history.color == pytest.approx(history.image_color, rel=1e-12)
            assert history.notes == []


def test_a_pixel_that_render_coloured_otherwise_is_pointed_out():
    integrator = Returns(RGBColor(0.25, 0.5, 0.75))
    integrator.add_scene(wall_scene())
    integrator.scene.rendered_image[0, 0] = (0.75, 0.5, 0.25)  # as set_pixel would put it
    [note] = explain_pixel(integrator, 0, 0).notes
    assert note.startswith("the rendered image holds (0.75, 0.5, 0.25) at this pixel, not "
                           "this colour")


@pytest.mark.parametrize("pixel", [(500, 0), (0, 500), (-1, 0), (2.5, 3)])
def test_a_pixel_outside_the_image_is_refused_with_the_range(pixel):
    integrator = PhongIntegrator("unused")
    integrator.add_scene(sphere_test_scene())
    with pytest.raises(ValueError, match=r"x goes from 0 to 499, y from 0 to 499"):
        explain_pixel(integrator, *pixel)


@pytest.mark.parametrize("value, components", [
    (Vector3D(1.0, 2.0, 3.0), (1.0, 2.0, 3.0)),
    (np.array([1.0, 2.0, 3.0]), (1.0, 2.0, 3.0)),  # the 2021-22 course's Ray defaults
    ("abc", None), (None, None),
])
def test_vectors_of_every_edition_are_read(value, components):
    assert vector(value) == components


def test_the_picture_is_saved_where_asked(tmp_path):
    integrator = PhongIntegrator("unused")
    integrator.add_scene(cornell_box_scene(0.75, 2))
    history = explain_pixel(integrator, *FLOOR_PIXEL)
    path = save_picture(history, integrator.scene, tmp_path / "new" / "pixel.png")
    assert path == tmp_path / "new" / "pixel.png"
    picture = read_png(path)
    assert picture.shape == (450, 990, 3)  # 11 x 5 inches at 90 dots per inch
    # the blocked shadow ray is drawn in red: matplotlib's tab:red is (214, 39, 40)
    red = np.all(np.abs(picture * 255 - (214, 39, 40)) < 2, axis=2)
    assert red.sum() > 50


def test_labels_of_points_that_coincide_in_a_view_are_merged_into_one():
    # A view 10 across merges labels closer than 0.03 x 10 = 0.3 to a group's first point:
    # the camera and a light above it (the sphere scene's top view), and a hit 0.2 from
    # the middle of an edge-on floor; the sphere's centre lies 2 from that hit.
    labels = [((0.0, 0.0), "camera"), ((0.0, 0.0), "light 0"), ((5.0, -2.0), "acne"),
              ((5.2, -2.0), "object 1"), ((5.0, 0.0), "object 0")]
    assert merged_labels(labels, 10.0) == [((0.0, 0.0), ["camera", "light 0"]),
                                           ((5.0, -2.0), ["acne", "object 1"]),
                                           ((5.0, 0.0), ["object 0"])]


def test_a_label_joins_a_group_by_its_distance_to_the_groups_first_point():
    # 0.25 from the first point joins it; 0.5 from it does not, though 0.25 from the second
    labels = [((0.0, 0.0), "a"), ((0.0, 0.25), "b"), ((0.0, 0.5), "c")]
    assert merged_labels(labels, 10.0) == [((0.0, 0.0), ["a", "b"]), ((0.0, 0.5), ["c"])]
    # in a view 100 across, 0.5 is far below 3: one label; in one 1 across, 0.25 is apart
    assert merged_labels(labels, 100.0) == [((0.0, 0.0), ["a", "b", "c"])]
    assert merged_labels(labels, 1.0) == [((0.0, 0.0), ["a"]), ((0.0, 0.25), ["b"]),
                                          ((0.0, 0.5), ["c"])]


# The course's own base code, as far as explain_pixel meets it: plain classes without
# PyRT's checks, a Ray whose defaults are numpy arrays (2021-22) and that has no t_min
# argument, a Normalize that divides by the length.
COURSE_BASE = '''
from math import sqrt
import numpy as np
EPSILON = 0.0001

class Vector3D:
    def __init__(self, x, y, z):
        self.x, self.y, self.z = x, y, z
    def __add__(self, w):
        return Vector3D(self.x + w.x, self.y + w.y, self.z + w.z)
    def __sub__(self, w):
        return Vector3D(self.x - w.x, self.y - w.y, self.z - w.z)
    def __mul__(self, s):
        return Vector3D(self.x * s, self.y * s, self.z * s)

def Dot(a, b):
    return a.x * b.x + a.y * b.y + a.z * b.z

def Normalize(v):
    return v * (1.0 / sqrt(Dot(v, v)))

class Ray:
    made = []
    def __init__(self, origin=np.array([0, 0, 0]), direction=np.array([0, 0, 0]), tmax=1e6):
        self.o, self.d, self.t_max, self.t_min = origin, direction, tmax, EPSILON
        Ray.made.append(self)

class HitData:
    def __init__(self, has_hit=False, hit_point=None, normal=None, hit_distance=1e6,
                 primitive_index=-1):
        self.has_hit, self.hit_point, self.normal = has_hit, hit_point, normal
        self.hit_distance, self.primitive_index = hit_distance, primitive_index

class Sphere:
    def __init__(self, origin, radius):
        self.origin, self.radius = origin, radius
    def intersect(self, ray):
        d, oc = Normalize(ray.d), ray.o - self.origin
        b, c = 2 * Dot(d, oc), Dot(oc, oc) - self.radius ** 2
        disc = b * b - 4 * c
        if disc < 0:
            return HitData()
        t = (-b - sqrt(disc)) / 2
        if not ray.t_min <= t <= ray.t_max:
            return HitData()
        p = ray.o + d * t
        return HitData(True, p, Normalize(p - self.origin), t)

class Camera:
    width = height = 1
    def get_direction(self, x, y):
        return Vector3D(0.0, 0.0, -1.0)

class Scene:
    def __init__(self):
        self.object_list, self.pointLights, self.camera = [], [], Camera()
    def closest_hit(self, ray):
        closest = HitData()
        for index, obj in enumerate(self.object_list):
            hit = obj.intersect(ray)
            if hit.has_hit and hit.hit_distance < closest.hit_distance:
                closest, closest.primitive_index = hit, index
        return closest
'''


class CourseDepth:
    """A student's integrator on the course's base code: no explain_pixel of its own, and
    a compute_color that returns the distance itself instead of an RGBColor."""

    def __init__(self, scene):
        self.scene = scene

    def compute_color(self, ray):
        return self.scene.closest_hit(ray).hit_distance


def test_an_integrator_on_the_course_base_code_is_explained_with_the_courses_ray(monkeypatch):
    # The camera ray (0, 0, -1) meets the unit sphere around (0, 0, -5) at distance 4,
    # at (0, 0, -4), where the outward normal is (0, 0, 1).
    module = type(sys)("course_base_core")
    exec(COURSE_BASE, module.__dict__)
    monkeypatch.setitem(sys.modules, "course_base_core", module)
    scene = module.Scene()
    scene.object_list.append(module.Sphere(module.Vector3D(0.0, 0.0, -5.0), 1.0))
    history = explain_pixel(CourseDepth(scene), 0, 0)
    assert len(module.Ray.made) == 1  # the camera ray is the course's Ray
    assert history.camera_ray.t_min == 0.0001
    hit = history.camera_hit.hit
    assert (hit.index, hit.distance, hit.point, hit.normal) == (
        0, 4.0, (0.0, 0.0, -4.0), (0.0, 0.0, 1.0))
    assert history.notes == ["the colour 4.0 is not an RGBColor: compute_color must return "
                             "one"]
