"""Which functions the fast paths repeat, and whether they are still what they were when
the fast paths were proven equal to them: fingerprints of their source, and the
integrators (Phong, classic and Bayesian Monte Carlo) that a fused version may stand in
for, which their own module registers."""
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
    "PyRT_Core.Scene.closest_hit": "b8f3be4604f3fb81",
    "PyRT_Core.Scene.any_hit": "b4260ae7059b6f3d",
    "PyRT_Core.unit_direction": "a918a0f2d2309304",
    "PyRT_Core.course_direction": "64a22aa7e6fffb14",
    "PyRT_Core.plane_hit_point": "fb8e16be5e26a818",
    "PyRT_Core.plane_distance": "0654dba6f824c144",
    "PyRT_Common.Ray.get_hitpoint": "4226c57767ef8a26",
    "PyRT_Core.Normalize": "41257e0e7f7f37cd",
    "PyRT_Core.Length": "4b4d97bb903012e7",
    "PyRT_Core.Dot": "5968b1bc66a4e991",
    "PyRT_Common.unit_components": "4fddd540ec7253a7",
    "PyRT_Common.euclidean_length": "ed684f71ac87a76c",
}
INTERSECT_FUNCTIONS = {  # each stood in for only while it is unchanged
    Sphere: ("PyRT_Core.Sphere.intersect", "2677b580cdc27c92"),
    InfinitePlane: ("PyRT_Core.InfinitePlane.intersect", "f84fd7ab7eb74ab0"),
    Parallelogram: ("PyRT_Core.Parallelogram.intersect", "a8a4f043cdad8e4d"),
}
# PhongIntegrator.compute_color and what it calls from its own module, named as that module
# names them: looked up in the module of the Phong integrator registered (register_fused)
PHONG_FUNCTIONS = {
    "PhongIntegrator.compute_color": "4c6b5443bdfb642b",
    "shadow_ray": "32ca8d4a3ead2a3b",
    "Length": "4b4d97bb903012e7",
    "Dot": "5968b1bc66a4e991",
}
PHONG_CALLS = {  # what PhongIntegrator.compute_color calls of the modules beneath it
    "PyRT_Core.Primitive.get_BRDF": "5009389ae19f8874",
    "PyRT_Core.Lambertian.get_value": "4a56e9c61b6d4186",
    "PyRT_Common.Ray.__init__": "308e8987ef15745f",
    "PyRT_Common.Vector3D.__sub__": "a7b23b59990f357e",
    "PyRT_Common.Vector3D.__mul__": "566dee40a844b2a9",
    "PyRT_Common.Vector3D.__truediv__": "4dc8cc15c2a222b9",
    "PyRT_Common.RGBColor.__add__": "126ec3224ad46034",
    "PyRT_Common.RGBColor.__mul__": "8e0ca007b4e3bfe8",
    "PyRT_Common.RGBColor.__truediv__": "85e151eb11f94b85",
    "PyRT_Common.RGBColor.multiply": "db6e9f232b4675f8",
}
# CMCIntegrator.compute_color and what it calls, as for Phong
CMC_FUNCTIONS = {
    "CMCIntegrator.compute_color": "dfa850a62a68c949",
    "Integrator.incoming_light": "0fdae8403b738c7e",
    "sample_set_hemisphere": "96811dd0dbd0d5fd",
    "center_around_normal": "35252ba91566888f",
    "UniformPDF.get_val": "c96ffa7b144b10b6",
    "UniformPDF.generate_dir": "5c490cc04585c51c",
    "CosinePDF.get_val": "016d6a63042db3b3",
    "CosinePDF.generate_dir": "3674677286641a5c",
    "Dot": "5968b1bc66a4e991",
    "Normalize": "41257e0e7f7f37cd",
    "Cross": "231231219460270a",
}
CMC_CALLS = {
    "PyRT_Core.Primitive.get_BRDF": "5009389ae19f8874",
    "PyRT_Core.Lambertian.get_value": "4a56e9c61b6d4186",
    "PyRT_Common.EnvironmentMap.getValue": "c10cca36338c7e73",
    "PyRT_Common.EnvironmentMap.euclideanToLatLong": "668772b80c629197",
    "PyRT_Common.unit_components": "4fddd540ec7253a7",
    "PyRT_Common.Ray.__init__": "308e8987ef15745f",
    "PyRT_Common.Vector3D.__init__": "b493185bd8c49e96",
    "PyRT_Common.Vector3D.__add__": "49d113308126edbd",
    "PyRT_Common.Vector3D.__mul__": "566dee40a844b2a9",
    "PyRT_Common.RGBColor.__init__": "21b84a3a382253a2",
    "PyRT_Common.RGBColor.__add__": "126ec3224ad46034",
    "PyRT_Common.RGBColor.__truediv__": "85e151eb11f94b85",
    "PyRT_Common.RGBColor.multiply": "db6e9f232b4675f8",
}
# BayesianMonteCarloIntegrator.compute_color and what it calls, as for Phong; the GP's
# add_sample_val and compute_integral_BMC are called by the fused version too, not repeated
BMC_FUNCTIONS = {
    "BayesianMonteCarloIntegrator.compute_color": "2533396463c3491a",
    "BayesianMonteCarloIntegrator.pick_sample_set": "d9bee35e840dfc0e",
    "BayesianMonteCarloIntegrator.sample_value": "a11f784f8639baf6",
    "Integrator.incoming_light": "0fdae8403b738c7e",
    "center_around_normal": "35252ba91566888f",
    "rotate_around_y": "7dc88a64ef41cc6c",
    "Normalize": "41257e0e7f7f37cd",
    "Cross": "231231219460270a",
}
BMC_CALLS = dict(CMC_CALLS)  # the same methods of the vectors, colours, BRDF and map
# BMCISIntegrator's: BayesianMonteCarloIntegrator's, with values of its own
BMCIS_FUNCTIONS = dict(BMC_FUNCTIONS, **{"BMCISIntegrator.sample_value": "dc976d52942d97cb"})
# PyRT's GP (GaussianProcess.py), whose compute_integral_BMC the fused Bayesian Monte Carlo
# repeats, and whose add_sample_val it leaves out for finite values, which it accepts
GP_FUNCTIONS = {
    "GP.compute_integral_BMC": "0e84c33a3f1fc0f4",
    "GP.add_sample_val": "ebf8fb32be7e7bec",
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
    """The first 16 hexadecimal digits of the SHA-256 of a function's source (dedented);
    '' when its source cannot be read."""
    try:
        source = textwrap.dedent(inspect.getsource(function))
    except (OSError, TypeError):
        return ""
    return hashlib.sha256(source.encode()).hexdigest()[:16]


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
