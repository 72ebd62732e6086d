"""The flat loops: the course's Phong, classic and Bayesian Monte Carlo images made with
no objects per pixel and no calls per ray.

flat_phong renders Figures 1 and 5 (Phong on scenes of spheres and parallelograms lit by
point lights) in one Python loop: plain floats, numpy only for each row's camera
directions. It gives the image Integrator.render() gives, bit for bit, from the same
numbers in the same order: Camera.row_directions' rays, the intersection formulas of
PyRT_Core's primitives, Scene.closest_hit's strict tie rule, shadow_ray's offsets and the
Phong sum of PhongIntegrator. It tests every object for every ray, where render() leaves
out the objects a ray cannot reach, so it measures what the interpreter needs for the
image: the speed table quotes the framework as a multiple of it. The intersection tests
are written out once, inside the loop over a pixel's rays (its camera ray, then its
shadow rays), not in a function: a function would be a call per test, which is what this
loop measures the framework without.
"""
import random
from math import acos, atan2, cos, floor, pi, sin, sqrt, tan

import numpy as np

from PyRT_Common import EPSILON, HUGEVALUE, INFINITY, OFFSET_SCALE, SHADOW_EPSILON
from PyRT_Core import EDGE_TOLERANCE, Parallelogram, Sphere


def flat_phong(scene) -> np.ndarray:
    """The Phong image of a scene of Spheres and Parallelograms with Lambertian BRDFs, as
    PhongIntegrator renders it, made by one flat loop."""
    camera, objects = scene.camera, flat_objects(scene, "flat_phong")
    lights = [(light.pos.x, light.pos.y, light.pos.z, light.intensity.r, light.intensity.g,
               light.intensity.b) for light in scene.pointLights]
    ambient_r, ambient_g, ambient_b = scene.i_a.r, scene.i_a.g, scene.i_a.b
    low, high = -EDGE_TOLERANCE, 1.0 + EDGE_TOLERANCE
    width, height = camera.width, camera.height
    scale_y, screen_x = screen_coordinates(camera)
    image = np.zeros((height, width, 3))
    for y in range(height):
        screen_y = (1.0 - 2.0 * (y + 0.5) / height) * scale_y
        inverse = 1.0 / np.sqrt(screen_x * screen_x + screen_y * screen_y + 1.0)
        row = []
        for dx, dy, dz in zip((screen_x * inverse).tolist(), (screen_y * inverse).tolist(),
                              (-inverse).tolist()):
            # The pixel's rays, one after the other: first its camera ray (r, from the
            # origin, t in [0, infinity]), whose nearest hit it keeps, a later object only
            # when strictly nearer; then a shadow ray to each light in front of the hit,
            # which stops at the first object in its way.
            ox = oy = oz = 0.0
            rx, ry, rz, t_min, t_max = dx, dy, dz, 0.0, INFINITY
            shadow_rays = None  # the lights left to test, once the camera ray has hit
            tx = ty = tz = to_light = ir = ig = ib = 0.0  # the light of the shadow ray
            while True:
                nearest = None
                for sphere, k, kd in objects:
                    if sphere:
                        cx, cy, cz, r = k
                        fx, fy, fz = (ox - cx) / r, (oy - cy) / r, (oz - cz) / r
                        b = fx * rx + fy * ry + fz * rz
                        ax, ay, az = fx - rx * b, fy - ry * b, fz - rz * b
                        disc = 1.0 - (ax * ax + ay * ay + az * az)
                        if disc < 0.0:
                            continue
                        f = sqrt(fx * fx + fy * fy + fz * fz)
                        if b > 0.0:
                            q = -b - sqrt(disc)
                            t0, t1 = q * r, (f - 1.0) * ((f + 1.0) / q) * r
                        else:
                            q = sqrt(disc) - b
                            t0, t1 = (f - 1.0) * ((f + 1.0) / q) * r, q * r
                        if t_min <= t0 <= t_max:
                            t = t0
                        elif t_min <= t1 <= t_max:
                            t = t1
                        else:
                            continue
                    else:
                        wx, wy, wz, cx, cy, cz, uax, uay, uaz, ubx, uby, ubz = k
                        # t along the direction normalised once more, as the course's
                        s = 1.0 / sqrt(rx * rx + ry * ry + rz * rz)
                        den = rx * s * wx + ry * s * wy + rz * s * wz
                        if den == 0.0:
                            continue
                        t = (wx * (cx - ox) + wy * (cy - oy) + wz * (cz - oz)) / den
                        if not t_min <= t <= t_max:
                            continue
                        qx, qy, qz = ox + rx * t - cx, oy + ry * t - cy, oz + rz * t - cz
                        if not (low <= qx * uax + qy * uay + qz * uaz <= high
                                and low <= qx * ubx + qy * uby + qz * ubz <= high):
                            continue
                    if nearest is not None and t == t_max:
                        continue  # as far as the nearest so far: the first one stays
                    nearest, t_max = (sphere, k, kd), t
                    if shadow_rays is not None:
                        break  # a shadow ray needs only one object in its way
                if shadow_rays is None:  # the camera ray's nearest hit
                    if nearest is None:
                        red = green = blue = 0.0
                        break
                    sphere, k, (kr, kg, kb) = nearest
                    t = t_max
                    if sphere:  # the point along the outward normal, one radius out
                        cx, cy, cz, r = k
                        vx, vy, vz = (dx * t - cx) / r, (dy * t - cy) / r, (dz * t - cz) / r
                        inverse_length = 1.0 / sqrt(vx * vx + vy * vy + vz * vz)
                        nx, ny, nz = vx * inverse_length, vy * inverse_length, vz * inverse_length
                        px, py, pz = cx + nx * r, cy + ny * r, cz + nz * r
                    else:  # the point on the ray, the normal facing the ray
                        nx, ny, nz = k[:3]
                        s = 1.0 / sqrt(dx * dx + dy * dy + dz * dz)
                        if dx * s * nx + dy * s * ny + dz * s * nz > 0.0:
                            nx, ny, nz = nx * -1.0, ny * -1.0, nz * -1.0
                        px, py, pz = 0.0 + dx * t, 0.0 + dy * t, 0.0 + dz * t
                    red, green, blue = kr * ambient_r, kg * ambient_g, kb * ambient_b
                    offset = OFFSET_SCALE * (max(abs(px), abs(py), abs(pz)) + t)
                    ox, oy, oz = px + nx * offset, py + ny * offset, pz + nz * offset
                    shadow_rays = iter(lights)
                elif nearest is None:  # nothing in the way: Lambertian kd * cos, over r^2
                    cos_theta = (nx * (tx / to_light) + ny * (ty / to_light)
                                 + nz * (tz / to_light))
                    if cos_theta > 0.0:
                        rr = to_light * to_light
                        red += ir * (kr * cos_theta) / rr
                        green += ig * (kg * cos_theta) / rr
                        blue += ib * (kb * cos_theta) / rr
                # The next shadow ray, to a light in front of the surface, from just above it
                for lx, ly, lz, ir, ig, ib in shadow_rays:
                    tx, ty, tz = lx - px, ly - py, lz - pz
                    to_light = sqrt(tx * tx + ty * ty + tz * tz)
                    if to_light * to_light != 0.0 and nx * tx + ny * ty + nz * tz > 0.0:
                        break
                else:
                    break  # no light left: the pixel is done
                rx, ry, rz = lx - ox, ly - oy, lz - oz
                distance = sqrt(rx * rx + ry * ry + rz * rz)
                rx, ry, rz = rx / distance, ry / distance, rz / distance
                t_min, t_max = offset, distance * (1.0 - SHADOW_EPSILON)
            row += (red, green, blue)
        image[y] = np.array(row).reshape(-1, 3)
    return image


def flat_cmc(scene, samples: int, stream_seed: int, pdf_exponent=None) -> np.ndarray:
    """The image CMCIntegrator(samples, ...) renders of a scene of Spheres and
    Parallelograms with Lambertian BRDFs, no emitting object and an environment map (or
    none), made by one flat loop (flat_hemisphere): render()'s image bit for bit when
    stream_seed is the number render() drew to seed its rows (pyrt.rows.RowStreams).
    pdf_exponent None samples UniformPDF, e CosinePDF(e)."""
    return flat_hemisphere(scene, stream_seed, ClassicPixels(samples, pdf_exponent),
                           "flat_cmc")


def flat_bmc(scene, pool: list, stream_seed: int, cosine_prior=False) -> np.ndarray:
    """The image BayesianMonteCarloIntegrator(n, pool, ...) renders (BMCISIntegrator's with
    cosine_prior) of a scene as flat_cmc's, with a pool of PyRT's GPs, made by the same
    flat loop: render()'s image bit for bit for render()'s stream seed."""
    return flat_hemisphere(scene, stream_seed, BayesianPixels(pool, cosine_prior),
                           "flat_bmc")


class ClassicPixels:
    """A pixel of classic Monte Carlo for flat_hemisphere: the sample directions drawn as
    sample_set_hemisphere draws them (u1, u2 per sample, all first), those facing the
    normal traced; the map's terms float32, as the course's arithmetic makes them
    (pyrt.acceleration.monte_carlo), summed with numpy."""

    def __init__(self, samples, pdf_exponent=None):
        self.samples, self.exponent = samples, pdf_exponent

    def directions(self, n, v, u):
        """(rays, cosines, densities) of a pixel's samples: the unit directions
        to trace and their cosine to the normal n and density, in the order of the
        samples; center_around_normal's frame is n, v, u."""
        (nx, ny, nz), (vx, vy, vz), (ux, uy, uz) = n, v, u
        draws = [random.random() for _ in range(2 * self.samples)]
        e, prob = self.exponent, 1 / (2 * pi)
        rays, cosines, densities = [], [], []
        for k in range(0, 2 * self.samples, 2):
            u1, u2 = draws[k], draws[k + 1]
            phi = 2 * pi * u1
            if e is None:
                sy, sin_theta = u2, sqrt(1 - u2 ** 2)
            else:
                sy, sin_theta = u2 ** (1 / (e + 1)), sqrt(1 - u2 ** (2 / (e + 1)))
                prob = (e + 1) / (2 * pi) * sy ** e
            sx, sz = sin(phi) * sin_theta, cos(phi) * sin_theta
            rx, ry, rz = (vx * sx + nx * sy + ux * sz, vy * sx + ny * sy + uy * sz,
                          vz * sx + nz * sy + uz * sz)
            s = 1.0 / sqrt(rx * rx + ry * ry + rz * rz)
            rx, ry, rz = rx * s, ry * s, rz * s
            cos_theta = nx * rx + ny * ry + nz * rz
            if cos_theta > 0.0:
                rays.append((rx, ry, rz))
                cosines.append(cos_theta)
                densities.append(prob)
        return rays, cosines, densities

    def color(self, kd, texels, traced, cosines, densities):
        """The pixel's colour from the texels its traced samples `traced` (indices into the
        lists of directions) see."""
        kr, kg, kb = kd
        factors = [(kr * cosines[j], kg * cosines[j], kb * cosines[j]) for j in traced]
        terms = texels * np.array(factors).astype(np.float32)
        terms /= np.array([densities[j] for j in traced], dtype=np.float32)[:, None]
        return np.cumsum(terms, axis=0)[-1] / np.float32(self.samples)


class BayesianPixels:
    """A pixel of Bayesian Monte Carlo for flat_hemisphere: a GP of the pool and an angle
    drawn, the GP's directions turned about y and centred, the BRDF's values times the
    texels, summed with the GP's weights in compute_integral_BMC's order."""

    def __init__(self, pool, cosine_prior):
        self.pool, self.cosine_prior = pool, cosine_prior
        self.positions = [[(o.x, o.y, o.z) for o in gp.samples_pos] for gp in pool]
        self.weights = [np.asarray(gp.weights, dtype=float) for gp in pool]
        self.gp = 0

    def directions(self, n, v, u):
        (nx, ny, nz), (vx, vy, vz), (ux, uy, uz) = n, v, u
        self.gp = floor(random.random() * len(self.pool))
        alpha = 2 * pi * random.random()
        c, s = cos(alpha), sin(alpha)
        rays, cosines = [], []
        for sx, sy, sz in self.positions[self.gp]:
            sx, sz = sx * c + sz * s, -sx * s + sz * c
            rx, ry, rz = (vx * sx + nx * sy + ux * sz, vy * sx + ny * sy + uy * sz,
                          vz * sx + nz * sy + uz * sz)
            q = 1.0 / sqrt(rx * rx + ry * ry + rz * rz)
            rx, ry, rz = rx * q, ry * q, rz * q
            rays.append((rx, ry, rz))
            cosines.append(nx * rx + ny * ry + nz * rz)
        if not self.cosine_prior:  # the BRDF's value is BLACK there: not traced
            keep = [j for j, c in enumerate(cosines) if c > 0.0]
            rays, cosines = [rays[j] for j in keep], [cosines[j] for j in keep]
            weights = self.weights[self.gp][keep]
        else:
            weights = self.weights[self.gp]
        return rays, cosines, weights

    def color(self, kd, texels, traced, cosines, weights):
        kr, kg, kb = kd
        if self.cosine_prior:
            factors = [(kr, kg, kb)] * len(traced)
        else:
            factors = [(kr * cosines[j], kg * cosines[j], kb * cosines[j]) for j in traced]
        values = texels * np.array(factors).astype(np.float32)
        terms = np.concatenate((np.zeros((1, 3)), values * weights[traced][:, None]))
        return np.cumsum(terms, axis=0)[-1]


def flat_hemisphere(scene, stream_seed: int, pixels, name: str) -> np.ndarray:
    """The image of a Monte Carlo integrator over the hemisphere of each hit, made by one
    flat loop: the camera ray of each pixel, then pixels.directions(n, v, u), the sample
    rays of the pixel, each traced to its nearest hit, and pixels.color of the texels of
    those that see the map (a sample ray that hits an object gets its emission, which is
    none). Each row draws from its own stream, as render() seeds it."""
    for obj in scene.object_list:
        if obj.emission.r or obj.emission.g or obj.emission.b:
            raise ValueError(f"{name} renders no emitting object, such as {obj!r}")
    camera, objects = scene.camera, flat_objects(scene, name)
    env_map = scene.env_map
    if env_map is not None:
        texels, last_row, last_column = env_map.env_map_hdr, env_map.height - 1, env_map.width - 1
    low, high = -EDGE_TOLERANCE, 1.0 + EDGE_TOLERANCE
    width, height = camera.width, camera.height
    scale_y, screen_x = screen_coordinates(camera)
    ax, ay, az = 0.00319, 1.0, 0.0078  # center_around_normal's jittered up
    image = np.zeros((height, width, 3))
    for y in range(height):
        random.seed(f"{stream_seed}:0:{y}")  # the row's own stream, as render() seeds it
        screen_y = (1.0 - 2.0 * (y + 0.5) / height) * scale_y
        inverse = 1.0 / np.sqrt(screen_x * screen_x + screen_y * screen_y + 1.0)
        for x, (dx, dy, dz) in enumerate(zip((screen_x * inverse).tolist(),
                                             (screen_y * inverse).tolist(),
                                             (-inverse).tolist())):
            # The camera ray, then the pixel's sample rays from the hit point: the nearest
            # hit of each, a later object only when strictly nearer.
            ox = oy = oz = 0.0
            rx, ry, rz, t_min, t_max = dx, dy, dz, 0.0, INFINITY
            rows, columns, traced = [], [], []  # the map's texels, and whose they are
            rays = None  # the pixel's sample rays, once the camera ray has hit
            k = 0  # the next sample ray
            while True:
                nearest = None
                for sphere, c, kd in objects:
                    if sphere:
                        cx, cy, cz, r = c
                        fx, fy, fz = (ox - cx) / r, (oy - cy) / r, (oz - cz) / r
                        b = fx * rx + fy * ry + fz * rz
                        qx, qy, qz = fx - rx * b, fy - ry * b, fz - rz * b
                        disc = 1.0 - (qx * qx + qy * qy + qz * qz)
                        if disc < 0.0:
                            continue
                        f = sqrt(fx * fx + fy * fy + fz * fz)
                        if b > 0.0:
                            q = -b - sqrt(disc)
                            t0, t1 = q * r, (f - 1.0) * ((f + 1.0) / q) * r
                        else:
                            q = sqrt(disc) - b
                            t0, t1 = (f - 1.0) * ((f + 1.0) / q) * r, q * r
                        if t_min <= t0 <= t_max:
                            t = t0
                        elif t_min <= t1 <= t_max:
                            t = t1
                        else:
                            continue
                    else:
                        wx, wy, wz, cx, cy, cz, uax, uay, uaz, ubx, uby, ubz = c
                        s = 1.0 / sqrt(rx * rx + ry * ry + rz * rz)
                        den = rx * s * wx + ry * s * wy + rz * s * wz
                        if den == 0.0:
                            continue
                        t = (wx * (cx - ox) + wy * (cy - oy) + wz * (cz - oz)) / den
                        if not t_min <= t <= t_max:
                            continue
                        qx, qy, qz = ox + rx * t - cx, oy + ry * t - cy, oz + rz * t - cz
                        if not (low <= qx * uax + qy * uay + qz * uaz <= high
                                and low <= qx * ubx + qy * uby + qz * ubz <= high):
                            continue
                    if nearest is not None and t == t_max:
                        continue  # as far as the nearest so far: the first one stays
                    nearest, t_max = (sphere, c, kd), t
                if rays is None:  # the camera ray's nearest hit
                    if nearest is None:
                        if env_map is not None:
                            u = (1 + (1 / pi) * atan2(dx, -dz)) / 2
                            v = (1 / pi) * acos(min(1.0, max(-1.0, dy)))
                            image[y, x] = texels[floor(v * last_row), floor(u * last_column)]
                        break
                    sphere, c, hit_kd = nearest
                    t = t_max
                    if sphere:  # the point along the outward normal, one radius out
                        cx, cy, cz, r = c
                        vx, vy, vz = (dx * t - cx) / r, (dy * t - cy) / r, (dz * t - cz) / r
                        s = 1.0 / sqrt(vx * vx + vy * vy + vz * vz)
                        nx, ny, nz = vx * s, vy * s, vz * s
                        px, py, pz = cx + nx * r, cy + ny * r, cz + nz * r
                    else:  # the point on the ray, the normal facing the ray
                        nx, ny, nz = c[:3]
                        s = 1.0 / sqrt(dx * dx + dy * dy + dz * dz)
                        if dx * s * nx + dy * s * ny + dz * s * nz > 0.0:
                            nx, ny, nz = nx * -1.0, ny * -1.0, nz * -1.0
                        px, py, pz = 0.0 + dx * t, 0.0 + dy * t, 0.0 + dz * t
                    vx, vy, vz = ay * nz - az * ny, az * nx - ax * nz, ax * ny - ay * nx
                    s = 1.0 / sqrt(vx * vx + vy * vy + vz * vz)
                    vx, vy, vz = vx * s, vy * s, vz * s
                    ux, uy, uz = vy * nz - vz * ny, vz * nx - vx * nz, vx * ny - vy * nx
                    rays, cosines, per_sample = pixels.directions((nx, ny, nz), (vx, vy, vz),
                                                             (ux, uy, uz))
                    ox, oy, oz = px, py, pz
                elif nearest is None and env_map is not None:  # the sample ray sees the map
                    u = (1 + (1 / pi) * atan2(rx, -rz)) / 2
                    v = (1 / pi) * acos(min(1.0, max(-1.0, ry)))
                    rows.append(floor(v * last_row))
                    columns.append(floor(u * last_column))
                    traced.append(k - 1)
                if k == len(rays):
                    break  # no sample left: the pixel is done
                rx, ry, rz = rays[k]  # the next sample ray
                k += 1
                t_min, t_max = EPSILON, HUGEVALUE
            if rows:
                image[y, x] = pixels.color(hit_kd, texels[rows, columns], traced, cosines,
                                           per_sample)
    return image


def flat_objects(scene, name: str) -> list:
    """The scene's objects as the flat loops read them: (is a sphere, the constants of its
    intersection test, its Lambertian kd as (r, g, b)); a TypeError naming the loop for an
    object that is neither a Sphere nor a Parallelogram."""
    objects = []
    for obj in scene.object_list:
        kd = obj.BRDF.kd
        if type(obj) is Sphere:
            c = obj.origin
            constants = (c.x, c.y, c.z, obj.radius)
        elif type(obj) is Parallelogram:
            n, p, a, b = obj.normal, obj.point, obj.coordinate_a, obj.coordinate_b
            constants = (n.x, n.y, n.z, p.x, p.y, p.z, a.x, a.y, a.z, b.x, b.y, b.z)
        else:
            raise TypeError(f"{name} renders spheres and parallelograms, not {obj!r}")
        objects.append((type(obj) is Sphere, constants, (kd.r, kd.g, kd.b)))
    return objects


def screen_coordinates(camera) -> tuple:
    """(scale_y, screen_x) of Camera.row_directions, whose row y has the directions
    (screen_x, (1 - 2 (y + 0.5)/height) scale_y, -1) * (1 / their length)."""
    scale_y = tan(camera.vertical_fov / 2.0)
    scale_x = scale_y * camera.aspect_ratio
    return scale_y, np.array([(2.0 * (x + 0.5) / camera.width - 1.0) * scale_x
                              for x in range(camera.width)])
