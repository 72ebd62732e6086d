# ------------------------------------------------------------------------------------------
# PyRT: Python Ray Tracer - common types and functions
# ------------------------------------------------------------------------------------------
import numpy as np
import cv2
import matplotlib.pyplot as plt
from abc import ABC, abstractmethod
from math import sqrt, acos, cos, sin, atan2, floor, pi


# -------------------------------------------------CONSTANTS
EPSILON = 0.0001
HUGEVALUE = 1000000.0
PI = pi
TWO_PI = 2.0 * pi
INVERTED_PI = 1.0 / pi


# -------------------------------------------------VECTOR 3D CLASS
class Vector3D:
    def __init__(self, x, y, z):
        self.x = x
        self.y = y
        self.z = z

    def __str__(self):
        return 'Vector3D(' + str(self.x) + ', ' + str(self.y) + ', ' + str(self.z) + ')'

    def __repr__(self):
        return self.__str__()

    def __add__(self, v):
        return Vector3D(self.x + v.x, self.y + v.y, self.z + v.z)

    def __sub__(self, v):
        return Vector3D(self.x - v.x, self.y - v.y, self.z - v.z)

    # multiplication by a scalar (the scalar must be on the right side!)
    def __mul__(self, s):
        return Vector3D(self.x * s, self.y * s, self.z * s)

    def __truediv__(self, s):
        return Vector3D(self.x / s, self.y / s, self.z / s)

    # element by element multiplication
    def multiply(self, v):
        return Vector3D(self.x * v.x, self.y * v.y, self.z * v.z)


def Dot(v1, v2):
    return v1.x * v2.x + v1.y * v2.y + v1.z * v2.z


def Cross(v1, v2):
    return Vector3D(v1.y * v2.z - v1.z * v2.y,
                    v1.z * v2.x - v1.x * v2.z,
                    v1.x * v2.y - v1.y * v2.x)


def Length(v):
    return sqrt(v.x * v.x + v.y * v.y + v.z * v.z)


def Normalize(v):
    return v * (1.0 / Length(v))


def orient_normal(normal, direction):
    if Dot(normal, direction) < 0.0:
        return normal * -1.0
    return normal


# -------------------------------------------------RGB COLOR CLASS
class RGBColor:
    def __init__(self, r, g, b):
        self.r = r
        self.g = g
        self.b = b

    def __str__(self):
        return 'RGBColor(' + str(self.r) + ', ' + str(self.g) + ', ' + str(self.b) + ')'

    def __repr__(self):
        return self.__str__()

    def __add__(self, c):
        return RGBColor(self.r + c.r, self.g + c.g, self.b + c.b)

    def __sub__(self, c):
        return RGBColor(self.r - c.r, self.g - c.g, self.b - c.b)

    # multiplication by a scalar (the scalar must be on the right side!)
    def __mul__(self, s):
        return RGBColor(self.r * s, self.g * s, self.b * s)

    def __truediv__(self, s):
        return RGBColor(self.r / s, self.g / s, self.b / s)

    # element by element multiplication
    def multiply(self, c):
        return RGBColor(self.r * c.r, self.g * c.g, self.b * c.b)

    def clamp(self, min_value, max_value):
        self.r = min(max(self.r, min_value), max_value)
        self.g = min(max(self.g, min_value), max_value)
        self.b = min(max(self.b, min_value), max_value)


# -------------------------------------------------COLOR CONSTANTS
BLACK = RGBColor(0.0, 0.0, 0.0)
WHITE = RGBColor(1.0, 1.0, 1.0)
RED = RGBColor(1.0, 0.0, 0.0)
GREEN = RGBColor(0.0, 1.0, 0.0)
BLUE = RGBColor(0.0, 0.0, 1.0)
YELLOW = RGBColor(1.0, 1.0, 0.0)
CYAN = RGBColor(0.0, 1.0, 1.0)
MAGENTA = RGBColor(1.0, 0.0, 1.0)


# -------------------------------------------------RAY CLASS
class Ray:
    def __init__(self, origin=Vector3D(0.0, 0.0, 0.0), direction=Vector3D(0.0, 0.0, 0.0), tmax=HUGEVALUE):
        self.o = origin
        self.d = direction
        self.t_max = tmax
        self.t_min = EPSILON

    def get_hitpoint(self, t):
        return self.o + self.d * t


# -------------------------------------------------HIT DATA CLASS
# stores the result of a ray-primitive intersection test
class HitData:
    def __init__(self, has_hit=False, hit_point=Vector3D(0.0, 0.0, 0.0), normal=Vector3D(0.0, 0.0, 0.0),
                 hit_distance=HUGEVALUE, primitive_index=-1):
        self.has_hit = has_hit
        self.hit_point = hit_point
        self.normal = normal
        self.hit_distance = hit_distance
        self.primitive_index = primitive_index


# -------------------------------------------------ENVIRONMENT MAP CLASS
class EnvironmentMap:
    def __init__(self, path):
        image = cv2.imread(path, cv2.IMREAD_ANYCOLOR | cv2.IMREAD_ANYDEPTH)
        self.image = cv2.cvtColor(image, cv2.COLOR_BGR2RGB)
        self.height = self.image.shape[0]
        self.width = self.image.shape[1]

    def euclideanToLatLong(self, d):
        u = (1 + atan2(d.x, -d.z) / pi) / 2
        v = acos(d.y) / pi
        return u, v

    def getValue(self, d):
        u, v = self.euclideanToLatLong(d)
        i = floor(u * (self.width - 1))
        j = floor(v * (self.height - 1))
        texel = self.image[j, i]
        return RGBColor(float(texel[0]), float(texel[1]), float(texel[2]))
