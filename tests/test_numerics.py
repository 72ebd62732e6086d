"""Numerical extremes: specific hard cases worked out by hand, scaled scenes, and defined
results at the edges of the course's scenes."""
import math

import numpy as np
import pytest

from AppRenderer import cornell_box_scene, sphere_test_scene
from helpers import INF, as_tuple, distance, make_ray
from PyRT_Common import HUGEVALUE, Length, Normalize, RGBColor, Ray, Vector3D
from PyRT_Core import Camera, InfinitePlane, Parallelogram, PointLight, Scene, Sphere
from PyRT_Integrators import DepthIntegrator, NormalIntegrator, PhongIntegrator


def is_finite(v):
    return all(math.isfinite(c) for c in as_tuple(v))


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
