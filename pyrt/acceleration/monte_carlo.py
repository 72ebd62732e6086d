"""AcceleratedCMC: CMCIntegrator.compute_color, equal to it bit for bit for the same draws
of random(), on plain floats, with the fast queries for its sample rays."""
from math import acos, atan2, cos, floor, pi, sin, sqrt
from typing import NamedTuple

import numpy as np

from PyRT_Common import (BLACK, EPSILON, HUGEVALUE, CosinePDF, RGBColor, UniformPDF,
                         sample_set_hemisphere, unit_components)
from PyRT_Core import UNIT_HIGH, UNIT_LOW, Lambertian
from pyrt.acceleration.culling import scene_size
from pyrt.acceleration.fingerprints import fused_integrator
from pyrt.scalar_intersections import POINT_AND_NORMAL

# center_around_normal's "jittered up", the vector its frame starts from
JITTERED_UP = (0.00319, 1.0, 0.0078)
# UniformPDF.get_val, the density of every sample direction
UNIFORM_DENSITY = 1 / (2 * pi)
# The pdfs whose generate_dir and get_val the fused version repeats
FUSED_PDFS = (UniformPDF, CosinePDF)
# A sample ray leaves its object's surface into the hemisphere around the normal. Its own
# object could meet it again only at a distance of about the rounding error of the hit
# point over its cosine, e * scene size / cos with e ~ 1e-15, and the ray starts at
# EPSILON: when cos > OWN_OBJECT_CLEARANCE * scene size, that distance is below 1e-6, far
# below EPSILON (1e-4), so the own object is not tested (a sphere is convex, a flat object
# is met at its plane only).
OWN_OBJECT_CLEARANCE = 1e-9


class HitFrame(NamedTuple):
    """Where a camera ray hits: the object's index and Lambertian kd, the hit point p, its
    normal n and center_around_normal's frame v, u about it, component by component."""
    index: int
    kd: object
    px: float
    py: float
    pz: float
    nx: float
    ny: float
    nz: float
    vx: float
    vy: float
    vz: float
    ux: float
    uy: float
    uz: float


class AcceleratedCMC:
    """CMCIntegrator.compute_color, equal to it bit for bit, for a scene whose queries are
    an AcceleratedQueries of PyRT's primitives: the same draws of random(), in the same
    order, and the same operations on plain floats. The frame of center_around_normal is
    made once per pixel (it depends on the normal alone); the sample rays are traced
    without a Ray or a HitData; Lambertian's get_value is inline.

    The environment map's texels are float32 (as OpenCV reads them), and so is the
    course's arithmetic on them: each term L * f / p and their running sum are float32
    operations, which numpy does here on all the terms of a pixel at once, in the same
    order (a float32 sum or product of two float32 numbers, computed in double precision
    and rounded to float32, is the float32 operation's result). The other terms are
    doubles. A scene with both a map and an object that emits light mixes the two kinds
    of term in an order-dependent way: there the plain code runs (can_stand_in), as it
    does for a pdf other than UniformPDF and CosinePDF."""

    def __init__(self, integrator, queries):
        self.integrator, self.queries = integrator, queries
        scene = integrator.scene
        self.objects = scene.object_list
        self.emissions = [(obj.emission.r, obj.emission.g, obj.emission.b)
                          for obj in scene.object_list]
        self.env_map = env_map = scene.env_map
        self.texels = self.last_column = self.last_row = None  # the map's, if there is one
        if env_map is not None:
            self.texels = env_map.env_map_hdr
            self.last_column, self.last_row = env_map.width - 1, env_map.height - 1
        self.samples = integrator.n_samples
        self.cosine_exponents = None  # UniformPDF; for CosinePDF(exp), its exponents
        pdf = getattr(integrator, "pdf", None)  # a Bayesian integrator has none
        if type(pdf) is CosinePDF:
            e = pdf.exp  # generate_dir's and get_val's constants, as they compute them
            self.cosine_exponents = (1 / (e + 1), 2 / (e + 1), (e + 1) / (2 * pi), e)
        # the scalar test of every object, in the order of object_list (can_fuse: every
        # object has one), for the sample rays, which start anywhere; and for those that
        # leave their object clearly (OWN_OBJECT_CLEARANCE), every other object's
        self.tests = [entry[:3] for entry in queries.everywhere]
        self.others = [[test for test in self.tests if test[2] != index]
                       for index in range(len(self.tests))]
        self.own_clearance = OWN_OBJECT_CLEARANCE * scene_size(scene.object_list,
                                                               scene.pointLights)
        # random() as sample_set_hemisphere draws it: Python's global generator
        self.random = sample_set_hemisphere.__globals__["random"]

    @staticmethod
    def can_stand_in(integrator) -> bool:
        """Whether the pdf is UniformPDF or CosinePDF, L_i is the registered integrator's
        incoming_light and the scene's terms are all of one kind: no environment map, or
        no object that emits light (see above)."""
        scene = integrator.scene
        registered = fused_integrator("cmc")
        if type(getattr(integrator, "pdf", None)) not in FUSED_PDFS or (
                type(integrator).incoming_light is not registered.incoming_light):
            return False
        return scene.env_map is None or not any(
            obj.emission.r or obj.emission.g or obj.emission.b for obj in scene.object_list)

    def camera_hit(self, ray):
        """The hit of a camera ray as the tuple of a HitFrame's fields (a plain tuple costs
        less to make, pixel after pixel), or the pixel's colour when the ray misses
        (the map, or BLACK), or when the plain code must make it (a direction that is not
        of unit length, a BRDF that is not a Lambertian)."""
        frame = self.camera_frame(ray)
        return self.plain_color(ray) if frame is None else frame

    def camera_frame(self, ray):
        """camera_hit(ray), but None where the plain code must make the pixel's colour."""
        d, o = ray.d, ray.o
        dx, dy, dz, ox, oy, oz = d.x, d.y, d.z, o.x, o.y, o.z
        squares = dx * dx + dy * dy + dz * dz
        if not UNIT_LOW <= squares <= UNIT_HIGH:
            return None
        inverse = 1.0 / sqrt(squares)  # r = Normalize(d), for the plane tests
        rx, ry, rz = dx * inverse, dy * inverse, dz * inverse
        nearest = self.queries.nearest(None, ox, oy, oz, dx, dy, dz, rx, ry, rz, ray.t_min,
                                       ray.t_max)
        if nearest is None:
            return BLACK if self.env_map is None else self.env_map.getValue(ray.d)
        test, constants, index, t = nearest
        brdf = self.objects[index].get_BRDF()
        if type(brdf) is not Lambertian:
            return None
        px, py, pz, nx, ny, nz = POINT_AND_NORMAL[test](constants, ox, oy, oz, dx, dy, dz,
                                                        rx, ry, rz, t)
        # center_around_normal's frame: w = n, v = Normalize(Cross(up, w)), u = Cross(v, w)
        ax, ay, az = JITTERED_UP
        vx, vy, vz = unit_components(ay * nz - az * ny, az * nx - ax * nz, ax * ny - ay * nx)
        ux, uy, uz = vy * nz - vz * ny, vz * nx - vx * nz, vx * ny - vy * nx
        return index, brdf.kd, px, py, pz, nx, ny, nz, vx, vy, vz, ux, uy, uz

    def sample_hit(self, point, w, cos_theta, index):
        """The index of the object that scene.closest_hit(Ray(point, w)) finds, as
        AcceleratedQueries.nearest answers it (w, of unit length, normalised once more
        as the plain code does; only a strictly nearer hit replaces the nearest so far),
        or None; cos_theta is w's cosine to the normal of object `index`, which w leaves."""
        px, py, pz = point
        wx, wy, wz = w
        inverse = 1.0 / sqrt(wx * wx + wy * wy + wz * wz)  # Normalize(wi) once more
        rx, ry, rz = wx * inverse, wy * inverse, wz * inverse
        hit_index, t_max = None, HUGEVALUE
        tests = self.others[index] if cos_theta > self.own_clearance else self.tests
        for test, constants, object_index in tests:
            t = test(constants, px, py, pz, wx, wy, wz, rx, ry, rz, EPSILON, t_max)
            if t is not None and (hit_index is None or t < t_max):
                hit_index, t_max = object_index, t
        return hit_index

    def compute_color(self, ray):
        """CMCIntegrator.compute_color(ray)."""
        frame = self.camera_hit(ray)
        if type(frame) is not tuple:
            return frame
        index, kd, px, py, pz, nx, ny, nz, vx, vy, vz, ux, uy, uz = frame
        kr, kg, kb = kd.r, kd.g, kd.b
        # sample_set_hemisphere(n, pdf): u1 then u2 for each sample, all first
        draw = self.random
        draws = [draw() for _ in range(2 * self.samples)]
        prob, cosine = UNIFORM_DENSITY, self.cosine_exponents
        uniform = cosine is None
        tests, emissions, env_map = self.tests, self.emissions, self.env_map
        others, clearance = self.others[index], self.own_clearance
        red = green = blue = 0.0  # the sum of the terms that are doubles
        map_rows, map_columns, map_factors, map_probs = [], [], [], []  # float32 terms
        for k in range(0, len(draws), 2):
            u1, u2 = draws[k], draws[k + 1]
            phi = 2 * pi * u1  # pdf.generate_dir(u1, u2) and pdf.get_val of it
            if uniform:  # UniformPDF
                sin_theta = sqrt(1 - u2 ** 2)
                y = u2
            else:  # CosinePDF(e): its Dot((0, 1, 0), omega) is y exactly
                y = u2 ** cosine[0]
                sin_theta = sqrt(1 - u2 ** cosine[1])
                prob = cosine[2] * y ** cosine[3]
            x, z = sin(phi) * sin_theta, cos(phi) * sin_theta
            # center_around_normal: Normalize(v x + w y + u z)
            wx, wy, wz = (vx * x + nx * y + ux * z, vy * x + ny * y + uy * z,
                          vz * x + nz * y + uz * z)
            inverse = 1.0 / sqrt(wx * wx + wy * wy + wz * wz)  # unit_components' arithmetic
            wx, wy, wz = wx * inverse, wy * inverse, wz * inverse
            cos_theta = nx * wx + ny * wy + nz * wz  # Lambertian.get_value(wi, wo, n)
            if not cos_theta > 0.0:
                continue  # f is BLACK: the term adds nothing
            # sample_hit(point, w, cos_theta, index), written out: a call per sample would
            # cost a sixth of the render
            inverse = 1.0 / sqrt(wx * wx + wy * wy + wz * wz)  # Normalize(wi) once more
            rx, ry, rz = wx * inverse, wy * inverse, wz * inverse
            hit_index, t_max = None, HUGEVALUE
            for test, constants, object_index in (others if cos_theta > clearance else tests):
                t = test(constants, px, py, pz, wx, wy, wz, rx, ry, rz, EPSILON, t_max)
                if t is not None and (hit_index is None or t < t_max):
                    hit_index, t_max = object_index, t
            if hit_index is not None:
                er, eg, eb = emissions[hit_index]
                if er or eg or eb:  # L.multiply(f) / prob, in doubles
                    red += er * (kr * cos_theta) / prob
                    green += eg * (kg * cos_theta) / prob
                    blue += eb * (kb * cos_theta) / prob
            elif env_map is not None:  # env_map.getValue(wi): the texel under (u, v)
                u = (1 + (1 / pi) * atan2(wx, -wz)) / 2  # texel_of(w), written out
                v = (1 / pi) * acos(min(1.0, max(-1.0, wy)))
                map_rows.append(floor(v * self.last_row))
                map_columns.append(floor(u * self.last_column))
                map_factors.append((kr * cos_theta, kg * cos_theta, kb * cos_theta))
                if not uniform:
                    map_probs.append(prob)
        if map_rows:  # the uniform density is one number for all
            return self.map_color(map_rows, map_columns, map_factors,
                                  UNIFORM_DENSITY if uniform else map_probs)
        return RGBColor(red / self.samples, green / self.samples, blue / self.samples)

    def texel_of(self, wx, wy, wz):
        """(row, column) of the texel env_map.getValue(w) reads for the unit vector w."""
        u = (1 + (1 / pi) * atan2(wx, -wz)) / 2
        v = (1 / pi) * acos(min(1.0, max(-1.0, wy)))
        return floor(v * self.last_row), floor(u * self.last_column)

    def map_color(self, rows, columns, factors, probs):
        """The colour of a pixel whose terms are the map's (see above): the float32 sum of
        texel * f / prob over the samples, in their order, over n_samples; probs is the
        density of each sample, or one number for all."""
        terms = self.texels[rows, columns] * np.array(factors).astype(np.float32)
        terms /= (np.float32(probs) if type(probs) is float else
                  np.array(probs, dtype=np.float32)[:, None])
        total = np.cumsum(terms, axis=0)[-1] / np.float32(self.samples)
        return RGBColor(float(total[0]), float(total[1]), float(total[2]))

    def plain_color(self, ray):
        """CMCIntegrator's own compute_color, with the accelerated queries."""
        return type(self.integrator).compute_color(self.integrator, ray)
