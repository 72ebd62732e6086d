"""The inputs of the checks of Practices 3 and 4 and what a correct answer to them is: no
framework, no student's code, numpy only.

The Gaussian process (3.1), with the course's Sobolev kernel k(omega_i, omega_j) =
2^(2s-1)/s - r^(2s-2), r = |omega_i - omega_j|, s = 1.4:
- Q on given positions: Q[i, j] = k(omega_i, omega_j) + noise^2 on the diagonal, and its
  inverse (kernel_matrix, inverse_q);
- z, the integral over the hemisphere around +y of k(omega_i, omega) p(omega) for p = 1 and
  p = cos: exactly, by a quadrature about omega_i (exact_z: k depends only on the angle t
  between omega_i and omega, and the part of the circle of directions at angle t that lies
  above the horizon has a closed form), and as the course estimates it after
  random.seed(seed) (course_z: the same 50,000 uniform directions that
  sample_set_hemisphere draws, u1 then u2 for each);
- the BMC sum, sum over i of w_i Y_i on given weights and colours.
The integrators (3.3, 3.3.2, 4.1, 4.2) run in the white furnace of practice2_scenes (a
Lambertian sphere of albedo rho under an environment map of one value c), for 3.3 also
inside a closed box of emitting walls, and, for 3.3.2, above a floor under the same sky. A GP's weights are what this module computes for its
sample set (weights), handed to the integrator inside a GP of the kit: the integrator's
checks never depend on the student's GaussianProcess.py. With the values Y_j = c (rho /
pi) cos(theta_j) of the uniform BMC integrator, the furnace's pixel is c (rho / pi) sum
w_j cos(theta_j), whatever the rotation about the normal; with BMC IS's Y_j = c rho / pi
it is c (rho / pi) sum w_j; classic Monte Carlo with cosine sampling gives c rho exactly.
"""
import functools
import math
import random as random_module
from typing import NamedTuple, Tuple

import numpy as np

import practice2_scenes

SOBOLEV_S = 1.4  # the course's SobolevCov() default
GP_NOISE = 0.01  # the course's GP(...) default noise_
COURSE_NS_Z = 50000  # the course's compute_z: its uniform directions
SIZE = 16  # pixels of the integrators' images
N_SAMPLES = 12  # sample directions of each GP handed to an integrator
POOL = 4  # GPs of 3.3.2's pool
N_POSITIONS = 3  # positions of the compute_inv_Q and compute_z checks
QUADRATURE_NODES = 400  # Gauss-Legendre nodes of each piece of exact_z


class SumCase(NamedTuple):
    """One case of the BMC sum: the weights and the colours Y_i, (r, g, b) each."""

    weights: Tuple[float, ...]
    values: Tuple[Tuple[float, float, float], ...]


class GPSet(NamedTuple):
    """The sample set of a GP the kit hands to an integrator: its unit directions and the
    weights z^T Q^-1 computed here for them (p = 1 for uniform sets, cos for cosine ones)."""

    positions: Tuple[Tuple[float, float, float], ...]
    weights: Tuple[float, ...]


class Floor(NamedTuple):
    """3.3.2's scene: a floor (normal +y) at height floor_y, of albedo (r, g, b), under an
    environment map of one value."""

    floor_y: float
    albedo: Tuple[float, float, float]
    sky: float


class Draw(NamedTuple):
    """The inputs of the checks of Practices 3 and 4: the images' size, the seed of the
    course's z estimate (and of the renders' draws), the noise and the positions of the
    Q and z checks, the BMC sums' cases, the uniform pool (3.3, 3.3.2) and the cosine pool
    (4.2) of GPs, the white furnace (practice2_scenes.Furnace) and 3.3.2's floor."""

    size: int
    seed: int
    noise: float
    positions: Tuple[Tuple[float, float, float], ...]
    sums: Tuple[SumCase, ...]
    pool: Tuple[GPSet, ...]
    pool_is: Tuple[GPSet, ...]
    furnace: practice2_scenes.Furnace
    floor: Floor

    @property
    def n_samples(self):
        return len(self.pool[0].positions)


# ------------------------------------------------------------------------------------------
# The Gaussian process, in numpy
# ------------------------------------------------------------------------------------------
def sobolev(r2, s=SOBOLEV_S):
    """The Sobolev kernel as a function of r^2 = |omega_i - omega_j|^2."""
    return 2 ** (2 * s - 1) / s - np.maximum(r2, 0.0) ** (s - 1)


def kernel_matrix(positions):
    """K[i, j] = k(omega_i, omega_j) for the rows of positions (n, 3)."""
    p = np.asarray(positions, dtype=float)
    difference = p[:, None, :] - p[None, :, :]
    return sobolev(np.sum(difference * difference, axis=-1))


def inverse_q(positions, noise=GP_NOISE):
    """Q^-1 with Q = K + noise^2 I, as compute_inv_Q gives it."""
    q = kernel_matrix(positions) + noise ** 2 * np.identity(len(positions))
    return np.linalg.inv(q)


@functools.lru_cache(maxsize=None)
def _legendre(nodes):
    """Gauss-Legendre's nodes and weights on [-1, 1] (an eigenvalue problem: made once)."""
    return np.polynomial.legendre.leggauss(nodes)


def _gauss(low, high, nodes=QUADRATURE_NODES):
    x, w = _legendre(nodes)
    half = (high - low) / 2.0
    return low + half * (x + 1.0), half * w


def exact_z(positions, p_exponent):
    """z_i = the integral over the hemisphere of k(omega_i, omega) cos(theta)^p_exponent
    (p_exponent 0: p = 1; 1: p = cos), to about 1e-9 relative. About omega_i (polar angle
    theta_i), omega lies at an angle t and an azimuth psi; its height is cos t cos theta_i +
    sin t sin theta_i cos psi, above the horizon for cos psi >= a = -cot t cot theta_i, an
    arc of 2 acos(a), over which the height integrates to 2 (cos t cos theta_i acos(a) +
    sin t sin theta_i sqrt(1 - a^2)). The arc is whole for t <= pi/2 - theta_i and empty
    beyond pi/2 + theta_i: the quadrature is split there."""
    z = []
    for position in np.asarray(positions, dtype=float):
        cos_i = min(max(position[1], 0.0), 1.0)
        theta = math.acos(cos_i)
        sin_i = math.sin(theta)
        total = 0.0
        for low, high in ((0.0, math.pi / 2 - theta), (math.pi / 2 - theta,
                                                         math.pi / 2 + theta)):
            if high <= low:
                continue
            t, w = _gauss(low, high)
            # the angle t: r^2 = 2 - 2 cos t; the arc's end in cos psi
            ct, st = np.cos(t), np.sin(t)
            with np.errstate(divide="ignore", invalid="ignore"):
                a = np.where(st * sin_i > 0, -ct * cos_i / (st * sin_i), -np.inf)
            a = np.clip(a, -1.0, 1.0)
            arc = 2.0 * np.arccos(a)
            if p_exponent == 0:
                measure = arc
            else:
                measure = ct * cos_i * arc + 2.0 * st * sin_i * np.sqrt(1.0 - a * a)
            total += float(np.sum(w * sobolev(2.0 - 2.0 * ct) * st * measure))
        z.append(total)
    return np.array(z)


def course_directions(seed, n=COURSE_NS_Z):
    """The n uniform directions (n, 3) that sample_set_hemisphere(n, UniformPDF()) draws
    after random.seed(seed): u1 then u2 for each, y = u2, phi = 2 pi u1, x = sin(phi)
    sqrt(1 - u2^2), z = cos(phi) sqrt(1 - u2^2)."""
    draws = random_module.Random(seed)
    u = np.array([draws.random() for _ in range(2 * n)]).reshape(n, 2)
    phi, y = 2 * math.pi * u[:, 0], u[:, 1]
    s = np.sqrt(1 - y * y)
    return np.stack([np.sin(phi) * s, y, np.cos(phi) * s], axis=1)


def course_z(seed, positions, p_exponent):
    """The course's estimate of z after random.seed(seed): (1 / ns_z) sum over j of
    k(omega_i, x_j) p(x_j) / (1 / (2 pi)) on course_directions(seed)."""
    x = course_directions(seed)
    p = x[:, 1] ** p_exponent
    z = []
    for position in np.asarray(positions, dtype=float):
        difference = x - position
        z.append(float(np.mean(sobolev(np.sum(difference * difference, axis=1)) * p)
                       * 2 * math.pi))
    return np.array(z)


def z_term_bound():
    """The largest term k p / (1 / (2 pi)) of the course's z estimate: k <= 2^(2s-1)/s, p
    <= 1; every term is at least 0 (k >= 2^(2s-1)/s - 2^(s-1) > 0 on the hemisphere)."""
    return 2 * math.pi * 2 ** (2 * SOBOLEV_S - 1) / SOBOLEV_S


def weights(positions, p_exponent, noise=GP_NOISE):
    """The BMC weights w = z^T Q^-1 of a sample set (solved, not inverted)."""
    q = kernel_matrix(positions) + noise ** 2 * np.identity(len(positions))
    return np.linalg.solve(q, exact_z(positions, p_exponent))


# ------------------------------------------------------------------------------------------
# The draw
# ------------------------------------------------------------------------------------------
def _direction(random, cosine):
    """A direction drawn as UniformPDF's (cosine False) or CosinePDF(1)'s generate_dir."""
    u1, u2 = random.random(), random.random()
    y = math.sqrt(u2) if cosine else u2
    s = math.sqrt(max(1.0 - y * y, 0.0))
    return (math.sin(2 * math.pi * u1) * s, y, math.cos(2 * math.pi * u1) * s)


def gp_set(random, n, cosine):
    """A GPSet of n directions drawn uniformly (cosine False) or from the cosine."""
    positions = tuple(_direction(random, cosine) for _ in range(n))
    return GPSet(positions, tuple(float(w) for w in weights(positions, int(cosine))))


def draw_inputs(random, size=SIZE):
    """A Draw made with random (a random.Random)."""
    def colour(low, high):
        return tuple(round(random.uniform(low, high), 4) for _ in range(3))

    positions = tuple(_direction(random, False) for _ in range(N_POSITIONS - 1)) + (
        (0.0, 1.0, 0.0),)  # the pole, whose z has a closed form
    sums = tuple(SumCase(tuple(round(random.uniform(-0.5, 1.5), 6) for _ in range(n)),
                         tuple(colour(0.0, 3.0) for _ in range(n)))
                 for n in (random.randint(3, 9), random.randint(10, 30)))
    furnace = practice2_scenes.Furnace(
        (round(random.uniform(-0.2, 0.2), 4), round(random.uniform(-0.2, 0.2), 4),
         round(random.uniform(-3.4, -3.0), 4)), round(random.uniform(0.9, 1.1), 4),
        colour(0.2, 0.9), random.choice(practice2_scenes.SKY_STEPS))
    floor = Floor(round(random.uniform(-1.5, -0.8), 4), colour(0.2, 0.9),
                  random.choice(practice2_scenes.SKY_STEPS))
    return Draw(size, random.randrange(2 ** 31), round(random.uniform(0.02, 0.2), 4),
                positions, sums,
                tuple(gp_set(random, N_SAMPLES, False) for _ in range(POOL)),
                (gp_set(random, N_SAMPLES, True),), furnace, floor)


def draw_from_json(value):
    """The Draw that json.loads gives back as lists."""
    size, seed, noise, positions, sums, pool, pool_is, furnace, floor = value

    def triples(rows):
        return tuple(tuple(map(float, row)) for row in rows)

    def gp_sets(sets):
        return tuple(GPSet(triples(p), tuple(map(float, w))) for p, w in sets)

    return Draw(int(size), int(seed), float(noise), triples(positions),
                tuple(SumCase(tuple(map(float, w)), triples(v)) for w, v in sums),
                gp_sets(pool), gp_sets(pool_is),
                practice2_scenes.Furnace(tuple(map(float, furnace[0])), float(furnace[1]),
                                         tuple(map(float, furnace[2])), float(furnace[3])),
                Floor(float(floor[0]), tuple(map(float, floor[1])), float(floor[2])))


# The published checks' inputs (the handout's own checks); the grader draws its own
PUBLISHED = draw_inputs(random_module.Random(2026))


# ------------------------------------------------------------------------------------------
# The integrators' closed forms
# ------------------------------------------------------------------------------------------
def bmc_sum(case):
    """sum over i of w_i Y_i, per channel."""
    return np.asarray(case.weights) @ np.asarray(case.values)


def cos_sum(gp):
    """sum over j of w_j cos(theta_j) of a GPSet: the furnace's BMC pixel over c rho / pi."""
    return float(np.asarray(gp.weights) @ np.asarray(gp.positions)[:, 1])


def furnace_expected(draw, factor):
    """The practice2_scenes.Expected of the white furnace whose sphere's pixels are c rho
    times factor, exactly, and the sky's c; only silhouettes are not judged."""
    f = draw.furnace
    t, edge = practice2_scenes._sphere_hits(practice2_scenes.camera_directions(draw.size),
                                            f.centre, f.radius)
    value = np.where(np.isfinite(t)[..., None], np.asarray(f.albedo) * f.sky * factor,
                     f.sky)
    return practice2_scenes.Expected(value, ~edge, np.zeros_like(edge), (0.0, 0.0, 0.0))


def furnace_sphere(draw):
    """Whether each camera ray (rows y) meets the furnace's sphere, away from its
    silhouette."""
    f = draw.furnace
    t, edge = practice2_scenes._sphere_hits(practice2_scenes.camera_directions(draw.size),
                                            f.centre, f.radius)
    return np.isfinite(t) & ~edge


# The emitting box of 3.3 around the camera and the furnace's sphere: its corners, and its
# walls' emission per unit of the furnace's sky value
BOX_LOW, BOX_HIGH = (-2.5, -2.5, -5.0), (2.5, 2.5, 1.0)
BOX_EMISSION = (1.0, 2.0, 3.0)


def box_emission(draw):
    """E, the emission of every wall of 3.3's box."""
    return tuple(e * draw.furnace.sky for e in BOX_EMISSION)


def box_expected(draw, factor):
    """The practice2_scenes.Expected of the furnace's sphere inside a closed box whose
    walls emit E and reflect nothing (no map): every sample ray from the sphere meets a
    wall, so the sphere's pixels are E rho times factor; the walls' own pixels are 0 (a
    camera ray's own hit adds no emission), exactly."""
    f = draw.furnace
    t, edge = practice2_scenes._sphere_hits(practice2_scenes.camera_directions(draw.size),
                                            f.centre, f.radius)
    value = np.where(np.isfinite(t)[..., None],
                     np.asarray(f.albedo) * np.asarray(box_emission(draw)) * factor, 0.0)
    return practice2_scenes.Expected(value, ~edge, np.zeros_like(edge), (0.0, 0.0, 0.0))


def floor_pixels(draw):
    """Whether each camera ray (rows y) meets 3.3.2's floor, well away from the horizon."""
    d = practice2_scenes.camera_directions(draw.size)
    return d[..., 1] < -practice2_scenes.EDGE * 10


def turned_sets(draw, chosen, angles):
    """3.3.2's data, (directions, chosen), of an integrator that used GP chosen[k] of the
    pool turned about y by angles[k] at the k-th floor hit (for the kit's tests and
    benchmarks: what a correct integrator, and each mistake, hands back)."""
    floor = floor_pixels(draw)
    directions = np.full((draw.size, draw.size, draw.n_samples, 3), np.nan)
    picked = np.full((draw.size, draw.size), -1.0)
    for k, (y, x) in enumerate(np.argwhere(floor)):
        p = np.asarray(draw.pool[chosen[k]].positions)
        c, s = math.cos(angles[k]), math.sin(angles[k])
        directions[y, x] = np.stack([p[:, 0] * c + p[:, 2] * s, p[:, 1],
                                     -p[:, 0] * s + p[:, 2] * c], axis=1)
        picked[y, x] = chosen[k]
    return directions, picked
