"""AcceleratedPhong: PhongIntegrator.compute_color, equal to it bit for bit, on plain floats,
with the fast queries' lists of objects for its shadow rays."""
from math import sqrt
from typing import NamedTuple

from PyRT_Common import (BLACK, OFFSET_SCALE, SHADOW_EPSILON, SQUARES_HIGH, SQUARES_LOW,
                         RGBColor, euclidean_length)
from PyRT_Core import UNIT_HIGH, UNIT_LOW, Lambertian
from pyrt.acceleration.queries import TowardsLight
from pyrt.scalar_intersections import POINT_AND_NORMAL


class PhongLight(NamedTuple):
    """A point light as AcceleratedPhong's loop reads it: its position, its intensity, the
    clear box of origins of its shadow rays (queries.TowardsLight) with the entries left
    inside it, and all its entries."""

    x: float
    y: float
    z: float
    red: float
    green: float
    blue: float
    x0: float
    x1: float
    y0: float
    y1: float
    z0: float
    z1: float
    inside: list
    entries: list


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
        # plain tuples, which the loop of compute_color unpacks faster than NamedTuples
        self.lights = [tuple(PhongLight(*light.pos, *light.intensity, *towards.clear_box,
                                        towards.inside, towards.entries))
                       for light, towards in zip(scene.pointLights,
                                                 map(TowardsLight._make, queries.towards_light))]

    @staticmethod
    def can_stand_in(integrator) -> bool:
        """Whether it may stand in for the integrator on its scene: on any scene."""
        return True

    def compute_color(self, ray):
        """PhongIntegrator.compute_color(ray)."""
        d, o = ray.d, ray.o
        dx, dy, dz, ox, oy, oz = d.x, d.y, d.z, o.x, o.y, o.z
        squares = dx * dx + dy * dy + dz * dz
        if not UNIT_LOW <= squares <= UNIT_HIGH:
            return self.plain_color(ray)
        inverse = 1.0 / sqrt(squares)  # u = Normalize(d), for the plane tests
        ux, uy, uz = dx * inverse, dy * inverse, dz * inverse
        nearest = self.queries.nearest(None, ox, oy, oz, dx, dy, dz, ux, uy, uz, ray.t_min,
                                       ray.t_max)
        if nearest is None:
            return BLACK
        test, constants, index, t = nearest
        brdf = self.objects[index].get_BRDF()
        if type(brdf) is not Lambertian:
            return self.plain_color(ray)
        px, py, pz, nx, ny, nz = POINT_AND_NORMAL[test](constants, ox, oy, oz, dx, dy, dz,
                                                        ux, uy, uz, t)
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
            # shadow_ray(hit, light.pos): the light is in front, so the offset is upwards;
            # (sox, soy, soz) is the shadow ray's origin, (sdx, sdy, sdz) its direction
            sox, soy, soz = px + nx * offset, py + ny * offset, pz + nz * offset
            sdx, sdy, sdz = x - sox, y - soy, z - soz
            squares = sdx * sdx + sdy * sdy + sdz * sdz
            distance = sqrt(squares) if SQUARES_LOW < squares < SQUARES_HIGH else (
                euclidean_length(sdx, sdy, sdz))
            if not 0.0 < distance <= longest:
                return self.plain_color(ray)
            sdx, sdy, sdz = sdx / distance, sdy / distance, sdz / distance
            squares = sdx * sdx + sdy * sdy + sdz * sdz
            if not UNIT_LOW <= squares <= UNIT_HIGH:
                return self.plain_color(ray)
            sux = None  # Normalize of its direction, made when an object is tested
            # any_hit of the shadow ray, with the entries of its light
            s_max = distance * (1.0 - SHADOW_EPSILON)
            if x0 < sox < x1 and y0 < soy < y1 and z0 < soz < z1:
                entries = inside
            for (test, constants, _, _, cone_x, cone_y, cone_z, cos_limit,
                 side_x, side_y, side_z, side_limit) in entries:
                if (sdx * cone_x + sdy * cone_y + sdz * cone_z >= cos_limit
                        and sox * side_x + soy * side_y + soz * side_z <= side_limit):
                    if sux is None:
                        inverse = 1.0 / sqrt(squares)
                        sux, suy, suz = sdx * inverse, sdy * inverse, sdz * inverse
                    if test(constants, sox, soy, soz, sdx, sdy, sdz, sux, suy, suz, offset,
                            s_max) is not None:
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
