"""PyRT common types: vectors, colours, rays, hit records, the environment map, and the
Monte Carlo half of the course's base code (densities, integrands and sample sets over the
hemisphere).

Students write ``from PyRT_Common import *``; besides the classes and functions below that
also brings ``np``, ``cv2``, ``plt``, ``ABC``, ``abstractmethod``, ``sqrt, acos, cos, sin,
atan2, floor, pi`` and ``random`` (the function random.random) into their module.

The operators below run millions of times per image, so the classes that every ray
touches (Vector3D, RGBColor, Ray, HitData) have ``__slots__``, and the operators that
return a new vector or colour make it with ``_new`` (object.__new__) and three
assignments: the object Vector3D(x, y, z) gives, without the call of __init__.
"""
from abc import ABC, abstractmethod
from math import acos, atan2, cos, floor, frexp, ldexp, pi, sin, sqrt
from numbers import Real
from pathlib import Path
from random import random  # Python's global generator, which random.seed seeds

import matplotlib.pyplot as plt
import numpy as np

from pyrt.environment_maps import sky_map
# cv2: OpenCV, or an ImportError that says how to repair it
from pyrt.images import cv2, native_path

__all__ = [
    "np", "cv2", "plt", "ABC", "abstractmethod",
    "sqrt", "acos", "cos", "sin", "atan2", "floor", "pi",
    "EPSILON", "HUGEVALUE", "INFINITY", "PI", "TWO_PI", "INVERTED_PI",
    "Vector3D", "Dot", "Cross", "Length", "Normalize", "orient_normal",
    "RGBColor", "BLACK", "WHITE", "GREEN", "RED",
    "Ray", "HitData", "shadow_ray", "EnvironmentMap", "random",
    "PDF", "UniformPDF", "CosinePDF", "Function", "Constant", "CosineLobe",
    "sample_set_hemisphere", "center_around_normal", "oriented_hemi_dir", "rotate_around_y",
    "euclidean_to_disk", "visualize_sample_set",
]

# ------------------------------------------------------------------------------------------
# Constants
# ------------------------------------------------------------------------------------------
EPSILON = 0.0001
HUGEVALUE = 1000000.0
INFINITY = float("inf")
PI = pi
TWO_PI = 2.0 * pi
INVERTED_PI = 1.0 / pi

_new = object.__new__  # makes an object without calling its __init__ (see above)
_SCALAR_HINT = ("{verb} a {cls} by a number only; for the element-wise product of two "
                "{cls} objects use a.multiply(b)")


def is_number(value, whole=False) -> bool:
    """Whether value is a number that PyRT takes for a size, a distance or a count: an int,
    float or numpy number (only an int or numpy integer when whole), True and False aside."""
    kinds = (int, np.integer) if whole else (int, float, np.number)
    return isinstance(value, kinds) and not isinstance(value, (bool, np.bool_))


# ------------------------------------------------------------------------------------------
# Vectors
# ------------------------------------------------------------------------------------------
def _shown(value):
    """A component as a repr shows it: any number (int, numpy's float64, ...) as a plain
    float, anything else as itself, so that a colour holding a vector or a string by
    mistake shows that mistake in a message instead of failing to print."""
    return repr(float(value)) if isinstance(value, Real) else repr(value)


class Vector3D:
    """A point or direction in 3D space, (x, y, z).

    ``v + w`` and ``v - w`` work component by component; ``v * s`` and ``v / s`` scale by a
    number s (``s * v`` works too); ``v.multiply(w)`` is the element-wise product
    (x1*x2, y1*y2, z1*z2).
    """

    __slots__ = ("x", "y", "z")

    def __init__(self, x_element, y_element, z_element):
        self.x = x_element
        self.y = y_element
        self.z = z_element

    def __add__(self, w):
        v = _new(Vector3D)
        v.x, v.y, v.z = self.x + w.x, self.y + w.y, self.z + w.z
        return v

    def __sub__(self, w):
        v = _new(Vector3D)
        v.x, v.y, v.z = self.x - w.x, self.y - w.y, self.z - w.z
        return v

    def __neg__(self):
        v = _new(Vector3D)
        v.x, v.y, v.z = -self.x, -self.y, -self.z
        return v

    def __mul__(self, s):
        if s.__class__ in _NOT_SCALARS:
            raise TypeError(_SCALAR_HINT.format(verb="multiply", cls="Vector3D"))
        v = _new(Vector3D)
        v.x, v.y, v.z = self.x * s, self.y * s, self.z * s
        return v

    __rmul__ = __mul__

    def __truediv__(self, s):
        if s.__class__ in _NOT_SCALARS:
            raise TypeError(_SCALAR_HINT.format(verb="divide", cls="Vector3D"))
        v = _new(Vector3D)
        v.x, v.y, v.z = self.x / s, self.y / s, self.z / s
        return v

    def __eq__(self, w):
        if not isinstance(w, Vector3D):
            return NotImplemented
        return self.x == w.x and self.y == w.y and self.z == w.z

    __hash__ = None  # mutable: equal vectors may not stay equal, so they cannot be dict keys

    def multiply(self, w):
        v = _new(Vector3D)
        v.x, v.y, v.z = self.x * w.x, self.y * w.y, self.z * w.z
        return v

    def __iter__(self):
        return iter((self.x, self.y, self.z))

    def __repr__(self):
        return f"Vector3D({_shown(self.x)}, {_shown(self.y)}, {_shown(self.z)})"


def Dot(a, b):
    """The dot product a . b = ax*bx + ay*by + az*bz."""
    return a.x * b.x + a.y * b.y + a.z * b.z


def Cross(a, b):
    """The cross product a x b, perpendicular to both (right-handed)."""
    v = _new(Vector3D)
    v.x, v.y, v.z = a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x
    return v


# Where x*x + y*y + z*z lies strictly between these, no square has overflowed, nor
# underflowed by enough to change the sum: the formula holds as it is computed.
SQUARES_LOW, SQUARES_HIGH = 2.0 ** -960, 2.0 ** 960


def Length(v):
    """The Euclidean length |v| = sqrt(v . v), as the course computes it, at every scale
    (see euclidean_length)."""
    x, y, z = v.x, v.y, v.z
    squares = x * x + y * y + z * z
    if SQUARES_LOW < squares < SQUARES_HIGH:  # no square over- or underflowed
        return sqrt(squares)
    return euclidean_length(x, y, z)


def Normalize(v):
    """The unit vector v * (1 / |v|), rounded as the course rounds it, at every scale (see
    unit_components); a zero vector has no direction and raises ValueError."""
    unit = _new(Vector3D)
    unit.x, unit.y, unit.z = unit_components(v.x, v.y, v.z)
    return unit


def euclidean_length(x, y, z):
    """sqrt(x*x + y*y + z*z), the length of the vector (x, y, z).

    The squares of components beyond about 1e154 overflow and those below 1e-154
    underflow. There the components are first divided by the power of two nearest to the
    largest of them and the result multiplied back: multiplying by a power of two is exact
    in floating point, so every rounding stays the same, and the result is the formula's
    at every scale."""
    squares = x * x + y * y + z * z
    if SQUARES_LOW < squares < SQUARES_HIGH:
        return sqrt(squares)
    x, y, z, exponent = _rescaled(x, y, z)
    return ldexp(sqrt(x * x + y * y + z * z), exponent)


def unit_components(x, y, z):
    """(x, y, z) * (1 / sqrt(x*x + y*y + z*z)), the unit vector of (x, y, z), with the
    power-of-two scaling of euclidean_length where the squares would over- or underflow;
    a ValueError for the zero vector, which has no direction."""
    squares = x * x + y * y + z * z
    if not SQUARES_LOW < squares < SQUARES_HIGH:
        x, y, z, _ = _rescaled(x, y, z)
        squares = x * x + y * y + z * z
        if squares == 0.0:
            raise ValueError(f"Normalize: cannot normalise the zero vector "
                             f"{Vector3D(x, y, z)!r}, it has no direction; check how the "
                             "vector was computed")
    inverse = 1.0 / sqrt(squares)
    return x * inverse, y * inverse, z * inverse


def _rescaled(x, y, z):
    """(x, y, z) / 2**e and e, for e the exponent of the largest |component| m
    (m = f * 2**e with 0.5 <= f < 1); e = 0 when m is zero or not finite, which no scaling
    helps."""
    largest = max(abs(x), abs(y), abs(z))
    exponent = frexp(largest)[1] if 0.0 < largest < INFINITY else 0
    return ldexp(x, -exponent), ldexp(y, -exponent), ldexp(z, -exponent), exponent


def orient_normal(normal, direction):
    """The normal flipped to the side of ``direction``: -normal when normal . direction < 0."""
    if Dot(normal, direction) < 0.0:
        flipped = _new(Vector3D)
        flipped.x, flipped.y, flipped.z = -normal.x, -normal.y, -normal.z
        return flipped
    return normal


# ------------------------------------------------------------------------------------------
# Colours
# ------------------------------------------------------------------------------------------
class RGBColor:
    """A linear RGB radiance value (r, g, b); the components may exceed 1 before tonemapping.

    ``c + d`` and ``c - d`` work per channel, ``c * s`` and ``c / s`` scale by a number,
    ``c.multiply(d)`` is the per-channel product used to filter light by a surface colour.
    """

    __slots__ = ("r", "g", "b")

    def __init__(self, red, green, blue):
        self.r = red
        self.g = green
        self.b = blue

    def __add__(self, d):
        c = _new(RGBColor)
        c.r, c.g, c.b = self.r + d.r, self.g + d.g, self.b + d.b
        return c

    def __sub__(self, d):
        c = _new(RGBColor)
        c.r, c.g, c.b = self.r - d.r, self.g - d.g, self.b - d.b
        return c

    def __mul__(self, s):
        if s.__class__ in _NOT_SCALARS:
            raise TypeError(_SCALAR_HINT.format(verb="multiply", cls="RGBColor"))
        c = _new(RGBColor)
        c.r, c.g, c.b = self.r * s, self.g * s, self.b * s
        return c

    __rmul__ = __mul__

    def __truediv__(self, s):
        if s.__class__ in _NOT_SCALARS:
            raise TypeError(_SCALAR_HINT.format(verb="divide", cls="RGBColor"))
        c = _new(RGBColor)
        c.r, c.g, c.b = self.r / s, self.g / s, self.b / s
        return c

    def __eq__(self, d):
        if not isinstance(d, RGBColor):
            return NotImplemented
        return self.r == d.r and self.g == d.g and self.b == d.b

    __hash__ = None  # mutable, see Vector3D

    def multiply(self, d):
        c = _new(RGBColor)
        c.r, c.g, c.b = self.r * d.r, self.g * d.g, self.b * d.b
        return c

    def clamp(self, minimum, maximum):
        """Clamps every channel to [minimum, maximum], in place."""
        self.r = min(max(self.r, minimum), maximum)
        self.g = min(max(self.g, minimum), maximum)
        self.b = min(max(self.b, minimum), maximum)

    def __iter__(self):
        return iter((self.r, self.g, self.b))

    def __repr__(self):
        return f"RGBColor({_shown(self.r)}, {_shown(self.g)}, {_shown(self.b)})"


# The shared colours, as the course has them: plain RGBColor objects. Code that changes one
# in place (c = BLACK, then c.r += 1) changes it for every later use, so check_constants()
# looks at them after every block of rows a render computes, and when an image is saved.
BLACK = RGBColor(0.0, 0.0, 0.0)
WHITE = RGBColor(1.0, 1.0, 1.0)
GREEN = RGBColor(0.0, 1.0, 0.0)
RED = RGBColor(1.0, 0.0, 0.0)

_CONSTANTS = {"BLACK": (BLACK, (0.0, 0.0, 0.0)), "WHITE": (WHITE, (1.0, 1.0, 1.0)),
              "GREEN": (GREEN, (0.0, 1.0, 0.0)), "RED": (RED, (1.0, 0.0, 0.0))}

_NOT_SCALARS = frozenset((Vector3D, RGBColor))


def check_constants(where):
    """Raises a RuntimeError naming the shared colour (BLACK, WHITE, GREEN, RED) that was
    changed in place, after giving it back its value; does nothing when all are intact."""
    for name, (constant, value) in _CONSTANTS.items():
        if (constant.r, constant.g, constant.b) != value:
            changed = repr(constant)
            constant.r, constant.g, constant.b = value
            raise RuntimeError(
                f"{where}: the shared colour {name} was changed in place to {changed}, so "
                f"every later use of {name} was wrong. Code such as `color = {name}` followed "
                f"by `color.r += ...` or `color.clamp(...)` does this; start from a copy "
                f"instead: `color = RGBColor{value}`. {name} has its value back.")


# ------------------------------------------------------------------------------------------
# Rays and hits
# ------------------------------------------------------------------------------------------
class Ray:
    """The half-line o + d*t, t in [t_min, t_max].

    t is measured as a distance along the ray: with a unit direction d this is the parameter
    itself, and PyRT's intersection tests also read it as a distance when d is not unit length.
    ``t_min`` defaults to EPSILON so that a ray starting on a surface does not hit it again.
    """

    __slots__ = ("o", "d", "t_max", "t_min")

    def __init__(self, origin=None, direction=None, tmax=HUGEVALUE, tmin=EPSILON):
        # Defaults are fresh vectors: a shared default would leak one ray's changes into all.
        self.o = Vector3D(0.0, 0.0, 0.0) if origin is None else origin
        self.d = Vector3D(0.0, 0.0, 0.0) if direction is None else direction
        self.t_max = tmax
        self.t_min = tmin

    def get_hitpoint(self, t):
        """The point o + d * t."""
        o, d = self.o, self.d
        p = _new(Vector3D)
        p.x, p.y, p.z = o.x + d.x * t, o.y + d.y * t, o.z + d.z * t
        return p

    def __repr__(self):
        return f"Ray({self.o!r}, {self.d!r}, t_min={self.t_min!r}, t_max={self.t_max!r})"


class HitData:
    """The result of one ray-object intersection test.

    ``has_hit`` says whether there is a hit; only then the rest means something:
    ``hit_point`` (on the surface), its unit ``normal``, ``hit_distance`` (the distance
    travelled along the ray) and ``primitive_index`` (the object's index in
    ``scene.object_list``, set by ``closest_hit``).
    """

    __slots__ = ("has_hit", "hit_point", "normal", "hit_distance", "primitive_index")

    def __init__(self, has_hit=False, hit_point=None, normal=None, hit_distance=HUGEVALUE,
                 primitive_index=-1):
        # Defaults are fresh zero vectors, as for Ray: a shared one would leak one hit's
        # changes into all.
        self.has_hit = has_hit
        self.hit_point = Vector3D(0.0, 0.0, 0.0) if hit_point is None else hit_point
        self.normal = Vector3D(0.0, 0.0, 0.0) if normal is None else normal
        self.hit_distance = hit_distance
        self.primitive_index = primitive_index

    def __repr__(self):
        if not self.has_hit:
            return "HitData(has_hit=False)"
        return (f"HitData(has_hit=True, hit_point={self.hit_point!r}, normal={self.normal!r}, "
                f"hit_distance={self.hit_distance!r}, primitive_index={self.primitive_index})")


# A shadow ray stops this fraction of its length short of its target, so that a light
# lying exactly on a surface is not hidden by that surface.
SHADOW_EPSILON = 1e-6
# Shadow rays start this far above the surface, relative to the size of the hit point's
# coordinates (see shadow_ray).
OFFSET_SCALE = 2.0 ** -32


def shadow_ray(hit, target):
    """The shadow ray from the point of `hit` (a HitData) to the point `target`, a light's
    position: a ray that meets an object only where the object lies between the two.

    A hit point lies on its surface only to within rounding, so a ray leaving it may hit
    that same surface again and shadow it in speckles ("shadow acne"). This ray starts a
    little above the surface, on the side of target, and ignores the same first stretch
    of its way (t_min), by offset = 2^-32 (largest |coordinate| of the point + its
    hit_distance): far above the rounding error of the point, about 1e-16 of its size, far
    below any detail of the scene, and the same at every scale, where a fixed EPSILON is
    too large for tiny scenes and too small for huge ones. (A hit at the world's origin,
    where its own ray starts, takes its size from the distance to target.) The ray stops a
    millionth of its length short of target (SHADOW_EPSILON), so that a light lying on a
    surface is not hidden by that surface."""
    p, n = hit.hit_point, hit.normal
    px, py, pz, nx, ny, nz = p.x, p.y, p.z, n.x, n.y, n.z
    tx, ty, tz = target.x, target.y, target.z
    size = max(abs(px), abs(py), abs(pz)) + hit.hit_distance  # the largest |coordinate|
    if size == 0.0:  # a hit at the origin, where its ray starts: the target gives the size
        size = euclidean_length(tx - px, ty - py, tz - pz)
    offset = OFFSET_SCALE * size
    if (tx - px) * nx + (ty - py) * ny + (tz - pz) * nz >= 0.0:
        ox, oy, oz = px + nx * offset, py + ny * offset, pz + nz * offset
    else:  # target lies behind the surface: start below it
        ox, oy, oz = px - nx * offset, py - ny * offset, pz - nz * offset
    dx, dy, dz = tx - ox, ty - oy, tz - oz
    distance = euclidean_length(dx, dy, dz)  # Length, without a Vector3D to make
    if distance == 0.0:  # target is the start itself: there is nothing in between
        return Ray(Vector3D(ox, oy, oz), Vector3D(nx, ny, nz), 0.0, offset)
    # Ray(Vector3D(ox, oy, oz), Vector3D(dx, dy, dz) / distance, distance * (1 - SHADOW_EPSILON),
    # offset), made without the calls of __init__, as the operators make their vectors
    ray, start, direction = _new(Ray), _new(Vector3D), _new(Vector3D)
    start.x, start.y, start.z = ox, oy, oz
    direction.x, direction.y, direction.z = dx / distance, dy / distance, dz / distance
    ray.o, ray.d, ray.t_max, ray.t_min = start, direction, distance * (1.0 - SHADOW_EPSILON), offset
    return ray


# ------------------------------------------------------------------------------------------
# Environment map
# ------------------------------------------------------------------------------------------
class EnvironmentMap:
    """Light arriving from infinitely far away, stored as a latitude-longitude HDR image.

    Read as the course reads it: cv2.imread(path, flags=cv2.IMREAD_ANYDEPTH), which gives
    OpenCV's grey reading of the file (each texel 0.299 R + 0.587 G + 0.114 B of its linear
    values), then cv2.cvtColor(..., cv2.COLOR_RGB2BGR), which makes it three equal channels:
    every radiance the map returns has r = g = b. ``colour=True`` reads the file's colours
    instead (PyRT's addition; the course's images lit by a map are grey-lit).

    A direction d maps to u = (1 + (1/PI) atan2(d.x, -d.z)) / 2 (longitude, 0.5 straight
    ahead) and v = (1/PI) acos(d.y) (0 straight up, 1 straight down), and getValue returns
    the texel at column floor(u (width - 1)), row floor(v (height - 1)).
    """

    def __init__(self, env_map_path, colour=False):
        path = _environment_map_file(env_map_path)
        if path is None:  # the course's own map, not here: PyRT's sky stands in for it
            self._set_texels(sky_map())
            return
        flags = cv2.IMREAD_ANYDEPTH | cv2.IMREAD_COLOR if colour else cv2.IMREAD_ANYDEPTH
        texels = cv2.imread(str(path), flags=flags)
        if texels is None:
            raise ValueError(f"EnvironmentMap: OpenCV cannot read {str(path)!r}; "
                             "give it an .hdr (Radiance) or .exr latitude-longitude image")
        if texels.ndim == 2:  # the grey reading: three equal channels, as the course's
            texels = cv2.cvtColor(texels, cv2.COLOR_RGB2BGR)
        else:  # OpenCV reads colours in the order blue, green, red
            texels = cv2.cvtColor(texels, cv2.COLOR_BGR2RGB)
        self._set_texels(texels.astype(np.float32, copy=False))

    @classmethod
    def from_texels(cls, texels):
        """A map made from an array of texels (height, width, 3) instead of a file, such as
        PyRT's own maps (pyrt.environment_maps); they are kept as float32, as OpenCV reads
        a file."""
        env_map = cls.__new__(cls)
        env_map._set_texels(np.asarray(texels, dtype=np.float32))
        return env_map

    def _set_texels(self, texels):
        self.env_map_hdr = texels
        self.height, self.width = texels.shape[:2]

    def euclideanToLatLong(self, d):
        """The (u, v) image coordinates, both in [0, 1], of the unit direction d."""
        u = (1 + (1 / PI) * atan2(d.x, -d.z)) / 2
        v = (1 / PI) * acos(min(1.0, max(-1.0, d.y)))  # rounding can push d.y out of [-1, 1]
        return u, v

    def getValue(self, d):
        """The radiance arriving from direction d: the texel under (u, v), its channels
        numpy float32 values as OpenCV read them."""
        u, v = self.euclideanToLatLong(d)
        texel = self.env_map_hdr[floor(v * (self.height - 1)), floor(u * (self.width - 1))]
        return RGBColor(texel[0], texel[1], texel[2])


# The course's environment map, as its scenes name it: relative to the folder the script
# runs in. It is the course's (the env_maps/ folder of its base code), not PyRT's to ship.
COURSE_ENV_MAP = "env_maps/arch_nozero.hdr"
_BESIDE_APP = Path(__file__).resolve().parent  # the folder of AppRenderer.py


def _environment_map_file(env_map_path):
    """The file of an environment map: the path as given (relative to the current folder);
    for the course's own map, also beside AppRenderer.py, and None when it is in neither
    place (one line says so: PyRT's sky then stands in); else a FileNotFoundError."""
    path = Path(native_path(env_map_path))  # a Windows path means the same on any system
    if path.is_file():
        return path
    if path.as_posix().removeprefix("./") == COURSE_ENV_MAP:
        if (_BESIDE_APP / COURSE_ENV_MAP).is_file():
            return _BESIDE_APP / COURSE_ENV_MAP
        print(f"EnvironmentMap: {COURSE_ENV_MAP} is the course's map, from the env_maps/ "
              "folder of the course's base code, and it is not here (put that folder beside "
              "AppRenderer.py or in the folder you run from); PyRT's own sky map stands in "
              "for it.")
        return None
    raise FileNotFoundError(f"EnvironmentMap: no image file at {str(path.resolve())!r}; "
                            "give the path of a latitude-longitude .hdr image")


# ------------------------------------------------------------------------------------------
# Monte Carlo: densities and integrands over the unit hemisphere around +y, sample sets
# ------------------------------------------------------------------------------------------
class PDF(ABC):
    """A probability density p(omega) over the directions of the unit hemisphere around +y,
    with a way to draw directions from it."""

    @abstractmethod
    def get_val(self, omega_i):
        """The density p(omega_i)."""

    @abstractmethod
    def generate_dir(self, u1, u2):
        """The direction of density p made from two uniform numbers u1, u2 in [0, 1)."""


class UniformPDF(PDF):
    """Every direction of the hemisphere equally likely: p(omega) = 1 / (2 pi).

    generate_dir: y = u2 (the cosine of the angle to +y is uniform in [0, 1)), phi = 2 pi u1,
    x = sin(phi) sqrt(1 - u2^2), z = cos(phi) sqrt(1 - u2^2)."""

    def get_val(self, omega_i):
        return 1 / (2 * pi)

    def generate_dir(self, u1, u2):
        phi = 2 * pi * u1
        sin_theta = sqrt(1 - u2 ** 2)
        return Vector3D(sin(phi) * sin_theta, u2, cos(phi) * sin_theta)


class CosinePDF(PDF):
    """Directions near +y more likely: p(omega) = (exp + 1) / (2 pi) cos^exp, cos the cosine
    of the angle between omega and +y (exp 1 is cosine-weighted sampling).

    generate_dir: y = u2^(1/(exp + 1)), phi = 2 pi u1, s = sqrt(1 - u2^(2/(exp + 1))),
    x = sin(phi) s, z = cos(phi) s."""

    def __init__(self, exp_):
        self.exp = exp_

    def get_val(self, omega_i):
        cos_theta = Dot(Vector3D(0.0, 1.0, 0.0), omega_i)
        return (self.exp + 1) / (2 * pi) * cos_theta ** self.exp

    def generate_dir(self, u1, u2):
        phi = 2 * pi * u1
        y = u2 ** (1 / (self.exp + 1))
        sin_theta = sqrt(1 - u2 ** (2 / (self.exp + 1)))
        return Vector3D(sin(phi) * sin_theta, y, cos(phi) * sin_theta)


class Function(ABC):
    """An integrand f(omega) over the hemisphere around +y, with ``ground_truth``, the value
    of its integral, to measure an estimate's error against."""

    def __init__(self, integral_value):
        self.ground_truth = integral_value

    @abstractmethod
    def eval(self, omega_i):
        """The value f(omega_i)."""

    @abstractmethod
    def get_integral(self):
        """The integral of f over the hemisphere."""


class Constant(Function):
    """f(omega) = c, whose integral over the hemisphere (solid angle 2 pi) is 2 pi c."""

    def __init__(self, const_value_):
        self.const_value = const_value_
        super().__init__(self.get_integral())

    def eval(self, omega_i):
        return self.const_value

    def get_integral(self):
        return 2 * pi * self.const_value


class CosineLobe(Function):
    """f(omega) = cos^exp, cos the cosine of the angle between omega and +y; its integral
    over the hemisphere is 2 pi / (exp + 1)."""

    def __init__(self, exp_):
        self.exp = exp_
        super().__init__(self.get_integral())

    def eval(self, omega_i):
        return Dot(Vector3D(0.0, 1.0, 0.0), omega_i) ** self.exp

    def get_integral(self):
        return 2 * pi / (self.exp + 1)


def sample_set_hemisphere(n_samples, pdf):
    """n_samples directions drawn from pdf and their densities: for each, u1 = random() then
    u2 = random() (Python's global generator, which random.seed seeds), the direction
    pdf.generate_dir(u1, u2) and pdf.get_val of it. Returns (directions, densities)."""
    sample_set, sample_prob = [], []
    for _ in range(n_samples):
        u1 = random()
        u2 = random()
        omega = pdf.generate_dir(u1, u2)
        sample_set.append(omega)
        sample_prob.append(pdf.get_val(omega))
    return sample_set, sample_prob


def center_around_normal(dir, normal):
    """The direction dir of the hemisphere around +y turned into the hemisphere around
    normal: in the frame w = normal, v = Normalize(Cross(up, w)) with the "jittered up"
    (0.00319, 1.0, 0.0078) (never parallel to an axis-aligned normal), u = Cross(v, w),
    the unit vector Normalize(v dir.x + w dir.y + u dir.z)."""
    w = normal
    v = Normalize(Cross(Vector3D(0.00319, 1.0, 0.0078), w))
    u = Cross(v, w)
    return Normalize(v * dir.x + w * dir.y + u * dir.z)


def oriented_hemi_dir(pdf, u1, u2, new_normal):
    """A direction drawn from pdf (from u1, u2) in the hemisphere around new_normal."""
    return center_around_normal(pdf.generate_dir(u1, u2), new_normal)


def rotate_around_y(alpha, dir_):
    """dir_ rotated by the angle alpha (radians) around the y axis:
    (x cos(alpha) + z sin(alpha), y, -x sin(alpha) + z cos(alpha))."""
    return Vector3D(dir_.x * cos(alpha) + dir_.z * sin(alpha), dir_.y,
                    -dir_.x * sin(alpha) + dir_.z * cos(alpha))


def euclidean_to_disk(sample_set):
    """The directions of sample_set as polar coordinates of a disk, two numpy arrays: r, the
    angle to +y, acos(d.y), and phi = atan2(d.x, d.z) around it."""
    r = np.array([acos(Dot(Vector3D(0.0, 1.0, 0.0), d)) for d in sample_set])
    phi = np.array([atan2(d.x, d.z) for d in sample_set])
    return r, phi


def visualize_sample_set(sample_set, weights=[], show=True):
    """A polar scatter plot of the directions of sample_set seen from above: the angle phi
    around +y, the distance from the centre the angle to +y (0 to pi/2). With weights (one
    per direction), each dot is coloured by its weight, colormap "jet" from 0.7/n to 1.3/n
    for n directions, with a colour bar. Shown with plt.show() (show=False: not shown);
    returns the figure."""
    r, phi = euclidean_to_disk(sample_set)
    figure = plt.figure()
    axes = figure.add_subplot(projection="polar")
    if len(weights):
        n = len(sample_set)
        dots = axes.scatter(phi, r, c=weights, cmap="jet", vmin=1 / n - 0.3 / n,
                            vmax=1 / n + 0.3 / n)
        figure.colorbar(dots)
    else:
        axes.scatter(phi, r)
    axes.set_xlim(0, 2 * pi)
    axes.set_ylim(0, pi / 2)
    if show:
        plt.show()
    return figure
