"""PyRT_Core's intersection tests on plain floats, for the fast queries of pyrt.acceleration.

Each ``*_distance(constants, ox, oy, oz, dx, dy, dz, ux, uy, uz, t_min, t_max)`` is the
distance at which a primitive's ``intersect`` finds its hit along the ray from (ox, oy, oz)
with unit direction (dx, dy, dz), or None on a miss; (ux, uy, uz) is that direction
normalised once more, Normalize(d), along which the plane tests measure t as
PyRT_Core.course_direction does (the queries normalise a ray's direction once for all the
objects it is tested against); ``constants`` holds what the test reads of the object, as
pyrt.acceleration.queries' ``_object_test`` gathers them. Each ``*_hit`` gives the hit
point and normal (px, py, pz, nx, ny, nz) at that distance, from the same arguments.
Every one repeats the operations of the method it stands for, in the same order, so that
it rounds the same way and gives the same numbers, bit for bit, without making a Vector3D
or a HitData.
"""
from math import sqrt

from PyRT_Common import INFINITY, SQUARES_HIGH, SQUARES_LOW, euclidean_length, unit_components
from PyRT_Core import EDGE_TOLERANCE


def sphere_distance(constants, ox, oy, oz, dx, dy, dz, ux, uy, uz, t_min, t_max):
    """Sphere.intersect's distance, or None on a miss."""
    cx, cy, cz, r = constants
    fx, fy, fz = (ox - cx) / r, (oy - cy) / r, (oz - cz) / r
    b = fx * dx + fy * dy + fz * dz
    ax, ay, az = fx - dx * b, fy - dy * b, fz - dz * b
    disc = 1.0 - (ax * ax + ay * ay + az * az)
    if disc < 0.0:
        return None
    squares = fx * fx + fy * fy + fz * fz
    distance = sqrt(squares) if SQUARES_LOW < squares < SQUARES_HIGH else (
        euclidean_length(fx, fy, fz))
    if b > 0.0:
        q = -b - sqrt(disc)
        t0, t1 = q * r, (distance - 1.0) * ((distance + 1.0) / q) * r
    else:
        q = sqrt(disc) - b
        if q == 0.0:
            t0 = t1 = 0.0
        else:
            t0, t1 = (distance - 1.0) * ((distance + 1.0) / q) * r, q * r
    if t_min <= t0 <= t_max:
        return t0
    if t_min <= t1 <= t_max:
        return t1
    return None


def sphere_hit(constants, ox, oy, oz, dx, dy, dz, ux, uy, uz, t):
    """The hit point and normal (px, py, pz, nx, ny, nz) of Sphere.intersect at distance t."""
    cx, cy, cz, r = constants
    vx, vy, vz = (ox + dx * t - cx) / r, (oy + dy * t - cy) / r, (oz + dz * t - cz) / r
    if vx == 0.0 and vy == 0.0 and vz == 0.0:
        nx, ny, nz = dx * -1.0, dy * -1.0, dz * -1.0
    else:
        nx, ny, nz = unit_components(vx, vy, vz)
    return cx + nx * r, cy + ny * r, cz + nz * r, nx, ny, nz


def infinite_plane_distance(constants, ox, oy, oz, dx, dy, dz, ux, uy, uz, t_min, t_max):
    """InfinitePlane.intersect's distance, or None on a miss."""
    nx, ny, nz, px, py, pz = constants
    denominator = ux * nx + uy * ny + uz * nz
    if denominator == 0.0:
        return None
    t = (nx * (px - ox) + ny * (py - oy) + nz * (pz - oz)) / denominator
    if not t_min <= t <= t_max or t == INFINITY:
        return None
    return t


def infinite_plane_hit(constants, ox, oy, oz, dx, dy, dz, ux, uy, uz, t):
    """The hit point and normal of InfinitePlane.intersect at distance t."""
    return ox + dx * t, oy + dy * t, oz + dz * t, constants[0], constants[1], constants[2]


def parallelogram_distance(constants, ox, oy, oz, dx, dy, dz, ux, uy, uz, t_min, t_max):
    """Parallelogram.intersect's distance, or None on a miss."""
    nx, ny, nz, px, py, pz, uax, uay, uaz, ubx, uby, ubz = constants
    denominator = ux * nx + uy * ny + uz * nz
    if denominator == 0.0:
        return None
    t = (nx * (px - ox) + ny * (py - oy) + nz * (pz - oz)) / denominator
    if not t_min <= t <= t_max:
        return None
    qx, qy, qz = ox + dx * t - px, oy + dy * t - py, oz + dz * t - pz
    if not -EDGE_TOLERANCE <= qx * uax + qy * uay + qz * uaz <= 1.0 + EDGE_TOLERANCE:
        return None
    if not -EDGE_TOLERANCE <= qx * ubx + qy * uby + qz * ubz <= 1.0 + EDGE_TOLERANCE:
        return None
    return t


def camera_test(test, constants):
    """(test, constants) for the rays from the camera, which start at the origin: for a
    parallelogram whose normal and coordinate vectors lie along the axes,
    aligned_wall_distance and its constants; any other test as it is."""
    if test is not parallelogram_distance:
        return test, constants
    normal, point = constants[0:3], constants[3:6]
    coordinate_a, coordinate_b = constants[6:9], constants[9:12]
    k, i, j = (_single_axis(v) for v in (normal, coordinate_a, coordinate_b))
    if k is None or i is None or j is None:
        return test, constants
    numerator = normal[k] * point[k]
    if numerator == 0.0:  # the camera lies on the plane
        return test, constants
    return aligned_wall_distance, normal + (k, numerator, normal[k], i, point[i],
                                             coordinate_a[i], j, point[j], coordinate_b[j])


def _single_axis(vector):
    """The index of the one non-zero component of vector, or None."""
    axes = [axis for axis in range(3) if vector[axis] != 0.0]
    return axes[0] if len(axes) == 1 else None


def aligned_wall_distance(constants, ox, oy, oz, dx, dy, dz, ux, uy, uz, t_min, t_max):
    """parallelogram_distance for a ray from the origin o = 0, where the normal n and the
    coordinate vectors u_a and u_b have one non-zero component each, k, i and j: the
    products with the zero components (and with o) are signed zeros, which change no
    non-zero sum, so that t = n_k p_k / (d_k n_k), a = (d_i t - p_i) u_a,i and
    b = (d_j t - p_j) u_b,j, exactly as there. There a product of zero and an infinite
    q = d t - p is NaN and fails its test; here too nothing passes then: an infinite t
    makes d_i t infinite or NaN, an infinite q_i or q_j fails its own test, and for a
    finite t, q_k is near zero, the hit lying on the plane. The denominator takes u_k of
    the direction normalised once more, u = Normalize(d), as parallelogram_distance does."""
    _, _, _, k, numerator, n_k, i, p_i, a_i, j, p_j, b_j = constants
    d = (dx, dy, dz)
    denominator = (ux, uy, uz)[k] * n_k
    if denominator == 0.0:
        return None
    t = numerator / denominator
    if not t_min <= t <= t_max:
        return None
    if not -EDGE_TOLERANCE <= (d[i] * t - p_i) * a_i <= 1.0 + EDGE_TOLERANCE:
        return None
    if not -EDGE_TOLERANCE <= (d[j] * t - p_j) * b_j <= 1.0 + EDGE_TOLERANCE:
        return None
    return t


def parallelogram_hit(constants, ox, oy, oz, dx, dy, dz, ux, uy, uz, t):
    """The hit point and normal of Parallelogram.intersect at distance t."""
    nx, ny, nz = constants[:3]
    if ux * nx + uy * ny + uz * nz > 0.0:
        nx, ny, nz = nx * -1.0, ny * -1.0, nz * -1.0
    return ox + dx * t, oy + dy * t, oz + dz * t, nx, ny, nz


# The hit point and normal that go with each distance test
POINT_AND_NORMAL = {sphere_distance: sphere_hit, infinite_plane_distance: infinite_plane_hit,
                    parallelogram_distance: parallelogram_hit,
                    aligned_wall_distance: parallelogram_hit}
