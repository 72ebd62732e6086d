"""The integrals of GaussianProcess.py: z_i, the integral over the hemisphere around +y of
k(omega_i, omega) p(omega), and k-bar, the double integral of k p p, by quadrature.

Around each sample omega_i the hemisphere is swept in rings: omega at the angle gamma from
omega_i, at the angle psi around it. k depends on gamma alone for a kernel of the distance
(r^2 = 4 sin^2(gamma/2)), and the ring lies wholly in the hemisphere for gamma up to
pi/2 - theta_i (theta_i the polar angle of omega_i), partly up to pi/2 + theta_i, and below
it beyond. On the arc inside, cos(theta) = a + b cos(psi) with a = cos(theta_i) cos(gamma),
b = sin(theta_i) sin(gamma), for |psi| <= psi0 = acos(-a / b). So

    z_i = integral over gamma in [0, pi/2 + theta_i] of k(gamma) sin(gamma) P(gamma) dgamma,

P the integral of p along the ring's arc inside: for p = c cos^e of the polar angle (a p
symmetric about +y), 2 pi c (e = 0) and 2 pi c a (e = 1) on the whole ring, 2 c psi0 and
2 c (a psi0 + b sin psi0) on the arc. The kink of r^(2s-2) at gamma = 0 and the square roots
of psi0 at the ends of the second range are endpoint singularities, which the tanh-sinh
(double exponential) rule integrates to rounding. Any other p, or a kernel of one's own,
takes the same sweep with psi integrated numerically (general_z).

The course's own estimator (course_z) is here too: classic Monte Carlo over 50,000 uniform
directions drawn as sample_set_hemisphere(50000, UniformPDF()) draws them.
"""
import math
from functools import lru_cache
from random import random
from typing import Callable, NamedTuple, Optional

import numpy as np

from pyrt.gp_kernels import (PolarProfile, RadialProfile, array_eval, polar_profile,
                             radial_profile)

HALF_PI = math.pi / 2
# The tanh-sinh rule: start with this step, halve it until two rules agree to TOLERANCE
# (relative), at most down to FINEST_STEP. Its error roughly squares as the step halves, so
# the finer rule of two that agree to 1e-9 is good to rounding.
FIRST_STEP = 1 / 8
FINEST_STEP = 1 / 128
TOLERANCE = 1e-9
# symmetric_z takes, for each kernel and p, the largest step whose z agrees with that of
# half the step to CALIBRATED (relative) at every polar angle of CALIBRATION_ANGLES: the
# whole range, and angles ever closer to the pole and to the horizon
CALIBRATED = 1e-13
CALIBRATION_ANGLES = np.concatenate([np.linspace(0.0, HALF_PI, 129),
                                     np.logspace(-12, -1, 23), HALF_PI - np.logspace(-12, -1, 23)])
# psi on the whole ring: the trapezoidal rule (exact for trigonometric polynomials of lower
# degree, spectrally accurate for smooth periodic integrands); on an arc: Gauss-Legendre
RING_POINTS = 64
ARC_POINTS = 32
# k-bar for a kernel or p of one's own: a grid of directions, in theta and phi (k_bar)
GENERAL_THETA_STEP = 1 / 4
GENERAL_PHI_POINTS = 16
# The course's estimator: ns_z uniform directions, two draws of random() each, taken
# COURSE_BLOCK at a time
COURSE_DIRECTIONS = 50_000
COURSE_BLOCK = 2048


class Rule(NamedTuple):
    """A quadrature rule on [0, 1]: its nodes and weights."""

    nodes: np.ndarray
    weights: np.ndarray


@lru_cache(maxsize=None)
def tanh_sinh(step: float) -> Rule:
    """The tanh-sinh rule of step h on [0, 1]: x = (1 + tanh(pi/2 sinh t)) / 2 at t = k h,
    weight h pi cosh(t) x (1 - x), for |t| up to 4, beyond which weights are below 1e-33.
    x and 1 - x are computed as 1 / (1 + e^-u) and 1 / (1 + e^u), u = pi sinh(t), which
    keep their digits however close to 0 they come."""
    t = np.arange(-math.ceil(4 / step), math.ceil(4 / step) + 1) * step
    u = math.pi * np.sinh(t)
    x, one_minus_x = 1 / (1 + np.exp(-u)), 1 / (1 + np.exp(u))
    return Rule(x, step * math.pi * np.cosh(t) * x * one_minus_x)


@lru_cache(maxsize=None)
def gauss_legendre(points: int) -> Rule:
    """The Gauss-Legendre rule of `points` nodes on [0, 1]."""
    nodes, weights = np.polynomial.legendre.leggauss(points)
    return Rule((1 + nodes) / 2, weights / 2)


def converged(integrate: Callable[[float], np.ndarray]) -> np.ndarray:
    """integrate(step) at the step where it agrees with the step twice as large to
    TOLERANCE, halving from FIRST_STEP (at FINEST_STEP whatever it gives)."""
    step, coarse = FIRST_STEP, integrate(FIRST_STEP)
    while step > FINEST_STEP:
        step /= 2
        fine = integrate(step)
        if np.all(np.abs(fine - coarse) <= TOLERANCE * np.maximum(np.abs(fine), 1e-300)):
            return fine
        coarse = fine
    return coarse


class Sweep(NamedTuple):
    """The angles gamma from omega_i of a rule's nodes on one range of the sweep, shape
    (samples, nodes), with their weights (times sin(gamma)) and the ring's a and b."""

    gamma: np.ndarray
    weights: np.ndarray
    a: np.ndarray
    b: np.ndarray
    whole_ring: bool


def sweeps(theta: np.ndarray, rule: Rule):
    """The two ranges of gamma for samples at polar angles theta (see the module's
    docstring): [0, pi/2 - theta] (whole rings) and [pi/2 - theta, pi/2 + theta] (arcs)."""
    theta = theta[:, None]
    inner = HALF_PI - theta
    for start, length, whole in ((0.0, inner, True), (inner, 2 * theta, False)):
        gamma = start + length * rule.nodes
        yield Sweep(gamma, length * rule.weights * np.sin(gamma),
                    np.cos(theta) * np.cos(gamma), np.sin(theta) * np.sin(gamma), whole)


def arc_end(sweep: Sweep) -> np.ndarray:
    """psi0 = acos(-a / b), the half-angle of the arc of a ring inside the hemisphere."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(sweep.b > 0, -sweep.a / sweep.b, -1.0)
    return np.arccos(np.clip(ratio, -1.0, 1.0))


def ring_integral(p: PolarProfile, sweep: Sweep) -> np.ndarray:
    """P(gamma): p = c cos^e integrated over the ring's part inside the hemisphere, in
    closed form for e = 0 and 1, by the trapezoidal rule (whole ring) or Gauss-Legendre
    (arc) for any other e."""
    a, b = sweep.a, sweep.b
    psi0 = np.pi if sweep.whole_ring else arc_end(sweep)
    if p.exponent == 0:
        return 2 * p.scale * psi0 * np.ones_like(a)
    if p.exponent == 1:
        if sweep.whole_ring:
            return 2 * math.pi * p.scale * a
        return 2 * p.scale * (a * psi0 + b * np.sin(psi0))
    if sweep.whole_ring:
        psi = np.arange(RING_POINTS) * (2 * math.pi / RING_POINTS)
        cosines = np.maximum(a[..., None] + b[..., None] * np.cos(psi), 0.0)
        return p(cosines).sum(axis=-1) * (2 * math.pi / RING_POINTS)
    rule = gauss_legendre(ARC_POINTS)
    psi = psi0[..., None] * rule.nodes
    cosines = np.maximum(a[..., None] + b[..., None] * np.cos(psi), 0.0)
    return 2 * psi0 * (p(cosines) * rule.weights).sum(axis=-1)


def polar_angles(positions: np.ndarray) -> np.ndarray:
    """The angles to +y of unit directions, from atan2 (acos(y) loses digits near +y)."""
    return np.arctan2(np.hypot(positions[:, 0], positions[:, 2]), positions[:, 1])


def swept_z(kernel: RadialProfile, p: PolarProfile, theta: np.ndarray,
            step: float) -> np.ndarray:
    """z at samples of polar angles theta, for a kernel of the distance and a p symmetric
    about +y (the module's docstring), by the tanh-sinh rule of the given step."""
    total = np.zeros(len(theta))
    for sweep in sweeps(theta, tanh_sinh(step)):
        k = kernel(4 * np.sin(sweep.gamma / 2) ** 2)
        total += (sweep.weights * k * ring_integral(p, sweep)).sum(axis=1)
    return total


@lru_cache(maxsize=64)
def calibrated_step(kernel: RadialProfile, p: PolarProfile) -> float:
    """The step of the tanh-sinh rule that gives this kernel's and p's z to CALIBRATED at
    every angle of CALIBRATION_ANGLES (FINEST_STEP at most)."""
    step, coarse = FIRST_STEP, swept_z(kernel, p, CALIBRATION_ANGLES, FIRST_STEP)
    while step > FINEST_STEP:
        fine = swept_z(kernel, p, CALIBRATION_ANGLES, step / 2)
        if np.all(np.abs(coarse - fine) <= CALIBRATED * np.abs(fine)):
            return step
        step, coarse = step / 2, fine
    return FINEST_STEP


def symmetric_z(kernel: RadialProfile, p: PolarProfile, theta: np.ndarray) -> np.ndarray:
    """z at samples of polar angles theta, for a kernel of the distance and a p symmetric
    about +y, to rounding, by the rule of the step calibrated for them."""
    return swept_z(kernel, p, theta, calibrated_step(kernel, p))


class Resolution(NamedTuple):
    """How finely general_z integrates: the tanh-sinh step in gamma (None: halved from
    FIRST_STEP until it converges) and the points of psi on whole rings and on arcs."""

    step: Optional[float]
    ring_points: int
    arc_points: int


# z to rounding; z on k_bar's grid of directions, to about 1e-7
FINE = Resolution(None, RING_POINTS, ARC_POINTS)
COARSE = Resolution(1 / 4, 16, 16)


def general_z(cov_func, p_func, positions: np.ndarray,
              resolution: Resolution = FINE) -> np.ndarray:
    """z for any kernel and p (k and p through their profiles when they have one, else
    through their eval), psi integrated on each ring by the trapezoidal rule (whole ring)
    or Gauss-Legendre (arc)."""
    kernel, p = radial_profile(cov_func), polar_profile(p_func)
    theta = polar_angles(positions)

    def integrate(step):
        total = np.zeros(len(positions))
        for i, omega_i in enumerate(positions):
            frame = ring_frame(omega_i, theta[i])
            for sweep in sweeps(theta[i:i + 1], tanh_sinh(step)):
                psi, psi_weights = ring_angles(sweep, resolution)
                omega = ring_directions(frame, sweep.gamma[0], psi)
                if kernel is not None:
                    k = np.repeat(kernel(4 * np.sin(sweep.gamma[0] / 2) ** 2),
                                  psi.shape[1])
                else:
                    k = array_eval(cov_func.eval, np.broadcast_to(omega_i, omega.shape),
                                   omega)
                values = k * (p(omega[:, 1]) if p is not None
                              else array_eval(p_func.eval, omega))
                values = values.reshape(psi.shape) * psi_weights
                total[i] += (sweep.weights[0] * values.sum(axis=1)).sum()
        return total
    if resolution.step is not None:
        return integrate(resolution.step)
    return converged(integrate)


def ring_frame(omega_i: np.ndarray, theta_i: float) -> np.ndarray:
    """Rows omega_i, e1, e2: e1 the unit tangent at omega_i towards +y (any tangent at the
    pole), e2 = omega_i x e1; a ring's psi is measured from e1."""
    if theta_i < 1e-8:
        e1 = np.array([1.0, 0.0, 0.0])
    else:
        e1 = (np.array([0.0, 1.0, 0.0]) - math.cos(theta_i) * omega_i) / math.sin(theta_i)
        e1 /= np.linalg.norm(e1)
    return np.array([omega_i, e1, np.cross(omega_i, e1)])


def ring_angles(sweep: Sweep, resolution: Resolution):
    """The angles psi of the nodes on each ring of a sweep (rows) and their weights."""
    if sweep.whole_ring:
        points = resolution.ring_points
        psi = np.arange(points) * (2 * math.pi / points)
        return np.broadcast_to(psi, sweep.gamma.shape[1:] + psi.shape), np.full(
            psi.shape, 2 * math.pi / points)
    rule = gauss_legendre(resolution.arc_points)
    psi0 = arc_end(sweep)[0][:, None]
    return psi0 * (2 * rule.nodes - 1), 2 * psi0 * rule.weights


def ring_directions(frame: np.ndarray, gamma: np.ndarray, psi: np.ndarray) -> np.ndarray:
    """The (rings x nodes, 3) directions cos(gamma) omega_i + sin(gamma) (cos(psi) e1 +
    sin(psi) e2), kept on the hemisphere (y >= 0) against rounding."""
    omega_i, e1, e2 = frame
    g = gamma[:, None, None]
    omega = (np.cos(g) * omega_i + np.sin(g) * (np.cos(psi)[..., None] * e1
                                                + np.sin(psi)[..., None] * e2))
    omega = omega.reshape(-1, 3)
    omega[:, 1] = np.maximum(omega[:, 1], 0.0)
    return omega


def exact_z(cov_func, p_func, positions: np.ndarray) -> np.ndarray:
    """z_i for every sample position, by quadrature: the symmetric reduction when the kernel
    depends on the distance alone and p on the polar angle alone, else general_z."""
    kernel, p = radial_profile(cov_func), polar_profile(p_func)
    if kernel is not None and p is not None:
        return symmetric_z(kernel, p, polar_angles(positions))
    return general_z(cov_func, p_func, positions)


@lru_cache(maxsize=64)
def symmetric_k_bar(kernel: RadialProfile, p: PolarProfile) -> float:
    """k-bar = 2 pi times the integral over theta in [0, pi/2] of z(theta) p(theta)
    sin(theta), for a kernel of the distance and a symmetric p."""
    def integrate(step):
        rule = tanh_sinh(step)
        theta = HALF_PI * rule.nodes
        z = symmetric_z(kernel, p, theta)
        return np.array([2 * math.pi * HALF_PI * np.sum(
            rule.weights * z * p(np.cos(theta)) * np.sin(theta))])
    return float(converged(integrate)[0])


def k_bar(cov_func, p_func) -> float:
    """The double integral over the hemisphere of k(omega, omega') p(omega) p(omega'): to
    rounding for a kernel of the distance and a symmetric p; for any other, from z (of
    COARSE resolution) on a grid of directions (the tanh-sinh rule of step
    GENERAL_THETA_STEP in theta, the trapezoidal rule of GENERAL_PHI_POINTS points in phi),
    good to about 1e-7."""
    kernel, p = radial_profile(cov_func), polar_profile(p_func)
    if kernel is not None and p is not None:
        return symmetric_k_bar(kernel, p)
    rule = tanh_sinh(GENERAL_THETA_STEP)
    theta = HALF_PI * rule.nodes
    phi = np.arange(GENERAL_PHI_POINTS) * (2 * math.pi / GENERAL_PHI_POINTS)
    t, f = np.meshgrid(theta, phi, indexing="ij")
    directions = np.stack([np.sin(t) * np.sin(f), np.cos(t), np.sin(t) * np.cos(f)],
                          axis=-1).reshape(-1, 3)
    z = general_z(cov_func, p_func, directions, COARSE)
    p_values = p(directions[:, 1]) if p is not None else array_eval(p_func.eval, directions)
    weights = np.repeat(HALF_PI * rule.weights * np.sin(theta), len(phi)) * (
        2 * math.pi / len(phi))
    return float(np.sum(weights * z * p_values))


def course_directions(n: int = COURSE_DIRECTIONS) -> np.ndarray:
    """The directions of sample_set_hemisphere(n, UniformPDF()) as the rows x, y, z of a
    (3, n) array: 2n draws of random(), u1 then u2 for each direction, y = u2,
    phi = 2 pi u1, x = sin(phi) sqrt(1 - u2^2), z = cos(phi) sqrt(1 - u2^2)."""
    # iter(random, -1.0) calls random() until it returns -1.0, which it never does: the
    # draws in order, without a Python loop
    u = np.fromiter(iter(random, -1.0), dtype=float, count=2 * n)
    u1, u2 = u[0::2], u[1::2]
    phi = 2 * math.pi * u1
    sin_theta = np.sqrt(1 - u2 * u2)
    return np.stack([np.sin(phi) * sin_theta, u2, np.cos(phi) * sin_theta])


def course_z(cov_func, p_func, positions: np.ndarray) -> Optional[np.ndarray]:
    """The course's estimate of z: (1/ns_z) sum over j of k(omega_i, x_j) p(x_j) / (1/(2 pi))
    over the ns_z = 50,000 directions x_j of course_directions, shared by every i. None
    (drawing nothing) for a kernel of one's own, which GaussianProcess.py's loop
    evaluates as written."""
    kernel = radial_profile(cov_func)
    if kernel is None:
        return None
    directions = course_directions()
    p = polar_profile(p_func)
    p_values = p(directions[1]) if p is not None else array_eval(p_func.eval, directions.T)
    p_over_pdf = p_values / (1 / (2 * math.pi))
    # r^2 = |a|^2 + |b|^2 - 2 a.b by matrix products, COURSE_BLOCK directions at a time (in
    # the processor's cache): its rounding (a few 1e-16) moves k only where r is tiny, for
    # a share of the 50,000 directions far below 1e-12
    squares_a = np.einsum("ij,ij->i", positions, positions)[:, None]
    squares_b = np.einsum("ij,ij->j", directions, directions)
    z = np.zeros(len(positions))
    for start in range(0, COURSE_DIRECTIONS, COURSE_BLOCK):
        block = slice(start, start + COURSE_BLOCK)
        r2 = positions @ (-2 * directions[:, block])
        r2 += squares_a
        r2 += squares_b[block]
        np.maximum(r2, 0.0, out=r2)
        z += kernel(r2) @ p_over_pdf[block]
    return z / COURSE_DIRECTIONS
