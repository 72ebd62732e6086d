"""The with-block that stands the fast queries and the fused integrators (Phong, classic
and Bayesian Monte Carlo) in for a scene's and an integrator's own methods during a render, and takes
them off again."""
import sys
from contextlib import contextmanager

from PyRT_Core import Scene
from pyrt.acceleration.fingerprints import (INTERSECT_FUNCTIONS, QUERY_FUNCTIONS,
                                            fused_integrator, fused_unchanged, unchanged)
from pyrt.acceleration.bayesian import AcceleratedBMC, AcceleratedBMCIS
from pyrt.acceleration.monte_carlo import AcceleratedCMC
from pyrt.acceleration.phong import AcceleratedPhong
from pyrt.acceleration.queries import AcceleratedQueries

# Renders of fewer camera rays than this per object list (camera, and each light) leave
# the plain methods in place: the setup would cost more than it saves.
MIN_RAYS_PER_LIST = 8
QUERIES = ("closest_hit", "any_hit")
# The fused integrators, by the name under which their integrator class registers
FUSED_INTEGRATORS = {"phong": AcceleratedPhong, "cmc": AcceleratedCMC, "bmc": AcceleratedBMC,
                     "bmcis": AcceleratedBMCIS}


@contextmanager
def accelerated(integrator, rays=None):
    """A with-block during which the queries of the integrator's scene are those of an
    AcceleratedQueries, when it may stand in for them (can_accelerate) and `rays`, the
    camera rays the block traces, repay its setup (None: assume they do); and, for PyRT's
    own PhongIntegrator and Monte Carlo integrators, compute_color that of their fused
    version (FUSED_INTEGRATORS). Nothing may change the scene meanwhile, as during a render."""
    scene = integrator.scene
    if not can_accelerate(scene) or (
            rays is not None and rays < MIN_RAYS_PER_LIST * (len(scene.pointLights) + 1)):
        yield integrator
        return
    queries = AcceleratedQueries(scene)
    for name in QUERIES:
        setattr(scene, name, getattr(queries, name))
    for name, fused in FUSED_INTEGRATORS.items():
        if can_fuse(name, integrator, queries) and fused.can_stand_in(integrator):
            integrator.compute_color = fused(integrator, queries).compute_color
    try:
        yield integrator
    finally:
        plain(integrator)
        plain(scene)


def plain(obj):
    """Takes what `accelerated` set on an integrator or scene off it again (for a copy made
    during the with-block, say); does nothing to an object without it."""
    own = getattr(obj, "__dict__", {})
    for name in QUERIES + ("compute_color",):
        if isinstance(getattr(own.get(name), "__self__", None),
                      (AcceleratedQueries, *FUSED_INTEGRATORS.values())):
            del own[name]


def can_accelerate(scene) -> bool:
    """Whether AcceleratedQueries may stand in for the scene's queries: the scene uses
    PyRT's own closest_hit and any_hit, unchanged, it holds one of PyRT's primitives at
    least, and no debugger is attached."""
    own = getattr(scene, "__dict__", {})
    return (type(scene).closest_hit is Scene.closest_hit
            and type(scene).any_hit is Scene.any_hit
            and not any(name in own for name in QUERIES)
            and any(type(obj) in INTERSECT_FUNCTIONS for obj in scene.object_list)
            and not debugger_attached()
            and unchanged(QUERY_FUNCTIONS))


def can_fuse(name, integrator, queries) -> bool:
    """Whether the fused version `name` (of FUSED_INTEGRATORS) may stand in for the
    integrator's compute_color: it is the compute_color of the integrator class registered
    for it, which with every function it calls is unchanged, and every object of the
    scene is tested by a scalar fast path."""
    registered = fused_integrator(name)
    return (registered is not None
            and type(integrator).compute_color is registered.compute_color
            and "compute_color" not in vars(integrator)
            and all(entry[0] is not None for entry in queries.everywhere)
            and fused_unchanged(name))


def debugger_attached() -> bool:
    """Whether a debugger traces this process (coverage measurement does not count)."""
    trace = sys.gettrace()
    tracer_module = getattr(trace, "__module__", None) or type(trace).__module__
    return "debugpy" in sys.modules or "pydevd" in sys.modules or (
        trace is not None and not tracer_module.startswith("coverage"))
