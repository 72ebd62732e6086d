"""Scene queries made fast, with the answers of the plain ones.

``Scene.closest_hit`` and ``Scene.any_hit`` (PyRT_Core.py) are the course's loops: every
object's ``intersect(ray)``, the nearest hit kept. They are what students read and write,
and they run whenever code of a student's own could be involved. During a render,
``accelerated(integrator)`` stands in for the two methods of a scene of PyRT's own classes
with those of ``AcceleratedQueries``, and for ``PhongIntegrator.compute_color`` with that
of ``AcceleratedPhong``; both give the plain code's answers, bit for bit, faster:

- scalar fast paths: the intersection tests of Sphere, InfinitePlane and Parallelogram
  (pyrt/scalar_intersections.py) and the Phong sum, written out on plain floats in the
  operations and order of the plain code, with a HitData made only for the nearest hit;
  for rays from the camera, a wall along the axes is tested without the products by
  zero, which add nothing;
- culling: a ray from the camera, or a shadow ray ending at a point light, tests only the
  objects that a ray from that point in its direction can reach (each object's cone, seen
  from the camera or the light, with a margin far above rounding); and a flat object
  cannot block a shadow ray that starts clearly on the light's side of its plane.

It never runs in place of a student's code. A subclass of Scene with its own closest_hit
or any_hit, a method assigned to the scene, and a change to one of the functions the fast
paths mirror (QUERY_FUNCTIONS, INTERSECT_FUNCTIONS, PHONG_FUNCTIONS: replaced, or edited
in place) leave the plain code to run. An object of a class of its own (a subclass of
Sphere, say) is asked through its own ``intersect`` at every query, in the order of
object_list. With a debugger attached the plain code runs, so that breakpoints in it work.

The setup takes time proportional to objects x (lights + 1), and renders too small to
repay it keep the plain code. tests/test_acceleration.py shows the answers equal to the
plain code's on random scenes and rays.
"""
import hashlib
import inspect
import sys
import textwrap
from contextlib import contextmanager
from functools import lru_cache
from math import sqrt

from PyRT_Common import (BLACK, INFINITY, OFFSET_SCALE, SHADOW_EPSILON, SQUARES_HIGH,
                         SQUARES_LOW, Dot, HitData, Length, RGBColor, Vector3D, _new,
                         euclidean_length)
from PyRT_Core import UNIT_HIGH, UNIT_LOW, InfinitePlane, Lambertian, Parallelogram, Scene, Sphere
from pyrt.scalar_intersections import (POINT_AND_NORMAL, camera_test, infinite_plane_distance,
                                      parallelogram_distance, sphere_distance)

# Culling margins, relative to the size of the scene (scene_size): an object's cone is that
# of a sphere CLEARANCE larger than the object, a light must lie CLEARANCE away from a
# plane for the plane to be left out, and a ray whose end lies within LIGHT_MATCH of a light
# counts as a ray towards that light. LIGHT_MATCH covers the millionth by which shadow_ray
# stops short of its light; ORIGIN_MARGIN is far above the rounding error of where a point
# lies relative to a plane.
CLEARANCE = 1e-4
LIGHT_MATCH = 1e-5
ORIGIN_MARGIN = 1e-12
# Renders of fewer camera rays than this per object list (camera, and each light) leave
# the plain methods in place: the setup would cost more than it saves.
MIN_RAYS_PER_LIST = 8
# any_hit's next light when there is none: a box that holds no point.
NO_LIGHT = (INFINITY, -INFINITY) * 3

# The functions whose operations the fast paths repeat, named where the plain code finds
# them, with the start of the SHA-256 of their source when the fast paths were proven
# equal to them (tests/test_acceleration.py). One replaced, by assignment or by editing
# its source in place, is not stood in for: the fast paths give way to the plain code.
QUERY_FUNCTIONS = {
    "PyRT_Core.Scene.closest_hit": "b8f3be4604f3fb81",
    "PyRT_Core.Scene.any_hit": "b4260ae7059b6f3d",
    "PyRT_Core.unit_direction": "a918a0f2d2309304",
    "PyRT_Core.plane_distance": "0654dba6f824c144",
    "PyRT_Core.Normalize": "41257e0e7f7f37cd",
    "PyRT_Core.Length": "4b4d97bb903012e7",
    "PyRT_Core.Dot": "5968b1bc66a4e991",
    "PyRT_Common.unit_components": "4fddd540ec7253a7",
    "PyRT_Common.euclidean_length": "ed684f71ac87a76c",
}
INTERSECT_FUNCTIONS = {  # each stood in for only while it is unchanged
    Sphere: ("PyRT_Core.Sphere.intersect", "2677b580cdc27c92"),
    InfinitePlane: ("PyRT_Core.InfinitePlane.intersect", "160459be816b77d7"),
    Parallelogram: ("PyRT_Core.Parallelogram.intersect", "097e24d3fd5a174c"),
}
PHONG_FUNCTIONS = {  # PhongIntegrator.compute_color and what it calls besides the queries
    "PyRT_Integrators.PhongIntegrator.compute_color": "4c6b5443bdfb642b",
    "PyRT_Integrators.shadow_ray": "32ca8d4a3ead2a3b",
    "PyRT_Integrators.Length": "4b4d97bb903012e7",
    "PyRT_Integrators.Dot": "5968b1bc66a4e991",
    "PyRT_Core.Primitive.get_BRDF": "5009389ae19f8874",
    "PyRT_Core.Lambertian.get_value": "4a56e9c61b6d4186",
    "PyRT_Common.Ray.__init__": "308e8987ef15745f",
    "PyRT_Common.Vector3D.__sub__": "a7b23b59990f357e",
    "PyRT_Common.Vector3D.__mul__": "566dee40a844b2a9",
    "PyRT_Common.Vector3D.__truediv__": "4dc8cc15c2a222b9",
    "PyRT_Common.RGBColor.__add__": "126ec3224ad46034",
    "PyRT_Common.RGBColor.__mul__": "8e0ca007b4e3bfe8",
    "PyRT_Common.RGBColor.__truediv__": "85e151eb11f94b85",
    "PyRT_Common.RGBColor.multiply": "3cff1994f44a3a5e",
}


def unchanged(functions) -> bool:
    """Whether every function named in `functions` (a dict such as QUERY_FUNCTIONS) has
    the source it had when the fast paths were proven equal to it."""
    return all(fingerprint(current(name)) == digest for name, digest in functions.items())


def current(name):
    """The object a dotted name such as "PyRT_Core.Scene.any_hit" stands for now, looked up
    in the loaded modules; None when there is no such thing."""
    module, *attributes = name.split(".")
    obj = sys.modules.get(module)
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


# ------------------------------------------------------------------------------------------
# Standing in for a scene's queries during a render
# ------------------------------------------------------------------------------------------
QUERIES = ("closest_hit", "any_hit")


@contextmanager
def accelerated(integrator, rays=None):
    """A with-block during which the queries of the integrator's scene are those of an
    AcceleratedQueries, when it may stand in for them (can_accelerate) and `rays`, the
    camera rays the block traces, repay its setup (None: assume they do); and, for PyRT's
    own PhongIntegrator, compute_color that of an AcceleratedPhong. Nothing may change the
    scene meanwhile, as during a render."""
    scene = integrator.scene
    if not can_accelerate(scene) or (
            rays is not None and rays < MIN_RAYS_PER_LIST * (len(scene.pointLights) + 1)):
        yield integrator
        return
    queries = AcceleratedQueries(scene)
    for name in QUERIES:
        setattr(scene, name, getattr(queries, name))
    if can_accelerate_phong(integrator, queries):
        integrator.compute_color = AcceleratedPhong(integrator, queries).compute_color
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
                      (AcceleratedQueries, AcceleratedPhong)):
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


def can_accelerate_phong(integrator, queries) -> bool:
    """Whether AcceleratedPhong may stand in for the integrator's compute_color: it is
    PyRT's own PhongIntegrator.compute_color, which with every function it calls is
    unchanged, and every object of the scene is tested by a scalar fast path."""
    phong = current("PyRT_Integrators.PhongIntegrator")
    return (phong is not None and type(integrator).compute_color is phong.compute_color
            and "compute_color" not in vars(integrator)
            and all(entry[0] is not None for entry in queries.everywhere)
            and unchanged(PHONG_FUNCTIONS))


def debugger_attached() -> bool:
    """Whether a debugger traces this process (coverage measurement does not count)."""
    trace = sys.gettrace()
    tracer_module = getattr(trace, "__module__", None) or type(trace).__module__
    return "debugpy" in sys.modules or "pydevd" in sys.modules or (
        trace is not None and not tracer_module.startswith("coverage"))


# ------------------------------------------------------------------------------------------
# The fast queries
# ------------------------------------------------------------------------------------------
class AcceleratedQueries:
    """closest_hit and any_hit of a scene, equal to Scene's, for rays traced while the
    scene does not change.

    Each query walks a list of entries, one per object in the order of object_list:
    (test, constants, index, object, ux, uy, uz, cos_limit, sx, sy, sz, side_limit). test
    is the scalar intersection test of the object's class (None for an object tested
    through its own intersect), constants what it reads. A ray of unit direction d with
    d.u < cos_limit cannot hit the object (its cone), nor can a ray from origin o with
    o.s > side_limit (the flat object's plane lies beyond the ray's end, seen from o).
    Lists: from_camera, for rays that start at the camera (the origin); everywhere, for
    any other ray, with nothing left out; and for the rays that end at point light i
    (shadow rays), towards_light[i]: (x_low, x_high, y_low, y_high, z_low, z_high), the
    box around the light where such a ray ends, then its clear_box, the shorter list of
    the entries left to test from an origin inside that box, its entries with the cones
    seen from the light, reversed, and the index of the light after it."""

    def __init__(self, scene):
        self.scene = scene
        objects, lights = scene.object_list, scene.pointLights
        scale = scene_size(objects, lights)
        tests = [_object_test(obj) for obj in objects]
        origin = Vector3D(0.0, 0.0, 0.0)
        self.everywhere = [(test, constants, index, obj, 0.0, 0.0, 0.0, -2.0, 0.0, 0.0, 0.0,
                            INFINITY)
                           for index, (obj, (test, constants)) in enumerate(zip(objects, tests))]
        self.from_camera = [
            camera_test(*entry[:2]) + entry[2:4] + cone(entry[3], origin, scale,
                                                         entry[0] is not None) + entry[8:]
            for entry in self.everywhere]
        self.light_match = within = LIGHT_MATCH * scale
        self.towards_light = []
        for number, light in enumerate(lights, 1):
            entries = [entry[:4] + _reversed(cone(entry[3], light.pos, scale,
                                                  entry[0] is not None))
                       + plane_beyond(entry[3], light.pos, scale, entry[0] is not None)
                       for entry in self.everywhere]
            x, y, z = light.pos
            self.towards_light.append((x - within, x + within, y - within, y + within,
                                       z - within, z + within, *clear_box(entries), entries,
                                       number % len(lights)))
        # Shadow rays come light after light: any_hit tries the light after the last one
        # found first.
        self.next_light = self.towards_light[0] if lights else NO_LIGHT

    def closest_hit(self, ray):
        """Scene.closest_hit(ray)."""
        d = ray.d
        dx, dy, dz = d.x, d.y, d.z
        if not UNIT_LOW <= dx * dx + dy * dy + dz * dz <= UNIT_HIGH:
            return Scene.closest_hit(self.scene, ray)  # a direction to normalise: rare
        o = ray.o
        ox, oy, oz = o.x, o.y, o.z
        nearest = self.nearest(ray, ox, oy, oz, dx, dy, dz, ray.t_min, ray.t_max)
        if nearest is None:
            return HitData()
        test, found, index, t = nearest
        if test is None:  # found is the HitData of the object's own intersect
            found.primitive_index = index
            return found
        # HitData(True, Vector3D(px, py, pz), Vector3D(nx, ny, nz), t, index), made without
        # the three calls of __init__, which closest_hit would make for nearly every pixel
        point, normal, hit = _new(Vector3D), _new(Vector3D), _new(HitData)
        point.x, point.y, point.z, normal.x, normal.y, normal.z = POINT_AND_NORMAL[test](
            found, ox, oy, oz, dx, dy, dz, t)
        hit.has_hit, hit.hit_point, hit.normal, hit.hit_distance = True, point, normal, t
        hit.primitive_index = index
        return hit

    def nearest(self, ray, ox, oy, oz, dx, dy, dz, t_min, t_max):
        """(test, constants, index, t) of the nearest hit of the ray from (ox, oy, oz) along
        the unit direction (dx, dy, dz) in [t_min, t_max], or None; for an object asked
        through its own intersect, (None, its HitData, index, t). Only a strictly nearer
        hit replaces the nearest so far, as in Scene.closest_hit."""
        from_camera = ox == 0.0 and oy == 0.0 and oz == 0.0 and t_min >= 0.0
        nearest = None
        for test, constants, index, obj, ux, uy, uz, cos_limit, _, _, _, _ in (
                self.from_camera if from_camera else self.everywhere):
            if dx * ux + dy * uy + dz * uz < cos_limit:
                continue
            if test is None:  # its own intersect, along the ray as it is
                hit = obj.intersect(ray)
                if hit.has_hit and (nearest is None or hit.hit_distance < t_max):
                    nearest, t_max = (None, hit, index, hit.hit_distance), hit.hit_distance
                continue
            t = test(constants, ox, oy, oz, dx, dy, dz, t_min, t_max)
            if t is not None and (nearest is None or t < t_max):
                nearest, t_max = (test, constants, index, t), t
        return nearest

    def any_hit(self, ray):
        """Scene.any_hit(ray)."""
        d = ray.d
        dx, dy, dz = d.x, d.y, d.z
        if not UNIT_LOW <= dx * dx + dy * dy + dz * dz <= UNIT_HIGH:
            return Scene.any_hit(self.scene, ray)  # a direction to normalise: rare
        o = ray.o
        ox, oy, oz, t_min, t_max = o.x, o.y, o.z, ray.t_min, ray.t_max
        entries = self.everywhere
        if t_min >= 0.0:
            if ox == 0.0 and oy == 0.0 and oz == 0.0:
                entries = self.from_camera
            elif t_max < INFINITY:  # a shadow ray, when it ends at a light
                ex, ey, ez = ox + dx * t_max, oy + dy * t_max, oz + dz * t_max
                light = self.next_light
                if not (light[0] <= ex <= light[1] and light[2] <= ey <= light[3]
                        and light[4] <= ez <= light[5]):
                    light = self.light_at(ex, ey, ez)
                if light is not None:
                    _, _, _, _, _, _, (x0, x1, y0, y1, z0, z1), inside, entries, after = light
                    self.next_light = self.towards_light[after]
                    if x0 < ox < x1 and y0 < oy < y1 and z0 < oz < z1:
                        entries = inside
        for test, constants, _, obj, ux, uy, uz, cos_limit, sx, sy, sz, side_limit in entries:
            if (dx * ux + dy * uy + dz * uz >= cos_limit
                    and ox * sx + oy * sy + oz * sz <= side_limit):
                if test is None:
                    if obj.intersect(ray).has_hit:
                        return True
                elif test(constants, ox, oy, oz, dx, dy, dz, t_min, t_max) is not None:
                    return True
        return False

    def light_at(self, x, y, z):
        """The towards_light entry of the first light whose box holds (x, y, z), or None."""
        for light in self.towards_light:
            if (light[0] <= x <= light[1] and light[2] <= y <= light[3]
                    and light[4] <= z <= light[5]):
                return light
        return None


class AcceleratedPhong:
    """PhongIntegrator.compute_color, equal to it bit for bit, for a scene whose queries
    are an AcceleratedQueries of PyRT's primitives: the same operations in the same order
    on plain floats; the closest hit without its HitData; the shadow ray of shadow_ray
    tested without building it, with the entries of its light; Lambertian's get_value
    inline. A BRDF other than Lambertian, and rays that PhongIntegrator's own code must
    decide, are left to that code, pixel by pixel."""

    def __init__(self, integrator, queries):
        self.integrator, self.queries = integrator, queries
        scene = integrator.scene
        self.objects, self.ambient = scene.object_list, scene.i_a
        # A shadow ray ends SHADOW_EPSILON of its length short of its light: the light's
        # entries hold for it when that is within light_match (else any_hit decides).
        self.longest_shadow_ray = queries.light_match / SHADOW_EPSILON
        self.lights = [(light.pos.x, light.pos.y, light.pos.z, light.intensity.r,
                        light.intensity.g, light.intensity.b) + box + (inside, entries)
                       for light, (_, _, _, _, _, _, box, inside, entries, _)
                       in zip(scene.pointLights, queries.towards_light)]

    def compute_color(self, ray):
        """PhongIntegrator.compute_color(ray)."""
        d, o = ray.d, ray.o
        dx, dy, dz, ox, oy, oz = d.x, d.y, d.z, o.x, o.y, o.z
        if not UNIT_LOW <= dx * dx + dy * dy + dz * dz <= UNIT_HIGH:
            return self.plain_color(ray)
        nearest = self.queries.nearest(None, ox, oy, oz, dx, dy, dz, ray.t_min, ray.t_max)
        if nearest is None:
            return BLACK
        test, constants, index, t = nearest
        brdf = self.objects[index].get_BRDF()
        if type(brdf) is not Lambertian:
            return self.plain_color(ray)
        px, py, pz, nx, ny, nz = POINT_AND_NORMAL[test](constants, ox, oy, oz, dx, dy, dz, t)
        kd, ambient = brdf.kd, self.ambient
        kr, kg, kb = kd.r, kd.g, kd.b
        red, green, blue = kr * ambient.r, kg * ambient.g, kb * ambient.b
        size = max(abs(px), abs(py), abs(pz)) + t
        if size == 0.0:  # shadow_ray takes the size from each light's distance
            return self.plain_color(ray)
        offset = OFFSET_SCALE * size
        longest = self.longest_shadow_ray
        for x, y, z, ir, ig, ib, x0, x1, y0, y1, z0, z1, inside, entries in self.lights:
            tx, ty, tz = x - px, y - py, z - pz  # to_light
            squares = tx * tx + ty * ty + tz * tz
            r = sqrt(squares) if SQUARES_LOW < squares < SQUARES_HIGH else (
                euclidean_length(tx, ty, tz))
            if r * r == 0.0 or nx * tx + ny * ty + nz * tz <= 0.0:
                continue
            # shadow_ray(hit, light.pos): the light is in front, so the offset is upwards
            sox, soy, soz = px + nx * offset, py + ny * offset, pz + nz * offset
            sx, sy, sz = x - sox, y - soy, z - soz
            squares = sx * sx + sy * sy + sz * sz
            distance = sqrt(squares) if SQUARES_LOW < squares < SQUARES_HIGH else (
                euclidean_length(sx, sy, sz))
            if not 0.0 < distance <= longest:
                return self.plain_color(ray)
            sx, sy, sz = sx / distance, sy / distance, sz / distance
            if not UNIT_LOW <= sx * sx + sy * sy + sz * sz <= UNIT_HIGH:
                return self.plain_color(ray)
            # any_hit of the shadow ray, with the entries of its light
            s_max = distance * (1.0 - SHADOW_EPSILON)
            if x0 < sox < x1 and y0 < soy < y1 and z0 < soz < z1:
                entries = inside
            for test, constants, _, _, ux, uy, uz, cos_limit, qx, qy, qz, side_limit in entries:
                if (sx * ux + sy * uy + sz * uz >= cos_limit
                        and sox * qx + soy * qy + soz * qz <= side_limit
                        and test(constants, sox, soy, soz, sx, sy, sz, offset, s_max) is not None):
                    break  # in the shadow of this object
            else:
                cos_theta = nx * (tx / r) + ny * (ty / r) + nz * (tz / r)  # get_value(wi, ...)
                if cos_theta > 0.0:
                    rr = r * r
                    red += ir * (kr * cos_theta) / rr
                    green += ig * (kg * cos_theta) / rr
                    blue += ib * (kb * cos_theta) / rr
        return RGBColor(red, green, blue)

    def plain_color(self, ray):
        """PhongIntegrator's own compute_color, with the accelerated queries."""
        return type(self.integrator).compute_color(self.integrator, ray)


# ------------------------------------------------------------------------------------------
# Culling
# ------------------------------------------------------------------------------------------
def scene_size(objects, lights) -> float:
    """The largest |coordinate| of the scene's lights and built-in objects (1 when there is
    none): the scale of the culling margins."""
    size = 0.0
    for obj in objects:
        kind = type(obj)
        if kind is Sphere:
            size = max(size, *map(abs, obj.origin), obj.radius)
        elif kind is Parallelogram:
            for corner in corners(obj):
                size = max(size, *map(abs, corner))
        elif kind is InfinitePlane:
            size = max(size, *map(abs, obj.origin))
    for light in lights:
        size = max(size, *map(abs, light.pos))
    return size or 1.0


def corners(parallelogram) -> list:
    """The four corners (x, y, z) of a parallelogram."""
    p, s1, s2 = parallelogram.point, parallelogram.s1, parallelogram.s2
    return [(p.x + a * s1.x + b * s2.x, p.y + a * s1.y + b * s2.y, p.z + a * s1.z + b * s2.z)
            for a, b in ((0, 0), (1, 0), (0, 1), (1, 1))]


def bounds(obj):
    """(centre, radius) of a sphere holding a built-in object; None for an infinite plane."""
    if type(obj) is Sphere:
        return obj.origin, obj.radius
    if type(obj) is Parallelogram:
        # The centre point + (s1 + s2)/2; the farthest corners lie half a diagonal from it.
        s1, s2 = obj.s1, obj.s2
        return obj.point + (s1 + s2) * 0.5, max(Length(s1 + s2), Length(s1 - s2)) * 0.5
    return None


def cone(obj, point, scale, built_in) -> tuple:
    """(ux, uy, uz, cos_limit): the directions d of rays from point that can hit obj are
    among those with d.u >= cos_limit. For a sphere around obj (CLEARANCE larger), u points
    to its centre and cos_limit is the cosine of the angle it fills. For a flat object
    whose bounding sphere holds the point, u is the normal towards its plane and cos_limit
    just below 0 (rays along the plane are kept); cos_limit -2 keeps every direction."""
    if not built_in:
        return 0.0, 0.0, 0.0, -2.0
    around = bounds(obj)
    if around is not None:
        centre, radius = around
        radius += CLEARANCE * scale
        vx, vy, vz = centre.x - point.x, centre.y - point.y, centre.z - point.z
        distance = euclidean_length(vx, vy, vz)
        if distance > radius:
            return (vx / distance, vy / distance, vz / distance,
                    sqrt((distance - radius) * (distance + radius)) / distance)
    height = _height(obj, point)
    if height is not None and abs(height) >= CLEARANCE * scale:
        towards = -1.0 if height > 0.0 else 1.0
        n = obj.normal
        return towards * n.x, towards * n.y, towards * n.z, -1e-9
    return 0.0, 0.0, 0.0, -2.0


def plane_beyond(obj, light_position, scale, built_in) -> tuple:
    """(sx, sy, sz, side_limit) such that a ray towards the light from an origin o with
    o.s > side_limit cannot meet obj: o lies more than ORIGIN_MARGIN on the light's side of
    the plane of a flat obj, the light more than CLEARANCE, so the whole way lies on one
    side. (0, 0, 0, infinity), which leaves out nothing, for other objects."""
    height = _height(obj, light_position) if built_in else None
    if height is None or abs(height) < CLEARANCE * scale:
        return 0.0, 0.0, 0.0, INFINITY
    side = 1.0 if height > 0.0 else -1.0
    n = obj.normal
    offset = Dot(n, _point_on_plane(obj))
    return side * n.x, side * n.y, side * n.z, side * offset + ORIGIN_MARGIN * scale


def clear_box(entries) -> tuple:
    """((x0, x1, y0, y1, z0, z1), inside): the open box of origins o from which no flat
    object with an axis-aligned normal among the entries (plane_beyond) can be met on the
    way to the light, and the entries that remain to be tested from inside the box. For
    such an object, o.s > side_limit is a bound on one coordinate of o: the box is where all
    of them hold, and the walls of a room lit from inside all drop out in one test."""
    bounds = [-INFINITY, INFINITY] * 3  # x0, x1, y0, y1, z0, z1
    inside = []
    for entry in entries:
        s, side_limit = entry[8:11], entry[11]
        axes = [axis for axis in range(3) if s[axis] != 0.0]
        if side_limit == INFINITY or len(axes) != 1 or abs(s[axes[0]]) != 1.0:
            inside.append(entry)
            continue
        axis = axes[0]
        if s[axis] > 0.0:  # o[axis] > side_limit
            bounds[2 * axis] = max(bounds[2 * axis], side_limit)
        else:  # -o[axis] > side_limit
            bounds[2 * axis + 1] = min(bounds[2 * axis + 1], -side_limit)
    return tuple(bounds), inside


def _height(obj, point):
    """The signed height of point over the plane of a flat built-in object, along its
    normal; None for a sphere."""
    if type(obj) not in (InfinitePlane, Parallelogram):
        return None
    return Dot(point, obj.normal) - Dot(obj.normal, _point_on_plane(obj))


def _point_on_plane(obj):
    return obj.origin if type(obj) is InfinitePlane else obj.point


def _reversed(cone_of_light) -> tuple:
    """A cone seen from a light, for the rays that run towards it: their direction d has
    -d in the cone, that is d.(-u) >= cos_limit."""
    ux, uy, uz, cos_limit = cone_of_light
    return -ux, -uy, -uz, cos_limit


# ------------------------------------------------------------------------------------------
# The scalar test of each object
# ------------------------------------------------------------------------------------------
def _object_test(obj):
    """(test, constants) for an object: its class's scalar test and what the test reads, or
    (None, None) when the object is asked through its own intersect: an object of a class
    of its own (a subclass of a built-in one too), or of a class whose intersect is not
    the one proven."""
    kind = type(obj)
    if kind not in INTERSECT_FUNCTIONS or not unchanged(dict([INTERSECT_FUNCTIONS[kind]])):
        return None, None
    if kind is Sphere:
        c = obj.origin
        return sphere_distance, (c.x, c.y, c.z, obj.radius)
    if kind is InfinitePlane:
        n, p = obj.normal, obj.origin
        return infinite_plane_distance, (n.x, n.y, n.z, p.x, p.y, p.z)
    n, p, a, b = obj.normal, obj.point, obj.coordinate_a, obj.coordinate_b
    return parallelogram_distance, (n.x, n.y, n.z, p.x, p.y, p.z,
                                    a.x, a.y, a.z, b.x, b.y, b.z)


if __name__ == "__main__":
    # For maintainers: the fingerprints of the mirrored functions as they are now, to copy
    # into the tables above once tests/test_acceleration.py shows that the fast paths
    # still give the same answers.
    import PyRT_Integrators  # noqa: F401  (loaded, so that its functions can be looked up)

    for functions in (QUERY_FUNCTIONS, dict(INTERSECT_FUNCTIONS.values()), PHONG_FUNCTIONS):
        for name in functions:
            print(f"{name}: {fingerprint(current(name))}")
