"""Which functions the fast paths repeat, and whether they are still what they were when
the fast paths were proven equal to them: fingerprints of their code (not of their
docstrings and comments, whose wording changes nothing they do), and the
integrators (Phong, classic Monte Carlo) that a fused version may stand in for, which
their own module registers."""
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
    "PyRT_Core.Scene.closest_hit": "7493691f2047afb1",
    "PyRT_Core.Scene.any_hit": "8896cbefe7669100",
    "PyRT_Core.unit_direction": "1941c49701d86ddf",
    "PyRT_Core.course_direction": "136ba9d995314715",
    "PyRT_Core.plane_hit_point": "42b95a1bf25ca11c",
    "PyRT_Core.plane_distance": "22968be12a71b664",
    "PyRT_Common.Ray.get_hitpoint": "c3b74a33ee61fa30",
    "PyRT_Core.Normalize": "10fd5857a74ad9a8",
    "PyRT_Core.Length": "13c45a1d03109cb7",
    "PyRT_Core.Dot": "351329371bd55412",
    "PyRT_Common.unit_components": "1c61375707f3aacb",
    "PyRT_Common.euclidean_length": "634a93cbdf618d4d",
}
INTERSECT_FUNCTIONS = {  # each stood in for only while it is unchanged
    Sphere: ("PyRT_Core.Sphere.intersect", "91b2b3e298fc6f92"),
    InfinitePlane: ("PyRT_Core.InfinitePlane.intersect", "e2a51e15014cb068"),
    Parallelogram: ("PyRT_Core.Parallelogram.intersect", "542b6675bfdbffa1"),
}
# PhongIntegrator.compute_color and what it calls from its own module, named as that module
# names them: looked up in the module of the Phong integrator registered (register_fused)
PHONG_FUNCTIONS = {
    "PhongIntegrator.compute_color": "581795d97b449003",
    "shadow_ray": "dcb01d055d1daee9",
    "Length": "13c45a1d03109cb7",
    "Dot": "351329371bd55412",
}
PHONG_CALLS = {  # what PhongIntegrator.compute_color calls of the modules beneath it
    "PyRT_Core.Primitive.get_BRDF": "4b007081b9b6210e",
    "PyRT_Core.Lambertian.get_value": "9cabd01a25691d18",
    "PyRT_Common.Ray.__init__": "5b4d680798accca2",
    "PyRT_Common.Vector3D.__sub__": "0887fa4510743eee",
    "PyRT_Common.Vector3D.__mul__": "82a9b624f897744c",
    "PyRT_Common.Vector3D.__truediv__": "3f1d54570dad9029",
    "PyRT_Common.RGBColor.__add__": "de6961a8acd0babe",
    "PyRT_Common.RGBColor.__mul__": "beb3c80b147bb08d",
    "PyRT_Common.RGBColor.__truediv__": "bd52efa803481ae7",
    "PyRT_Common.RGBColor.multiply": "a4ddb243c868a0da",
}
# CMCIntegrator.compute_color and what it calls, as for Phong
CMC_FUNCTIONS = {
    "CMCIntegrator.compute_color": "f71f88d5c5489e53",
    "sample_set_hemisphere": "67c9141ef04a6345",
    "center_around_normal": "18cb5fb864839088",
    "UniformPDF.get_val": "cfd6c770500a4a41",
    "UniformPDF.generate_dir": "d29c53d615cddccc",
    "Normalize": "10fd5857a74ad9a8",
    "Cross": "db8c33ea3856a8aa",
}
CMC_CALLS = {
    "PyRT_Core.Primitive.get_BRDF": "4b007081b9b6210e",
    "PyRT_Core.Lambertian.get_value": "9cabd01a25691d18",
    "PyRT_Common.EnvironmentMap.getValue": "89bb15d0572059f2",
    "PyRT_Common.EnvironmentMap.euclideanToLatLong": "63017bbf8a97b6df",
    "PyRT_Common.unit_components": "1c61375707f3aacb",
    "PyRT_Common.Ray.__init__": "5b4d680798accca2",
    "PyRT_Common.Vector3D.__init__": "8c8e2974e3f03ed6",
    "PyRT_Common.Vector3D.__add__": "a630d5ec25dd1d66",
    "PyRT_Common.Vector3D.__mul__": "82a9b624f897744c",
    "PyRT_Common.RGBColor.__init__": "5f5df1a5f5cbfc06",
    "PyRT_Common.RGBColor.__add__": "de6961a8acd0babe",
    "PyRT_Common.RGBColor.__truediv__": "bd52efa803481ae7",
    "PyRT_Common.RGBColor.multiply": "a4ddb243c868a0da",
}
# The integrators whose compute_color a fused version repeats, by name: the functions of
# their own module (looked up there) and of the modules beneath it
FUSED = {"phong": (PHONG_FUNCTIONS, PHONG_CALLS), "cmc": (CMC_FUNCTIONS, CMC_CALLS)}


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
    if isinstance(node, ast.expr_context):  # Load, Store, Del: the place says which
        return ""
    fields = [f"{name}={code_text(value)}" for name, value in ast.iter_fields(node)
              if value is not None and value != []]
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
    return [(name, digest, fingerprint(current(name, namespace)))
            for functions, namespace in tables for name, digest in functions.items()]
