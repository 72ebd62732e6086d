"""GaussianProcess.py's kernels and known parts p on numpy arrays, for PyRT's quadrature.

A kernel of the course that depends on the distance r alone gives its radial profile, k as a
function of r^2 (RadialProfile); a p that depends on the angle to +y alone (Constant,
CosineLobe, a number) gives its polar profile, p as a function of cos(theta)
(PolarProfile). Anything else (a kernel or a Function of your own) is evaluated through its
own eval: on arrays when it computes the same numbers there, else one direction at a time.
"""
import math
from dataclasses import dataclass
from typing import Callable, NamedTuple, Optional

import numpy as np

from PyRT_Common import Constant, CosineLobe, Function, Vector3D, _new

# How many directions an array evaluation is checked on, one at a time, before it is trusted
CHECKED_DIRECTIONS = 3


@dataclass(frozen=True)
class RadialProfile:
    """k(omega_i, omega_j) = g(r^2), r = |omega_i - omega_j|: "sobolev" with parameter s,
    g = 2^(2s-1)/s - (r^2)^(s-1); "se" with parameter l, g = exp(-r^2 / (2 l^2))."""

    kind: str
    parameter: float

    @property
    def positive(self) -> bool:
        """Whether every matrix of the kernel is positive semi-definite: the squared
        exponential's always; the Sobolev kernel's for s up to 2, where r^(2s-2) is
        conditionally negative definite."""
        return self.kind == "se" or self.parameter <= 2

    def __call__(self, r2: np.ndarray) -> np.ndarray:
        if self.kind == "sobolev":
            s = self.parameter
            return 2.0 ** (2 * s - 1) / s - np.power(r2, s - 1)
        return np.exp(r2 * (-1.0 / (2 * self.parameter ** 2)))


@dataclass(frozen=True)
class PolarProfile:
    """p(omega) = scale * cos(theta)^exponent, theta the angle between omega and +y."""

    scale: float
    exponent: float

    def __call__(self, cos_theta: np.ndarray) -> np.ndarray:
        if self.exponent == 0:
            return np.full_like(cos_theta, self.scale)
        return self.scale * np.power(cos_theta, self.exponent)


def radial_profile(cov_func) -> Optional[RadialProfile]:
    """The kernel's RadialProfile, or None for a kernel of one's own (or one whose eval is
    overridden)."""
    give = getattr(cov_func, "radial_profile", None)
    return give() if callable(give) else None


def polar_profile(p_func) -> Optional[PolarProfile]:
    """p's PolarProfile: a number, a Constant or a CosineLobe whose eval is the course's;
    None for any other Function."""
    if not isinstance(p_func, Function):
        return PolarProfile(float(p_func), 0.0)
    if type(p_func).eval is Constant.eval and isinstance(p_func, Constant):
        return PolarProfile(float(p_func.const_value), 0.0)
    if type(p_func).eval is CosineLobe.eval and isinstance(p_func, CosineLobe):
        return PolarProfile(1.0, float(p_func.exp))
    return None


def array_vector(x, y, z):
    """A Vector3D whose components are numpy arrays: one call of a student's eval then
    computes many directions at once (see array_eval)."""
    v = _new(Vector3D)
    v.x, v.y, v.z = x, y, z
    return v


def array_eval(function: Callable, *points: np.ndarray) -> np.ndarray:
    """function(*Vector3Ds) at every row of the (m, 3) arrays points: once on arrays when it
    gives there, for the first CHECKED_DIRECTIONS rows, what it gives one row at a time
    (to 1e-13 relative), else one row at a time."""
    m = len(points[0])
    try:
        with np.errstate(all="ignore"):
            values = np.asarray(function(*(array_vector(*p.T) for p in points)), dtype=float)
        values = np.broadcast_to(values, (m,)).copy()
    except Exception:  # an eval written for floats (math functions, comparisons)
        values = None
    checked = range(min(m, CHECKED_DIRECTIONS))
    singles = [float(function(*(Vector3D(*p[k]) for p in points))) for k in checked]
    if values is not None and all(math.isclose(values[k], singles[k], rel_tol=1e-13,
                                               abs_tol=1e-300) for k in checked):
        return values
    return np.array([float(function(*(Vector3D(*p[k]) for p in points)))
                     for k in range(m)])


def pairwise_r2(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The squared distances |a_i - b_j|^2 of the rows of two (n, 3) and (m, 3) arrays, from
    the differences (which keep their digits for nearby directions)."""
    r2 = np.square(a[:, 0, None] - b[None, :, 0])
    r2 += np.square(a[:, 1, None] - b[None, :, 1])
    r2 += np.square(a[:, 2, None] - b[None, :, 2])
    return r2


class Covariances(NamedTuple):
    """K[i, j] = k(pos_i, pos_j), and whether the kernel makes it positive semi-definite."""

    K: np.ndarray
    positive: bool


def covariance_matrix(cov_func, positions: np.ndarray) -> Optional[Covariances]:
    """Q without noise, K, from the kernel's radial profile; None for a kernel of one's
    own, which GaussianProcess.py's loop evaluates."""
    profile = radial_profile(cov_func)
    if profile is None:
        return None
    return Covariances(profile(pairwise_r2(positions, positions)), profile.positive)
