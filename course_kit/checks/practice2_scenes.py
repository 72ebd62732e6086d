"""The inputs of the checks of Practice 2 and what a correct answer to them is, in closed
form: no framework, no student's code, numpy only.

- The estimate (2.1): sample sets, each a list of densities p and of values f, whose
  classic Monte Carlo estimate is (1/N) sum f/p.
- The workbench's curve (2.1): the average absolute error of n_estimates estimates of the
  integral of cos over the hemisphere (pi), uniformly sampled, for each number of samples;
  Python's generator seeded, so that sample_set_hemisphere (u1 then u2 for each sample)
  draws what the closed form below draws.
- The white furnace (2.3): a Lambertian sphere of albedo rho under an environment map of
  one value c everywhere. The light it reflects is rho c (the integral of (rho / pi) cos
  over the hemisphere times c); a term of the uniform estimator, c (rho / pi) cos / (1 /
  (2 pi)) = 2 rho c cos, lies within [0, 2 rho c]. A camera ray that misses sees c.
- The emitter (2.3): a floor (an InfinitePlane, normal +y, albedo rho) under a sphere of
  emission L and radius R whose centre lies h >= R above it, no environment map. A floor
  point p at distance d from the centre sees the sphere under a cone of half-angle alpha,
  sin(alpha) = R / d, wholly above its horizon, so the irradiance is pi L sin^2(alpha)
  cos(theta), theta between the normal and the centre, and the light reflected is
  rho L (R / d)^2 (h_p / d), h_p the centre's height above p. A term lies within
  [0, 2 rho L]. What the camera sees of the sphere itself is 0 (its sample rays meet the
  black floor or nothing), and so is the sky.
The camera is the course's: at the origin, looking down -z, 60 degrees of vertical field.
"""
import math
import random as random_module
from typing import NamedTuple, Tuple

import numpy as np

SIZE = 32  # pixels of the published images
N_SAMPLES = 32  # sample rays per pixel of the integrator's checks
FOV = 60.0
CURVE_NS = (20, 40, 60, 80, 100)  # the workbench's numbers of samples
CURVE_ESTIMATES = 100  # estimates averaged per number of samples
EDGE = 1e-6  # a camera ray this close (relative) to a silhouette is not judged
# The map's value: k / 256 with 128 <= k < 256 is exact in Radiance's 8-bit mantissa
SKY_STEPS = tuple(k / 256 for k in range(128, 256))


class SampleSet(NamedTuple):
    """The densities and values (red channel) of one sample set handed to the estimate."""

    probs: Tuple[float, ...]
    values: Tuple[float, ...]


class Furnace(NamedTuple):
    """The white furnace: the sphere's centre and radius, its albedo (r, g, b) and the
    environment map's one value."""

    centre: Tuple[float, float, float]
    radius: float
    albedo: Tuple[float, float, float]
    sky: float


class Emitter(NamedTuple):
    """The emitter scene: the floor's height, its albedo, the emitting sphere's centre,
    radius, emission and albedo."""

    floor_y: float
    floor_albedo: Tuple[float, float, float]
    centre: Tuple[float, float, float]
    radius: float
    emission: Tuple[float, float, float]
    albedo: Tuple[float, float, float]


class Draw(NamedTuple):
    """The inputs of the checks of Practice 2: the images' size, the sample rays per pixel,
    the seed of the workbench's curve (and of the renders' draws), the sample sets of the
    estimate, and the two scenes."""

    size: int
    n_samples: int
    seed: int
    sample_sets: Tuple[SampleSet, ...]
    furnace: Furnace
    emitter: Emitter


def _sample_set(random, n, pdf_exponent, lobe_exponent):
    """A sample set of n directions drawn from CosinePDF(pdf_exponent) (0: uniform), with
    the values of CosineLobe(lobe_exponent) there, as the workbench makes them."""
    probs, values = [], []
    for _ in range(n):
        cos = random.random() ** (1.0 / (pdf_exponent + 1))
        probs.append((pdf_exponent + 1) / (2 * math.pi) * cos ** pdf_exponent)
        values.append(cos ** lobe_exponent)
    return SampleSet(tuple(probs), tuple(values))


def draw_inputs(random, size=SIZE):
    """A Draw made with random (a random.Random): sample sets of 5 to 60 samples from the
    uniform and cosine densities, the seed, and the scenes' places, sizes and colours."""
    sets = tuple(_sample_set(random, random.randint(5, 60), pdf, lobe)
                 for pdf, lobe in ((0, 1), (0, 2), (0, 4), (1, 2), (1, 4), (4, 1)))

    def colour(low, high):
        return tuple(round(random.uniform(low, high), 4) for _ in range(3))

    furnace = Furnace((round(random.uniform(-0.4, 0.4), 4), round(random.uniform(-0.4, 0.4), 4),
                       round(random.uniform(-3.6, -2.8), 4)),
                      round(random.uniform(0.8, 1.0), 4), colour(0.2, 0.9),
                      random.choice(SKY_STEPS))
    radius = round(random.uniform(0.6, 1.0), 4)
    floor_y = round(random.uniform(-1.8, -1.3), 4)
    emitter = Emitter(floor_y, colour(0.3, 0.9),
                      (round(random.uniform(-0.6, 0.6), 4),
                       round(floor_y + radius + random.uniform(0.5, 1.2), 4),
                       round(random.uniform(-6.5, -5.0), 4)),
                      radius, colour(1.0, 4.0), colour(0.2, 0.9))
    return Draw(size, N_SAMPLES, random.randrange(2 ** 31), sets, furnace, emitter)


def draw_from_json(value):
    """The Draw that json.loads gives back as lists."""
    size, n_samples, seed, sets, furnace, emitter = value
    return Draw(int(size), int(n_samples), int(seed),
                tuple(SampleSet(tuple(map(float, p)), tuple(map(float, v))) for p, v in sets),
                Furnace(tuple(map(float, furnace[0])), float(furnace[1]),
                        tuple(map(float, furnace[2])), float(furnace[3])),
                Emitter(float(emitter[0]), tuple(map(float, emitter[1])),
                        tuple(map(float, emitter[2])), float(emitter[3]),
                        tuple(map(float, emitter[4])), tuple(map(float, emitter[5]))))


# The published checks' inputs (the handout's own checks); the grader draws its own
PUBLISHED = draw_inputs(random_module.Random(2025))


# ------------------------------------------------------------------------------------------
# The closed forms
# ------------------------------------------------------------------------------------------
def estimates(draw):
    """The classic Monte Carlo estimate of each sample set, (1/N) sum f/p."""
    return np.array([sum(f / p for p, f in zip(s.probs, s.values)) / len(s.values)
                     for s in draw.sample_sets])


def curve(seed, ns_vector=CURVE_NS, n_estimates=CURVE_ESTIMATES):
    """The workbench's curve for the integral of cos (pi), uniformly sampled, after
    random.seed(seed): sample_set_hemisphere draws u1 then u2 per sample, the direction's
    cosine is u2 and its density 1 / (2 pi), so an estimate is the mean of u2 / (1 / (2 pi))."""
    random = random_module.Random(seed)
    density = 1 / (2 * math.pi)
    errors = []
    for ns in ns_vector:
        total_error = 0.0
        for _ in range(n_estimates):
            f_over_p_sum = 0.0
            for _ in range(ns):
                random.random()  # u1, the azimuth: the cosine does not depend on it
                f_over_p_sum += random.random() / density
            total_error += abs(f_over_p_sum / ns - math.pi)
        errors.append(total_error / n_estimates)
    return np.array(errors)


class Expected(NamedTuple):
    """What a correct integrator gives for each pixel (rows y, columns x, channels): where
    `exact` is True, the value `value` (to rounding); where `estimated` is True, a random
    value of mean `value`, the mean of n terms within [0, bound[channel]]; elsewhere (on a
    silhouette) anything."""

    value: np.ndarray
    exact: np.ndarray
    estimated: np.ndarray
    bound: Tuple[float, float, float]


def camera_directions(size):
    """The unit directions of the course's camera rays, (size, size, 3), rows y."""
    scale = math.tan(FOV * math.pi / 180.0 / 2.0)
    xs = (2.0 * (np.arange(size) + 0.5) / size - 1.0) * scale
    ys = (1.0 - 2.0 * (np.arange(size) + 0.5) / size) * scale
    p = np.stack(np.broadcast_arrays(xs[None, :], ys[:, None], -1.0), axis=-1)
    return p / np.linalg.norm(p, axis=-1, keepdims=True)


def _sphere_hits(d, centre, radius):
    """(the distance to the sphere along each unit direction d from the origin, inf where
    it misses; whether the ray passes within EDGE of its silhouette)."""
    c = np.asarray(centre)
    along = d @ c
    passing = np.sqrt(np.maximum(c @ c - along ** 2, 0.0))
    hit = (passing < radius) & (along > 0)
    t = np.where(hit, along - np.sqrt(np.maximum(radius ** 2 - passing ** 2, 0.0)), np.inf)
    return t, np.abs(passing - radius) < EDGE * radius


def furnace_expected(draw):
    """The Expected of the white furnace (see the module's docstring)."""
    f = draw.furnace
    d = camera_directions(draw.size)
    t, edge = _sphere_hits(d, f.centre, f.radius)
    hit = np.isfinite(t)
    value = np.where(hit[..., None], np.asarray(f.albedo) * f.sky, f.sky)
    estimated = hit & ~edge
    return Expected(value, ~hit & ~edge, estimated,
                    tuple(2.0 * a * f.sky for a in f.albedo))


def emitter_expected(draw):
    """The Expected of the emitter scene (see the module's docstring)."""
    e = draw.emitter
    d = camera_directions(draw.size)
    t_sphere, edge = _sphere_hits(d, e.centre, e.radius)
    down = d[..., 1] < -EDGE
    t_floor = np.where(down, e.floor_y / np.where(down, d[..., 1], -1.0), np.inf)
    floor = down & (t_floor < t_sphere)
    p = d * np.where(floor, t_floor, 0.0)[..., None]
    to_centre = np.asarray(e.centre) - p
    distance = np.linalg.norm(to_centre, axis=-1)
    light = (e.radius / distance) ** 2 * (to_centre[..., 1] / distance)
    value = np.where(floor[..., None], light[..., None]
                     * np.asarray(e.floor_albedo) * np.asarray(e.emission), 0.0)
    return Expected(value, ~floor & ~edge, floor & ~edge,
                    tuple(2.0 * a * L for a, L in zip(e.floor_albedo, e.emission)))


EXPECTED = {"furnace": furnace_expected, "emitter": emitter_expected}
