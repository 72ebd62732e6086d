"""The course framework's arithmetic for a hit (course_kit/arithmetic.py), against hand
calculations and against PyRT's own primitives away from the edges."""
import sys

import numpy as np

import AppRenderer
import course_kit.arithmetic
import course_kit.handout
import course_kit.references
from helpers import render_image
from PyRT_Common import BLACK, EPSILON, Dot, Normalize, Ray, Vector3D
from PyRT_Core import InfinitePlane, Parallelogram, Scene, Sphere
from PyRT_Integrators import Integrator

sys.path.insert(0, str(course_kit.handout.CHECKS))
import practice1_render as render  # noqa: E402  (found through the line above)

COURSE_SEAMS = course_kit.handout.REPO / "tests" / "data" / "course_figure1_seams.npz"
SEAM_SAMPLE = 5  # every 5th of Figure 1's 6952 seam pixels: a second of rendering

SQUARE = Parallelogram(Vector3D(0.0, 0.0, -2.0), Vector3D(1.0, 0.0, 0.0),
                       Vector3D(0.0, 1.0, 0.0))


def towards(x, y, z):
    return Ray(Vector3D(0.0, 0.0, 0.0), Normalize(Vector3D(x, y, z)))


def test_a_parallelogram_is_hit_inside_and_missed_outside():
    hit = course_kit.arithmetic.parallelogram_intersect(SQUARE, towards(0.5, 0.5, -2.0))
    assert hit.has_hit
    assert abs(hit.hit_distance - np.sqrt(4.5)) < 1e-12  # |(0.5, 0.5, -2)|
    assert (hit.normal.x, hit.normal.y, hit.normal.z) == (0.0, 0.0, 1.0)  # faces the ray
    assert not course_kit.arithmetic.parallelogram_intersect(SQUARE, towards(1.01, 0.5, -2)).has_hit
    assert not course_kit.arithmetic.parallelogram_intersect(SQUARE, towards(-0.01, 0.5,
                                                                         -2)).has_hit
    # its corner is inside: the course would divide by its zero distance from the corner
    assert course_kit.arithmetic.parallelogram_intersect(SQUARE, towards(0.0, 0.0, -1.0)).has_hit


def test_a_ray_parallel_to_a_plane_or_beyond_t_max_misses():
    plane = InfinitePlane(Vector3D(0.0, -1.0, 0.0), Vector3D(0.0, 1.0, 0.0))
    assert not course_kit.arithmetic.plane_intersect(plane, towards(1.0, 0.0, 0.0)).has_hit
    down = towards(0.0, -1.0, 0.0)
    assert course_kit.arithmetic.plane_intersect(plane, down).hit_distance == 1.0
    down.t_max = 0.5
    assert not course_kit.arithmetic.plane_intersect(plane, down).has_hit


def test_a_sphere_is_hit_at_its_near_side_then_from_inside_at_its_far_side():
    sphere = Sphere(Vector3D(0.0, 0.0, -5.0), 1.0)
    ray = towards(0.0, 0.0, -1.0)
    hit = course_kit.arithmetic.sphere_intersect(sphere, ray)
    assert (hit.has_hit, hit.hit_distance, hit.normal.z) == (True, 4.0, 1.0)
    ray.t_min = 5.0
    assert course_kit.arithmetic.sphere_intersect(sphere, ray).hit_distance == 6.0
    ray.t_min = EPSILON
    assert not course_kit.arithmetic.sphere_intersect(sphere, towards(0.0, 1.0, -1.0)).has_hit


def test_away_from_the_edges_it_answers_as_pyrts_primitives():
    scene = render.cornell_box(40)
    course = course_kit.arithmetic.with_course_arithmetic(render.cornell_box(40))
    camera = scene.camera
    for y in range(0, 40, 3):
        for x in range(0, 40, 3):
            if abs(x - y) <= 1 or abs(x + y - 39) <= 1:
                continue  # the image's diagonals: the box's edges
            ray = Ray(Vector3D(0.0, 0.0, 0.0), camera.get_direction(x, y))
            ours, theirs = Scene.closest_hit(scene, ray), Scene.closest_hit(course, ray)
            assert ours.primitive_index == theirs.primitive_index, (x, y)
            assert abs(ours.hit_distance - theirs.hit_distance) < 1e-12


def test_it_lets_the_rays_through_the_cornell_boxs_corners_at_40_pixels():
    # What the course's framework renders at 40 x 40: pixels (35, 4) and (4, 35) see the
    # background between two walls, where PyRT's edge tolerance closes the crack.
    scene = render.cornell_box(40)
    course = course_kit.arithmetic.with_course_arithmetic(render.cornell_box(40))
    for x, y in ((35, 4), (4, 35)):
        ray = Ray(Vector3D(0.0, 0.0, 0.0), scene.camera.get_direction(x, y))
        assert not Scene.closest_hit(course, ray).has_hit
        assert Scene.closest_hit(scene, ray).has_hit


def test_it_renders_figure_1s_seams_as_the_course_did():
    # The course's Figure 1 on the Cornell box's seams (tests/data, stored from the course
    # framework's own render): with shadow rays lifted EPSILON along the normal, the
    # course's arithmetic sees at every one of these pixels the surface and the shadows
    # the course saw, so its colour to the rounding of the terms' order.
    scene = course_kit.arithmetic.with_course_arithmetic(AppRenderer.cornell_box_scene(0.75, 2))
    phong = course_kit.references.PhongVariant(
        "unused", blocked=course_kit.references.blocked_from_lifted_start)
    phong.add_scene(scene)
    with np.load(COURSE_SEAMS) as seams:
        ys, xs, course = (seams[key][::SEAM_SAMPLE] for key in ("y", "x", "rgb"))
    for y, x, expected in zip(ys.tolist(), xs.tolist(), course):
        colour = phong.compute_color(Ray(Vector3D(0.0, 0.0, 0.0),
                                         scene.camera.get_direction(x, y)))
        np.testing.assert_allclose((colour.r, colour.g, colour.b), expected, rtol=1e-12,
                                   atol=0, err_msg=f"pixel ({x}, {y})")


class IndexShadowPhong(Integrator):
    """A Phong of a public student solution: a light counts when the first object its ray
    towards the hit point meets is the hit's own object (compared by primitive_index)."""

    def __init__(self, filename_):
        super().__init__(filename_ + "_IndexShadow")

    def compute_color(self, ray):
        scene = self.scene
        hit = scene.closest_hit(ray)
        if not hit.has_hit:
            return BLACK
        brdf = scene.object_list[hit.primitive_index].get_BRDF()
        color = brdf.kd.multiply(scene.i_a)
        for light in scene.pointLights:
            to_hit = hit.hit_point - light.pos
            first = scene.closest_hit(Ray(light.pos, Normalize(to_hit)))
            if first.has_hit and first.primitive_index == hit.primitive_index:
                wi = Normalize(light.pos - hit.hit_point)
                f = brdf.get_value(wi, ray.d * -1.0, hit.normal)
                color = color + light.intensity.multiply(f) / Dot(to_hit, to_hit)
        return color


def test_a_shadow_test_by_object_index_sees_on_pyrt_what_it_sees_on_the_course(tmp_path):
    # At the seams the light's ray meets two walls at the same t but for its last bits, and
    # which one comes first decides the pixel: PyRT's planes measure t along the direction
    # normalised once more, as the course's do, so at 64 x 64 (where 7 pixels differed
    # while PyRT took a unit direction as it was) every pixel is the course's, to rounding.
    size = 64
    course_scene = course_kit.arithmetic.with_course_arithmetic(
        AppRenderer.cornell_box_scene(0.75, 2, width=size, height=size))
    student = IndexShadowPhong("unused")
    student.add_scene(course_scene)
    camera = course_scene.camera
    course = np.zeros((size, size, 3))
    for y in range(size):
        for x in range(size):
            colour = student.compute_color(Ray(Vector3D(0.0, 0.0, 0.0),
                                               camera.get_direction(x, y)))
            course[y, x] = (colour.r, colour.g, colour.b)
    image = render_image(IndexShadowPhong(str(tmp_path / "img")),
                         AppRenderer.cornell_box_scene(0.75, 2, width=size, height=size),
                         workers=1)
    assert np.count_nonzero(course) > size * size  # lit, shadowed and coloured pixels
    np.testing.assert_allclose(image, course, rtol=1e-9, atol=1e-12)
