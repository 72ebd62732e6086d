"""PyRT core: the scene, its objects (primitives), materials (BRDFs), lights and camera.

Scene.closest_hit and Scene.any_hit are the course's loops: every object of the scene is
asked for its intersection with the ray, and the nearest hit is kept. Every intersection
test measures t as a distance along the ray and works on the ray's unit direction, so a
ray whose direction is not of unit length hits the same point at the same distance as its
normalised version. (During a render, pyrt.acceleration answers the same queries faster,
with the same answers, whenever the scene is made of PyRT's own classes.)
"""
from math import isfinite, tan

from PyRT_Common import *
from PyRT_Common import check_constants, is_number
from pyrt.images import write_image_files

# A ray direction whose squared length is this close to 1 is used as it is; anything else
# is normalised first (a normalised vector is only of unit length to within rounding).
UNIT_LOW, UNIT_HIGH = 1.0 - 1e-12, 1.0 + 1e-12
# Parallelogram edge test tolerance, in units of the sides: rounding in the hit point must
# not open cracks along edges and corners, where neighbouring walls meet.
EDGE_TOLERANCE = 1e-9


# ------------------------------------------------------------------------------------------
# Input checks: raised where the mistake is made, naming the argument
# ------------------------------------------------------------------------------------------
def _checked(owner, name, value, cls):
    """A copy of value, a Vector3D or RGBColor, with plain float components; or a
    TypeError/ValueError naming the argument."""
    if not isinstance(value, cls):
        raise TypeError(f"{owner}: {name} must be a {cls.__name__}, got {value!r}")
    try:
        parts = [float(part) for part in value]
    except (TypeError, ValueError):
        raise TypeError(f"{owner}: {name} must hold numbers, got {value!r}") from None
    if not all(map(isfinite, parts)):
        raise ValueError(f"{owner}: {name} must have finite components, got {value!r}")
    return cls(*parts)


def _check_vector(owner, name, v):
    return _checked(owner, name, v, Vector3D)


def _check_color(owner, name, c):
    return _checked(owner, name, c, RGBColor)


def _check_nonzero(owner, name, v):
    v = _check_vector(owner, name, v)
    if v.x == 0.0 and v.y == 0.0 and v.z == 0.0:
        raise ValueError(f"{owner}: {name} must not be the zero vector")
    return v


def _check_positive(owner, name, value):
    if not is_number(value):
        raise TypeError(f"{owner}: {name} must be a number, got {value!r}")
    value = float(value)
    if not 0.0 < value < INFINITY:
        raise ValueError(f"{owner}: {name} must be positive and finite, got {value!r}")
    return value


def unit_direction(ray):
    """The unit vector of ray.d: ray.d itself when it is of unit length to within rounding
    (so that a camera ray is traced exactly along its direction), else Normalize(ray.d).
    A ValueError when the direction is zero or not finite, as the d of a Ray() that was
    never set."""
    d = ray.d
    if UNIT_LOW <= d.x * d.x + d.y * d.y + d.z * d.z <= UNIT_HIGH:
        return d
    if not (0.0 < Length(d) < INFINITY):
        raise ValueError(f"the ray direction must be a non-zero finite vector, got {d!r}; "
                         "set ray.d before tracing the ray")
    return Normalize(d)


def course_direction(ray):
    """Normalize(ray.d), the unit direction along which the course's plane and
    parallelogram tests measure t. The course normalises even a direction already of unit
    length, which can move its last bits, and so does PyRT: where two walls meet, which one
    a ray sees first is decided on those bits. A ValueError when the direction is zero or
    not finite (see unit_direction)."""
    d = ray.d
    if UNIT_LOW <= d.x * d.x + d.y * d.y + d.z * d.z <= UNIT_HIGH:
        return Normalize(d)
    return unit_direction(ray)


def plane_hit_point(ray, d, t):
    """The point at distance t of a ray that meets a plane along its unit direction d:
    ray.get_hitpoint(t), o + ray.d * t, as the course builds it, when ray.d is of unit
    length (d is ray.d then, but for the last bits); else o + d * t along d (the course's
    point lies elsewhere there, t being measured along d)."""
    r = ray.d
    if UNIT_LOW <= r.x * r.x + r.y * r.y + r.z * r.z <= UNIT_HIGH:
        return ray.get_hitpoint(t)
    return ray.o + d * t


def plane_distance(ray, d, normal, point):
    """Where the ray, of unit direction d, meets the plane through point with the given unit
    normal: t = (point - o).n / (d.n), as the course computes it; None when that is not in
    [ray.t_min, ray.t_max], or when the ray runs parallel to the plane (d.n = 0)."""
    denominator = Dot(d, normal)
    if denominator == 0.0:
        return None
    t = Dot(normal, point - ray.o) / denominator
    return t if ray.t_min <= t <= ray.t_max else None


class _GeometricAttribute:
    """An attribute of a primitive or camera from which its owner precomputes constants
    (_derive): assigning it derives them anew, so that `sphere.radius = 3` moves the
    surface, as a student expects."""

    def __set_name__(self, owner, name):
        self.slot = "_" + name

    def __get__(self, obj, owner=None):
        return self if obj is None else getattr(obj, self.slot)

    def __set__(self, obj, value):
        setattr(obj, self.slot, value)
        obj._derive()


# ------------------------------------------------------------------------------------------
# Scene
# ------------------------------------------------------------------------------------------
class Scene:
    """Everything that is rendered: camera, objects, point lights, ambient light i_a and an
    optional environment map, plus the image they are rendered into."""


    def __init__(self):
        self.camera = None
        self.env_map = None
        self.rendered_image = None
        self.object_list = []
        self.pointLights = []
        self.i_a = RGBColor(0.0, 0.0, 0.0)

    def set_ambient(self, i_a):
        self.i_a = _check_color("Scene.set_ambient", "i_a", i_a)

    def set_camera(self, camera):
        if not isinstance(camera, Camera):
            raise TypeError(f"Scene.set_camera: camera must be a Camera, got {camera!r}")
        self.camera = camera
        self.rendered_image = np.zeros((camera.height, camera.width, 3))

    def set_environment_map(self, env_map_path):
        """Lights the scene with the latitude-longitude image at env_map_path, read as the
        course reads it (PyRT_Common.EnvironmentMap)."""
        self.env_map = EnvironmentMap(env_map_path)

    def add_object(self, new_object):
        if not isinstance(new_object, Primitive):
            raise TypeError("Scene.add_object: new_object must be a Primitive (Sphere, "
                            "InfinitePlane, Parallelogram or your own subclass), got "
                            f"{new_object!r}")
        self.object_list.append(new_object)

    def add_point_light_sources(self, point_light):
        if not isinstance(point_light, PointLight):
            raise TypeError(f"Scene.add_point_light_sources: point_light must be a "
                            f"PointLight, got {point_light!r}")
        self.pointLights.append(point_light)

    def any_hit(self, ray):
        """True when the ray hits any object at a distance in [ray.t_min, ray.t_max]."""
        # ASSIGNMENT 1.2 BEGIN
        for obj in self.object_list:
            if obj.intersect(ray).has_hit:
                return True
        return False
        # ASSIGNMENT 1.2 END

    def closest_hit(self, ray):
        """The nearest hit in [ray.t_min, ray.t_max], as a HitData whose primitive_index is
        the object's index in object_list; a HitData with has_hit False on a miss."""
        closest = HitData()  # no hit yet
        for index, obj in enumerate(self.object_list):
            hit = obj.intersect(ray)
            # Strictly nearer only: of objects hit at the same distance, the first stays.
            if hit.has_hit and (not closest.has_hit or hit.hit_distance < closest.hit_distance):
                closest = hit
                closest.primitive_index = index
        return closest

    def set_pixel(self, pixel_val, x, y):
        """Stores the RGBColor pixel_val at column x, row y of rendered_image."""
        image = self.rendered_image
        if image is None:
            raise RuntimeError("Scene.set_pixel: the scene has no image yet; call "
                               "scene.set_camera(camera) first")
        height, width = image.shape[:2]
        if not (0 <= x < width and 0 <= y < height):
            raise IndexError(f"Scene.set_pixel: pixel ({x}, {y}) is outside the "
                             f"{width}x{height} image (0 <= x < {width}, 0 <= y < {height})")
        try:
            image[y, x] = (pixel_val.r, pixel_val.g, pixel_val.b)
        except AttributeError:
            raise TypeError(f"Scene.set_pixel: pixel_val must be an RGBColor, "
                            f"got {pixel_val!r} for pixel ({x}, {y})") from None

    def save_image(self, full_filename, tonemap=True):
        """Writes full_filename + '.png' (display image), '.npy' (the linear float image) and
        '.hdr' (Radiance HDR); creates the folder if needed. Each file appears whole or not
        at all: it is written to a temporary file that then replaces the target.

        With tonemap False the PNG shows the linear values clipped to [0, 1] (Figure 2).
        Returns the path of the PNG (a name with Windows's separators is saved where it
        means on every system, pyrt.images.native_path)."""
        image = self.rendered_image
        if image is None:
            raise RuntimeError("Scene.save_image: the scene has no image yet; call "
                               "scene.set_camera(camera) and render first")
        check_constants("Scene.save_image")
        return write_image_files(image, full_filename, tonemap)


# ------------------------------------------------------------------------------------------
# Primitives
# ------------------------------------------------------------------------------------------
class Primitive(ABC):
    """An object of the scene: a surface that rays can hit, with a material (BRDF) and an
    emitted radiance (BLACK unless the object is an area light)."""


    def __init__(self, emission=BLACK):
        self.emission = _check_color(type(self).__name__, "emission", emission)
        self.BRDF = None

    def set_BRDF(self, BRDF):
        self.BRDF = _check_brdf(f"{type(self).__name__}.set_BRDF", BRDF)

    def get_BRDF(self):
        """The object's BRDF; a RuntimeError that says what to call when it has none."""
        if self.BRDF is None:
            raise RuntimeError(f"{self!r} has no BRDF; call obj.set_BRDF(Lambertian("
                               "RGBColor(...))) on it before rendering")
        return self.BRDF

    @abstractmethod
    def intersect(self, ray):
        """The hit of this object along ray, as a HitData (has_hit False on a miss)."""


class Sphere(Primitive):
    """The sphere |p - origin| = radius; its normal (p - origin)/radius points outward, also
    for rays that start inside.

    Intersection works in units of the radius r, so that no square over- or underflows at
    any scale: with f = (o - origin)/r and unit d it solves t'^2 + 2bt' + c = 0 for b = f.d
    and c = |f|^2 - 1, and the distance is t = r t'. The textbook discriminant b^2 - c
    cancels catastrophically when the sphere is far away compared with its radius, so it is
    computed as 1 - |f - b d|^2, and the two roots as q = -b - sign(b) sqrt(disc) and c / q,
    which never subtracts nearly equal numbers (Ray Tracing Gems, chapter 7). c / q is worked
    out as (|f| - 1) ((|f| + 1) / q), which cannot overflow however far away the sphere is."""

    origin = _GeometricAttribute()
    radius = _GeometricAttribute()

    def __init__(self, sphere_origin, sphere_radius, emission=BLACK):
        super().__init__(emission)
        self._origin = sphere_origin
        self._radius = sphere_radius
        self._derive()

    def _derive(self):
        self._origin = _check_vector("Sphere", "sphere_origin", self._origin)
        self._radius = _check_positive("Sphere", "sphere_radius", self._radius)
        self.radius_squared = self._radius * self._radius

    def __repr__(self):
        return f"Sphere({self._origin!r}, {self._radius!r})"

    def intersect(self, ray):
        d, r = unit_direction(ray), self._radius
        f = (ray.o - self._origin) / r
        b = Dot(f, d)
        across = f - d * b  # from the centre to the ray's nearest point, in radii
        disc = 1.0 - Dot(across, across)
        if disc < 0.0:
            return HitData()  # the ray passes the sphere by
        distance = Length(f)
        if b > 0.0:  # q = -(b + sqrt(disc)) is the near root
            q = -b - sqrt(disc)
            t0, t1 = q * r, (distance - 1.0) * ((distance + 1.0) / q) * r
        else:  # q = sqrt(disc) - b = |b| + sqrt(disc) is the far root
            q = sqrt(disc) - b
            if q == 0.0:  # b == disc == 0: the ray starts on the sphere, touching it
                t0 = t1 = 0.0
            else:
                t0, t1 = (distance - 1.0) * ((distance + 1.0) / q) * r, q * r
        if ray.t_min <= t0 <= ray.t_max:
            t = t0
        elif ray.t_min <= t1 <= ray.t_max:
            t = t1
        else:
            return HitData()
        outward = (ray.o + d * t - self._origin) / r
        if outward.x == 0.0 and outward.y == 0.0 and outward.z == 0.0:
            normal = d * -1.0  # a sphere far below the precision of its position
        else:
            normal = Normalize(outward)
        # Rounding leaves o + d*t slightly off the surface; the point along the normal at
        # exactly one radius from the centre is on it.
        return HitData(True, self._origin + normal * r, normal, t)


class InfinitePlane(Primitive):
    """The plane through origin with unit normal n: the points p with (p - origin).n = 0.
    A ray o + t d meets it at t = (origin - o).n / (d.n); a ray parallel to it (d.n = 0)
    misses. The normal is returned as given, whichever side the ray comes from."""

    origin = _GeometricAttribute()
    normal = _GeometricAttribute()

    def __init__(self, plane_origin, plane_normal, emission=BLACK):
        super().__init__(emission)
        self._origin = plane_origin
        self._normal = plane_normal
        self._derive()

    def _derive(self):
        self._origin = _check_vector("InfinitePlane", "plane_origin", self._origin)
        self._normal = Normalize(_check_nonzero("InfinitePlane", "plane_normal", self._normal))

    def __repr__(self):
        return f"InfinitePlane({self._origin!r}, {self._normal!r})"

    def intersect(self, ray):
        d, n = course_direction(ray), self._normal
        t = plane_distance(ray, d, n, self._origin)
        # A ray nearly parallel to the plane can overflow t to infinity: no hit there.
        if t is None or t == INFINITY:
            return HitData()
        return HitData(True, plane_hit_point(ray, d, t), Vector3D(n.x, n.y, n.z), t)


class Parallelogram(Primitive):
    """The region {point + a*s1 + b*s2 : 0 <= a, b <= 1}, edges and corners included.

    The ray meets the supporting plane (unit normal n, along s1 x s2) at p, as it meets an
    InfinitePlane (plane_distance). With q = p - point and m = s1 x s2, the coordinates are
    a = q.(s2 x m)/(m.m) and b = q.(m x s1)/(m.m), exact for any pair of non-parallel sides,
    orthogonal or not. The normal is flipped to face the ray."""

    point = _GeometricAttribute()
    s1 = _GeometricAttribute()
    s2 = _GeometricAttribute()

    def __init__(self, point, s1, s2, emission=BLACK):
        super().__init__(emission)
        self._point, self._s1, self._s2 = point, s1, s2
        self._derive()

    def _derive(self):
        self._point = _check_vector("Parallelogram", "point", self._point)
        s1 = self._s1 = _check_nonzero("Parallelogram", "s1", self._s1)
        s2 = self._s2 = _check_nonzero("Parallelogram", "s2", self._s2)
        # Worked out from the unit sides e1, e2 and their lengths l1, l2, so that no product
        # over- or underflows at any scale (s1 x s2 is the product of two lengths, its
        # square of four). With c = e1 x e2 (|c| = sin of the angle between the sides) the
        # coordinates above are a = q.(e2 x c)/(c.c l1) and b = q.(c x e1)/(c.c l2).
        l1, l2 = Length(s1), Length(s2)
        e1, e2 = s1 / l1, s2 / l2
        c = Cross(e1, e2)
        cc = Dot(c, c)
        if cc <= 1e-24:  # sin(angle) <= 1e-12: parallel sides span no area
            raise ValueError(f"Parallelogram: s1 {s1!r} and s2 {s2!r} are parallel, so they "
                             "span no area; give two sides that point in different directions")
        self.normal = Normalize(c)
        self.coordinate_a = Cross(e2, c) / cc / l1  # q . coordinate_a = a
        self.coordinate_b = Cross(c, e1) / cc / l2  # q . coordinate_b = b

    def __repr__(self):
        return f"Parallelogram({self._point!r}, {self._s1!r}, {self._s2!r})"

    def intersect(self, ray):
        d, n = course_direction(ray), self.normal
        t = plane_distance(ray, d, n, self._point)
        if t is None:
            return HitData()
        p = plane_hit_point(ray, d, t)
        q = p - self._point
        low, high = -EDGE_TOLERANCE, 1.0 + EDGE_TOLERANCE
        if not (low <= Dot(q, self.coordinate_a) <= high
                and low <= Dot(q, self.coordinate_b) <= high):
            return HitData()  # outside the parallelogram, on its plane
        facing = n * -1.0 if Dot(d, n) > 0.0 else Vector3D(n.x, n.y, n.z)
        return HitData(True, p, facing, t)


# ------------------------------------------------------------------------------------------
# BRDFs
# ------------------------------------------------------------------------------------------
class BRDF(ABC):
    """How a surface reflects light: the ratio of radiance leaving towards wo to irradiance
    arriving from wi (both unit vectors pointing away from the surface)."""


    @abstractmethod
    def get_value(self, incoming, outgoing, normal):
        """The reflected fraction for light arriving from incoming and seen from outgoing."""


def _check_brdf(owner, value):
    """value when it is a BRDF; else a TypeError naming what to give."""
    if not isinstance(value, BRDF):
        raise TypeError(f"{owner}: BRDF must be a BRDF such as Lambertian(RGBColor(...)), "
                        f"got {value!r}")
    return value


class Lambertian(BRDF):
    """A perfectly matte surface: f = diffuse_colour / pi for every pair of directions.

    ``kd`` already holds the 1/pi, and get_value includes the cosine of the light's angle:
    get_value(wi, wo, n) = kd * (n.wi) when n.wi > 0, else BLACK."""

    def __init__(self, diffuse_colour):
        diffuse_colour = _check_color("Lambertian", "diffuse_colour", diffuse_colour)
        self.kd = diffuse_colour / pi

    def get_value(self, wi, wo, normal):
        cos_theta = Dot(normal, wi)
        if cos_theta > 0.0:
            return self.kd * cos_theta
        return BLACK

    def get_kd(self):
        """kd, the diffuse colour / pi."""
        return self.kd


# ------------------------------------------------------------------------------------------
# Lights
# ------------------------------------------------------------------------------------------
class PointLight:
    """A point that emits ``intensity`` in every direction; the irradiance it gives a point
    at distance r, facing it, is intensity / r^2."""


    def __init__(self, pos_, intensity_):
        self.pos = _check_vector("PointLight", "pos_", pos_)
        self.intensity = _check_color("PointLight", "intensity_", intensity_)


# ------------------------------------------------------------------------------------------
# Camera
# ------------------------------------------------------------------------------------------
class Camera:
    """A pinhole camera at the origin looking down -z with +y up.

    Pixel (x, y) has screen coordinates x_s = 2(x + 0.5)/width - 1 and
    y_s = 1 - 2(y + 0.5)/height; its ray goes through the point
    p = (x_s * tan(fov/2) * aspect_ratio, y_s * tan(fov/2), -1) of the image plane z = -1,
    along p * (1 / |p|), the unit direction rounded as the course's Normalize rounds it (so
    that the ties where two walls meet fall as in the course's images)."""


    width = _GeometricAttribute()
    height = _GeometricAttribute()
    vertical_fov = _GeometricAttribute()

    def __init__(self, width_, height_, vertical_fov_):
        self._width, self._height = width_, height_
        fov = _check_positive("Camera", "vertical_fov_", vertical_fov_)
        if not fov < 180.0:
            raise ValueError(f"Camera: vertical_fov_ is in degrees and must lie strictly "
                             f"between 0 and 180, got {vertical_fov_!r}")
        self._vertical_fov = fov * pi / 180.0
        self._derive()

    def _derive(self):
        for name in ("width", "height"):
            value = getattr(self, "_" + name)
            if not is_number(value):
                raise TypeError(f"Camera: {name} must be a whole number of pixels, "
                                f"got {value!r}")
            if not (value >= 1 and value == int(value)):  # 500.0 is fine, 2.5 and nan not
                raise ValueError(f"Camera: {name} must be a positive whole number of pixels, "
                                 f"got {value!r}")
            setattr(self, "_" + name, int(value))
        if not 0.0 < self._vertical_fov < pi:
            raise ValueError(f"Camera: vertical_fov is in radians once the camera exists and "
                             f"must lie strictly between 0 and pi, got {self._vertical_fov!r}")
        self.aspect_ratio = self._width / self._height
        self._scale_y = tan(self._vertical_fov / 2.0)
        self._scale_x = self._scale_y * self.aspect_ratio
        self._row_x = np.array([(2.0 * (x + 0.5) / self._width - 1.0) * self._scale_x
                                for x in range(self._width)])

    def get_direction(self, x, y, u=0.5, v=0.5):
        """The unit direction through the point (u, v) of pixel (x, y); (0.5, 0.5), the
        default, is the pixel centre. Other values of u and v in [0, 1) serve
        anti-aliasing."""
        px = (2.0 * (x + u) / self._width - 1.0) * self._scale_x
        py = (1.0 - 2.0 * (y + v) / self._height) * self._scale_y
        return Normalize(Vector3D(px, py, -1.0))

    def row_directions(self, y):
        """get_direction(x, y) for every x of row y, the same numbers computed with numpy in
        one go: IEEE arithmetic rounds numpy's operations exactly as Python's."""
        py = (1.0 - 2.0 * (y + 0.5) / self._height) * self._scale_y
        px = self._row_x
        inverse = 1.0 / np.sqrt(px * px + py * py + 1.0)  # Normalize's arithmetic
        return list(map(Vector3D, (px * inverse).tolist(), (py * inverse).tolist(),
                        (-inverse).tolist()))
