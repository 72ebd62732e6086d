"""AcceleratedQueries: a scene's closest_hit and any_hit, equal to Scene's bit for bit, on
plain floats, each ray testing only the objects it can reach (culling.py)."""
from PyRT_Common import INFINITY, HitData, Vector3D, _new
from PyRT_Core import UNIT_HIGH, UNIT_LOW, InfinitePlane, Scene, Sphere
from pyrt.acceleration.culling import (LIGHT_MATCH, clear_box, cone, plane_beyond,
                                       scene_size, _reversed)
from pyrt.acceleration.fingerprints import INTERSECT_FUNCTIONS, unchanged
from pyrt.scalar_intersections import (POINT_AND_NORMAL, camera_test, infinite_plane_distance,
                                       parallelogram_distance, sphere_distance)

# any_hit's next light when there is none: a box that holds no point.
NO_LIGHT = (INFINITY, -INFINITY) * 3


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
