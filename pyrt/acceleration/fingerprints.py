"""Which functions the fast paths repeat, and whether they are still what they were when
the fast paths were proven equal to them: fingerprints of their code (not of their
docstrings and comments, whose wording changes nothing they do), and the
integrators (Phong, classic and Bayesian Monte Carlo) that a fused version may stand in
for, which their own module registers."""
import ast
import hashlib
import inspect
import sys
import textwrap
from functools import lru_cache

from PyRT_Core import InfinitePlane, Parallelogram, Sphere

# The functions whose operations the fast paths repeat, named where the plain code finds
# them, with the start of the SHA-256 of their source when the fast paths were proven
# equal to them (tests/test_acceleration.py). One replaced, by assignment or by editing
# its source in place, is not stood in for: the fast paths give way to the plain code.
QUERY_FUNCTIONS = {
    "PyRT_Core.Scene.closest_hit": "58fe69200c5959a7",
    "PyRT_Core.Scene.any_hit": "9107f59cd738ce4b",
    "PyRT_Core.unit_direction": "4255ce1eebb36602",
    "PyRT_Core.course_direction": "9a705656ecc58950",
    "PyRT_Core.plane_hit_point": "2313766aec2173d5",
    "PyRT_Core.plane_distance": "be621b7a73d0501c",
    "PyRT_Common.Ray.get_hitpoint": "6a3b941cc734a077",
    "PyRT_Core.Normalize": "4e0d7b65981f7e18",
    "PyRT_Core.Length": "8b4dc7f8cfbe67d3",
    "PyRT_Core.Dot": "b0580826f7affd8f",
    "PyRT_Common.unit_components": "8122dd21893d8e28",
    "PyRT_Common.euclidean_length": "17e7f9d481206d68",
}
INTERSECT_FUNCTIONS = {  # each stood in for only while it is unchanged
    Sphere: ("PyRT_Core.Sphere.intersect", "5bcd8d685e9a02a6"),
    InfinitePlane: ("PyRT_Core.InfinitePlane.intersect", "84172fca9d1318f7"),
    Parallelogram: ("PyRT_Core.Parallelogram.intersect", "615f8d9c8d40da54"),
}
# PhongIntegrator.compute_color and what it calls from its own module, named as that module
# names them: looked up in the module of the Phong integrator registered (register_fused)
PHONG_FUNCTIONS = {
    "PhongIntegrator.compute_color": "830011959174f404",
    "shadow_ray": "ef4f0001280c5f94",
    "Length": "8b4dc7f8cfbe67d3",
    "Dot": "b0580826f7affd8f",
}
PHONG_CALLS = {  # what PhongIntegrator.compute_color calls of the modules beneath it
    "PyRT_Core.Primitive.get_BRDF": "5b51817f668590c1",
    "PyRT_Core.Lambertian.get_value": "49c4f4efded29f98",
    "PyRT_Common.Ray.__init__": "fe3ed9dc7a88556a",
    "PyRT_Common.Vector3D.__sub__": "f71839dd2a08f91a",
    "PyRT_Common.Vector3D.__mul__": "9d9c56e1bc943543",
    "PyRT_Common.Vector3D.__truediv__": "e3c12859e6e0b56e",
    "PyRT_Common.RGBColor.__add__": "9be1c6822a714e5c",
    "PyRT_Common.RGBColor.__mul__": "b0e55e66354bf902",
    "PyRT_Common.RGBColor.__truediv__": "1206d8380a5657ac",
    "PyRT_Common.RGBColor.multiply": "f71c9682e17487cb",
}
# CMCIntegrator.compute_color and what it calls, as for Phong
CMC_FUNCTIONS = {
    "CMCIntegrator.compute_color": "4bbdad6354d6d0d8",
    "Integrator.incoming_light": "8a6e174cf11ff580",
    "sample_set_hemisphere": "8dc0c1a4b5c85e0e",
    "center_around_normal": "02bb7e079fb76f12",
    "UniformPDF.get_val": "d7dae845af7d6099",
    "UniformPDF.generate_dir": "b3163f41abdf49ce",
    "CosinePDF.get_val": "9ecf50333845530e",
    "CosinePDF.generate_dir": "eaa2a1f5eb946f6e",
    "Dot": "b0580826f7affd8f",
    "Normalize": "4e0d7b65981f7e18",
    "Cross": "32f98e5e40676616",
}
CMC_CALLS = {
    "PyRT_Core.Primitive.get_BRDF": "5b51817f668590c1",
    "PyRT_Core.Lambertian.get_value": "49c4f4efded29f98",
    "PyRT_Common.EnvironmentMap.getValue": "8519365ebbec49ad",
    "PyRT_Common.EnvironmentMap.euclideanToLatLong": "f4b3cd7d60f135ec",
    "PyRT_Common.unit_components": "8122dd21893d8e28",
    "PyRT_Common.Ray.__init__": "fe3ed9dc7a88556a",
    "PyRT_Common.Vector3D.__init__": "d210fb32c4d2ffc0",
    "PyRT_Common.Vector3D.__add__": "0c58ebe2d5e388e3",
    "PyRT_Common.Vector3D.__mul__": "9d9c56e1bc943543",
    "PyRT_Common.RGBColor.__init__": "d58fa7e4e3e1be24",
    "PyRT_Common.RGBColor.__add__": "9be1c6822a714e5c",
    "PyRT_Common.RGBColor.__truediv__": "1206d8380a5657ac",
    "PyRT_Common.RGBColor.multiply": "f71c9682e17487cb",
}
# BayesianMonteCarloIntegrator.compute_color and what it calls, as for Phong; the GP's
# add_sample_val and compute_integral_BMC are called by the fused version too, not repeated
BMC_FUNCTIONS = {
    "BayesianMonteCarloIntegrator.compute_color": "6c9a947b2482131e",
    "BayesianMonteCarloIntegrator.pick_sample_set": "ccab0fd69e7bc3c7",
    "BayesianMonteCarloIntegrator.sample_value": "f50b893bb7b84347",
    "Integrator.incoming_light": "8a6e174cf11ff580",
    "center_around_normal": "02bb7e079fb76f12",
    "rotate_around_y": "66b1685ec30beeea",
    "Normalize": "4e0d7b65981f7e18",
    "Cross": "32f98e5e40676616",
}
BMC_CALLS = dict(CMC_CALLS)  # the same methods of the vectors, colours, BRDF and map
# BMCISIntegrator's: BayesianMonteCarloIntegrator's, with values of its own
BMCIS_FUNCTIONS = dict(BMC_FUNCTIONS, **{"BMCISIntegrator.sample_value": "50cf7ab5d593dd94"})
# PyRT's GP (GaussianProcess.py), whose compute_integral_BMC the fused Bayesian Monte Carlo
# repeats, and whose add_sample_val it leaves out for finite values, which it accepts
GP_FUNCTIONS = {
    "GP.compute_integral_BMC": "6dd75cd7e173656e",
    "GP.add_sample_val": "8b9c3478701a699c",
}
# The integrators whose compute_color a fused version repeats, by name: the functions of
# their own module (looked up there) and of the modules beneath it
FUSED = {"phong": (PHONG_FUNCTIONS, PHONG_CALLS), "cmc": (CMC_FUNCTIONS, CMC_CALLS),
         "bmc": (BMC_FUNCTIONS, BMC_CALLS), "bmcis": (BMCIS_FUNCTIONS, BMC_CALLS)}


def own_gp(gp) -> bool:
    """Whether gp is a GP of PyRT's GaussianProcess.py whose add_sample_val and
    compute_integral_BMC are those the fused Bayesian Monte Carlo was proven equal to."""
    cls = type(gp)
    return (cls.__name__ == "GP" and cls.__module__ == "GaussianProcess"
            and not {"add_sample_val", "compute_integral_BMC"} & set(vars(gp))
            and unchanged(GP_FUNCTIONS, {"GP": cls}))


def unchanged(functions, namespace=None) -> bool:
    """Whether every function named in `functions` (a dict such as QUERY_FUNCTIONS, its
    names looked up in namespace as current does) has the source it had when the fast
    paths were proven equal to it."""
    return all(fingerprint(current(name, namespace)) == digest
               for name, digest in functions.items())


def current(name, namespace=None):
    """The object a dotted name such as "PyRT_Core.Scene.any_hit" stands for now, its first
    part looked up in namespace (a dict; default: the loaded modules); None when there is no
    such thing."""
    first, *attributes = name.split(".")
    obj = (sys.modules if namespace is None else namespace).get(first)
    for attribute in attributes:
        obj = getattr(obj, attribute, None)
    return obj


@lru_cache(maxsize=None)
def fingerprint(function) -> str:
    """The first 16 hexadecimal digits of the SHA-256 of a function's code: its syntax
    tree without docstrings (code_text), so that comments, docstrings and layout leave it
    unchanged; '' when its source cannot be read."""
    try:
        tree = ast.parse(textwrap.dedent(inspect.getsource(function)))
    except (OSError, TypeError, SyntaxError):
        return ""
    return hashlib.sha256(code_text(tree).encode()).hexdigest()[:16]


def code_text(node) -> str:
    """A syntax tree as text, docstrings left out: each node's type and its fields, those
    that are None or empty left out, so that the text is the same on every Python the
    project supports (their trees differ in such optional fields)."""
    if isinstance(node, list):
        return "[" + ", ".join(code_text(item) for item in _without_docstring(node)) + "]"
    if not isinstance(node, ast.AST):
        return repr(node)
    # a name's context (Load, Store, Del) left out too: its place in the tree says which
    fields = [f"{name}={code_text(value)}" for name, value in ast.iter_fields(node)
              if value is not None and value != [] and not isinstance(value, ast.expr_context)]
    return f"{type(node).__name__}({', '.join(fields)})"


def _without_docstring(body):
    """A list of statements without its first when that is a string alone (a docstring)."""
    if (body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant)
            and isinstance(body[0].value.value, str)):
        return body[1:]
    return body


# The integrator classes whose compute_color a fused version repeats, once their module has
# registered them: the acceleration stands beneath the integrators and never imports them.
_registered = {}


def register_fused(name, integrator_class):
    """Registers the integrator class whose compute_color the fused version `name` (a key
    of FUSED) repeats (PyRT_Integrators registers its PhongIntegrator and CMCIntegrator);
    the last one registered counts."""
    _registered[name] = integrator_class


def fused_integrator(name):
    """The integrator class registered for the fused version `name`, or None."""
    return _registered.get(name)


def fused_namespace(name):
    """The globals of the module of the integrator registered for `name`, where its table
    of own functions is looked up (empty before one is registered)."""
    integrator = fused_integrator(name)
    return vars(sys.modules[integrator.__module__]) if integrator is not None else {}


def fused_unchanged(name) -> bool:
    """Whether the registered integrator's compute_color and every function it calls have
    the source they had when the fused version `name` was proven equal to it."""
    functions, calls = FUSED[name]
    return unchanged(functions, fused_namespace(name)) and unchanged(calls)


def mirrored_functions():
    """(name, fingerprint when proven, fingerprint now) of every function the fast paths
    repeat, table after table (each registered integrator's own after its calls)."""
    tables = [(QUERY_FUNCTIONS, None), (dict(INTERSECT_FUNCTIONS.values()), None)]
    for name, (functions, calls) in FUSED.items():
        tables += [(calls, None), (functions, fused_namespace(name))]
    if "GaussianProcess" in sys.modules:
        tables.append((GP_FUNCTIONS, vars(sys.modules["GaussianProcess"])))
    return [(name, digest, fingerprint(current(name, namespace)))
            for functions, namespace in tables for name, digest in functions.items()]
