"""AcceleratedBMC and AcceleratedBMCIS: the compute_color of BayesianMonteCarloIntegrator
and of BMCISIntegrator, equal to it bit for bit for the same draws of random(), with the
sample rays of many pixels traced together on numpy arrays."""
from math import acos, atan2, cos, floor, pi, sin

import numpy as np

from PyRT_Common import EPSILON, HUGEVALUE, RGBColor
from pyrt.acceleration.fingerprints import fused_integrator, own_gp
from pyrt.acceleration.lookahead import Lookahead, Prediction
from pyrt.acceleration.monte_carlo import AcceleratedCMC
from pyrt.array_intersections import ARRAY_TESTS
from pyrt.gaussian_pools import pool_members


class AcceleratedBMC(AcceleratedCMC):
    """BayesianMonteCarloIntegrator.compute_color, equal to it bit for bit, for a scene
    whose queries are an AcceleratedQueries of PyRT's primitives.

    A pixel's colour depends on its camera ray and on two draws of random() (the GP of
    the pool, then the angle of the turn about y), nothing else: during a render, the
    colours of the next camera rays of the task are made together, from the draws a
    copy of the generator gives, and each is handed out when the loop asks for that ray
    and the live generator draws those very numbers (lookahead.py); otherwise the pixel
    is made on its own, from the numbers drawn then.

    For all the pixels' samples at once, on numpy arrays whose element-wise products,
    sums, quotients and square roots are the IEEE operations of the plain floats, in the
    same order: the rotation about y, the frame of center_around_normal and the
    normalisations of each sample direction, the sample rays' tests against every object
    in the order of object_list, each with the t_max its ray has then (array_intersections
    .py), and the values Y_j = L_i (x) f, with L_i a float32 texel of the map (whose
    product with a double is float32, as the course's arithmetic makes it; the texel's
    angles from math.atan2 and math.acos, as the plain code takes them) or an object's
    emission (doubles). f is the Lambertian's kd cos, BLACK where cos <= 0: such a
    sample's ray is not traced (its value is zero whatever it meets).

    The estimate: for PyRT's own GP, unchanged (GP_FUNCTIONS), compute_integral_BMC's sum
    res + Y_i * w_i from BLACK, in doubles, in the order of the samples (numpy's cumulative
    sum); values that are not finite, which its add_sample_val refuses, and any other GP
    go through the GP's own add_sample_val and compute_integral_BMC, when the pixel's
    colour is asked for."""

    name = "bmc"  # the registered integrator whose sample_value this one repeats
    trace_all = False  # whether a sample whose cosine is not positive is traced

    def __init__(self, integrator, queries):
        super().__init__(integrator, queries)
        self.pool = pool_members(integrator.myGP)
        # each GP's sample directions as a (3, n) array of rows x, y and z; its weights
        # when compute_integral_BMC is repeated here, else None
        self.directions = [np.array([[omega.x, omega.y, omega.z] for omega in gp.samples_pos],
                                    dtype=float).reshape(-1, 3).T for gp in self.pool]
        self.weights = [np.asarray(gp.weights, dtype=float) if own_gp(gp) else None
                        for gp in self.pool]
        self.emission_rows = np.array(self.emissions, dtype=float).reshape(-1, 3)
        self.array_tests = [(ARRAY_TESTS[test], constants, index)
                            for test, constants, index in self.tests]
        self.lookahead = Lookahead(integrator.scene, self.random.__self__, self.predict)

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
        guess = self.lookahead.prediction(ray)
        if guess is None:  # this pixel on its own
            frame = self.camera_hit(ray)
            if type(frame) is not tuple:
                return frame
            draw = self.random
            return self.color(self.made([frame], [(draw(), draw())])[0])
        if not guess.draws:  # a camera ray that misses: its colour
            return guess.made
        draw = self.random
        draws = draw(), draw()  # pick_sample_set: the GP, then the angle
        if draws != guess.draws:  # not the numbers predicted: made from these
            self.lookahead.stop()
            return self.color(self.made([guess.hit], [draws])[0])
        return self.color(guess.made)

    def predict(self, rays, draw):
        """The Predictions of the camera rays `rays` (see lookahead.py), draw the copy's
        random(): up to the first ray whose colour the plain code makes."""
        predictions, hits, draws = [], [], []
        for ray in rays:
            frame = self.camera_frame(ray)
            if frame is None:
                break
            d = ray.d
            if type(frame) is tuple:
                hits.append(len(predictions))
                draws.append((draw(), draw()))
                predictions.append(Prediction(d.x, d.y, d.z, draws[-1], frame, None))
            else:
                predictions.append(Prediction(d.x, d.y, d.z, (), None, frame))
        for k, made in zip(hits, self.made([predictions[k].hit for k in hits], draws)):
            predictions[k] = predictions[k]._replace(made=made)
        return predictions

    def color(self, made):
        """The colour of a pixel from what made() gave for it."""
        return made if type(made) is RGBColor else self.estimate(*made)

    def made(self, frames, draws) -> list:
        """For the camera hits `frames` (HitFrame tuples), with the draws (GP, angle) of
        each: its colour, or (which, values) for the GP's own estimate. Pixels whose GPs
        have different numbers of samples are made apart."""
        if not frames:
            return []
        which = [floor(u * len(self.pool)) for u, _ in draws]
        counts = [self.directions[w].shape[1] for w in which]
        if len(set(counts)) > 1:
            made = [None] * len(frames)
            for count in set(counts):
                pixels = [k for k in range(len(frames)) if counts[k] == count]
                for k, result in zip(pixels, self.made([frames[k] for k in pixels],
                                                       [draws[k] for k in pixels])):
                    made[k] = result
            return made
        values = self.values(frames, which, [2 * pi * u for _, u in draws])
        return self.estimates(which, values)

    def values(self, frames, which, angles):
        """Y_j of every sample of every pixel, an array (pixels, samples, 3)."""
        frame = np.array([hit[2:] for hit in frames], dtype=float)  # p, n, v, u of each
        point, normal, v, u = (frame[:, k:k + 3] for k in (0, 3, 6, 9))
        normal, v, u = normal[:, :, None], v[:, :, None], u[:, :, None]
        c = np.array([cos(alpha) for alpha in angles])[:, None]
        s = np.array([sin(alpha) for alpha in angles])[:, None]
        directions = np.array([self.directions[w] for w in which])
        x, y, z = directions[:, 0], directions[:, 1], directions[:, 2]
        # rotate_around_y(alpha, omega), then center_around_normal: Normalize(v x + w y + u z)
        x, z = x * c + z * s, -x * s + z * c
        w = v * x[:, None] + normal * y[:, None] + u * z[:, None]
        squares = w * w
        w = w * (1.0 / np.sqrt(squares[:, 0] + squares[:, 1] + squares[:, 2]))[:, None]
        products = normal * w
        cosines = products[:, 0] + products[:, 1] + products[:, 2]  # get_value's Dot(n, wi)
        squares = w * w
        r = w * (1.0 / np.sqrt(squares[:, 0] + squares[:, 1] + squares[:, 2]))[:, None]
        traced = np.ones(cosines.shape, bool) if self.trace_all else cosines > 0.0
        count = cosines.shape[1]
        each = np.broadcast_to  # a pixel's number for each of its samples
        px, py, pz = (each(point[:, k:k + 1], cosines.shape)[traced] for k in range(3))
        wx, wy, wz = (w[:, k][traced] for k in range(3))
        rx, ry, rz = (r[:, k][traced] for k in range(3))
        cos_theta = cosines[traced]
        hit_index = self.nearest(px, py, pz, wx, wy, wz, rx, ry, rz)
        kd = each(np.array([[hit[1].r, hit[1].g, hit[1].b] for hit in frames])[:, None],
                  (len(frames), count, 3))[traced]
        traced_values = np.zeros((len(cos_theta), 3))
        emitted = hit_index >= 0  # L is the object's emission (BLACK: a value of zero)
        if emitted.any():  # L.multiply(f) in doubles
            traced_values[emitted] = self.emission_rows[hit_index[emitted]] * self.factors(
                kd[emitted], cos_theta[emitted])
        sky = hit_index < 0
        if self.env_map is not None and sky.any():  # L.multiply(f) of a float32 texel
            rows, columns = self.texels_of(wx[sky], wy[sky], wz[sky])
            traced_values[sky] = self.texels[rows, columns] * self.factors(
                kd[sky], cos_theta[sky]).astype(np.float32)
        values = np.zeros(cosines.shape + (3,))  # Y_j: zero unless set here
        values[traced] = traced_values
        return values

    def nearest(self, px, py, pz, wx, wy, wz, rx, ry, rz):
        """The index of the object each sample ray meets first, -1 for none:
        scene.closest_hit(Ray(p, w)), every object in the order of object_list, each
        tested with the ray's t_max so far."""
        hit_index = np.full(len(px), -1)
        t_max = np.full(len(px), HUGEVALUE)
        with np.errstate(all="ignore"):  # the tests' misses: values their masks leave out
            for test, constants, index in self.array_tests:
                t, hit = test(constants, px, py, pz, wx, wy, wz, rx, ry, rz, EPSILON, t_max)
                # only a strictly nearer hit replaces the nearest so far
                nearer = hit & ((hit_index < 0) | (t < t_max))
                hit_index[nearer] = index
                t_max[nearer] = t[nearer]
        return hit_index

    def texels_of(self, wx, wy, wz):
        """(rows, columns) of the texels env_map.getValue(w) reads for the unit vectors w,
        their angles from math.atan2 and math.acos, as texel_of takes them."""
        inverse_pi = 1 / pi
        u = (1 + inverse_pi * np.array([atan2(x, -z) for x, z in zip(wx.tolist(),
                                                                        wz.tolist())])) / 2
        v = inverse_pi * np.array([acos(y if -1.0 <= y <= 1.0 else min(1.0, max(-1.0, y)))
                                   for y in wy.tolist()])
        rows, columns = np.floor(v * self.last_row), np.floor(u * self.last_column)
        if not (np.isfinite(rows).all() and np.isfinite(columns).all()):
            raise ValueError("cannot convert float NaN to integer")  # as math.floor does
        return rows.astype(np.intp), columns.astype(np.intp)

    @staticmethod
    def factors(kd, cosines):
        """f of sample_value, Lambertian.get_value(wi, wo, n) for each sample: kd cos as
        rows (r, g, b), zero where cos <= 0 (BLACK); kd has a row for each sample."""
        return kd * np.where(cosines > 0.0, cosines, 0.0)[:, None]

    def estimates(self, which, values) -> list:
        """For each pixel, the integral of its GP `which` for its values Y_j (samples, r g b):
        the colour, or (which, values) for the GP's own estimate (estimate)."""
        own = [self.weights[w] is not None for w in which]
        finite = np.isfinite(values).all(axis=(1, 2)).tolist()
        made = [(w, pixel_values) for w, pixel_values in zip(which, values)]
        summed = [k for k in range(len(which)) if own[k] and finite[k]]
        if summed:
            weights = np.array([self.weights[which[k]] for k in summed])
            # compute_integral_BMC: res = BLACK, then res + Y_i * w_i for each i
            # (0.0 + the cumulative sum: a total of -0.0, all terms being zeros, is 0.0
            # there, as when the first term is added to BLACK's 0.0)
            totals = (np.cumsum(values[summed] * weights[:, :, None], axis=1)[:, -1]
                      + 0.0).tolist()
            for k, (r, g, b) in zip(summed, totals):
                made[k] = RGBColor(r, g, b)
        return made

    def estimate(self, which, values):
        """The GP's own integral for the values Y_j (rows r, g, b) of GP `which`."""
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
        """f of BMCISIntegrator.sample_value for each sample: its kd, rows (r, g, b)."""
        return kd
