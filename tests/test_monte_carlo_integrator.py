"""CMCIntegrator (Practice 2, Assignment 2.3) renders what the rendering equation says: a
white furnace and emitters of known solid angle give their closed forms, unbiased at every
sample count, with an error that falls as 1/sqrt(n); the course's own seeded render is
reproduced number for number by the plain code, and matched statistically by render()'s
fast path, which equals the plain code bit for bit for the same draws, whatever the
workers, and gives way to it where it must.

Every statistical check runs on fixed seeds, with a tolerance of STANDARD_ERRORS standard
errors worked out here from the variance of one sample (known in closed form) or from the
course's own renders: it cannot fail by chance, and it would pass for almost every seed."""
import math
import random as random_module

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import pyrt.acceleration.accelerated
import pyrt.acceleration.fingerprints
from AppRenderer import cornell_box_scene, sphere_scene
from benchmarks.flat_loop import flat_cmc
from helpers import (ALBEDO, EMISSION, FURNACE_CENTRE, FURNACE_RADIUS, RADIANCE,  # noqa: F401
                     course_renders, emissive_box_scene, emitter, furnace_scene,
                     global_generator_kept, lambertian, render_image, sky_sphere_scene,
                     sphere_pixels, with_map_and_emitter)
from pyrt.acceleration.culling import scene_size
from pyrt.acceleration.monte_carlo import OWN_OBJECT_CLEARANCE
from pyrt.environment_maps import sky_map
from pyrt.workers import START_METHOD_VARIABLE
from PyRT_Common import (BLACK, Cross, Dot, EnvironmentMap, Length, Normalize, Ray,
                         UniformPDF, Vector3D, center_around_normal, sample_set_hemisphere)
from PyRT_Core import Camera, InfinitePlane, Parallelogram, Scene, Sphere
from PyRT_Integrators import CMCIntegrator

STANDARD_ERRORS = 5  # the width of every statistical tolerance
FLOAT32_STEP = 2.0 ** -24  # the relative rounding of one float32 operation


# ------------------------------------------------------------------------------------------
# Scenes and what is known of them
# ------------------------------------------------------------------------------------------
def assert_mean_within(values, expected, sample_sd, samples, slack=0.0):
    """The mean of `values` (one estimate of n = samples samples per pixel, the pixels
    independent), channel by channel, is within STANDARD_ERRORS standard errors of
    `expected`, sample_sd the standard deviation of one sample (per channel), plus slack
    for rounding. Returns the means."""
    values = values.reshape(-1, 3)
    means = values.mean(axis=0)
    standard_error = np.asarray(sample_sd) / math.sqrt(samples * len(values))
    assert np.all(np.abs(means - expected) <= STANDARD_ERRORS * standard_error + slack), (
        means, expected, standard_error)
    return means


def uniform_cosine_sd(scale):
    """The standard deviation of scale * u with u uniform on [0, 1): scale / sqrt(12)."""
    return np.asarray(scale) / math.sqrt(12.0)


def float32_slack(samples, bound):
    """A bound of the rounding of a float32 sum of `samples` terms each at most `bound`,
    each term from three float32 operations: far below every statistical tolerance."""
    return (samples + 3) * FLOAT32_STEP * np.asarray(bound)


def render_cmc(tmp_path, scene, samples, seed, name="img", integrator_class=CMCIntegrator,
               **options):
    """The image CMCIntegrator(samples) renders of scene after random.seed(seed)."""
    random_module.seed(seed)
    integrator = integrator_class(samples, str(tmp_path / name))
    return render_image(integrator, scene, **dict({"workers": 1}, **options))


# ------------------------------------------------------------------------------------------
# White furnace: c L at every hit, the map where the camera ray misses
# ------------------------------------------------------------------------------------------
# One sample of uniform hemisphere sampling: f/p = L (c/pi) cos / (1/(2 pi)) = 2 c L cos,
# with cos = u2 uniform on [0, 1): mean c L, standard deviation 2 c L / sqrt(12).
@pytest.mark.parametrize("samples", [1, 4, 64])
def test_white_furnace_gives_albedo_times_radiance_at_every_sample_count(tmp_path, samples):
    scene = furnace_scene(16)
    image = render_cmc(tmp_path, scene, samples, seed=samples)
    hit, _ = sphere_pixels(scene.camera, FURNACE_CENTRE, FURNACE_RADIUS)
    assert hit.sum() > 0.8 * hit.size and not hit.all()
    c_l = np.array(ALBEDO) * float(np.float32(RADIANCE))
    assert_mean_within(image[hit], c_l, uniform_cosine_sd(2 * c_l), samples,
                       float32_slack(samples, 2 * c_l))
    assert np.all(image[~hit] == RADIANCE)  # a camera ray that misses sees the map
    assert np.all(image[hit] >= 0.0) and np.all(image[hit] <= 2 * c_l)


class CosineTwice(CMCIntegrator):
    """The mistake the spec names: the Lambertian's get_value holds the cosine, and this
    multiplies by it once more."""

    def compute_color(self, ray):
        scene = self.scene
        hit = scene.closest_hit(ray)
        if not hit.has_hit:
            return scene.env_map.getValue(ray.d)
        brdf = scene.object_list[hit.primitive_index].get_BRDF()
        directions, probabilities = sample_set_hemisphere(self.n_samples, UniformPDF())
        color = BLACK
        for omega, prob in zip(directions, probabilities):
            wi = center_around_normal(omega, hit.normal)
            f = brdf.get_value(wi, Vector3D(0.0, 0.0, 0.0), hit.normal)
            light = scene.env_map.getValue(wi)
            color = color + light.multiply(f) * Dot(wi, hit.normal) / prob
        return color / self.n_samples


def test_white_furnace_catches_the_cosine_counted_twice(tmp_path):
    # 2 c L cos^2 has the mean 2/3 c L and the variance (2 c L)^2 (1/5 - 1/9)
    samples = 16
    scene = furnace_scene(16)
    hit, _ = sphere_pixels(scene.camera, FURNACE_CENTRE, FURNACE_RADIUS)
    c_l = np.array(ALBEDO) * RADIANCE
    image = render_cmc(tmp_path, scene, samples, 3, integrator_class=CosineTwice)
    means = assert_mean_within(image[hit], 2 / 3 * c_l, 2 * c_l * math.sqrt(1 / 5 - 1 / 9),
                               samples, float32_slack(samples, 2 * c_l))
    # ... which the furnace test's assertion rejects, in every channel, by a wide margin
    with pytest.raises(AssertionError):
        assert_mean_within(image[hit], c_l, uniform_cosine_sd(2 * c_l), samples,
                           float32_slack(samples, 2 * c_l))
    tolerance = STANDARD_ERRORS * uniform_cosine_sd(2 * c_l) / math.sqrt(samples * hit.sum())
    assert np.all(np.abs(means - c_l) > 3 * tolerance)


# ------------------------------------------------------------------------------------------
# Emitters, and no environment map
# ------------------------------------------------------------------------------------------
def test_sphere_in_an_emitting_box_gives_albedo_times_emission_and_the_walls_are_dark(
        tmp_path):
    samples = 16
    scene = emissive_box_scene(16)
    assert scene.env_map is None
    image = render_cmc(tmp_path, scene, samples, 5)
    hit, _ = sphere_pixels(scene.camera, FURNACE_CENTRE, FURNACE_RADIUS)
    c_e = np.array(ALBEDO) * np.array(EMISSION)
    assert_mean_within(image[hit], c_e, uniform_cosine_sd(2 * c_e), samples, 1e-12)
    # the course adds no emission where the camera ray hits: a light seen directly is as
    # dark as its black Lambertian makes it
    assert np.all(image[~hit] == 0.0) and (~hit).sum() > 0


PLANE_HEIGHT = 1.5
TILTED_CENTRE, TILTED_RADIUS = (0.0, 0.0, -2.0), 1.0


def emitting_plane_scene(size):
    """A Lambertian sphere under an emitting InfinitePlane y = PLANE_HEIGHT, no map."""
    scene = Scene()
    scene.add_object(lambertian(Sphere(Vector3D(*TILTED_CENTRE), TILTED_RADIUS), ALBEDO))
    scene.add_object(emitter(InfinitePlane(Vector3D(0.0, PLANE_HEIGHT, 0.0),
                                           Vector3D(0.0, -1.0, 0.0))))
    scene.set_camera(Camera(size, size, 90))
    return scene


def test_sphere_under_an_emitting_plane_sees_it_over_the_sky_view_factor(tmp_path):
    # From a point of the sphere with normal n, the plane fills every direction above the
    # horizon (the sphere is convex: it hides nothing from itself): the cosine-weighted
    # share of n's hemisphere above the horizon is (1 + n.y) / 2, so the point's colour is
    # c E (1 + n.y) / 2: c E at the top, half of it facing sideways, 0 at the bottom.
    # One sample is at most 2 c E cos: its second moment, and variance, at most (2 c E)^2/3.
    samples = 64
    scene = emitting_plane_scene(24)
    image = render_cmc(tmp_path, scene, samples, 11)
    hit, normals = sphere_pixels(scene.camera, TILTED_CENTRE, TILTED_RADIUS)
    c_e = np.array(ALBEDO) * np.array(EMISSION)
    expected = c_e * ((1.0 + normals[:, :, 1:2]) / 2.0)
    residuals = image - expected
    sd_bound = 2 * c_e / math.sqrt(3.0)
    for facing in (normals[:, :, 1] > 0.3, (normals[:, :, 1] < -0.3) & hit):
        assert facing.sum() > 20
        assert_mean_within(residuals[facing & hit], 0.0, sd_bound, samples, 1e-12)
    # a camera ray that misses the sphere sees the light (looking up: its black
    # Lambertian, no emission added) or nothing (no map): black either way
    looking_up = np.array([[scene.camera.get_direction(x, y).y > 0.0 for x in range(24)]
                           for y in range(24)])
    assert (looking_up & ~hit).sum() > 50
    assert np.all(image[~hit] == 0.0)


# ------------------------------------------------------------------------------------------
# The error falls as 1/sqrt(n)
# ------------------------------------------------------------------------------------------
def test_furnace_error_halves_each_time_the_samples_quadruple(tmp_path):
    # A pixel's error is the mean of n samples of 2 c L (u - 1/2): RMSE c L / sqrt(3 n),
    # and kurtosis 3 - 1.2/n, so the mean square over H pixels has the relative standard
    # deviation sqrt((2 - 1.2/n) / H), the RMSE half of that.
    scene = furnace_scene(24)
    hit, _ = sphere_pixels(scene.camera, FURNACE_CENTRE, FURNACE_RADIUS)
    c_l = ALBEDO[2] * RADIANCE  # the blue channel; the others have the same draws
    rmse = []
    for samples in (4, 16, 64, 256):
        image = render_cmc(tmp_path, scene, samples, 100 + samples, name=f"n{samples}")
        error = math.sqrt(np.mean((image[hit][:, 2] - c_l) ** 2))
        relative_sd = math.sqrt((2 - 1.2 / samples) / hit.sum()) / 2
        expected = c_l / math.sqrt(3 * samples)
        assert abs(error / expected - 1) <= STANDARD_ERRORS * relative_sd, samples
        rmse.append(error)
    ratios = [a / b for a, b in zip(rmse, rmse[1:])]
    assert all(1.6 <= ratio <= 2.5 for ratio in ratios), ratios


# ------------------------------------------------------------------------------------------
# The course's Practice 2 renders (../shared/course-renders)
# ------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def sky_renders():
    """(path of pyrt_sky.hdr, the course's 16-sample seed-0 render, its 1024-sample
    reference), or the test is skipped."""
    folder = course_renders()
    if folder is None or not (folder / "p2_sky_128_16_seed0.npz").is_file():
        pytest.skip("the course's renders (shared/course-renders beside the repository) "
                    "are not here")
    return (str(folder / "env_maps" / "pyrt_sky.hdr"),
            np.load(folder / "p2_sky_128_16_seed0.npz")["image"],
            np.load(folder / "p2_sky_128_1024_ref.npz")["image"])


def test_student_loop_reproduces_the_courses_seeded_render(sky_renders):
    # The course's draws go pixel after pixel, x outer: the first columns, all rows, are
    # the start of its loop, and their pixels draw what the course's drew.
    sky_path, course, reference = sky_renders
    columns = 32
    scene = sphere_scene(envMap=sky_path, width=128, height=128)
    integrator = CMCIntegrator(16, "unused")
    integrator.add_scene(scene)
    image = np.zeros((128, columns, 3))
    random_module.seed(0)
    for x in range(columns):
        for y in range(128):
            color = integrator.compute_color(Ray(Vector3D(0, 0, 0),
                                                 scene.camera.get_direction(x, y)))
            image[y, x] = (color.r, color.g, color.b)
    # the surfaces the sample rays leave (where the renders differ), not only the map
    surfaces = np.any(course[:, :columns] != reference[:, :columns], axis=2)
    assert surfaces.sum() > 500
    np.testing.assert_allclose(image, course[:, :columns], rtol=1e-9, atol=0.0)


def test_render_matches_the_courses_render_statistically(tmp_path, sky_renders):
    # render() draws other numbers than the course's loop (a stream per row), so its image
    # is another 16-sample estimate: unbiased against the 1024-sample reference, with the
    # error of the course's own 16-sample render. The standard error of the mean difference
    # comes from the course's render: sum over pixels of (course - reference)^2 estimates
    # the sum of the pixels' variances.
    sky_path, course, reference = sky_renders
    image = render_cmc(tmp_path, sphere_scene(envMap=sky_path, width=128, height=128), 16, 2)
    pixels = reference.shape[0] * reference.shape[1]
    course_error = (course - reference).reshape(-1, 3)
    standard_error = np.sqrt((course_error ** 2).sum(axis=0)) / pixels
    mean_difference = (image - reference).reshape(-1, 3).mean(axis=0)
    assert np.all(np.abs(mean_difference) <= STANDARD_ERRORS * standard_error), (
        mean_difference, standard_error)
    rmse = math.sqrt(np.mean((image - reference) ** 2))
    course_rmse = math.sqrt(np.mean(course_error ** 2))
    assert abs(rmse / course_rmse - 1) <= 0.15, (rmse, course_rmse)
    # where the camera ray misses, every render shows the map, number for number
    missed = np.all(course == reference, axis=2)
    assert missed.sum() > 1000 and np.array_equal(image[missed], course[missed])


# ------------------------------------------------------------------------------------------
# render()'s fast path: the plain code's image, bit for bit, and only where it may
# ------------------------------------------------------------------------------------------
def sky_over_infinite_floor(size):
    """A sphere on an InfinitePlane floor under PyRT's sky map."""
    scene = Scene()
    scene.add_object(lambertian(Sphere(Vector3D(0.0, 0.0, -3.0), 1.0), ALBEDO))
    scene.add_object(lambertian(InfinitePlane(Vector3D(0.0, -1.0, 0.0),
                                              Vector3D(0.0, 1.0, 0.0)), (0.2, 0.8, 0.2)))
    scene.set_camera(Camera(size, size, 60))
    scene.env_map = EnvironmentMap.from_texels(sky_map())
    return scene


FUSED_SCENES = {
    "sphere_scene_with_sky": sky_sphere_scene,
    "cornell_box_area_light": lambda size: cornell_box_scene(0.75, 2, areaLS=True,
                                                             width=size, height=size),
    "emitting_infinite_plane": emitting_plane_scene,
    "sky_over_infinite_floor": sky_over_infinite_floor,
}


def plain_render(tmp_path, monkeypatch, scene, samples, seed, **options):
    """The image render() gives with CMCIntegrator's own compute_color (no fused path)."""
    with monkeypatch.context() as patch:
        patch.delitem(pyrt.acceleration.accelerated.FUSED_INTEGRATORS, "cmc")
        return render_cmc(tmp_path, scene, samples, seed, name="plain", **options)


@pytest.mark.parametrize("make", FUSED_SCENES.values(), ids=FUSED_SCENES.keys())
def test_fused_path_gives_the_plain_codes_image_bit_for_bit(tmp_path, monkeypatch,
                                                           fused_calls, make):
    size, samples = 16, 8
    fused = render_cmc(tmp_path, make(size), samples, 21)
    assert fused_calls[0] == size * size  # it stood in for every camera ray
    plain = plain_render(tmp_path, monkeypatch, make(size), samples, 21)
    assert fused_calls[0] == size * size
    assert plain.any() and np.array_equal(fused, plain)


class ReadableCMC(CMCIntegrator):
    """A subclass with a compute_color of its own (here the parent's, called)."""

    def compute_color(self, ray):
        return super().compute_color(ray)


def changed_fingerprint(monkeypatch):
    monkeypatch.setitem(pyrt.acceleration.fingerprints.CMC_FUNCTIONS,
                        "center_around_normal", "0")


@pytest.mark.parametrize("integrator_class, make, change", [
    (ReadableCMC, sky_sphere_scene, None),
    (CMCIntegrator, with_map_and_emitter, None),
    (CMCIntegrator, sky_sphere_scene, changed_fingerprint),
], ids=["subclass_with_its_own_compute_color", "map_and_emitter", "changed_fingerprint"])
def test_fused_path_gives_way_to_the_plain_code(tmp_path, monkeypatch, fused_calls,
                                               integrator_class, make, change):
    size, samples = 12, 4
    if change:
        change(monkeypatch)
    image = render_cmc(tmp_path, make(size), samples, 8, integrator_class=integrator_class)
    assert fused_calls[0] == 0
    plain = plain_render(tmp_path, monkeypatch, make(size), samples, 8)
    assert plain.any() and np.array_equal(image, plain)


# ------------------------------------------------------------------------------------------
# Seeded renders: the same image for any workers, and the flat loop's
# ------------------------------------------------------------------------------------------
def test_seeded_render_is_the_same_for_any_workers_and_start_method(tmp_path, monkeypatch,
                                                                    capfd):
    renders = {}
    for name, seed, workers, start_method in [("one", 9, 1, None), ("two", 9, 2, None),
                                              ("spawned", 9, 2, "spawn"),
                                              ("other_seed", 10, 1, None)]:
        with monkeypatch.context() as patch:
            if start_method:
                patch.setenv(START_METHOD_VARIABLE, start_method)
            renders[name] = render_cmc(tmp_path, sky_sphere_scene(16), 8, seed, name=name,
                                       workers=workers)
    assert "Traceback" not in capfd.readouterr().err
    assert renders["one"].any()
    assert np.array_equal(renders["one"], renders["two"])
    assert np.array_equal(renders["one"], renders["spawned"])
    assert not np.array_equal(renders["one"], renders["other_seed"])


@pytest.mark.parametrize("make", [sky_sphere_scene, lambda size: sphere_scene(width=size,
                                                                              height=size)],
                         ids=["sky_map", "no_map"])
def test_flat_loop_gives_renders_image_bit_for_bit(tmp_path, make):
    size, samples, seed = 20, 8, 4
    random_module.seed(seed)
    stream_seed = int(random_module.random() * 2 ** 53)  # render()'s one draw
    expected = render_cmc(tmp_path, make(size), samples, seed)
    assert np.array_equal(flat_cmc(make(size), samples, stream_seed), expected)
    if make(size).env_map is None:  # no map and no emitter: no light at all
        assert not expected.any()


# ------------------------------------------------------------------------------------------
# The integrator's file name
# ------------------------------------------------------------------------------------------
def test_cmc_render_saves_under_its_samples_name(tmp_path):
    integrator = CMCIntegrator(3, str(tmp_path / "img"), "_furnace")
    assert integrator.n_samples == 3
    render_image(integrator, furnace_scene(4), workers=1)
    assert sorted(path.name for path in tmp_path.iterdir()) == [
        "img_MC_3_samples_furnace.hdr", "img_MC_3_samples_furnace.npy",
        "img_MC_3_samples_furnace.png"]


# ------------------------------------------------------------------------------------------
# The object a sample ray leaves, left out of its tests (AcceleratedCMC)
# ------------------------------------------------------------------------------------------
def leaving_direction(normal, cos_theta, around):
    """A unit direction at the angle acos(cos_theta) from the unit normal, turned by
    `around` radians about it."""
    helper = Vector3D(1.0, 0.0, 0.0) if abs(normal.x) < 0.9 else Vector3D(0.0, 1.0, 0.0)
    u = Normalize(Cross(normal, helper))
    v = Cross(normal, u)
    sin_theta = math.sqrt(1.0 - cos_theta * cos_theta)
    return Normalize(normal * cos_theta + (u * math.cos(around) + v * math.sin(around))
                     * sin_theta)


coordinates = st.floats(-100.0, 100.0)


@settings(max_examples=300)
@given(centre=st.tuples(coordinates, coordinates, coordinates),
       radius=st.floats(0.01, 100.0), towards=st.tuples(coordinates, coordinates, coordinates),
       around=st.floats(0.0, 2 * math.pi))
def test_a_sample_ray_that_clearly_leaves_a_sphere_never_meets_it_again(centre, radius,
                                                                        towards, around):
    # The own object is left out of a sample ray's tests once its cosine exceeds
    # OWN_OBJECT_CLEARANCE of the scene's size: the plain test, at that very cosine, says
    # the same, for the hit points PyRT's own arithmetic makes.
    sphere = Sphere(Vector3D(*centre), radius)
    outward = Normalize(Vector3D(*towards) + Vector3D(0.0, 0.0, 1e-3))
    target = Vector3D(*centre) + outward * radius
    start = target * 3.0 + Vector3D(250.0, 250.0, 250.0)
    hit = sphere.intersect(Ray(start, Normalize(target - start)))
    assume(hit.has_hit)
    size = max(max(abs(c) for c in centre), radius, 1e-300)
    cos_theta = OWN_OBJECT_CLEARANCE * size * 1.0001
    assume(cos_theta < 1.0)
    w = leaving_direction(hit.normal, cos_theta, around)
    assert not sphere.intersect(Ray(hit.hit_point, w)).has_hit


@settings(max_examples=300)
@given(corner=st.tuples(coordinates, coordinates, coordinates),
       a=st.floats(0.0, 1.0), b=st.floats(0.0, 1.0), around=st.floats(0.0, 2 * math.pi),
       start=st.tuples(coordinates, coordinates, coordinates))
def test_a_sample_ray_that_clearly_leaves_a_parallelogram_never_meets_it_again(
        corner, a, b, around, start):
    wall = Parallelogram(Vector3D(*corner), Vector3D(3.0, 0.5, 0.0), Vector3D(0.0, 1.0, 2.0))
    target = Vector3D(*corner) + Vector3D(3.0, 0.5, 0.0) * a + Vector3D(0.0, 1.0, 2.0) * b
    assume(Length(target - Vector3D(*start)) > 1e-3)
    hit = wall.intersect(Ray(Vector3D(*start), Normalize(target - Vector3D(*start))))
    assume(hit.has_hit)
    size = scene_size([wall], [])  # the scale AcceleratedCMC takes: the wall's four corners
    cos_theta = OWN_OBJECT_CLEARANCE * size * 1.0001
    assume(cos_theta < 1.0)
    w = leaving_direction(hit.normal, cos_theta, around)
    assert not wall.intersect(Ray(hit.hit_point, w)).has_hit
