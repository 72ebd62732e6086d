"""PyRT core: the scene, its objects (primitives), materials (BRDFs), lights and camera.

Every intersection test measures t as a distance along the ray and works on a unit
direction, so a ray whose direction is not unit length hits the same point at the same
distance as its normalised version.

Speed note: ``Scene.closest_hit`` and ``Scene.any_hit`` run for every ray, so they talk to
the primitives through ``_distance``, which takes the ray as plain floats and returns the
distance or None; only the nearest hit is turned into a ``HitData`` (by ``_hit_data``).
The rays traced most share a point: every camera ray starts at the camera, every shadow
ray ends at its light. For each such point the scene works out once which objects a ray
from it can hit (``_Sightlines``), and tests only those.
"""
import os
import threading
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from math import hypot, isfinite, tan
from pathlib import Path

from PyRT_Common import *
from PyRT_Common import _new, _restore_state, check_constants

# ------------------------------------------------------------------------------------------
# Robustness constants
# ------------------------------------------------------------------------------------------
INFINITY = float("inf")
# A ray direction whose squared length is this close to 1 is used as it is; anything else
# is normalised first (a normalised vector is only unit length to within rounding).
UNIT_LOW, UNIT_HIGH = 1.0 - 1e-12, 1.0 + 1e-12
# Parallelogram edge test tolerance, in units of the sides: rounding in the hit point must
# not open cracks along edges and corners, where neighbouring walls meet.
EDGE_TOLERANCE = 1e-9
# closest_hit: a later object must be nearer than TIE_SHRINK times the nearest distance so
# far, nearer by more than a ten-billionth. Where two surfaces meet or overlap (the edges
# of the Cornell box lie exactly on the image's diagonals), rounding would otherwise pick
# either, one way on one machine and the other way on the next; so the first one wins.
TIE_SHRINK = 1.0 - 1e-10
# A shadow ray stops this fraction short of its light, so a light lying exactly on a
# surface is not hidden by that surface.
SHADOW_EPSILON = 1e-6
# Shadow rays start this far above the surface, relative to the size of the hit point's
# coordinates: far above the rounding error of a hit point (about 1e-16 relative), far below
# any detail of the scene, and the same at every scale of the scene.
OFFSET_SCALE = 2.0 ** -32
# Clearances, relative to the size of the scene, that let visible_lights leave an object
# out of the shadow rays towards a light (see _may_block): the light must be this far from
# the object's plane, and the other object this far on the light's side of it, or touch it.
CLEARANCE = 1e-4
TOUCHING = 1e-12
# any_hit: a ray from a hit point whose end lies this close to a point light (relative to
# the scene's size) is a shadow ray towards that light; and shadow rays that ignore this
# first stretch of their way (t_min) do not see a plane they start on, whatever rounding
# made of their start point.
LIGHT_MATCH = 1e-9
SHADOW_T_MIN = 1e-7


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
    if isinstance(value, bool) or not isinstance(value, (int, float, np.number)):
        raise TypeError(f"{owner}: {name} must be a number, got {value!r}")
    value = float(value)
    if not 0.0 < value < INFINITY:
        raise ValueError(f"{owner}: {name} must be positive and finite, got {value!r}")
    return value


def _unit(d):
    """The components of the unit direction of d: d itself when it is unit length to within
    rounding, d / |d| otherwise; a ValueError when d has no direction."""
    dx, dy, dz = d.x, d.y, d.z
    if UNIT_LOW <= dx * dx + dy * dy + dz * dz <= UNIT_HIGH:
        return dx, dy, dz
    length = hypot(dx, dy, dz)  # hypot, unlike sqrt(x*x + ...), never over/underflows
    if not 0.0 < length < INFINITY:
        raise ValueError(f"the ray direction must be a non-zero finite vector, got {d!r}; "
                         "set ray.d before tracing the ray")
    return d.x / length, d.y / length, d.z / length


class _Shape:
    """A geometric attribute of a primitive or camera: assigning it re-derives the cached
    constants of its owner (so ``sphere.radius = 3`` moves the surface, as expected) and
    counts the change, so that scenes know that what they worked out from it is out of date."""

    changes = 0

    def __set_name__(self, owner, name):
        self.slot = "_" + name

    def __get__(self, obj, owner=None):
        return self if obj is None else getattr(obj, self.slot)

    def __set__(self, obj, value):
        setattr(obj, self.slot, value)
        obj._derive()
        _Shape.changes += 1


# ------------------------------------------------------------------------------------------
# Scene
# ------------------------------------------------------------------------------------------
class Scene:
    """Everything that is rendered: camera, objects, point lights, ambient light i_a and an
    optional environment map, plus the image they are rendered into."""

    __setstate__ = _restore_state

    def __init__(self):
        self.camera = None
        self.env_map = None
        self.rendered_image = None
        self.object_list = []
        self.pointLights = []
        self.i_a = RGBColor(0.0, 0.0, 0.0)
        self._known = None  # see _sightlines
        self._still = False  # see unchanged
        self._last_hit = (None,)  # see closest_hit and any_hit
        self._next_light = 0  # see any_hit

    def set_ambient(self, i_a):
        self.i_a = _check_color("Scene.set_ambient", "i_a", i_a)

    def set_camera(self, camera):
        if not isinstance(camera, Camera):
            raise TypeError(f"Scene.set_camera: camera must be a Camera, got {camera!r}")
        self.camera = camera
        self.rendered_image = np.zeros((camera.height, camera.width, 3))

    def set_environment_map(self, path):
        self.env_map = EnvironmentMap(path)

    def add_object(self, obj):
        if not isinstance(obj, Primitive):
            raise TypeError("Scene.add_object: obj must be a Primitive (Sphere, InfinitePlane, "
                            f"Parallelogram or your own subclass), got {obj!r}")
        self.object_list.append(obj)

    def add_point_light_sources(self, light):
        if not isinstance(light, PointLight):
            raise TypeError(f"Scene.add_point_light_sources: light must be a PointLight, "
                            f"got {light!r}")
        self.pointLights.append(light)

    # any_hit and closest_hit run for every ray: they read the ray once into floats, and
    # repeat _unit's unit-length test inline (camera and shadow rays pass it) so that the
    # common case costs no function call. They test the objects of a _Sightlines list:
    # each object with the cone, seen from the ray's origin, that holds it; a direction
    # outside the cone cannot hit the object, which costs a dot product to find out.
    # During a render (unchanged) the lists are taken as they are, without a call of
    # _sightlines: `self._known if self._still else self._sightlines()`.
    def any_hit(self, ray):
        """True when the ray hits any object at a distance in [ray.t_min, ray.t_max].

        A shadow ray of the Phong model, from the hit point that closest_hit returned last
        to a point light, tests only the objects that can lie between that object and that
        light (_Sightlines). It is taken for one when it starts at that very point,
        unchanged, in the scene as it was, ignores its first stretch as shadow rays do
        (longer than the rounding error of where it crosses a plane it starts on), and
        ends at a light's position to within rounding."""
        o, d = ray.o, ray.d
        dx, dy, dz = d.x, d.y, d.z
        if not UNIT_LOW <= dx * dx + dy * dy + dz * dz <= UNIT_HIGH:  # also catches NaN
            dx, dy, dz = _unit(d)
        ox, oy, oz, t_min, t_max = o.x, o.y, o.z, ray.t_min, ray.t_max
        sightlines = self._known if self._still else self._sightlines()
        entries = sightlines.anywhere
        last = self._last_hit  # (point, its x, y, z, sightlines, object index)
        if (o is last[0] and ox == last[1] and oy == last[2] and oz == last[3]
                and last[4] is sightlines and t_min >= sightlines.t_min):
            lights = sightlines.per_object[last[5]]
            ex, ey, ez = ox + dx * t_max, oy + dy * t_max, oz + dz * t_max
            near = sightlines.near
            i = self._next_light  # shadow rays come light after light: try the next first
            for _ in lights:
                if i >= len(lights):
                    i = 0
                _, lx, ly, lz, blockers = lights[i]
                i += 1
                if (-near <= lx - ex <= near and -near <= ly - ey <= near
                        and -near <= lz - ez <= near):
                    self._next_light = i
                    entries = blockers
                    break
        for obj, _, ux, uy, uz, reach in entries:
            if dx * ux + dy * uy + dz * uz >= reach and (
                    obj._distance(ox, oy, oz, dx, dy, dz, t_min, t_max) is not None):
                return True
        return False

    def closest_hit(self, ray):
        """The nearest hit in [ray.t_min, ray.t_max], as a HitData whose primitive_index is
        the object's index in object_list; a HitData with has_hit False on a miss."""
        o, d = ray.o, ray.d
        dx, dy, dz = d.x, d.y, d.z
        if not UNIT_LOW <= dx * dx + dy * dy + dz * dz <= UNIT_HIGH:  # also catches NaN
            dx, dy, dz = _unit(d)
        ox, oy, oz = o.x, o.y, o.z
        t_min, t_max = ray.t_min, ray.t_max
        sightlines = self._known if self._still else self._sightlines()
        camera_ray = ox == 0.0 and oy == 0.0 and oz == 0.0  # the camera sits at the origin
        nearest = None
        for obj, index, ux, uy, uz, reach in (
                sightlines.camera if camera_ray else sightlines.anywhere):
            if dx * ux + dy * uy + dz * uz >= reach:
                t = obj._distance(ox, oy, oz, dx, dy, dz, t_min, t_max)
                if t is not None:
                    nearest, k, distance = obj, index, t
                    t_max = t * TIE_SHRINK
        if nearest is None:
            return HitData()
        hit = nearest._hit_data(ox, oy, oz, dx, dy, dz, distance)
        hit.primitive_index = k
        p = hit.hit_point
        self._last_hit = (p, p.x, p.y, p.z, sightlines, k)  # for shadow rays that may follow
        return hit

    def visible_lights(self, hit):
        """The point lights that light the point of ``hit`` (a HitData of closest_hit): for
        each light in front of the surface with nothing in between, (light, wi, r2), wi the
        unit direction from the point to the light and r2 its squared distance.

        A shadow ray towards each light decides whether something is in between. It starts
        just above the surface, on the light's side, and ignores the first `offset` of its
        way, which skips the surface itself and, on an edge where two walls meet, the other
        wall; both scale with the scene, where a fixed t_min would be too large for tiny
        scenes and too small for huge ones. It tests only the objects that can be in its
        way (see _Sightlines): in the Cornell box, only the sphere, and that only when the
        ray's direction lies in the cone the sphere fills, seen from the light."""
        p, n = hit.hit_point, hit.normal
        px, py, pz, nx, ny, nz = p.x, p.y, p.z, n.x, n.y, n.z
        offset = OFFSET_SCALE * (max(abs(px), abs(py), abs(pz)) + hit.hit_distance)
        sx, sy, sz = px + nx * offset, py + ny * offset, pz + nz * offset
        seen = []
        sightlines = self._known if self._still else self._sightlines()
        lights = sightlines.per_object.get(hit.primitive_index, sightlines.unculled)
        for light, x, y, z, blockers in lights:
            lx, ly, lz = x - px, y - py, z - pz
            # The light's height above the surface: at or below `offset` it is behind the
            # surface or lies on it, and lights no part of it.
            if lx * nx + ly * ny + lz * nz <= offset:
                continue
            r2 = lx * lx + ly * ly + lz * lz
            distance = sqrt(r2)
            wx, wy, wz = lx / distance, ly / distance, lz / distance
            t_max = distance * (1.0 - SHADOW_EPSILON) - offset
            for obj, _, ux, uy, uz, reach in blockers:
                if wx * ux + wy * uy + wz * uz >= reach and (
                        obj._distance(sx, sy, sz, wx, wy, wz, offset, t_max) is not None):
                    break
            else:
                wi = _new(Vector3D)  # Vector3D(wx, wy, wz) without its __init__
                wi.x, wi.y, wi.z = wx, wy, wz
                seen.append((light, wi, r2))
        return seen

    @contextmanager
    def unchanged(self):
        """A with-block during which the scene does not change, as during a render: what
        the queries work out from the scene (_Sightlines) is checked once, on entry,
        instead of at every query."""
        self._sightlines()
        self._still = True
        try:
            yield self
        finally:
            self._still = False

    def _sightlines(self):
        """The _Sightlines of the scene as it is: the last ones, unless an object or a
        light was added, removed, moved or reshaped since (which unchanged rules out)."""
        sightlines = self._known
        if not self._still and (sightlines is None or not sightlines.fit(self)):
            sightlines = self._known = _Sightlines(self)
        return sightlines

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

        With tonemap False the PNG shows the linear values clipped to [0, 1] (Figure 2)."""
        image = self.rendered_image
        if image is None:
            raise RuntimeError("Scene.save_image: the scene has no image yet; call "
                               "scene.set_camera(camera) and render first")
        check_constants("Scene.save_image")
        base = Path(full_filename)
        base.parent.mkdir(parents=True, exist_ok=True)
        # The linear files are written on a second thread meanwhile: the encoders, numpy's
        # arithmetic and the writes all run without holding Python's global lock.
        with ThreadPoolExecutor(1) as pool:
            linear = pool.submit(_write_linear_files, image, base)
            display = tonemap_image(image) if tonemap else np.clip(np.nan_to_num(image), 0, 1)
            # 8 bits as matplotlib makes them from floats, floor(255 v); zlib's fastest
            # level writes twice as fast for a slightly larger file.
            pixels = np.multiply(display, 255.0, out=display).astype(np.uint8)
            _write_atomically(_with_suffix(base, ".png"), lambda f: plt.imsave(
                f, pixels, format="png", pil_kwargs={"compress_level": 1}))
            linear.result()


class _Sightlines:
    """What the queries of a scene work out once about the rays they trace most: camera
    rays, which start at the origin, and shadow rays, which end at a point light.

    Each list holds (object, its index in object_list, ux, uy, uz, reach) for the objects a
    ray may hit: u is the unit direction from the camera to the centre of a sphere around
    the object (from that centre to the light, for shadow rays), reach the cosine of the
    angle that sphere fills seen from the camera (or the light), so that only a ray whose
    direction d has d.u >= reach can hit the object (see _cone; reach -2 when nothing is
    known). The spheres are a little larger than the objects (CLEARANCE times the scene's
    size), so that rounding, and shadow rays starting just above a surface, stay inside.

    camera: every object, for rays from the camera. anywhere: every object, with no cone.
    per_object[k]: for each point light, (light, its x, y, z, the objects that can lie
    between it and a point of object k (_may_block), with their cones from the light).
    unculled: the same with every object, for a point of no object of the list."""

    __slots__ = ("changes", "objects", "lights", "camera", "anywhere", "per_object",
                 "unculled", "near", "t_min")

    def __init__(self, scene):
        objects, lights = scene.object_list, scene.pointLights
        self.changes, self.objects, self.lights = _Shape.changes, list(objects), _lights(lights)
        scale = _scene_size(objects, lights)

        def seen_from(point, sign, kept=lambda obj: True):
            entries = []
            for index, obj in enumerate(objects):
                if kept(obj):
                    ux, uy, uz, reach = _cone(obj, point, scale)
                    entries.append((obj, index, sign * ux, sign * uy, sign * uz, reach))
            return entries

        self.camera = seen_from(Vector3D(0.0, 0.0, 0.0), 1.0)
        self.anywhere = [(obj, index, 0.0, 0.0, 0.0, -2.0) for index, obj in enumerate(objects)]
        # Shadow rays run towards their light: their direction d must have -d in the cone
        # seen from the light, that is d.(-u) >= reach.
        self.per_object = {k: [(light, x, y, z, seen_from(
            light.pos, -1.0, lambda obj: _may_block(obj, blocked, light.pos, scale)))
            for light, x, y, z in self.lights] for k, blocked in enumerate(objects)}
        self.unculled = [(light, x, y, z, seen_from(light.pos, -1.0))
                         for light, x, y, z in self.lights]
        self.near = LIGHT_MATCH * scale
        self.t_min = SHADOW_T_MIN * scale

    def fit(self, scene):
        """Whether the scene is still the one these lists were worked out for: the same
        objects and lights, none of them moved since."""
        return (self.changes == _Shape.changes and self.objects == scene.object_list
                and self.lights == _lights(scene.pointLights))


def _cone(obj, point, scale):
    """(ux, uy, uz, reach) of obj seen from point, for _Sightlines: the cone that a sphere
    around obj fills; for a flat object around point (or with no bounds, as an infinite
    plane), the half of all directions that head towards its plane (reach just below 0:
    directions along the plane are kept too)."""
    bounds = obj._bounds()
    if bounds is not None:
        centre, radius = bounds
        radius += CLEARANCE * scale
        vx, vy, vz = centre.x - point.x, centre.y - point.y, centre.z - point.z
        distance = hypot(vx, vy, vz)
        if distance > radius:
            return (vx / distance, vy / distance, vz / distance,
                    sqrt((distance - radius) * (distance + radius)) / distance)
    if type(obj) in (InfinitePlane, Parallelogram):
        n, height = obj.normal, Dot(point, obj.normal) - obj._k[3]
        if abs(height) >= CLEARANCE * scale:
            towards = -1.0 if height > 0.0 else 1.0
            return towards * n.x, towards * n.y, towards * n.z, -1e-9
    return 0.0, 0.0, 0.0, -2.0


def _lights(lights):
    return [(light, light.pos.x, light.pos.y, light.pos.z) for light in lights]


def _scene_size(objects, lights):
    """The largest coordinate of the scene's lights and built-in objects (1 when there are
    none): the scale of the clearances of _Sightlines and _may_block."""
    size = 0.0
    for obj in objects:
        if type(obj) is Sphere:
            c = obj.origin
            size = max(size, abs(c.x), abs(c.y), abs(c.z), obj.radius)
        elif type(obj) is Parallelogram:
            for corner in _corners(obj):
                size = max(size, *map(abs, corner))
    for light in lights:
        size = max(size, abs(light.pos.x), abs(light.pos.y), abs(light.pos.z))
    return size or 1.0


def _corners(parallelogram):
    p, s1, s2 = parallelogram.point, parallelogram.s1, parallelogram.s2
    return [(p.x + a * s1.x + b * s2.x, p.y + a * s1.y + b * s2.y, p.z + a * s1.z + b * s2.z)
            for a, b in ((0, 0), (1, 0), (0, 1), (1, 1))]


def _may_block(obj, blocked, light_pos, scale):
    """False when obj cannot lie between the point light at light_pos and a point of the
    object `blocked` from which visible_lights traces a shadow ray; True when it may.

    A plane (of an InfinitePlane or Parallelogram) cannot cut a segment whose two ends lie
    on the same side of it, nor touch it but at an end that lies on it. So obj is left out
    when it is flat, the light lies clearly on one side of its plane (by CLEARANCE times
    the scene's size) and `blocked` lies entirely on that side: clearly (a sphere, or a
    parallelogram's corners), or touching the plane (a wall meeting obj at an edge) with a
    normal that, turned towards the light, does not point through obj's plane, so that a
    shadow ray starting just above `blocked` starts on the light's side of obj too.
    obj itself is left out when flat, the light clear of its plane: a shadow ray leaving a
    plane cannot meet it again."""
    if type(obj) not in (InfinitePlane, Parallelogram):
        return True  # a sphere, or an object of your own: always tested
    n, height = obj.normal, obj._k[3]
    side = 1.0 if Dot(light_pos, n) > height else -1.0

    def above(x, y, z):  # the height of (x, y, z) over obj's plane, on the light's side
        return side * (x * n.x + y * n.y + z * n.z - height)

    if above(light_pos.x, light_pos.y, light_pos.z) < CLEARANCE * scale:
        return True
    if obj is blocked:
        return False
    if type(blocked) is Sphere:
        c = blocked.origin
        return above(c.x, c.y, c.z) - blocked.radius < CLEARANCE * scale
    if type(blocked) is not Parallelogram:
        return True
    lowest = min(above(*corner) for corner in _corners(blocked))
    if lowest >= CLEARANCE * scale:
        return False
    if lowest < -TOUCHING * scale:
        return True  # blocked reaches across obj's plane
    m = blocked.normal
    facing = Dot(m, light_pos) - blocked._k[3]  # the light's height over blocked's plane
    if abs(facing) < CLEARANCE * scale:
        return True
    return side * Dot(m, n) * (1.0 if facing > 0.0 else -1.0) < 0.0


def tonemap_image(image, gamma=2.5):
    """The course's display mapping, OpenCV's default tonemapper cv2.createTonemap(gamma):
    the whole image (all pixels and channels) is mapped linearly so that its minimum becomes
    0 and its maximum 1, raised to the power 1/gamma and clipped to [0, 1].

    Unlike OpenCV it ignores non-finite values when it looks for the minimum and maximum,
    so one NaN from a buggy integrator does not turn the whole picture black; NaN and -inf
    pixels are shown as the minimum, +inf as the maximum."""
    lo, hi = float(image.min()), float(image.max())  # NaN if any pixel is NaN
    out = image
    if not (isfinite(lo) and isfinite(hi)):
        finite = np.isfinite(image)
        if not finite.any():
            return np.zeros(image.shape, np.float32)
        lo, hi = float(image[finite].min()), float(image[finite].max())
        out = np.nan_to_num(image, nan=lo, posinf=hi, neginf=lo)
    if hi - lo > np.finfo(float).eps:  # OpenCV leaves a flat image as it is
        out = np.subtract(out, lo)
        out /= hi - lo
    # The power in single precision, as OpenCV computes it (and twice as fast as double).
    # Clipping straight into the single-precision array saves a temporary image.
    display = np.clip(out, 0.0, 1.0, out=np.empty(image.shape, np.float32))
    return np.power(display, np.float32(1.0 / gamma), out=display)


def _write_linear_files(image, base):
    """Writes the .npy and .hdr files of the linear image."""
    ok, hdr = cv2.imencode(".hdr", np.ascontiguousarray(image[:, :, ::-1], np.float32))
    if not ok:
        raise RuntimeError("Scene.save_image: OpenCV could not encode the HDR image")
    _write_atomically(_with_suffix(base, ".hdr"), lambda f: f.write(hdr))
    _write_atomically(_with_suffix(base, ".npy"), lambda f: np.save(f, image))


def _with_suffix(base, suffix):
    return base.parent / (base.name + suffix)


def _write_atomically(path, write):
    """Calls write(file) on a temporary file that then replaces path, so that path is
    always either the previous file or the new one, never half written. The temporary
    file is created like any other file (readable by others, as the umask allows), where
    tempfile.mkstemp would make it private to its owner."""
    tmp = path.with_name(f".{path.name}.{os.getpid()}-{threading.get_ident()}.tmp")
    try:
        with open(tmp, "wb") as f:
            write(f)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


# ------------------------------------------------------------------------------------------
# Primitives
# ------------------------------------------------------------------------------------------
class Primitive(ABC):
    """An object of the scene: a surface that rays can hit, with a material (BRDF) and an
    emitted radiance (BLACK unless the object is an area light)."""

    __setstate__ = _restore_state

    def __init__(self, emission=BLACK):
        self.emission = _check_color(type(self).__name__, "emission", emission)
        self.BRDF = None

    def set_BRDF(self, brdf):
        if not isinstance(brdf, BRDF):
            raise TypeError(f"{type(self).__name__}.set_BRDF: brdf must be a BRDF such as "
                            f"Lambertian(RGBColor(...)), got {brdf!r}")
        self.BRDF = brdf

    def get_BRDF(self):
        return self.BRDF

    @abstractmethod
    def intersect(self, ray):
        """The hit of this object along ray, as a HitData (has_hit False on a miss)."""

    # The two methods below are what Scene uses. The built-in primitives override them with
    # fast versions; a student's own Primitive subclass only needs intersect(), whose last
    # hit is kept for the _hit_data call that follows when it is the nearest.
    def _distance(self, ox, oy, oz, dx, dy, dz, t_min, t_max):
        hit = self.intersect(Ray(Vector3D(ox, oy, oz), Vector3D(dx, dy, dz), t_max, t_min))
        self._last_hit = hit
        return hit.hit_distance if hit.has_hit else None

    def _hit_data(self, ox, oy, oz, dx, dy, dz, t):
        return self._last_hit

    def _bounds(self):
        """(centre, radius) of a sphere holding the object, or None when there is none."""
        return None


def _hit(px, py, pz, nx, ny, nz, t):
    """HitData(True, Vector3D(px, py, pz), Vector3D(nx, ny, nz), t), built without calling
    the three __init__ methods: closest_hit makes one for nearly every pixel, and this
    costs about a third less (see the speed note of PyRT_Common)."""
    p, n, hit = _new(Vector3D), _new(Vector3D), _new(HitData)
    p.x, p.y, p.z = px, py, pz
    n.x, n.y, n.z = nx, ny, nz
    hit.has_hit, hit.hit_point, hit.normal, hit.hit_distance = True, p, n, t
    hit.primitive_index = -1
    return hit


class _FastPrimitive(Primitive):
    """A built-in primitive: intersect() is the public face of _distance and _hit_data."""

    def intersect(self, ray):
        o, (dx, dy, dz) = ray.o, _unit(ray.d)
        t = self._distance(o.x, o.y, o.z, dx, dy, dz, ray.t_min, ray.t_max)
        if t is None:
            return HitData()
        return self._hit_data(o.x, o.y, o.z, dx, dy, dz, t)


class Sphere(_FastPrimitive):
    """The sphere |p - origin| = radius; its normal (p - origin)/radius points outward, also
    for rays that start inside.

    Intersection works in units of the radius r, so that no square over- or underflows at
    any scale: with f = (o - origin)/r and unit d it solves t'^2 + 2bt' + c = 0 for b = f.d
    and c = |f|^2 - 1, and the distance is t = r t'. The textbook discriminant b^2 - c
    cancels catastrophically when the sphere is far away compared with its radius, so it is
    computed as 1 - |f - b d|^2, and the two roots as q = -b - sign(b) sqrt(disc) and c / q,
    which never subtracts nearly equal numbers (Ray Tracing Gems, chapter 7). c / q is worked
    out as (|f| - 1) ((|f| + 1) / q), which cannot overflow however far away the sphere is."""

    origin = _Shape()
    radius = _Shape()

    def __init__(self, sphere_origin, sphere_radius, emission=BLACK):
        super().__init__(emission)
        self._origin = sphere_origin
        self._radius = sphere_radius
        self._derive()

    def _derive(self):
        self._origin = _check_vector("Sphere", "sphere_origin", self._origin)
        self._radius = _check_positive("Sphere", "sphere_radius", self._radius)
        self.radius_squared = self._radius * self._radius
        c = self._origin
        self._k = (c.x, c.y, c.z, self._radius)

    def _distance(self, ox, oy, oz, dx, dy, dz, t_min, t_max):
        cx, cy, cz, r = self._k
        fx, fy, fz = (ox - cx) / r, (oy - cy) / r, (oz - cz) / r
        b = fx * dx + fy * dy + fz * dz
        lx, ly, lz = fx - b * dx, fy - b * dy, fz - b * dz
        disc = 1.0 - (lx * lx + ly * ly + lz * lz)
        if disc < 0.0:
            return None
        f = hypot(fx, fy, fz)
        if b > 0.0:    # q = -(b + sqrt(disc)) is the near root
            q = -b - sqrt(disc)
            t0, t1 = q * r, (f - 1.0) * ((f + 1.0) / q) * r
        else:          # q = sqrt(disc) - b = |b| + sqrt(disc) is the far root
            q = sqrt(disc) - b
            if q == 0.0:  # b == disc == 0: the ray starts on the sphere, touching it
                t0 = t1 = 0.0
            else:
                t0, t1 = (f - 1.0) * ((f + 1.0) / q) * r, q * r
        if t_min <= t0 <= t_max:
            return t0
        if t_min <= t1 <= t_max:
            return t1
        return None

    def _bounds(self):
        return self._origin, self._radius

    def _hit_data(self, ox, oy, oz, dx, dy, dz, t):
        cx, cy, cz, r = self._k
        # (p - origin)/r, unit length to within rounding (and free of over- and underflow)
        vx, vy, vz = (ox + dx * t - cx) / r, (oy + dy * t - cy) / r, (oz + dz * t - cz) / r
        length = sqrt(vx * vx + vy * vy + vz * vz)
        if length == 0.0:  # a sphere far below the precision of its position
            nx, ny, nz = -dx, -dy, -dz
        else:
            nx, ny, nz = vx / length, vy / length, vz / length
        # Rounding leaves o + d*t slightly off the surface; the point along the normal at
        # exactly one radius from the centre is on it.
        return _hit(cx + nx * r, cy + ny * r, cz + nz * r, nx, ny, nz, t)


class InfinitePlane(_FastPrimitive):
    """The plane through origin with unit normal n: the points p with (p - origin).n = 0.
    A ray o + t d meets it at t = (origin - o).n / (d.n); a ray parallel to it (d.n = 0)
    misses. The normal is returned as given, whichever side the ray comes from."""

    origin = _Shape()
    normal = _Shape()

    def __init__(self, plane_origin, plane_normal, emission=BLACK):
        super().__init__(emission)
        self._origin = plane_origin
        self._normal = plane_normal
        self._derive()

    def _derive(self):
        self._origin = _check_vector("InfinitePlane", "plane_origin", self._origin)
        self._normal = Normalize(_check_nonzero("InfinitePlane", "plane_normal", self._normal))
        n, p = self._normal, self._origin
        self._k = (n.x, n.y, n.z, Dot(p, n))

    def _distance(self, ox, oy, oz, dx, dy, dz, t_min, t_max):
        nx, ny, nz, pn = self._k
        den = dx * nx + dy * ny + dz * nz
        if den == 0.0:
            return None
        t = (pn - (ox * nx + oy * ny + oz * nz)) / den
        # A ray nearly parallel to the plane can overflow t to infinity: no hit there.
        return t if t_min <= t <= t_max and t != INFINITY else None

    def _hit_data(self, ox, oy, oz, dx, dy, dz, t):
        nx, ny, nz, _ = self._k
        return _hit(ox + dx * t, oy + dy * t, oz + dz * t, nx, ny, nz, t)


class Parallelogram(_FastPrimitive):
    """The region {point + a*s1 + b*s2 : 0 <= a, b <= 1}, edges and corners included.

    The ray meets the supporting plane (normal m = s1 x s2) at p; with q = p - point, the
    coordinates are a = q.(s2 x m)/(m.m) and b = q.(m x s1)/(m.m), exact for any pair of
    non-parallel sides, orthogonal or not. The unit normal m/|m| is flipped to face the ray."""

    point = _Shape()
    s1 = _Shape()
    s2 = _Shape()

    def __init__(self, point, s1, s2, emission=BLACK):
        super().__init__(emission)
        self._point, self._s1, self._s2 = point, s1, s2
        self._derive()

    def _derive(self):
        p = self._point = _check_vector("Parallelogram", "point", self._point)
        s1 = self._s1 = _check_nonzero("Parallelogram", "s1", self._s1)
        s2 = self._s2 = _check_nonzero("Parallelogram", "s2", self._s2)
        # Everything is worked out from the unit sides e1, e2 and their lengths l1, l2, so no
        # product over- or underflows at any scale (s1 x s2 is the product of two lengths,
        # its square of four). With c = e1 x e2 (|c| = sin of the angle between the sides)
        # the coordinates above are a = q.(e2 x c)/(c.c l1) and b = q.(c x e1)/(c.c l2).
        l1, l2 = Length(s1), Length(s2)
        e1, e2 = s1 / l1, s2 / l2
        c = Cross(e1, e2)
        cc = Dot(c, c)
        if cc <= 1e-24:  # sin(angle) <= 1e-12: parallel sides span no area
            raise ValueError(f"Parallelogram: s1 {s1!r} and s2 {s2!r} are parallel, so they "
                             "span no area; give two sides that point in different directions")
        self.normal = Normalize(c)
        n = self.normal
        ua, ub = Cross(e2, c) / cc / l1, Cross(c, e1) / cc / l2
        self._k = (n.x, n.y, n.z, Dot(p, n))
        self._k2 = (p.x, p.y, p.z, ua.x, ua.y, ua.z, ub.x, ub.y, ub.z)

    def _distance(self, ox, oy, oz, dx, dy, dz, t_min, t_max):
        nx, ny, nz, pn = self._k
        den = dx * nx + dy * ny + dz * nz
        if den == 0.0:
            return None
        t = (pn - (ox * nx + oy * ny + oz * nz)) / den
        if not t_min <= t <= t_max:
            return None
        px, py, pz, uax, uay, uaz, ubx, uby, ubz = self._k2
        qx, qy, qz = ox + dx * t - px, oy + dy * t - py, oz + dz * t - pz
        a = qx * uax + qy * uay + qz * uaz
        if not -EDGE_TOLERANCE <= a <= 1.0 + EDGE_TOLERANCE:
            return None
        b = qx * ubx + qy * uby + qz * ubz
        if not -EDGE_TOLERANCE <= b <= 1.0 + EDGE_TOLERANCE:
            return None
        return t

    def _bounds(self):
        # The centre point + (s1 + s2)/2; the farthest corners lie half a diagonal from it.
        s1, s2 = self._s1, self._s2
        return self._point + (s1 + s2) * 0.5, max(Length(s1 + s2), Length(s1 - s2)) * 0.5

    def _hit_data(self, ox, oy, oz, dx, dy, dz, t):
        nx, ny, nz, _ = self._k
        if dx * nx + dy * ny + dz * nz > 0.0:  # the ray comes from behind: face it
            nx, ny, nz = -nx, -ny, -nz
        return _hit(ox + dx * t, oy + dy * t, oz + dz * t, nx, ny, nz, t)


# ------------------------------------------------------------------------------------------
# BRDFs
# ------------------------------------------------------------------------------------------
class BRDF(ABC):
    """How a surface reflects light: the ratio of radiance leaving towards wo to irradiance
    arriving from wi (both unit vectors pointing away from the surface)."""

    __setstate__ = _restore_state

    @abstractmethod
    def get_value(self, incoming, outgoing, normal):
        """The reflected fraction for light from ``incoming`` seen from ``outgoing``."""


class Lambertian(BRDF):
    """A perfectly matte surface: f = diffuse_colour / pi for every pair of directions.

    ``kd`` already holds the 1/pi, and get_value includes the cosine of the light's angle:
    get_value(wi, wo, n) = kd * (n.wi) when n.wi > 0, else BLACK."""

    def __init__(self, diffuse_colour):
        diffuse_colour = _check_color("Lambertian", "diffuse_colour", diffuse_colour)
        self.kd = diffuse_colour / pi

    def get_value(self, wi, wo, normal):
        cos_theta = normal.x * wi.x + normal.y * wi.y + normal.z * wi.z  # Dot, inlined
        if cos_theta > 0.0:
            kd = self.kd
            value = _new(RGBColor)  # RGBColor(...) without its __init__: see PyRT_Common
            value.r, value.g, value.b = kd.r * cos_theta, kd.g * cos_theta, kd.b * cos_theta
            return value
        return BLACK


# ------------------------------------------------------------------------------------------
# Lights
# ------------------------------------------------------------------------------------------
class PointLight:
    """A point that emits ``intensity`` in every direction; the irradiance it gives a point
    at distance r, facing it, is intensity / r^2."""

    __setstate__ = _restore_state

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
    (x_s * tan(fov/2) * aspect_ratio, y_s * tan(fov/2), -1) of the image plane z = -1."""

    __setstate__ = _restore_state

    width = _Shape()
    height = _Shape()
    vertical_fov = _Shape()

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
            if isinstance(value, bool) or not isinstance(value, (int, float, np.number)):
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
        length = sqrt(px * px + (py * py + 1.0))
        return Vector3D(px / length, py / length, -1.0 / length)

    def row_directions(self, y):
        """get_direction(x, y) for every x of row y, the same numbers computed with numpy in
        one go: IEEE arithmetic rounds numpy's operations exactly as Python's."""
        py = (1.0 - 2.0 * (y + 0.5) / self._height) * self._scale_y
        px = self._row_x
        length = np.sqrt(px * px + (py * py + 1.0))
        return list(map(Vector3D, (px / length).tolist(), (py / length).tolist(),
                        (-1.0 / length).tolist()))
