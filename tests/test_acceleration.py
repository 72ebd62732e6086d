"""pyrt/acceleration.py: the fast queries give the plain loops' answers, bit for bit, on
random scenes and rays; they never stand in for code of a student's own; their setup grows
with objects x lights; and Figure 1's seams fall as in the course's own render."""
import ast
import math
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import pyrt.acceleration.accelerated
import pyrt.acceleration.fingerprints
from AppRenderer import cornell_box_scene, sphere_test_scene
from helpers import REPO, fov90_scene, render_image, small_cornell_box
from pyrt.acceleration.accelerated import accelerated, can_accelerate, can_fuse
from pyrt.acceleration.phong import AcceleratedPhong
from pyrt.acceleration.queries import AcceleratedQueries
from PyRT_Common import *
from PyRT_Core import *
from PyRT_Integrators import *

PROPERTY = settings(max_examples=120, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
WHITE_LIGHT = RGBColor(1.0, 1.0, 1.0)
GREY = RGBColor(0.5, 0.5, 0.5)


def hit_fields(hit):
    """Everything a HitData tells, as plain numbers, for exact comparison."""
    if not hit.has_hit:
        return (False,)
    p, n = hit.hit_point, hit.normal
    return (True, hit.primitive_index, hit.hit_distance, (p.x, p.y, p.z), (n.x, n.y, n.z))


def assert_same_answers(scene, ray):
    """The fast queries of scene answer ray as Scene's plain methods do, exactly."""
    fast = AcceleratedQueries(scene)
    assert hit_fields(fast.closest_hit(ray)) == hit_fields(Scene.closest_hit(scene, ray)), ray
    assert fast.any_hit(ray) is Scene.any_hit(scene, ray), ray


# ------------------------------------------------------------------------------------------
# Random scenes and rays
# ------------------------------------------------------------------------------------------
class OwnSphere(Sphere):
    """A Sphere of a class of its own: the fast queries ask it through its intersect."""


class OwnParallelogram(Parallelogram):
    """A Parallelogram of a class of its own, asked through its intersect."""


coordinates = st.floats(-3.0, 3.0)
points = st.tuples(coordinates, coordinates, coordinates)
sides = points.filter(lambda v: sum(c * c for c in v) > 0.25)
lengths = st.floats(0.5, 3.0) | st.floats(-3.0, -0.5)


@st.composite
def aligned_sides(draw):
    """Two sides along two different axes (the walls of a room), or one side along an
    axis and the other in the same plane, askew."""
    first, second = draw(st.permutations([0, 1, 2]))[:2]
    s1, s2 = [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
    s1[first], s2[second] = draw(lengths), draw(lengths)
    if draw(st.booleans()):
        s2[first] = draw(lengths)
    return tuple(s1), tuple(s2)


@st.composite
def random_scenes(draw):
    """Parallelograms (some of classes of their own, some along the axes), spheres,
    infinite planes and 1 to 3 lights, some of them on an object's surface."""
    scene = Scene()
    for point, s1, s2, own in draw(st.lists(st.tuples(points, sides, sides, st.booleans()),
                                            max_size=5)):
        assume(Length(Cross(Vector3D(*s1), Vector3D(*s2))) > 0.3)
        kind = OwnParallelogram if own else Parallelogram
        scene.add_object(kind(Vector3D(*point), Vector3D(*s1), Vector3D(*s2)))
    for point, (s1, s2) in draw(st.lists(st.tuples(points, aligned_sides()), max_size=3)):
        scene.add_object(Parallelogram(Vector3D(*point), Vector3D(*s1), Vector3D(*s2)))
    for centre, radius, own in draw(st.lists(st.tuples(points, st.floats(0.1, 1.0),
                                                       st.booleans()), max_size=2)):
        scene.add_object((OwnSphere if own else Sphere)(Vector3D(*centre), radius))
    for point, normal in draw(st.lists(st.tuples(points, sides), max_size=1)):
        scene.add_object(InfinitePlane(Vector3D(*point), Vector3D(*normal)))
    for position in draw(st.lists(points, min_size=1, max_size=3)):
        scene.add_point_light_sources(PointLight(Vector3D(*position), WHITE_LIGHT))
    for obj, a, b in draw(st.lists(st.tuples(st.sampled_from(scene.object_list or [None]),
                                             st.floats(0.0, 1.0), st.floats(0.0, 1.0)),
                                   max_size=1 if scene.object_list else 0)):
        scene.add_point_light_sources(PointLight(on_surface(obj, a, b), WHITE_LIGHT))
    assume(any(type(obj) in (Sphere, Parallelogram, InfinitePlane)
               for obj in scene.object_list))
    return scene


def on_surface(obj, a, b):
    """A point of obj's surface: point + a s1 + b s2 of a parallelogram, a point of a
    sphere at the angles (pi a, 2 pi b), the plane's own point."""
    if isinstance(obj, Parallelogram):
        return obj.point + obj.s1 * a + obj.s2 * b
    if isinstance(obj, Sphere):
        theta, phi = math.pi * a, 2 * math.pi * b
        return obj.origin + Vector3D(math.sin(theta) * math.cos(phi),
                                     math.sin(theta) * math.sin(phi), math.cos(theta)) * obj.radius
    return obj.origin


@st.composite
def cornell_boxes(draw):
    """The Cornell box at some distance and of some size, its walls meeting at their
    edges, with 1 to 3 lights in it, around it and on its walls."""
    side = draw(st.floats(0.5, 4.0))
    scene = cornell_box_scene(draw(st.floats(0.0, 2.0)), side)
    scene.pointLights.clear()
    inside = st.tuples(st.floats(-0.6 * side, 0.6 * side), st.floats(-0.6 * side, 0.6 * side),
                       st.floats(-3.0 * side, 0.0))
    for position in draw(st.lists(inside, min_size=1, max_size=3)):
        scene.add_point_light_sources(PointLight(Vector3D(*position), WHITE_LIGHT))
    for index, a, b in draw(st.lists(st.tuples(st.integers(1, 5), st.floats(0.0, 1.0),
                                               st.floats(0.0, 1.0)), max_size=1)):
        scene.add_point_light_sources(
            PointLight(on_surface(scene.object_list[index], a, b), WHITE_LIGHT))
    return scene


scenes = st.one_of(random_scenes(), cornell_boxes())


@PROPERTY
@given(scenes, st.lists(points, min_size=1, max_size=4))
def test_camera_rays_and_their_shadow_rays_get_the_plain_answers(scene, targets):
    # Rays from the camera as render() traces them (t from 0 to infinity) and as students
    # build them (Ray(direction=d)), and from each hit the shadow rays of shadow_ray and
    # the students' own towards every light.
    for target in targets:
        direction = Vector3D(*target)
        assume(Length(direction) > 0.1)
        for ray in (Ray(Vector3D(0.0, 0.0, 0.0), Normalize(direction), INFINITY, 0.0),
                    Ray(direction=direction)):
            assert_same_answers(scene, ray)
            hit = Scene.closest_hit(scene, ray)
            if not hit.has_hit:
                continue
            for light in scene.pointLights:
                assert_same_answers(scene, shadow_ray(hit, light.pos))
                to_light = light.pos - hit.hit_point
                if Length(to_light) > 0.0:
                    assert_same_answers(scene, Ray(hit.hit_point, Normalize(to_light),
                                                   Length(to_light)))


@PROPERTY
@given(scenes, points, points, st.floats(-2.0, 2.0), st.floats(0.0, 10.0),
       st.floats(0.5, 2.0))
def test_any_ray_gets_the_plain_answers(scene, origin, target, t_min, length, scale):
    # Rays from anywhere, of any length, t_min negative too, directions of any length
    direction = Vector3D(*target) - Vector3D(*origin)
    assume(Length(direction) > 0.1)
    for t_max in (t_min + length, INFINITY):
        assert_same_answers(scene, Ray(Vector3D(*origin), direction * scale, t_max, t_min))


@PROPERTY
@given(scenes, st.lists(points, min_size=1, max_size=4))
def test_accelerated_phong_gives_the_colours_of_phong_integrators_own_code(scene, targets):
    # Every object gets a Lambertian colour of its own; objects of classes of their own
    # leave no AcceleratedPhong to compare, so they are left out of these scenes.
    scene.object_list[:] = [obj for obj in scene.object_list
                            if type(obj) in (Sphere, Parallelogram, InfinitePlane)]
    for number, obj in enumerate(scene.object_list):
        obj.set_BRDF(Lambertian(RGBColor(0.1 * number, 0.5, 1.0 - 0.1 * number)))
    scene.set_ambient(RGBColor(0.25, 0.5, 0.125))
    integrator = PhongIntegrator("unused")
    integrator.add_scene(scene)
    queries = AcceleratedQueries(scene)
    assert can_fuse("phong", integrator, queries)
    fast = AcceleratedPhong(integrator, queries)
    for target in targets:
        direction = Vector3D(*target)
        assume(Length(direction) > 0.1)
        ray = Ray(Vector3D(0.0, 0.0, 0.0), Normalize(direction), INFINITY, 0.0)
        expected = PhongIntegrator.compute_color(integrator, ray)  # plain queries
        assert tuple(fast.compute_color(ray)) == tuple(expected), ray


def test_the_course_images_are_the_same_with_and_without_the_fast_paths(monkeypatch,
                                                                         tmp_path):
    # Every integrator of the course's figures, on both scenes, bit for bit
    jobs = [(make(str(tmp_path / "img")), scene)
            for make in (IntersectionIntegrator, lambda f: DepthIntegrator(f, 5),
                         NormalIntegrator, PhongIntegrator)
            for scene in (small_cornell_box, lambda s: sphere_test_scene(width=s, height=s))]
    fast = [render_image(integrator, scene(30), workers=1) for integrator, scene in jobs]
    monkeypatch.setattr(pyrt.acceleration.accelerated, "can_accelerate", lambda scene: False)
    plain = [render_image(integrator, scene(30), workers=1) for integrator, scene in jobs]
    for a, b in zip(fast, plain):
        assert a.any() and np.array_equal(a, b)


# ------------------------------------------------------------------------------------------
# Student code runs: overridden and replaced methods
# ------------------------------------------------------------------------------------------
def missing(base):
    """A subclass of base whose intersect never hits."""
    return type("Never" + base.__name__, (base,), {"intersect": lambda self, ray: HitData()})


def farther(base):
    """A subclass of base whose intersect reports its hits 1 farther than they are."""
    def intersect(self, ray):
        hit = base.intersect(self, ray)
        if hit.has_hit:
            hit.hit_distance += 1.0
        return hit
    return type("Farther" + base.__name__, (base,), {"intersect": intersect})


def facing_wall(kind):
    """A primitive of `kind` (a class derived from one of PyRT's) covering the view of a
    camera at the origin looking down -z, 2 away."""
    if issubclass(kind, Sphere):
        return kind(Vector3D(0.0, 0.0, -3.0), 1.0)
    if issubclass(kind, InfinitePlane):
        return kind(Vector3D(0.0, 0.0, -2.0), Vector3D(0.0, 0.0, 1.0))
    return kind(Vector3D(-5.0, -5.0, -2.0), Vector3D(10.0, 0.0, 0.0), Vector3D(0.0, 10.0, 0.0))


BUILT_IN = [Sphere, InfinitePlane, Parallelogram]


@pytest.mark.parametrize("base", BUILT_IN, ids=lambda kind: kind.__name__)
def test_a_subclass_whose_intersect_misses_is_never_hit(base, tmp_path):
    scene = fov90_scene(3, 3, [(facing_wall(missing(base)), GREY)])
    scene.add_object(facing_wall(base))  # object 1: PyRT's own, to be accelerated
    scene.add_point_light_sources(PointLight(Vector3D(0.0, 0.0, 0.0), WHITE_LIGHT))
    ray = Ray(Vector3D(0.0, 0.0, 0.0), Vector3D(0.0, 0.0, -1.0), INFINITY, 0.0)
    assert can_accelerate(scene)
    fast = AcceleratedQueries(scene)
    assert fast.closest_hit(ray).primitive_index == Scene.closest_hit(scene, ray).primitive_index == 1
    scene.object_list[1:] = []
    fast = AcceleratedQueries(scene)
    assert fast.closest_hit(ray).has_hit is fast.any_hit(ray) is False
    assert not render_image(DepthIntegrator(str(tmp_path / "img"), 10.0), scene).any()


@pytest.mark.parametrize("base", BUILT_IN, ids=lambda kind: kind.__name__)
def test_a_subclass_whose_intersect_reports_another_distance_is_seen_there(base, tmp_path):
    # The subclass's hit lies 1 farther than its surface: a depth of 1 - d/10 with d one
    # more than the surface's distance (2 for the plane and the parallelogram, 2 for the
    # sphere's front at z = -2)
    scene = fov90_scene(1, 1, [(facing_wall(farther(base)), GREY)])
    ray = Ray(Vector3D(0.0, 0.0, 0.0), Vector3D(0.0, 0.0, -1.0), INFINITY, 0.0)
    assert AcceleratedQueries(scene).closest_hit(ray).hit_distance == pytest.approx(3.0)
    image = render_image(DepthIntegrator(str(tmp_path / "img"), 10.0), scene)
    assert image[0, 0] == pytest.approx([0.7, 0.7, 0.7])


def test_a_scene_subclass_with_its_own_queries_keeps_them_during_a_render(tmp_path):
    calls = []

    class CountingScene(Scene):
        def closest_hit(self, ray):
            calls.append(ray)
            return super().closest_hit(ray)

    scene = CountingScene()
    scene.add_object(facing_wall(Parallelogram))
    scene.set_camera(Camera(4, 4, 90))
    assert not can_accelerate(scene)
    render_image(NormalIntegrator(str(tmp_path / "img")), scene, workers=1)
    assert len(calls) == 16


def test_queries_assigned_to_the_scene_or_its_class_are_what_runs(monkeypatch, tmp_path):
    # As a student's script does: Scene.any_hit = my_any_hit (tests/student/render_all.py)
    scene = fov90_scene(4, 4, [(facing_wall(Parallelogram), GREY)])
    monkeypatch.setattr(scene, "any_hit", lambda ray: False, raising=False)
    assert not can_accelerate(scene)
    assert not render_image(IntersectionIntegrator(str(tmp_path / "a")), scene).any()
    monkeypatch.undo()
    monkeypatch.setattr(Scene, "any_hit", lambda self, ray: False)
    assert not can_accelerate(scene)
    assert not render_image(IntersectionIntegrator(str(tmp_path / "b")), scene).any()


def test_an_intersect_replaced_on_its_class_is_what_runs(monkeypatch, tmp_path):
    scene = fov90_scene(4, 4, [(facing_wall(Parallelogram), GREY)])
    monkeypatch.setattr(Parallelogram, "intersect", lambda self, ray: HitData())
    assert AcceleratedQueries(scene).everywhere[0][0] is None  # asked through intersect
    assert not render_image(IntersectionIntegrator(str(tmp_path / "img")), scene).any()


def test_a_function_edited_in_place_is_not_stood_in_for(monkeypatch):
    # An edit changes the function's source, which its fingerprint no longer matches
    scene = fov90_scene(4, 4, [(facing_wall(Sphere), GREY)])
    integrator = PhongIntegrator("unused")
    integrator.add_scene(scene)
    assert can_accelerate(scene) and can_fuse("phong", integrator, AcceleratedQueries(scene))
    monkeypatch.setitem(pyrt.acceleration.fingerprints.PHONG_FUNCTIONS, "shadow_ray", "0")
    assert can_accelerate(scene) and not can_fuse("phong", integrator,
                                                  AcceleratedQueries(scene))
    monkeypatch.setitem(pyrt.acceleration.fingerprints.QUERY_FUNCTIONS, "PyRT_Core.Normalize",
                        "0")
    assert not can_accelerate(scene)


def test_a_phong_subclass_with_its_own_compute_color_keeps_it(tmp_path):
    class Brighter(PhongIntegrator):
        def compute_color(self, ray):
            return super().compute_color(ray) * 2.0

    scene = fov90_scene(1, 1, [(facing_wall(Sphere), GREY)])
    scene.add_point_light_sources(PointLight(Vector3D(0.0, 0.0, 0.0), WHITE_LIGHT))
    brighter = render_image(Brighter(str(tmp_path / "a")), scene)
    plain = render_image(PhongIntegrator(str(tmp_path / "b")), scene)
    assert plain.any() and np.array_equal(brighter, 2.0 * plain)


def test_a_debugger_leaves_the_plain_code_to_run(monkeypatch):
    scene = fov90_scene(4, 4, [(facing_wall(Sphere), GREY)])
    assert can_accelerate(scene)
    previous = sys.gettrace()
    sys.settrace(lambda frame, event, arg: None)
    try:
        assert not can_accelerate(scene)
    finally:
        sys.settrace(previous)


FUNCTION = '''
def half(x):
    """Half of x."""
    return x / 2  # exact in binary
'''


def test_a_fingerprint_is_of_the_code_alone_not_of_its_docstrings_comments_or_layout():
    code_text = pyrt.acceleration.fingerprints.code_text
    assert code_text(ast.parse("x = 1")) == (
        "Module(body=[Assign(targets=[Name(id='x')], value=Constant(value=1))])")
    text = code_text(ast.parse(FUNCTION))
    reworded = FUNCTION.replace("Half of x.", "x halved.").replace("# exact in binary", "")
    assert code_text(ast.parse(reworded.replace("x / 2", "x/2"))) == text
    assert code_text(ast.parse(FUNCTION.replace("x / 2", "x * 0.5"))) != text


def test_the_fingerprints_are_those_of_the_functions_the_fast_paths_repeat():
    # A failure here means a function the fast paths repeat has changed: make the fast
    # path do what it does now, check it with this file's tests, and copy the new
    # fingerprints that `python -m pyrt.acceleration` prints into its tables.
    # The Phong integrator's functions are looked up where it registered itself.
    assert pyrt.acceleration.fingerprints.fused_integrator("phong") is PhongIntegrator
    for name, proven, now in pyrt.acceleration.fingerprints.mirrored_functions():
        assert now == proven, name


# ------------------------------------------------------------------------------------------
# Setup and its limits
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("count", [10, 100])
def test_the_setup_holds_objects_times_lights_entries(count):
    # one list for the camera, one for any ray, two for each of the 3 lights: 8 entries
    # per object, however many objects there are
    scene = Scene()
    for k in range(count):
        scene.add_object(Sphere(Vector3D(k * 0.1, 0.0, -5.0), 0.01))
    for x in (-1.0, 0.0, 1.0):
        scene.add_point_light_sources(PointLight(Vector3D(x, 3.0, 0.0), WHITE_LIGHT))
    fast = AcceleratedQueries(scene)
    lists = [fast.everywhere, fast.from_camera] + [
        entries for light in fast.towards_light for entries in light[7:9]]
    assert sum(map(len, lists)) == 8 * count


def test_a_render_of_a_few_pixels_keeps_the_plain_queries():
    scene = fov90_scene(2, 2, [(facing_wall(Sphere), GREY)])
    integrator = NormalIntegrator("unused")
    integrator.add_scene(scene)
    with accelerated(integrator, rays=4):
        assert "closest_hit" not in vars(scene)
    with accelerated(integrator, rays=1000):
        assert isinstance(scene.closest_hit.__self__, AcceleratedQueries)
    assert "closest_hit" not in vars(scene)


# ------------------------------------------------------------------------------------------
# The seams of Figure 1, as the course renders them
# ------------------------------------------------------------------------------------------
COURSE_SEAMS = REPO / "tests" / "data" / "course_figure1_seams.npz"


def test_figure1_shows_on_its_seams_what_the_course_renders(all_figures):
    # The course's own render of Figure 1 on the seams where the walls meet (the image's
    # diagonals, 3 pixels either side), stored from ../shared/course-renders by
    # tools/make_references.py: the course's camera arithmetic and strict tie rule give
    # the same surface, and the same colour to rounding, at every one of them.
    result, out = all_figures
    assert result.returncode == 0, result.stderr
    image = np.load(out / "rendered_image_Phong_figure1.npy")
    course = np.load(COURSE_SEAMS)
    ys, xs = course["y"], course["x"]
    assert len(ys) > 5000
    np.testing.assert_allclose(image[ys, xs], course["rgb"], rtol=1e-9, atol=0)


# ------------------------------------------------------------------------------------------
# Rays on the edge of what culling leaves out
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("centre, radius", [((0.3, -0.2, -4.0), 0.7), ((-2.0, 1.0, -9.0), 0.05),
                                            ((0.0, 0.0, -2.0), 1.5)])
def test_rays_grazing_a_sphere_get_the_plain_answers(centre, radius):
    # Rays from the camera at the angle asin(r/D) from the sphere's centre, the edge of the
    # cone it fills, give or take a few roundings: rounding decides whether they touch it,
    # and the cone the fast queries test first must not decide it otherwise.
    scene = Scene()
    scene.add_object(Sphere(Vector3D(*centre), radius))
    c = Vector3D(*centre)
    u = Normalize(c)
    v = Normalize(Cross(u, Vector3D(0.0, 1.0, 0.0)))
    w = Cross(u, v)
    edge = math.asin(radius / Length(c))
    for k in range(60):
        around = 2 * math.pi * k / 60
        for nudge in (-4e-16, -1e-16, 0.0, 1e-16, 4e-16):
            angle = edge * (1.0 + nudge)
            d = (u * math.cos(angle) + (v * math.cos(around) + w * math.sin(around))
                 * math.sin(angle))
            assert_same_answers(scene, Ray(Vector3D(0.0, 0.0, 0.0), d, INFINITY, 0.0))


@pytest.mark.parametrize("direction", [
    (0.6, 0.8, -1e-310), (0.6, -0.8, 1e-300), (1.0, 0.0, 0.0), (0.0, -1.0, -5e-324),
    (1 / math.sqrt(3),) * 2 + (-1 / math.sqrt(3),), (-0.5, -0.5, -math.sqrt(0.5))])
@pytest.mark.parametrize("scale", [2.0 ** -1000, 1.0, 2.0 ** 1000])
def test_camera_rays_at_walls_along_the_axes_get_the_plain_answers(direction, scale):
    # Walls along the axes, one through the camera, met head on, at their corners, at
    # angles whose distance overflows to infinity and along them: the shorter test that
    # camera rays get for such walls answers as the plain one.
    scene = Scene()
    for point, s1, s2 in [((-1, -1, -1), (2, 0, 0), (0, 2, 0)), ((1, -1, 0), (0, 0, -1), (0, 2, 0)),
                          ((-1, -1, 0), (2, 0, 0), (0, 0, -1)), ((0, 0, -1), (1, 0, 0), (0, 1, 0)),
                          ((0, -1, -1), (0, 1, 0), (0, 0, 1))]:
        scene.add_object(Parallelogram(*(Vector3D(*v) * scale for v in (point, s1, s2))))
    assert_same_answers(scene, Ray(Vector3D(0.0, 0.0, 0.0), Vector3D(*direction), INFINITY, 0.0))


def test_rays_that_end_near_a_light_but_not_at_it_get_the_plain_answers():
    # A light at the origin of a small ball 1e-3 behind it: rays from the floor towards
    # the light that end a little past it meet the ball, those that end short of it do not;
    # the ends lie too far from the light for its own list of objects to hold.
    scene = Scene()
    scene.add_object(Parallelogram(Vector3D(-2.0, -1.0, 2.0), Vector3D(4.0, 0.0, 0.0),
                                   Vector3D(0.0, 0.0, -4.0)))
    light = Vector3D(0.0, 1.0, 0.0)
    scene.add_object(Sphere(light + Vector3D(0.0, 1.5e-3, 0.0), 1e-3))
    scene.add_point_light_sources(PointLight(light, WHITE_LIGHT))
    for x in (-1.5, -0.5, 0.0, 0.7):
        origin = Vector3D(x, -1.0, 0.25)
        to_light = light - origin
        d = Normalize(to_light)
        for beyond in (-1e-3, -1e-4, 1e-4, 1e-3, 3e-3):
            ray = Ray(origin, d, Length(to_light) + beyond, 1e-6)
            assert_same_answers(scene, ray)
            assert Scene.any_hit(scene, ray) is (beyond > 5e-4)
