"""Helpers shared by the tests: small scenes, test integrators, running the scripts.

Most test scenes use a camera with a vertical field of view of 90 degrees, so
tan(fov/2) = 1: pixel (x, y) of a width x height image looks along
(x_s * width/height, y_s, -1) with x_s = 2(x + 0.5)/width - 1 and y_s = 1 - 2(y + 0.5)/height.
The centre pixel of an image with odd sides looks straight down -z."""
import math
import multiprocessing
import os
import random as random_module  # the star imports below bind random to random.random
import subprocess
import sys
import time
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest
from hypothesis import strategies as st

from AppRenderer import cornell_box_scene, sphere_scene
import pyrt.acceleration.queries
import pyrt.workers
from pyrt.environment_maps import constant_map, sky_map
from PyRT_Core import *
from PyRT_Integrators import *

REPO = Path(__file__).resolve().parent.parent
# The course's own renders (PYRT_SPEC.md), in shared/ beside the repository's folder: beside
# it as resolved, or beside it as named (a clone reached through a link elsewhere)
COURSE_RENDERS = [Path(__file__).resolve().parents[2] / "shared" / "course-renders",
                  Path(os.path.abspath(__file__)).parents[2] / "shared" / "course-renders"]
APP = REPO / "AppRenderer.py"
# matplotlib stores a PNG channel v as floor(255 v) / 255: up to one 8-bit step below v
# (plus float32 rounding when it is read back).
PNG_TOLERANCE = 1.0 / 255.0 + 1e-6
SUBPROCESS_TIMEOUT = 300  # seconds; only there so that a hung child cannot hang the suite
TIGHT = 1e-12  # the tolerance of values worked out by hand
INF = float("inf")
GOOD = Vector3D(0.0, 0.0, -5.0)  # a valid point, for the arguments not under test

# Hypothesis strategies: points, unit directions and PyRT's primitives within a few units
# of the origin, for the property tests of the intersection tests
coordinates = st.floats(-4.0, 4.0)
vectors = st.tuples(coordinates, coordinates, coordinates).map(lambda v: Vector3D(*v))
directions = vectors.filter(lambda v: Length(v) > 0.1).map(Normalize)
long_vectors = vectors.filter(lambda v: Length(v) > 0.5)
primitives = st.one_of(
    st.builds(Sphere, vectors, st.floats(0.05, 3.0)),
    st.builds(InfinitePlane, vectors, long_vectors),
    st.tuples(vectors, long_vectors, long_vectors).filter(
        lambda sides: Length(Cross(sides[1], sides[2])) > 0.2).map(
        lambda sides: Parallelogram(*sides)))

# CI's main Python: the course kit's matrices of submissions (each graded, in every mode)
# run on it alone; their verdicts do not depend on the Python, and the kit's other tests,
# which grade too, run on every Python and start method (.ci/run)
MAIN_PYTHON = (3, 11)


def matrix_on_the_main_python_only():
    """Skips, outside MAIN_PYTHON, the test (or fixture) of a matrix of submissions."""
    if sys.version_info[:2] != MAIN_PYTHON:
        pytest.skip("the course kit's matrices of submissions run on Python "
                    f"{MAIN_PYTHON[0]}.{MAIN_PYTHON[1]} only, CI's main Python")


def as_tuple(v):
    """The components (x, y, z) of a Vector3D, to compare with numbers."""
    return (v.x, v.y, v.z)


def rgb(c):
    """The channels (r, g, b) of an RGBColor, to compare with numbers."""
    return (c.r, c.g, c.b)


def approx3(values, tol=TIGHT):
    """Three numbers to compare with, within tol."""
    return pytest.approx(values, abs=tol)


def ray(origin, direction, **limits):
    """A Ray from two (x, y, z) tuples, with its limits (t_min=..., t_max=...) set."""
    r = Ray(Vector3D(*origin), Vector3D(*direction))
    for name, value in limits.items():
        setattr(r, name, value)
    return r


def assert_hit(hit, point, normal, distance, tol=TIGHT):
    """hit is a hit at point, with normal, at distance, all within tol."""
    assert hit.has_hit is True
    assert as_tuple(hit.hit_point) == approx3(point, tol)
    assert as_tuple(hit.normal) == approx3(normal, tol)
    assert hit.hit_distance == pytest.approx(distance, abs=tol)


def distance(a, b):
    """The distance between two points."""
    return Length(a - b)


def make_ray(origin, direction, t_max=HUGEVALUE, t_min=0.0):
    """A ray with both limits chosen: t_min 0 keeps hits closer than EPSILON."""
    ray = Ray(origin, direction, t_max)
    ray.t_min = t_min
    return ray


def course_renders():
    """The folder of the course's own renders, or None when it is not beside the
    repository."""
    return next((folder for folder in COURSE_RENDERS if folder.is_dir()), None)


@pytest.fixture(autouse=True)
def global_generator_kept():
    """Python's global generator as it was before each test, whatever the test drew (a
    module that imports this fixture gets it for every test)."""
    state = random_module.getstate()
    yield
    random_module.setstate(state)


def render_image(integrator, scene, **render_options):
    """Attaches scene to integrator, renders it without a progress bar and returns the
    linear image it saved (the .npy file)."""
    integrator.add_scene(scene)
    integrator.render(progress=False, **render_options)
    return np.load(integrator.get_filename() + ".npy")


def read_png(path):
    """The RGB channels of a PNG as floats in [0, 1], as matplotlib reads them."""
    return plt.imread(str(path))[:, :, :3].astype(float)


def headless_env():
    """The environment for a child Python: no display, matplotlib's Agg backend, and the
    repository on the import path."""
    env = {name: value for name, value in os.environ.items() if name != "DISPLAY"}
    if env.get("MUTANT_UNDER_TEST") == "stats":
        # mutmut's first run, which records what each test calls, needs its pyproject.toml in
        # the working folder; a child Python started elsewhere runs the code unmutated.
        del env["MUTANT_UNDER_TEST"]
    env["MPLBACKEND"] = "Agg"
    env["PYTHONPATH"] = os.pathsep.join(
        [str(REPO)] + ([env["PYTHONPATH"]] if env.get("PYTHONPATH") else []))
    return env


def run_python(args, cwd):
    """Runs `python *args` headless in cwd and returns the CompletedProcess (text output)."""
    return subprocess.run([sys.executable, *map(str, args)], cwd=cwd, env=headless_env(),
                          capture_output=True, text=True, timeout=SUBPROCESS_TIMEOUT)


# ------------------------------------------------------------------------------------------
# Small scenes and test integrators
# ------------------------------------------------------------------------------------------
GREY = RGBColor(0.5, 0.5, 0.5)


def fov90_scene(width, height, objects=(), lights=(), ambient=BLACK):
    """A scene seen by a width x height camera with a 90 degree field of view; objects are
    (primitive, albedo) pairs and get a Lambertian BRDF of that albedo."""
    scene = Scene()
    scene.set_ambient(ambient)
    for primitive, albedo in objects:
        primitive.set_BRDF(Lambertian(albedo))
        scene.add_object(primitive)
    for position, intensity in lights:
        scene.add_point_light_sources(PointLight(position, intensity))
    scene.set_camera(Camera(width, height, 90))
    return scene


def direction_through(x, y, width, height):
    """The (unnormalised) direction of the ray through the centre of pixel (x, y) of a
    90 degree camera, from the formula in this module's docstring."""
    return ((2 * (x + 0.5) / width - 1) * width / height, 1 - 2 * (y + 0.5) / height, -1.0)


def image_camera(camera):
    """The scene's own camera: during a render, compute_color sees scene.camera as the
    camera of a task, over its rays (pyrt.rows.TaskCamera), whose `camera` it is."""
    return getattr(camera, "camera", camera)


def pixel_of(ray, camera):
    """The pixel whose centre ray is `ray`: get_direction inverted, so that a test
    integrator can give chosen pixels chosen colours."""
    camera = image_camera(camera)
    d = ray.d
    scale_y = math.tan(camera.vertical_fov / 2)
    x_s = d.x / -d.z / (scale_y * camera.aspect_ratio)
    y_s = d.y / -d.z / scale_y
    return (round((x_s + 1) * camera.width / 2 - 0.5),
            round((1 - y_s) * camera.height / 2 - 0.5))


def small_cornell_box(size):
    """The Cornell box of Figure 1, closer (0.75) and smaller (side 2)."""
    return cornell_box_scene(0.75, 2, width=size, height=size)


class PixelGrey(Integrator):
    """Grey (x + 10 y) / 100 at pixel (x, y), found from the ray's direction."""

    def __init__(self, filename_):
        super().__init__(filename_ + "_PixelGrey")
        self.calls = 0

    def grey(self, x, y):
        return (x + 10 * y) / 100

    def compute_color(self, ray):
        self.calls += 1
        g = self.grey(*pixel_of(ray, self.scene.camera))
        return RGBColor(g, g, g)


class StudentPhongIntegrator(Integrator):
    """Phong written the way a student writes it from the assignment, with PyRT's vector
    and colour classes and a shadow ray of its own (Ray(hit point, wi, distance))."""

    def __init__(self, filename_, experiment_name=""):
        super().__init__(filename_ + "_StudentPhong", experiment_name)

    def compute_color(self, ray):
        hit_data = self.scene.closest_hit(ray)
        if not hit_data.has_hit:
            return BLACK
        hit_point = hit_data.hit_point
        normal = hit_data.normal
        brdf = self.scene.object_list[hit_data.primitive_index].get_BRDF()
        wo = ray.d * -1.0
        color = brdf.kd.multiply(self.scene.i_a)
        for light in self.scene.pointLights:
            to_light = light.pos - hit_point
            distance = Length(to_light)
            wi = Normalize(to_light)
            shadow_ray = Ray(hit_point, wi, distance)
            if not self.scene.any_hit(shadow_ray):
                light_color = light.intensity.multiply(brdf.get_value(wi, wo, normal))
                color = color + light_color / (distance * distance)
        return color


class ShadowRayFrom(Integrator):
    """The course's Phong, its shadow ray Ray(hit_point, wi, distance) with t_min set to
    `t_min`: 0 leaves out the offset that keeps the ray off its own surface."""

    def __init__(self, t_min):
        super().__init__("unused")
        self.t_min = t_min

    def compute_color(self, ray):
        hit = self.scene.closest_hit(ray)
        if not hit.has_hit:
            return RGBColor(0.0, 0.0, 0.0)
        brdf = self.scene.object_list[hit.primitive_index].get_BRDF()
        color = brdf.kd.multiply(self.scene.i_a)
        for light in self.scene.pointLights:
            to_light = light.pos - hit.hit_point
            distance = Length(to_light)
            wi = Normalize(to_light)
            shadow = Ray(hit.hit_point, wi, distance)
            shadow.t_min = self.t_min
            if not self.scene.any_hit(shadow):
                f = brdf.get_value(wi, ray.d * -1.0, hit.normal)
                color = color + light.intensity.multiply(f) / (distance * distance)
        return color


def visible_lights(scene, hit):
    """The point lights that light the point of hit (a HitData) as PhongIntegrator decides
    it: each light in front of the surface, n . (pos - p) > 0, whose shadow_ray meets
    nothing, as (light, wi, r2), wi the unit direction to the light and r2 its squared
    distance. The scene's own any_hit and pyrt.acceleration's decide alike, or the test
    fails."""
    fast = pyrt.acceleration.queries.AcceleratedQueries(scene)
    seen = []
    for light in scene.pointLights:
        to_light = light.pos - hit.hit_point
        if Dot(hit.normal, to_light) <= 0.0:
            continue
        ray = shadow_ray(hit, light.pos)
        blocked = scene.any_hit(ray)
        assert fast.any_hit(ray) == blocked, f"the fast any_hit differs for {ray!r}"
        if not blocked:
            r = Length(to_light)
            seen.append((light, to_light / r, r * r))
    return seen


def wait_for_file(path, seconds=SUBPROCESS_TIMEOUT):
    """Waits until another process has made the file at path; `seconds` is only there so
    that a process that hangs cannot hang the suite."""
    deadline = time.monotonic() + seconds
    while not os.path.exists(path) and time.monotonic() < deadline:
        time.sleep(0.005)


def wait_for_worker(path, seconds=SUBPROCESS_TIMEOUT):
    """Waits until a worker process of this one has made the file at path, or none is alive
    any more (it stopped, or could not start): however late a loaded machine starts it.
    `seconds` is only there so that a worker that hangs cannot hang the suite."""
    deadline = time.monotonic() + seconds
    while (not os.path.exists(path) and multiprocessing.active_children()
           and time.monotonic() < deadline):
        time.sleep(0.005)


# The worker process's functions as pyrt.workers defines them, before any test replaces
# them: what a HeldBackWorker runs, whether its process was forked or started afresh.
_WORKER = pyrt.workers._worker
_RENDER_BLOCK = pyrt.workers.render_block
_FINISH = pyrt.workers._SharedImage.finish


class HeldBackWorker:
    """pyrt.workers._worker holding back its first block until the main process has taken
    one (the file `taken` exists), and leaving the file `marker` once it has finished a
    block; raise_in_worker = (exception class, arguments): it raises that exception in
    its first block instead, once it has rendered the rows and left the marker. The
    worker_first fixture (conftest.py) installs it. It is an object that pickle sends to
    the worker process, so it reaches workers of every start method (spawned ones import
    pyrt.workers afresh, without the test's changes)."""

    def __init__(self, marker, taken, raise_in_worker=None):
        self.marker, self.taken, self.raise_in_worker = marker, taken, raise_in_worker

    def __call__(self, *args):
        def finish_and_mark(shared, i):
            _FINISH(shared, i)
            Path(self.marker).touch()

        def held_back(integrator, y0, y1, rows):
            wait_for_file(self.taken)
            block = _RENDER_BLOCK(integrator, y0, y1, rows)
            if self.raise_in_worker:  # as an error in compute_color: the block unfinished
                Path(self.marker).touch()
                error_class, arguments = self.raise_in_worker
                raise error_class(*arguments)
            return block

        # This is the worker's own process, which ends with the render.
        pyrt.workers.render_block = held_back
        pyrt.workers._SharedImage.finish = finish_and_mark
        _WORKER(*args)


def image_point(ray, camera):
    """(x + u, y + v): where the ray crosses the image plane, in pixels from the image's
    top left corner (get_direction inverted)."""
    camera = image_camera(camera)
    d = ray.d
    scale_y = math.tan(camera.vertical_fov / 2)
    x_s = d.x / -d.z / (scale_y * camera.aspect_ratio)
    y_s = d.y / -d.z / scale_y
    return (x_s + 1) * camera.width / 2, (1 - y_s) * camera.height / 2


class StepAt(Integrator):
    """White left of the vertical line X = edge of the image plane (in pixels), black right
    of it; records where every ray crosses the image plane."""

    def __init__(self, filename_, edge):
        super().__init__(filename_ + "_Step")
        self.edge = edge
        self.points = []

    def compute_color(self, ray):
        x, y = image_point(ray, self.scene.camera)
        self.points.append((x, y))
        return WHITE if x < self.edge else BLACK


class ConstantGrey(Integrator):
    """The same grey for every ray; counts its rays."""

    def __init__(self, filename_):
        super().__init__(filename_ + "_Constant")
        self.calls = 0

    def compute_color(self, ray):
        self.calls += 1
        return RGBColor(0.25, 0.5, 0.75)


class RandomGrey(Integrator):
    """Each pixel a grey drawn from Python's global generator with the course's random(),
    as a student's Monte Carlo integrator draws its numbers."""

    def __init__(self, filename_):
        super().__init__(filename_ + "_RandomGrey")

    def compute_color(self, ray):
        grey = random()
        return RGBColor(grey, grey, grey)


# ------------------------------------------------------------------------------------------
# Monte Carlo scenes whose light is known in closed form
# ------------------------------------------------------------------------------------------
ALBEDO = (0.25, 0.5, 0.75)  # c, a colour, so that each channel is checked on its own
RADIANCE = 1.5  # L of the furnace: a float32 number exactly (np.float32(1.5) == 1.5)
# The furnace: a sphere of radius 1.5, 2 in front of a 90 degree camera, fills most of it
FURNACE_CENTRE, FURNACE_RADIUS = (0.0, 0.0, -2.0), 1.5
EMISSION = (1.0, 2.0, 3.0)  # E of the emitters


def lambertian(primitive, albedo):
    primitive.set_BRDF(Lambertian(RGBColor(*albedo)))
    return primitive


def furnace_scene(size, radiance=RADIANCE):
    """A Lambertian sphere of albedo ALBEDO alone under a constant environment map."""
    scene = Scene()
    scene.add_object(lambertian(Sphere(Vector3D(*FURNACE_CENTRE), FURNACE_RADIUS), ALBEDO))
    scene.set_camera(Camera(size, size, 90))
    scene.env_map = EnvironmentMap.from_texels(constant_map(radiance))
    return scene


def sphere_pixels(camera, centre, radius):
    """(hit, normals): which pixels' camera rays hit the sphere, and the outward unit normal
    where they do, from the ray-sphere quadratic in closed form. No pixel lies within
    1e-6 of the silhouette, where rounding could decide."""
    hit = np.zeros((camera.height, camera.width), dtype=bool)
    normals = np.zeros((camera.height, camera.width, 3))
    c = np.array(centre)
    for y in range(camera.height):
        for x in range(camera.width):
            d = camera.get_direction(x, y)
            d = np.array([d.x, d.y, d.z])
            b = d @ c
            disc = b * b - (c @ c - radius * radius)
            assert abs(disc) > 1e-6, (x, y)
            if disc > 0.0:
                hit[y, x] = True
                normals[y, x] = ((b - math.sqrt(disc)) * d - c) / radius
    return hit, normals


EMISSION = (1.0, 2.0, 3.0)


def emitter(primitive, emission=EMISSION):
    """An area light as the course makes one: emission, and a black Lambertian."""
    primitive.emission = RGBColor(*emission)
    return lambertian(primitive, (0.0, 0.0, 0.0))


def emissive_box_scene(size):
    """The furnace's sphere inside a closed box, camera included, whose six walls emit
    EMISSION: every sample ray hits a wall, and L = E in every direction."""
    scene = Scene()
    scene.add_object(lambertian(Sphere(Vector3D(*FURNACE_CENTRE), FURNACE_RADIUS), ALBEDO))
    low, high = Vector3D(-2.0, -2.0, -4.0), Vector3D(2.0, 2.0, 1.0)
    x, y, z = Vector3D(4.0, 0.0, 0.0), Vector3D(0.0, 4.0, 0.0), Vector3D(0.0, 0.0, 5.0)
    for corner, s1, s2 in [(low, x, y), (low, y, z), (low, z, x),
                           (high, x * -1.0, y * -1.0), (high, y * -1.0, z * -1.0),
                           (high, z * -1.0, x * -1.0)]:
        scene.add_object(emitter(Parallelogram(corner, s1, s2)))
    scene.set_camera(Camera(size, size, 90))
    return scene


def sky_sphere_scene(size):
    """The course's sphere scene lit by PyRT's sky map."""
    scene = sphere_scene(width=size, height=size)
    scene.env_map = EnvironmentMap.from_texels(sky_map())
    return scene


def counted_calls(monkeypatch, fused_class):
    """The number of camera rays fused_class.compute_color (a fused integrator's) answers
    from now on, as a one-element list."""
    calls = [0]
    original = fused_class.compute_color

    def counted(self, ray):
        calls[0] += 1
        return original(self, ray)

    monkeypatch.setattr(fused_class, "compute_color", counted)
    return calls


def with_map_and_emitter(size):
    """The Cornell box with its area light, and PyRT's sky map as well."""
    scene = cornell_box_scene(0.75, 2, areaLS=True, width=size, height=size)
    scene.env_map = EnvironmentMap.from_texels(sky_map())
    return scene


def write_texts(folder, texts):
    """Writes {file name: text} into the new folder; returns the folder."""
    folder = Path(folder)
    folder.mkdir(parents=True)
    for name, text in texts.items():
        (folder / name).write_text(text, encoding="utf-8")
    return folder


def seeded_render(integrator, scene, seed=1, **render_options):
    """render_image after random.seed(seed), in one process unless workers is given."""
    random_module.seed(seed)
    return render_image(integrator, scene, **dict({"workers": 1}, **render_options))
