"""The course's API on PyRT: every name, parameter and default of the three editions
(PYRT_SPEC.md, "The course's signatures, every edition"), the attributes the spec names,
and the names that the course's `from PyRT_Common import *` gives its students."""
import inspect
import json
import math
import random

import cv2
import numpy as np
import pytest

import AppRenderer
import course_submissions
import PyRT_Common
import PyRT_Core
import PyRT_Integrators
from helpers import run_python

REQUIRED = inspect.Parameter.empty  # a parameter the course gives no default
SOME_DEFAULT = object()  # a default whose value the spec leaves to PyRT (fresh zero vectors)
BLACK = PyRT_Common.BLACK
HUGEVALUE = PyRT_Common.HUGEVALUE


def params(*names, **defaults):
    """The course's parameters in order: names without a default, then name=default."""
    return tuple((name, REQUIRED) for name in names) + tuple(defaults.items())


# (module, name of a class, function or Class.method, the course's parameters in order).
# A class stands for its constructor; a method's self is left out.
SIGNATURES = [
    # PyRT_Common
    (PyRT_Common, "Vector3D", params("x_element", "y_element", "z_element")),
    (PyRT_Common, "Vector3D.multiply", params("v")),  # (2023-24)
    (PyRT_Common, "Dot", params("a", "b")),
    (PyRT_Common, "Cross", params("a", "b")),
    (PyRT_Common, "Length", params("v")),
    (PyRT_Common, "Normalize", params("v")),
    (PyRT_Common, "orient_normal", params("normal", "direction")),
    (PyRT_Common, "RGBColor", params("red", "green", "blue")),
    (PyRT_Common, "RGBColor.multiply", params("c")),
    (PyRT_Common, "RGBColor.clamp", params("minimum", "maximum")),
    (PyRT_Common, "Ray", params(origin=SOME_DEFAULT, direction=SOME_DEFAULT, tmax=HUGEVALUE)),
    (PyRT_Common, "Ray.get_hitpoint", params("t")),
    (PyRT_Common, "HitData", params(has_hit=False, hit_point=SOME_DEFAULT, normal=SOME_DEFAULT,
                                    hit_distance=HUGEVALUE, primitive_index=-1)),
    (PyRT_Common, "EnvironmentMap", params("env_map_path")),
    (PyRT_Common, "EnvironmentMap.euclideanToLatLong", params("d")),
    (PyRT_Common, "EnvironmentMap.getValue", params("d")),
    (PyRT_Common, "Function", params("integral_value")),
    (PyRT_Common, "Function.eval", params("omega_i")),
    (PyRT_Common, "Function.get_integral", params()),
    (PyRT_Common, "Constant", params("const_value_")),
    (PyRT_Common, "Constant.eval", params("omega_i")),
    (PyRT_Common, "Constant.get_integral", params()),
    (PyRT_Common, "CosineLobe", params("exp_")),
    (PyRT_Common, "CosineLobe.eval", params("omega_i")),
    (PyRT_Common, "CosineLobe.get_integral", params()),
    (PyRT_Common, "PDF.get_val", params("omega_i")),
    (PyRT_Common, "PDF.generate_dir", params("u1", "u2")),
    (PyRT_Common, "UniformPDF", params()),
    (PyRT_Common, "UniformPDF.get_val", params("omega_i")),
    (PyRT_Common, "UniformPDF.generate_dir", params("u1", "u2")),
    (PyRT_Common, "CosinePDF", params("exp_")),
    (PyRT_Common, "CosinePDF.get_val", params("omega_i")),
    (PyRT_Common, "CosinePDF.generate_dir", params("u1", "u2")),
    (PyRT_Common, "sample_set_hemisphere", params("n_samples", "pdf")),
    (PyRT_Common, "center_around_normal", params("dir", "normal")),
    (PyRT_Common, "oriented_hemi_dir", params("pdf", "u1", "u2", "new_normal")),
    (PyRT_Common, "rotate_around_y", params("alpha", "dir_")),
    (PyRT_Common, "euclidean_to_disk", params("sample_set")),
    (PyRT_Common, "visualize_sample_set", params("sample_set", weights=[])),
    # PyRT_Core
    (PyRT_Core, "Scene", params()),
    (PyRT_Core, "Scene.set_ambient", params("i_a")),
    (PyRT_Core, "Scene.set_camera", params("camera")),
    (PyRT_Core, "Scene.set_environment_map", params("env_map_path")),
    (PyRT_Core, "Scene.add_object", params("new_object")),
    (PyRT_Core, "Scene.add_point_light_sources", params("point_light")),
    (PyRT_Core, "Scene.any_hit", params("ray")),
    (PyRT_Core, "Scene.closest_hit", params("ray")),
    (PyRT_Core, "Scene.set_pixel", params("pixel_val", "x", "y")),
    (PyRT_Core, "Scene.save_image", params("full_filename")),
    (PyRT_Core, "Primitive", params(emission=BLACK)),
    (PyRT_Core, "Primitive.intersect", params("ray")),
    (PyRT_Core, "Primitive.set_BRDF", params("BRDF")),
    (PyRT_Core, "Primitive.get_BRDF", params()),
    (PyRT_Core, "Sphere", params("sphere_origin", "sphere_radius", emission=BLACK)),
    (PyRT_Core, "Sphere.intersect", params("ray")),
    (PyRT_Core, "InfinitePlane", params("plane_origin", "plane_normal", emission=BLACK)),
    (PyRT_Core, "InfinitePlane.intersect", params("ray")),
    (PyRT_Core, "Parallelogram", params("point", "s1", "s2", emission=BLACK)),
    (PyRT_Core, "Parallelogram.intersect", params("ray")),
    (PyRT_Core, "BRDF.get_value", params("incoming", "outgoing", "normal")),
    (PyRT_Core, "Lambertian", params("diffuse_colour")),
    (PyRT_Core, "Lambertian.get_value", params("wi", "wo", "normal")),
    (PyRT_Core, "Lambertian.get_kd", params()),  # (2023-24)
    (PyRT_Core, "PointLight", params("pos_", "intensity_")),
    (PyRT_Core, "Camera", params("width_", "height_", "vertical_fov_")),
    (PyRT_Core, "Camera.get_direction", params("x", "y")),
    # PyRT_Integrators
    (PyRT_Integrators, "Integrator", params("filename_", experiment_name="")),
    (PyRT_Integrators, "Integrator.add_scene", params("scene")),
    (PyRT_Integrators, "Integrator.add_environment_map", params("env_map_path")),  # 2021-22
    (PyRT_Integrators, "Integrator.get_filename", params()),
    (PyRT_Integrators, "Integrator.compute_color", params("ray")),
    (PyRT_Integrators, "Integrator.render", params()),
    (PyRT_Integrators, "LazyIntegrator", params("filename_")),
    (PyRT_Integrators, "IntersectionIntegrator", params("filename_")),
    (PyRT_Integrators, "DepthIntegrator", params("filename_", max_depth_=10)),
    (PyRT_Integrators, "NormalIntegrator", params("filename_")),
    (PyRT_Integrators, "PhongIntegrator", params("filename_")),
    (PyRT_Integrators, "CMCIntegrator", params("n", "filename_", experiment_name="")),
    (PyRT_Integrators, "BayesianMonteCarloIntegrator",
     params("n", "myGP", "filename_", experiment_name="")),
] + [(PyRT_Integrators, name + ".compute_color", params("ray"))
     for name in ("LazyIntegrator", "IntersectionIntegrator", "DepthIntegrator",
                  "NormalIntegrator", "PhongIntegrator", "CMCIntegrator",
                  "BayesianMonteCarloIntegrator")] + [
    # AppRenderer: 2021-22 and 2023-24, and the 2025-26 handout's scene
    (AppRenderer, "sphere_test_scene", params(areaLS=False, use_env_map=False)),
    (AppRenderer, "cornell_box_scene", params("dist", "side", areaLS=False)),
    (AppRenderer, "sphere_scene", params(envMap=None)),
]


def find(module, dotted):
    """The class, function or method module.dotted, or a failure naming what is missing."""
    found = module
    for part in dotted.split("."):
        assert hasattr(found, part), f"{module.__name__}.{dotted}: {part} is missing"
        found = getattr(found, part)
    return found


def parameters(module, dotted):
    """The parameters of module.dotted as a student calls it: a method's self left out."""
    listed = list(inspect.signature(find(module, dotted)).parameters.values())
    return listed[1:] if "." in dotted else listed


def same_default(actual, expected):
    """Whether a default of PyRT is the course's: equal, and of the same type."""
    return type(actual) is type(expected) and actual == expected


@pytest.mark.parametrize("module, dotted, course", SIGNATURES,
                         ids=[f"{m.__name__}.{name}" for m, name, _ in SIGNATURES])
def test_every_course_name_takes_the_courses_parameters_first(module, dotted, course):
    """The course's parameters lead, in order, by name, callable by position and keyword."""
    listed = parameters(module, dotted)
    assert [p.name for p in listed[:len(course)]] == [name for name, _ in course], \
        f"{dotted}{inspect.signature(find(module, dotted))}"
    for p, (name, default) in zip(listed, course):
        assert p.kind is inspect.Parameter.POSITIONAL_OR_KEYWORD, (dotted, name, p.kind)
        if default is REQUIRED:
            assert p.default is REQUIRED, (dotted, name, p.default)
        elif default is SOME_DEFAULT:
            assert p.default is not REQUIRED, (dotted, name)
        else:
            assert same_default(p.default, default), (dotted, name, p.default)


@pytest.mark.parametrize("module, dotted, course", SIGNATURES,
                         ids=[f"{m.__name__}.{name}" for m, name, _ in SIGNATURES])
def test_parameters_pyrt_adds_have_defaults(module, dotted, course):
    """A call with the course's arguments alone still works: PyRT's extras are optional."""
    extra = parameters(module, dotted)[len(course):]
    assert all(p.default is not REQUIRED
               or p.kind in (inspect.Parameter.VAR_POSITIONAL, inspect.Parameter.VAR_KEYWORD)
               for p in extra), f"{dotted}{inspect.signature(find(module, dotted))}"


ABSTRACT = [(PyRT_Common, "PDF"), (PyRT_Common, "Function"), (PyRT_Core, "Primitive"),
            (PyRT_Core, "BRDF"), (PyRT_Integrators, "Integrator")]


@pytest.mark.parametrize("module, name", ABSTRACT, ids=[name for _, name in ABSTRACT])
def test_the_courses_abstract_bases_stay_abstract(module, name):
    """PDF, Function, Primitive, BRDF and Integrator are abstract, as the course's are."""
    assert inspect.isabstract(find(module, name)), name


# ------------------------------------------------------------------------------------------
# The attributes the spec names
# ------------------------------------------------------------------------------------------
PRESENT = object()  # an attribute whose value other tests check


class FakeGP:
    """Stands for the Gaussian process a student hands to BayesianMonteCarloIntegrator."""


GP = FakeGP()


@pytest.fixture
def env_map_path(tmp_path):
    """A 4 x 2 latitude-longitude map in grey 1.0 (every channel), as a course's .hdr."""
    path = tmp_path / "map.hdr"
    assert cv2.imwrite(str(path), np.ones((2, 4, 3), dtype=np.float32))
    return str(path)


def vector(x, y, z):
    return PyRT_Common.Vector3D(x, y, z)


def colour(r, g, b):
    return PyRT_Common.RGBColor(r, g, b)


# (what, how it is made, {attribute: value the spec gives, or PRESENT})
ATTRIBUTES = [
    ("Vector3D", lambda: vector(1.0, 2.0, 3.0), {"x": 1.0, "y": 2.0, "z": 3.0}),
    ("RGBColor", lambda: colour(0.25, 0.5, 0.75), {"r": 0.25, "g": 0.5, "b": 0.75}),
    ("Ray", lambda: PyRT_Common.Ray(vector(1.0, 2.0, 3.0), vector(0.0, 0.0, -1.0), 7.5),
     {"o": vector(1.0, 2.0, 3.0), "d": vector(0.0, 0.0, -1.0), "t_max": 7.5,
      "t_min": 0.0001}),
    ("HitData", PyRT_Common.HitData,
     {"has_hit": False, "hit_point": PRESENT, "normal": PRESENT, "hit_distance": 1e6,
      "primitive_index": -1}),
    ("UniformPDF", lambda: PyRT_Common.UniformPDF(), {}),
    ("CosinePDF", lambda: PyRT_Common.CosinePDF(3), {"exp": 3}),
    ("Constant", lambda: PyRT_Common.Constant(0.5), {"const_value": 0.5, "ground_truth": PRESENT}),
    ("CosineLobe", lambda: PyRT_Common.CosineLobe(2), {"exp": 2, "ground_truth": PRESENT}),
    ("Scene", PyRT_Core.Scene,
     {"camera": None, "env_map": None, "rendered_image": PRESENT, "object_list": [],
      "pointLights": [], "i_a": PRESENT}),
    ("Sphere", lambda: PyRT_Core.Sphere(vector(0.0, 0.0, -5.0), 2.0),
     {"origin": vector(0.0, 0.0, -5.0), "radius": 2.0, "radius_squared": 4.0,
      "emission": BLACK, "BRDF": PRESENT}),
    ("InfinitePlane", lambda: PyRT_Core.InfinitePlane(vector(0.0, -1.0, 0.0),
                                                      vector(0.0, 2.0, 0.0)),
     {"normal": vector(0.0, 1.0, 0.0), "emission": BLACK, "BRDF": PRESENT}),
    ("Parallelogram", lambda: PyRT_Core.Parallelogram(
        vector(0.0, 0.0, -1.0), vector(1.0, 0.0, 0.0), vector(0.0, 1.0, 0.0),
        colour(1.0, 2.0, 3.0)),
     {"emission": colour(1.0, 2.0, 3.0), "BRDF": PRESENT}),
    ("Lambertian", lambda: PyRT_Core.Lambertian(colour(math.pi, 0.0, 0.0)), {"kd": PRESENT}),
    ("PointLight", lambda: PyRT_Core.PointLight(vector(0.0, 5.0, 0.0), colour(8.0, 8.0, 8.0)),
     {"pos": vector(0.0, 5.0, 0.0), "intensity": colour(8.0, 8.0, 8.0)}),
    ("Camera", lambda: PyRT_Core.Camera(4, 2, 90),
     {"width": 4, "height": 2, "vertical_fov": math.pi / 2, "aspect_ratio": 2.0}),
    ("LazyIntegrator", lambda: PyRT_Integrators.LazyIntegrator("out/x"),
     {"filename": "out/x_Lazy", "scene": None, "env_map": None}),
    ("DepthIntegrator", lambda: PyRT_Integrators.DepthIntegrator("out/x", 5),
     {"max_depth": 5, "scene": None}),
    ("CMCIntegrator", lambda: PyRT_Integrators.CMCIntegrator(8, "out/x"),
     {"n_samples": 8, "scene": None}),
    ("BayesianMonteCarloIntegrator",
     lambda: PyRT_Integrators.BayesianMonteCarloIntegrator(8, GP, "out/x"),
     {"n_samples": 8, "myGP": GP, "scene": None}),
]


def assert_value(what, name, actual, expected):
    """actual is the value the spec gives (floats to 1e-12, the rest equal or the same)."""
    if expected is PRESENT:
        return
    if expected is None or expected is GP:
        assert actual is expected, (what, name, actual)
    elif isinstance(expected, float):
        assert actual == pytest.approx(expected, abs=1e-12), (what, name, actual)
    else:
        assert type(actual) is type(expected) and actual == expected, (what, name, actual)


@pytest.mark.parametrize("what, make, attributes", ATTRIBUTES,
                         ids=[what for what, _, _ in ATTRIBUTES])
def test_the_attributes_the_course_names_are_there(what, make, attributes):
    """Every attribute the spec names exists, with the value the spec gives it."""
    made = make()
    for name, expected in attributes.items():
        assert hasattr(made, name), f"{what} has no attribute {name}"
        assert_value(what, name, getattr(made, name), expected)


def test_the_environment_maps_attributes_are_there(env_map_path):
    """EnvironmentMap(env_map_path) has env_map_hdr, width and height."""
    env_map = PyRT_Common.EnvironmentMap(env_map_path=env_map_path)
    assert (env_map.width, env_map.height) == (4, 2)
    assert env_map.env_map_hdr.shape == (2, 4, 3)


def test_the_2021_22_integrator_keeps_an_environment_map_of_its_own(env_map_path):
    """add_environment_map(env_map_path) sets the integrator's env_map, None before."""
    integrator = PyRT_Integrators.PhongIntegrator("out/x")
    assert integrator.env_map is None
    integrator.add_environment_map(env_map_path=env_map_path)
    assert isinstance(integrator.env_map, PyRT_Common.EnvironmentMap)
    assert integrator.env_map.env_map_hdr.shape == (2, 4, 3)


# ------------------------------------------------------------------------------------------
# from PyRT_Common import *
# ------------------------------------------------------------------------------------------
# What each name of a star import is, in terms that two different implementations share:
# a library's module or function by its name, a number by its value, a colour by its
# channels, a class or function of the course's modules (or PyRT's) by its kind.
DESCRIBE = '''
import inspect
import random


def describe(value):
    if value is random.random:
        return ["the global generator's random"]
    if inspect.ismodule(value):
        return ["module", value.__name__]
    if isinstance(value, (int, float)):
        return ["number", float(value)]
    module = getattr(value, "__module__", None) or ""
    ours = module.startswith("PyRT_") or module.startswith("pyrt")
    if inspect.isclass(value):
        return ["course class"] if ours else ["class", module, value.__qualname__]
    if callable(value):
        return ["course function"] if ours else ["function", module, value.__qualname__]
    if all(hasattr(value, channel) for channel in "rgb"):
        return ["colour", float(value.r), float(value.g), float(value.b)]
    return ["other", type(value).__name__]


def star_names():
    namespace = {}
    exec("from PyRT_Common import *", namespace)
    return {name: describe(value) for name, value in namespace.items()
            if not name.startswith("_")}
'''
COURSE_STAR_IMPORT = DESCRIBE + '''
import json
import sys

sys.path.insert(0, sys.argv[1])
print(json.dumps(star_names()))
'''


def course_star_import(folder, edition):
    """{public name: description} of edition's course star import, in a Python of its own."""
    # a Python of its own: the course's PyRT_Common never meets PyRT's in sys.modules
    base = folder / edition
    base.mkdir()
    (base / "PyRT_Common.py").write_text(
        course_submissions.base_text(edition, "PyRT_Common.py"), encoding="utf-8")
    result = run_python(["-c", COURSE_STAR_IMPORT, base], cwd=folder)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout.splitlines()[-1])


def pyrt_star_import():
    """{public name: description} of PyRT's `from PyRT_Common import *`."""
    scope = {}
    exec(DESCRIBE, scope)
    return json.loads(json.dumps(scope["star_names"]()))


@pytest.mark.parametrize("edition", course_submissions.EDITIONS)
def test_the_star_import_gives_every_name_of_the_courses(tmp_path, edition):
    """Every public name the course's star import gives, PyRT's gives, and the same thing."""
    course = course_star_import(tmp_path, edition)
    pyrt = pyrt_star_import()
    assert sorted(set(course) - set(pyrt)) == []
    assert {name: pyrt[name] for name in course} == course


def test_the_course_base_gives_the_names_the_spec_lists(tmp_path):
    """The cross-check of the test data: the 2023-24 base's star import holds the spec's."""
    course = course_star_import(tmp_path, "2023-24")
    spec = ["np", "cv2", "plt", "ABC", "abstractmethod", "sqrt", "acos", "cos", "sin",
            "atan2", "floor", "pi", "random", "EPSILON", "HUGEVALUE", "PI", "TWO_PI",
            "INVERTED_PI", "Vector3D", "Dot", "Cross", "Length", "Normalize", "orient_normal",
            "RGBColor", "BLACK", "WHITE", "GREEN", "RED", "Ray", "HitData", "EnvironmentMap",
            "PDF", "UniformPDF", "CosinePDF", "Function", "Constant", "CosineLobe",
            "sample_set_hemisphere", "center_around_normal", "oriented_hemi_dir",
            "rotate_around_y", "euclidean_to_disk", "visualize_sample_set"]
    assert sorted(course) == sorted(spec)
    assert course["random"] == ["the global generator's random"]
    assert course["GREEN"] == ["colour", 0.0, 1.0, 0.0]


def test_the_star_import_gives_the_function_random_of_the_global_generator():
    """`random` is random.random itself: random.seed(s) makes a student's draws repeat."""
    namespace = {}
    exec("from PyRT_Common import *", namespace)
    assert namespace["random"] is random.random
    random.seed(2024)
    first = [namespace["random"]() for _ in range(3)]
    random.seed(2024)
    assert [random.random() for _ in range(3)] == first
