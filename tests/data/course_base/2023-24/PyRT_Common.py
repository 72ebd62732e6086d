# ------------------------------------------------------------------------------------------
# PyRT: Python Ray Tracer - common types and functions
# ------------------------------------------------------------------------------------------
import numpy as np
import cv2
import matplotlib.pyplot as plt
from abc import ABC, abstractmethod
from math import sqrt, acos, cos, sin, atan2, floor, pi
from random import random


# -------------------------------------------------CONSTANTS
EPSILON = 0.0001
HUGEVALUE = 1000000.0
PI = pi
TWO_PI = 2.0 * pi
INVERTED_PI = 1.0 / pi


# -------------------------------------------------RAY CLASS
class Ray:
    def __init__(self, origin=np.zeros(3), direction=np.zeros(3), tmax=HUGEVALUE):
        self.o = origin
        self.d = direction
        self.t_max = tmax
        self.t_min = EPSILON

    def get_hitpoint(self, t):
        return self.o + self.d * t


# -------------------------------------------------HIT DATA CLASS
# stores the result of a ray-primitive intersection test
class HitData:
    def __init__(self, has_hit=False, hit_point=np.zeros(3), normal=np.zeros(3),
                 hit_distance=HUGEVALUE, primitive_index=-1):
        self.has_hit = has_hit
        self.hit_point = hit_point
        self.normal = normal
        self.hit_distance = hit_distance
        self.primitive_index = primitive_index


# -------------------------------------------------VECTOR 3D CLASS
class Vector3D:
    def __init__(self, x_element, y_element, z_element):
        self.x = x_element
        self.y = y_element
        self.z = z_element

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


def Dot(a, b):
    return a.x * b.x + a.y * b.y + a.z * b.z


def Cross(a, b):
    return Vector3D(a.y * b.z - a.z * b.y,
                    a.z * b.x - a.x * b.z,
                    a.x * b.y - a.y * b.x)


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
    def __init__(self, red, green, blue):
        self.r = red
        self.g = green
        self.b = blue

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

    def clamp(self, minimum, maximum):
        self.r = min(max(self.r, minimum), maximum)
        self.g = min(max(self.g, minimum), maximum)
        self.b = min(max(self.b, minimum), maximum)


# -------------------------------------------------COLOR CONSTANTS
BLACK = RGBColor(0.0, 0.0, 0.0)
WHITE = RGBColor(1.0, 1.0, 1.0)
GREEN = RGBColor(0.0, 1.0, 0.0)
RED = RGBColor(1.0, 0.0, 0.0)


# -------------------------------------------------ENVIRONMENT MAP CLASS
# an HDR latitude-longitude image: the light arriving from every direction
class EnvironmentMap:
    def __init__(self, env_map_path):
        self.env_map_hdr = cv2.imread(env_map_path, flags=cv2.IMREAD_ANYDEPTH)
        self.env_map_hdr = cv2.cvtColor(self.env_map_hdr, cv2.COLOR_RGB2BGR)
        self.height = self.env_map_hdr.shape[0]
        self.width = self.env_map_hdr.shape[1]

    # (u, v) image coordinates of the direction d
    def euclideanToLatLong(self, d):
        u = (1 + (1 / PI) * atan2(d.x, -d.z)) / 2
        v = (1 / PI) * acos(d.y)
        return u, v

    def getValue(self, d):
        u, v = self.euclideanToLatLong(d)
        i = floor(u * (self.width - 1))
        j = floor(v * (self.height - 1))
        texel = self.env_map_hdr[j, i]
        return RGBColor(texel[0], texel[1], texel[2])


# -------------------------------------------------PROBABILITY DENSITY FUNCTIONS
# pdfs over the directions of the unit hemisphere around (0, 1, 0)
class PDF(ABC):
    @abstractmethod
    def get_val(self, omega_i):
        pass

    # a direction of the hemisphere from two uniform random numbers u1, u2 in [0, 1)
    @abstractmethod
    def generate_dir(self, u1, u2):
        pass


class UniformPDF(PDF):
    def __init__(self):
        pass

    def get_val(self, omega_i):
        return 1 / (2 * pi)

    def generate_dir(self, u1, u2):
        phi = 2 * pi * u1
        x = sin(phi) * sqrt(1 - u2 ** 2)
        y = u2
        z = cos(phi) * sqrt(1 - u2 ** 2)
        return Vector3D(x, y, z)


class CosinePDF(PDF):
    def __init__(self, exp_):
        self.exp = exp_

    def get_val(self, omega_i):
        cos_theta = Dot(Vector3D(0.0, 1.0, 0.0), omega_i)
        return (self.exp + 1) / (2 * pi) * cos_theta ** self.exp

    def generate_dir(self, u1, u2):
        phi = 2 * pi * u1
        s = sqrt(1 - u2 ** (2 / (self.exp + 1)))
        x = sin(phi) * s
        y = u2 ** (1 / (self.exp + 1))
        z = cos(phi) * s
        return Vector3D(x, y, z)


# -------------------------------------------------FUNCTIONS TO INTEGRATE OVER THE HEMISPHERE
class Function(ABC):
    def __init__(self, integral_value):
        self.ground_truth = integral_value

    @abstractmethod
    def eval(self, omega_i):
        pass

    # the integral of the function over the hemisphere
    @abstractmethod
    def get_integral(self):
        pass


class Constant(Function):
    def __init__(self, const_value_):
        self.const_value = const_value_
        super().__init__(self.get_integral())

    def eval(self, omega_i):
        return self.const_value

    def get_integral(self):
        return 2 * pi * self.const_value


class CosineLobe(Function):
    def __init__(self, exp_):
        self.exp = exp_
        super().__init__(self.get_integral())

    def eval(self, omega_i):
        return Dot(Vector3D(0.0, 1.0, 0.0), omega_i) ** self.exp

    def get_integral(self):
        return 2 * pi / (self.exp + 1)


# -------------------------------------------------SAMPLING THE HEMISPHERE
# n_samples directions drawn from pdf, and the pdf's value for each
def sample_set_hemisphere(n_samples, pdf):
    sample_set = []
    sample_prob = []
    for i in range(n_samples):
        u1 = random()
        u2 = random()
        omega = pdf.generate_dir(u1, u2)
        sample_set.append(omega)
        sample_prob.append(pdf.get_val(omega))
    return sample_set, sample_prob


# the direction dir of the hemisphere around (0, 1, 0) moved to the hemisphere around normal
def center_around_normal(dir, normal):
    jittered_up = Vector3D(0.00319, 1.0, 0.0078)
    w = normal
    v = Normalize(Cross(jittered_up, w))
    u = Cross(v, w)
    return Normalize(v * dir.x + w * dir.y + u * dir.z)


def oriented_hemi_dir(pdf, u1, u2, new_normal):
    omega = pdf.generate_dir(u1, u2)
    return center_around_normal(omega, new_normal)


def rotate_around_y(alpha, dir_):
    x = dir_.x * cos(alpha) + dir_.z * sin(alpha)
    y = dir_.y
    z = -dir_.x * sin(alpha) + dir_.z * cos(alpha)
    return Vector3D(x, y, z)


# polar coordinates of the directions of a sample set: angle to (0, 1, 0) and azimuth
def euclidean_to_disk(sample_set):
    r = []
    phi = []
    for d in sample_set:
        r.append(acos(Dot(Vector3D(0.0, 1.0, 0.0), d)))
        phi.append(atan2(d.x, d.z))
    return np.array(r), np.array(phi)


def visualize_sample_set(sample_set, weights=[]):
    r, phi = euclidean_to_disk(sample_set)
    n = len(sample_set)
    plt.figure()
    ax = plt.subplot(projection='polar')
    if len(weights) == 0:
        ax.scatter(phi, r)
    else:
        points = ax.scatter(phi, r, c=weights, cmap='jet', vmin=1 / n - 0.3 / n, vmax=1 / n + 0.3 / n)
        plt.colorbar(points)
    plt.axis([0, 2 * pi, 0, pi / 2])
    plt.show()
