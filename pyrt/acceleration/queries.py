"""AcceleratedQueries: a scene's closest_hit and any_hit, equal to Scene's bit for bit, on
plain floats, each ray testing only the objects it can reach (culling.py)."""
from math import sqrt
from typing import Callable, NamedTuple, Optional

from PyRT_Common import INFINITY, HitData, Vector3D, _new
from PyRT_Core import UNIT_HIGH, UNIT_LOW, InfinitePlane, Scene, Sphere
from pyrt.acceleration.culling import (LIGHT_MATCH, clear_box, cone, plane_beyond,
                                       scene_size, _reversed)
from pyrt.acceleration.fingerprints import INTERSECT_FUNCTIONS, unchanged
from pyrt.scalar_intersections import (POINT_AND_NORMAL, camera_test, infinite_plane_distance,
                                       parallelogram_distance, sphere_distance)


class Entry(NamedTuple):
    """An object as the queries test it. test is the scalar intersection test of the
    object's class (None for an object tested through its own intersect), constants what it
    reads. A ray of unit direction d with d.cone < cos_limit cannot hit the object (its
    cone, seen from where the ray starts), nor can a ray from origin o with
    o.side > side_limit (the flat object's plane lies beyond the ray's end, seen from o)."""

    test: Optional[Callable]
    constants: Optional[tuple]
    index: int
    obj: object
    cone_x: float
    cone_y: float
    cone_z: float
    cos_limit: float
    side_x: float
    side_y: float
    side_z: float
    side_limit: float


class TowardsLight(NamedTuple):
    """What the queries know of the rays that end at one point light (shadow rays): the box
    around the light where such a ray ends, the clear_box of origins (x0, x1, y0, y1, z0,
    z1) with its shorter list of entries left to test from inside it, the light's entries
    with the cones seen from the light, reversed, and the index of the next light."""

    x_low: float
    x_high: float
    y_low: float
    y_high: float
    z_low: float
    z_high: float
    clear_box: tuple
    inside: list
    entries: list
    next_light: int


# any_hit's next light when there is none: a box that holds no point.
NO_LIGHT = tuple(TowardsLight(INFINITY, -INFINITY, INFINITY, -INFINITY, INFINITY, -INFINITY,
                              (), [], [], 0))


class AcceleratedQueries:
    """closest_hit and any_hit of a scene, equal to Scene's, for rays traced while the
    scene does not change.

    Each query walks a list of entries, one per object in the order of object_list, each an
    Entry held as a plain tuple (a NamedTuple unpacks slower in the queries' loops:
    docs/performance.md). Lists: from_camera, for rays that start at the
    camera (the origin); everywhere, for any other ray, with nothing left out; and for the
    rays that end at point light i, towards_light[i], a TowardsLight held as a tuple."""

    def __init__(self, scene):
        self.scene = scene
        objects, lights = scene.object_list, scene.pointLights
        scale = scene_size(objects, lights)
        origin = Vector3D(0.0, 0.0, 0.0)
        everywhere = [Entry(test, constants, index, obj, 0.0, 0.0, 0.0, -2.0,
                            0.0, 0.0, 0.0, INFINITY)
                      for index, obj in enumerate(objects)
                      for test, constants in [_object_test(obj)]]
        from_camera = [
            Entry(*camera_test(entry.test, entry.constants), entry.index, entry.obj,
                  *cone(entry.obj, origin, scale, entry.test is not None),
                  entry.side_x, entry.side_y, entry.side_z, entry.side_limit)
            for entry in everywhere]
        self.everywhere = [tuple(entry) for entry in everywhere]
        self.from_camera = [tuple(entry) for entry in from_camera]
        self.light_match = within = LIGHT_MATCH * scale
        self.towards_light = []
        for number, light in enumerate(lights, 1):
            entries = [Entry(entry.test, entry.constants, entry.index, entry.obj,
                             *_reversed(cone(entry.obj, light.pos, scale,
                                             entry.test is not None)),
                             *plane_beyond(entry.obj, light.pos, scale, entry.test is not None))
                       for entry in everywhere]
            box, inside = clear_box(entries)
            x, y, z = light.pos
            self.towards_light.append(tuple(TowardsLight(
                x - within, x + within, y - within, y + within, z - within, z + within,
                box, [tuple(entry) for entry in inside], [tuple(entry) for entry in entries],
                number % len(lights))))
        # Shadow rays come light after light: any_hit tries the light after the last one
        # found first.
        self.next_light = self.towards_light[0] if lights else NO_LIGHT

    def closest_hit(self, ray):
        """Scene.closest_hit(ray)."""
        d = ray.d
        dx, dy, dz = d.x, d.y, d.z
        squares = dx * dx + dy * dy + dz * dz
        if not UNIT_LOW <= squares <= UNIT_HIGH:
            return Scene.closest_hit(self.scene, ray)  # a direction to normalise: rare
        inverse = 1.0 / sqrt(squares)  # u = Normalize(d), for the plane tests
        ux, uy, uz = dx * inverse, dy * inverse, dz * inverse
        o = ray.o
        ox, oy, oz = o.x, o.y, o.z
        nearest = self.nearest(ray, ox, oy, oz, dx, dy, dz, ux, uy, uz, ray.t_min, ray.t_max)
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
            found, ox, oy, oz, dx, dy, dz, ux, uy, uz, t)
        hit.has_hit, hit.hit_point, hit.normal, hit.hit_distance = True, point, normal, t
        hit.primitive_index = index
        return hit

    def nearest(self, ray, ox, oy, oz, dx, dy, dz, ux, uy, uz, t_min, t_max):
        """(test, constants, index, t) of the nearest hit of the ray from (ox, oy, oz) along
        the unit direction (dx, dy, dz), (ux, uy, uz) = Normalize(d), in [t_min, t_max], or
        None; for an object asked
        through its own intersect, (None, its HitData, index, t). Only a strictly nearer
        hit replaces the nearest so far, as in Scene.closest_hit."""
        from_camera = ox == 0.0 and oy == 0.0 and oz == 0.0 and t_min >= 0.0
        nearest = None
        for test, constants, index, obj, cone_x, cone_y, cone_z, cos_limit, _, _, _, _ in (
                self.from_camera if from_camera else self.everywhere):
            if dx * cone_x + dy * cone_y + dz * cone_z < cos_limit:
                continue
            if test is None:  # its own intersect, along the ray as it is
                hit = obj.intersect(ray)
                if hit.has_hit and (nearest is None or hit.hit_distance < t_max):
                    nearest, t_max = (None, hit, index, hit.hit_distance), hit.hit_distance
                continue
            t = test(constants, ox, oy, oz, dx, dy, dz, ux, uy, uz, t_min, t_max)
            if t is not None and (nearest is None or t < t_max):
                nearest, t_max = (test, constants, index, t), t
        return nearest

    def any_hit(self, ray):
        """Scene.any_hit(ray)."""
        d = ray.d
        dx, dy, dz = d.x, d.y, d.z
        squares = dx * dx + dy * dy + dz * dz
        if not UNIT_LOW <= squares <= UNIT_HIGH:
            return Scene.any_hit(self.scene, ray)  # a direction to normalise: rare
        ux = None  # u = Normalize(d), for the plane tests, made when an object is tested
        o = ray.o
        ox, oy, oz, t_min, t_max = o.x, o.y, o.z, ray.t_min, ray.t_max
        entries = self.everywhere
        if t_min >= 0.0:
            if ox == 0.0 and oy == 0.0 and oz == 0.0:
                entries = self.from_camera
            elif t_max < INFINITY:  # a shadow ray, when it ends at a light
                ex, ey, ez = ox + dx * t_max, oy + dy * t_max, oz + dz * t_max
                light = self.next_light
                x_low, x_high, y_low, y_high, z_low, z_high, _, _, _, _ = light
                if not (x_low <= ex <= x_high and y_low <= ey <= y_high
                        and z_low <= ez <= z_high):
                    light = self.light_at(ex, ey, ez)
                if light is not None:
                    _, _, _, _, _, _, (x0, x1, y0, y1, z0, z1), inside, entries, next_light = light
                    self.next_light = self.towards_light[next_light]
                    if x0 < ox < x1 and y0 < oy < y1 and z0 < oz < z1:
                        entries = inside
        for (test, constants, _, obj, cone_x, cone_y, cone_z, cos_limit,
             side_x, side_y, side_z, side_limit) in entries:
            if (dx * cone_x + dy * cone_y + dz * cone_z >= cos_limit
                    and ox * side_x + oy * side_y + oz * side_z <= side_limit):
                if test is None:
                    if obj.intersect(ray).has_hit:
                        return True
                    continue
                if ux is None:
                    inverse = 1.0 / sqrt(squares)
                    ux, uy, uz = dx * inverse, dy * inverse, dz * inverse
                if test(constants, ox, oy, oz, dx, dy, dz, ux, uy, uz, t_min, t_max) is not None:
                    return True
        return False

    def light_at(self, x, y, z):
        """The towards_light entry of the first light whose box holds (x, y, z), or None."""
        for light in self.towards_light:
            x_low, x_high, y_low, y_high, z_low, z_high, _, _, _, _ = light
            if x_low <= x <= x_high and y_low <= y <= y_high and z_low <= z <= z_high:
                return light
        return None


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
