"""The scalar tests of pyrt/scalar_intersections.py on numpy arrays of rays, for the fast
Bayesian integrators (pyrt.acceleration.bayesian), which trace many sample rays at once.

Each ``*_distances(constants, ox, oy, oz, dx, dy, dz, ux, uy, uz, t_min, t_max)`` takes the
arguments of its scalar test with arrays (of one shape) for the rays' origins, unit
directions d, directions normalised once more u, and their t_max; t_min is one number. It
returns (t, hit): the distance the scalar test returns for each ray where `hit` is True.
Both do the same IEEE operations (+, -, *, / and the square root, each correctly rounded,
which numpy's element-wise operations are too) in the same order, so each t is the
scalar test's, bit for bit; where the scalar test divides by zero it returns None first,
and there the division here gives a value that `hit` leaves out.
"""
import numpy as np

from PyRT_Common import INFINITY, SQUARES_HIGH, SQUARES_LOW, euclidean_length
from PyRT_Core import EDGE_TOLERANCE
from pyrt.scalar_intersections import (infinite_plane_distance, parallelogram_distance,
                                       sphere_distance)


def sphere_distances(constants, ox, oy, oz, dx, dy, dz, ux, uy, uz, t_min, t_max):
    """sphere_distance on arrays: the nearer root in [t_min, t_max], else the farther."""
    cx, cy, cz, r = constants
    fx, fy, fz = (ox - cx) / r, (oy - cy) / r, (oz - cz) / r
    b = fx * dx + fy * dy + fz * dz
    ax, ay, az = fx - dx * b, fy - dy * b, fz - dz * b
    disc = 1.0 - (ax * ax + ay * ay + az * az)
    squares = fx * fx + fy * fy + fz * fz
    distance = np.sqrt(squares)
    scaled = ~((SQUARES_LOW < squares) & (squares < SQUARES_HIGH))
    if scaled.any():  # a square over- or underflowed: euclidean_length's rescaling
        distance[scaled] = [euclidean_length(x, y, z) for x, y, z in
                            zip(fx[scaled].tolist(), fy[scaled].tolist(), fz[scaled].tolist())]
    root = np.sqrt(disc)  # NaN where disc < 0, a ray the test leaves at once
    outward = b > 0.0
    q = np.where(outward, -b - root, root - b)
    ratio = (distance - 1.0) * ((distance + 1.0) / q) * r
    # Where q is 0 (b = 0 and disc = 0: the ray leaves the sphere's surface along its
    # tangent) the scalar test takes t0 = t1 = 0. Here t1 = q r = 0 too, and t0 is NaN
    # (disc = 1 - |f|^2 = 0 makes distance exactly 1, and 0 * inf is NaN), which no range
    # holds: the answer is t1's, the same.
    t0 = np.where(outward, q * r, ratio)
    t1 = np.where(outward, ratio, q * r)
    first = (t_min <= t0) & (t0 <= t_max)
    second = (t_min <= t1) & (t1 <= t_max)
    return np.where(first, t0, t1), ~(disc < 0.0) & (first | second)


def infinite_plane_distances(constants, ox, oy, oz, dx, dy, dz, ux, uy, uz, t_min, t_max):
    """infinite_plane_distance on arrays: the plane's distance along u, within the range."""
    nx, ny, nz, px, py, pz = constants
    denominator = ux * nx + uy * ny + uz * nz
    t = (nx * (px - ox) + ny * (py - oy) + nz * (pz - oz)) / denominator
    return t, (denominator != 0.0) & (t_min <= t) & (t <= t_max) & (t != INFINITY)


def parallelogram_distances(constants, ox, oy, oz, dx, dy, dz, ux, uy, uz, t_min, t_max):
    """parallelogram_distance on arrays: the plane's distance, where the point on it lies
    within the two sides (with EDGE_TOLERANCE)."""
    nx, ny, nz, px, py, pz, uax, uay, uaz, ubx, uby, ubz = constants
    denominator = ux * nx + uy * ny + uz * nz
    t = (nx * (px - ox) + ny * (py - oy) + nz * (pz - oz)) / denominator
    qx, qy, qz = ox + dx * t - px, oy + dy * t - py, oz + dz * t - pz
    a = qx * uax + qy * uay + qz * uaz
    b = qx * ubx + qy * uby + qz * ubz
    high = 1.0 + EDGE_TOLERANCE
    return t, ((denominator != 0.0) & (t_min <= t) & (t <= t_max)
               & (-EDGE_TOLERANCE <= a) & (a <= high) & (-EDGE_TOLERANCE <= b) & (b <= high))


# The array version of each scalar test
ARRAY_TESTS = {sphere_distance: sphere_distances,
               infinite_plane_distance: infinite_plane_distances,
               parallelogram_distance: parallelogram_distances}
