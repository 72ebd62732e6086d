"""AcceleratedPhong: PhongIntegrator.compute_color, equal to it bit for bit, on plain floats,
with the fast queries' lists of objects for its shadow rays."""
from math import sqrt

from PyRT_Common import (BLACK, OFFSET_SCALE, SHADOW_EPSILON, SQUARES_HIGH, SQUARES_LOW,
                         RGBColor, euclidean_length)
from PyRT_Core import UNIT_HIGH, UNIT_LOW, Lambertian
from pyrt.scalar_intersections import POINT_AND_NORMAL


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
