"""AcceleratedBMC and AcceleratedBMCIS: the compute_color of BayesianMonteCarloIntegrator
and of BMCISIntegrator, equal to it bit for bit for the same draws of random(), on plain
floats, with the fast queries for the sample rays."""
from math import cos, floor, pi, sin, sqrt

import numpy as np

from PyRT_Common import BLACK, RGBColor
from pyrt.acceleration.fingerprints import fused_integrator
from pyrt.acceleration.monte_carlo import AcceleratedCMC, HitFrame


class AcceleratedBMC(AcceleratedCMC):
    """BayesianMonteCarloIntegrator.compute_color, equal to it bit for bit, for a scene
    whose queries are an AcceleratedQueries of PyRT's primitives.

    The same draws of random() in the same order (the GP of the pool, then the angle), the
    same rotation about y and frame of center_around_normal on plain floats, the sample
    rays traced without a Ray or a HitData, and the same values Y_j: L_i (x) f, with L_i a
    float32 texel of the map (whose product with a double is float32, as the course's
    arithmetic makes it: numpy does all the map's products of a pixel at once) or an
    object's emission (doubles). The GP's own add_sample_val and compute_integral_BMC make
    the estimate from them, as in the plain code, so any GP of the course's interface is
    stood in for exactly. f is the Lambertian's kd cos, BLACK where cos <= 0: such a
    sample's ray is not traced (its value is zero whatever it meets)."""

    name = "bmc"  # the registered integrator whose sample_value this one repeats

    def __init__(self, integrator, queries):
        super().__init__(integrator, queries)
        my_gp = integrator.myGP
        self.pool = list(my_gp) if isinstance(my_gp, (list, tuple)) else [my_gp]
        # each GP's sample directions, as plain floats
        self.directions = [[(omega.x, omega.y, omega.z) for omega in gp.samples_pos]
                           for gp in self.pool]

    @classmethod
    def can_stand_in(cls, integrator) -> bool:
        """Whether the integrator's values are those this class repeats (its sample_value
        is the registered integrator's) and every GP has Vector3D-like sample positions."""
        registered = fused_integrator(cls.name)
        if registered is None or type(integrator).sample_value is not registered.sample_value:
            return False
        my_gp = getattr(integrator, "myGP", None)
        pool = list(my_gp) if isinstance(my_gp, (list, tuple)) else [my_gp]
        return bool(pool) and all(
            getattr(gp, "samples_pos", None) is not None
            and all(hasattr(omega, "z") for omega in gp.samples_pos) for gp in pool)

    def compute_color(self, ray):
        """BayesianMonteCarloIntegrator.compute_color(ray) (or BMCISIntegrator's)."""
        frame = self.camera_hit(ray)
        if type(frame) is not HitFrame:
            return frame
        (nx, ny, nz), (vx, vy, vz), (ux, uy, uz) = frame.normal, frame.v, frame.u
        draw = self.random
        which = floor(draw() * len(self.pool))  # pick_sample_set: the GP, then the angle
        alpha = 2 * pi * draw()
        gp = self.pool[which]
        c, s = cos(alpha), sin(alpha)
        emissions, env_map, index, sample_hit = (self.emissions, self.env_map, frame.index,
                                                 self.sample_hit)
        kd = frame.kd
        values = []  # Y_j, or, for the map's samples, its (row, column, factors)
        map_rows, map_columns, map_factors, map_at = [], [], [], []
        for x, y, z in self.directions[which]:
            # rotate_around_y(alpha, omega), then center_around_normal: Normalize(v x + w y
            # + u z)
            x, z = x * c + z * s, -x * s + z * c
            wx, wy, wz = (vx * x + nx * y + ux * z, vy * x + ny * y + uy * z,
                          vz * x + nz * y + uz * z)
            inverse = 1.0 / sqrt(wx * wx + wy * wy + wz * wz)  # unit_components' arithmetic
            wx, wy, wz = wx * inverse, wy * inverse, wz * inverse
            cos_theta = nx * wx + ny * wy + nz * wz
            factors = self.factors(kd, cos_theta)
            if factors is None:  # f is BLACK
                values.append(BLACK)
                continue
            hit_index = sample_hit(frame.point, (wx, wy, wz), cos_theta, index)
            if hit_index is not None:  # the object's emission times f, in doubles
                er, eg, eb = emissions[hit_index]
                fr, fg, fb = factors
                values.append(RGBColor(er * fr, eg * fg, eb * fb))
            elif env_map is not None:
                row, column = self.texel_of(wx, wy, wz)
                map_rows.append(row)
                map_columns.append(column)
                map_factors.append(factors)
                map_at.append(len(values))
                values.append(None)
            else:
                values.append(BLACK)
        if map_rows:  # texel * f in float32, all of the pixel's at once
            terms = self.texels[map_rows, map_columns] * np.array(map_factors).astype(
                np.float32)
            for at, (r, g, b) in zip(map_at, terms):
                values[at] = RGBColor(r, g, b)
        gp.add_sample_val(values)
        return gp.compute_integral_BMC()

    @staticmethod
    def factors(kd, cos_theta):
        """f of BayesianMonteCarloIntegrator.sample_value, Lambertian.get_value(wi, wo, n):
        kd cos as (r, g, b), or None for BLACK (cos <= 0)."""
        if not cos_theta > 0.0:
            return None
        return kd.r * cos_theta, kd.g * cos_theta, kd.b * cos_theta


class AcceleratedBMCIS(AcceleratedBMC):
    """BMCISIntegrator.compute_color, equal to it bit for bit: AcceleratedBMC with the
    values L_i (x) kd (BMCISIntegrator.sample_value), every sample's ray traced."""

    name = "bmcis"

    @staticmethod
    def factors(kd, cos_theta):
        return kd.r, kd.g, kd.b
