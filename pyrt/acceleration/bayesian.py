"""AcceleratedBMC and AcceleratedBMCIS: the compute_color of BayesianMonteCarloIntegrator
and of BMCISIntegrator, equal to it bit for bit for the same draws of random(), on plain
floats, with the fast queries for the sample rays."""
from math import acos, atan2, cos, floor, pi, sin

import numpy as np

from PyRT_Common import EPSILON, HUGEVALUE, RGBColor
from pyrt.acceleration.fingerprints import fused_integrator, own_gp
from pyrt.acceleration.monte_carlo import AcceleratedCMC, HitFrame
from pyrt.gaussian_pools import pool_members


class AcceleratedBMC(AcceleratedCMC):
    """BayesianMonteCarloIntegrator.compute_color, equal to it bit for bit, for a scene
    whose queries are an AcceleratedQueries of PyRT's primitives.

    The same draws of random() in the same order (the GP of the pool, then the angle); the
    rotation about y, the frame of center_around_normal and the normalisations of each
    sample direction on all of a hit's samples at once with numpy, whose element-wise
    products, sums, quotients and square roots are the IEEE operations of the plain
    floats, in the same order; the sample rays traced without a Ray or a HitData; and
    the same values Y_j = L_i (x) f, with L_i a float32 texel of the map (whose product
    with a double is float32, as the course's arithmetic makes it) or an object's
    emission (doubles). f is the Lambertian's kd cos, BLACK where cos <= 0: such a sample's
    ray is not traced (its value is zero whatever it meets).

    The estimate: for PyRT's own GP, unchanged (GP_FUNCTIONS), compute_integral_BMC's sum
    res + Y_i * w_i from BLACK, in doubles, in the order of the samples (numpy's cumulative
    sum); values that are not finite, which its add_sample_val refuses, and any other GP
    go through the GP's own add_sample_val and compute_integral_BMC."""

    name = "bmc"  # the registered integrator whose sample_value this one repeats
    trace_all = False  # whether a sample whose cosine is not positive is traced

    def __init__(self, integrator, queries):
        super().__init__(integrator, queries)
        self.pool = pool_members(integrator.myGP)
        # each GP's sample directions as three arrays of x, y and z; its weights when
        # compute_integral_BMC is repeated here, else None
        self.directions = [tuple(np.array([getattr(omega, axis) for omega in gp.samples_pos],
                                          dtype=float) for axis in "xyz")
                           for gp in self.pool]
        self.weights = [np.asarray(gp.weights, dtype=float) if own_gp(gp) else None
                        for gp in self.pool]
        self.emitting = [any(emission) for emission in self.emissions]

    @classmethod
    def can_stand_in(cls, integrator) -> bool:
        """Whether the integrator's draws, light and values are those this class repeats
        (its pick_sample_set, incoming_light and sample_value are the registered
        integrator's) and every GP has sample positions with x, y, z."""
        registered = fused_integrator(cls.name)
        if registered is None or any(
                getattr(type(integrator), method, None) is not getattr(registered, method)
                for method in ("sample_value", "pick_sample_set", "incoming_light")):
            return False
        pool = pool_members(getattr(integrator, "myGP", None))
        return bool(pool) and all(
            getattr(gp, "samples_pos", None) is not None
            and all(hasattr(omega, "z") for omega in gp.samples_pos) for gp in pool)

    def compute_color(self, ray):
        """BayesianMonteCarloIntegrator.compute_color(ray) (or BMCISIntegrator's)."""
        frame = self.camera_hit(ray)
        if type(frame) is not tuple:
            return frame
        frame = HitFrame(*frame)
        normal = self.columns((frame.nx, frame.ny, frame.nz))
        draw = self.random
        which = floor(draw() * len(self.pool))  # pick_sample_set: the GP, then the angle
        alpha = 2 * pi * draw()
        c, s = cos(alpha), sin(alpha)
        x, y, z = self.directions[which]
        # rotate_around_y(alpha, omega), then center_around_normal: Normalize(v x + w y + u z)
        # on the rows x, y, z of all samples at once, each row an operation of the plain code
        x, z = x * c + z * s, -x * s + z * c
        w = (self.columns((frame.vx, frame.vy, frame.vz)) * x + normal * y
             + self.columns((frame.ux, frame.uy, frame.uz)) * z)
        squares = w * w
        w = w * (1.0 / np.sqrt(squares[0] + squares[1] + squares[2]))  # unit_components'
        products = normal * w
        cosines = products[0] + products[1] + products[2]  # get_value's Dot(n, wi)
        squares = w * w
        r = w * (1.0 / np.sqrt(squares[0] + squares[1] + squares[2]))  # closest_hit's Normalize
        px, py, pz = frame.px, frame.py, frame.pz
        tests, others = self.tests, self.others[frame.index]
        clearance, emitting, emissions = self.own_clearance, self.emitting, self.emissions
        env_map, trace_all = self.env_map, self.trace_all
        last_row, last_column, to_floor = self.last_row, self.last_column, floor
        arc_tangent, arc_cosine, inverse_pi = atan2, acos, 1 / pi
        emitted, emitted_at = [], []  # the emission of the samples that hit an emitter
        map_rows, map_columns, map_at = [], [], []  # the texels of those that see the map
        for j, (wx, wy, wz, rx, ry, rz, cos_theta) in enumerate(
                np.vstack((w, r, cosines)).T.tolist()):
            if not (trace_all or cos_theta > 0.0):
                continue  # f is BLACK: the value is zero whatever the ray meets
            # scene.closest_hit(Ray(hit_point, wi)) (AcceleratedCMC.sample_hit), written out
            hit_index, t_max = None, HUGEVALUE
            for test, constants, object_index in (others if cos_theta > clearance else tests):
                t = test(constants, px, py, pz, wx, wy, wz, rx, ry, rz, EPSILON, t_max)
                if t is not None and (hit_index is None or t < t_max):
                    hit_index, t_max = object_index, t
            if hit_index is not None:
                if emitting[hit_index]:  # else L is BLACK, and so is the value
                    emitted.append(emissions[hit_index])
                    emitted_at.append(j)
            elif env_map is not None:  # env_map.getValue(wi) (texel_of), written out
                u = (1 + inverse_pi * arc_tangent(wx, -wz)) / 2
                v = inverse_pi * arc_cosine(wy if -1.0 <= wy <= 1.0 else min(1.0, max(-1.0, wy)))
                map_rows.append(to_floor(v * last_row))
                map_columns.append(to_floor(u * last_column))
                map_at.append(j)
        values = np.zeros((len(cosines), 3))  # Y_j: zero unless set here
        if emitted_at or map_at:
            factors = self.factors(frame.kd, cosines)
            if emitted_at:  # L.multiply(f) in doubles
                values[emitted_at] = np.array(emitted) * factors[emitted_at]
            if map_at:  # L.multiply(f) of a float32 texel: float32
                values[map_at] = self.texels[map_rows, map_columns] * factors[map_at].astype(
                    np.float32)
        return self.estimate(which, values)

    @staticmethod
    def columns(vector):
        """The (x, y, z) tuple vector as a column, to multiply a row of every sample's."""
        return np.array(vector)[:, None]

    @staticmethod
    def factors(kd, cosines):
        """f of sample_value, Lambertian.get_value(wi, wo, n) for each sample: kd cos as
        rows (r, g, b), zero where cos <= 0 (BLACK)."""
        return np.array([kd.r, kd.g, kd.b]) * np.where(cosines > 0.0, cosines, 0.0)[:, None]

    def estimate(self, which, values):
        """The GP's integral for the values Y_j (rows r, g, b) of GP `which` of the pool."""
        weights = self.weights[which]
        if weights is not None and np.isfinite(values).all():
            # compute_integral_BMC: res = BLACK, then res + Y_i * w_i for each i
            # (0.0 + the cumulative sum: a total of -0.0, all terms being zeros, is 0.0
            # there, as when the first term is added to BLACK's 0.0)
            r, g, b = (np.cumsum(values * weights[:, None], axis=0)[-1] + 0.0).tolist()
            return RGBColor(r, g, b)
        gp = self.pool[which]
        gp.add_sample_val([RGBColor(*row) for row in values])
        return gp.compute_integral_BMC()


class AcceleratedBMCIS(AcceleratedBMC):
    """BMCISIntegrator.compute_color, equal to it bit for bit: AcceleratedBMC with the
    values L_i (x) kd (BMCISIntegrator.sample_value), every sample's ray traced."""

    name = "bmcis"
    trace_all = True

    @staticmethod
    def factors(kd, cosines):
        """f of BMCISIntegrator.sample_value for each sample: kd as rows (r, g, b)."""
        return np.broadcast_to(np.array([kd.r, kd.g, kd.b]), (len(cosines), 3))
