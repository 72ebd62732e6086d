"""Culling: which objects a ray from a point can reach. Each object's cone, seen from the
camera or from a light, with a margin far above rounding; the plane of a flat object,
which a shadow ray starting clearly on the light's side of it cannot cross; the box of
origins from which fewer objects are left to test."""
from math import sqrt

from PyRT_Common import INFINITY, Dot, Length, euclidean_length
from PyRT_Core import InfinitePlane, Parallelogram, Sphere

# Culling margins, relative to the size of the scene (scene_size): an object's cone is that
# of a sphere CLEARANCE larger than the object, a light must lie CLEARANCE away from a
# plane for the plane to be left out, and a ray whose end lies within LIGHT_MATCH of a light
# counts as a ray towards that light. LIGHT_MATCH covers the millionth by which shadow_ray
# stops short of its light; ORIGIN_MARGIN is far above the rounding error of where a point
# lies relative to a plane.
CLEARANCE = 1e-4
LIGHT_MATCH = 1e-5
ORIGIN_MARGIN = 1e-12


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
    """(cone_x, cone_y, cone_z, cos_limit): the directions d of rays from point that can hit
    obj are among those with d.cone >= cos_limit. For a sphere around obj (CLEARANCE
    larger), cone points to its centre and cos_limit is the cosine of the angle it fills.
    For a flat object whose bounding sphere holds the point, cone is the normal towards its
    plane and cos_limit
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
    """(side_x, side_y, side_z, side_limit) such that a ray towards the light from an origin
    o with o.side > side_limit cannot meet obj: o lies more than ORIGIN_MARGIN on the light's side of
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
    object with an axis-aligned normal among the entries (queries.Entry records, with the
    sides of plane_beyond) can be met on the way to the light, and the entries that remain
    to be tested from inside the box. For such an object, o.side > side_limit is a bound on
    one coordinate of o: the box is where all of them hold, and the walls of a room lit from
    inside all drop out in one test."""
    bounds = [-INFINITY, INFINITY] * 3  # x0, x1, y0, y1, z0, z1
    inside = []
    for entry in entries:
        s, side_limit = (entry.side_x, entry.side_y, entry.side_z), entry.side_limit
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
    -d in the cone, that is d.(-cone) >= cos_limit."""
    cone_x, cone_y, cone_z, cos_limit = cone_of_light
    return -cone_x, -cone_y, -cone_z, cos_limit
