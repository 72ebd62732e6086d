"""Gaussian processes for Bayesian Monte Carlo (Practices 3 and 4).

Bayesian Monte Carlo (BMC) puts a Gaussian process prior, of mean 0 and covariance k, on
the unknown part f of an integrand f p over the hemisphere around +y (p, p_func, is the
part known analytically: 1, or the cosine). Given the values Y of f at N sample directions,
the integral's posterior mean is

    I = z^T Q^-1 Y = sum over i of w_i Y_i,    Q[i, j] = k(omega_i, omega_j) + noise^2 delta_ij,
                                               z_i = integral of k(omega_i, omega) p(omega),

so the weights w = z^T Q^-1 depend on the sample positions only, never on the values: one
GP serves every estimate made with the same positions. Its variance, k-bar - z^T Q^-1 z
with k-bar the double integral of k p p, says how sure the GP is.

Write ``from GaussianProcess import *``: it brings PyRT_Common's names too, and ``exp``.
"""
from math import exp

from PyRT_Common import *
from PyRT_Common import __all__ as _common_names
# FRAMEWORK ONLY BEGIN
from pyrt.gp_inputs import (check_cov_func, check_noise, check_p_func,
                            check_positive_number, check_values, check_z_estimate,
                            positions_array)
from pyrt.gp_integrals import course_z, exact_z, k_bar
from pyrt.gp_kernels import RadialProfile, covariance_matrix
from pyrt.gp_solves import check_covariance, posterior_variance, refined_weights
# FRAMEWORK ONLY END

__all__ = _common_names + ["exp", "CovarianceFunction", "SobolevCov", "SECov", "GP"]


# ------------------------------------------------------------------------------------------
# Covariance functions (kernels)
# ------------------------------------------------------------------------------------------
class CovarianceFunction(ABC):
    """A covariance function k(omega_i, omega_j) between the values of f at two directions:
    how alike the GP believes them to be."""

    @abstractmethod
    def eval(self, omega_i, omega_j):
        """The covariance k(omega_i, omega_j)."""

    # FRAMEWORK ONLY BEGIN
    def radial_profile(self):
        """k as a function of r^2 on numpy arrays (pyrt/gp_kernels.py), for PyRT's
        quadrature; None: a kernel of one's own is evaluated through its eval."""
        return None
    # FRAMEWORK ONLY END


class SobolevCov(CovarianceFunction):
    """The Sobolev kernel of Marques et al. (2019): with r = |omega_i - omega_j|,

        k(omega_i, omega_j) = 2^(2s-1) / s - r^(2s-2),

    largest, 2^(2s-1)/s (2.487287 at s = 1.4), where omega_i = omega_j."""

    def __init__(self, s=1.4):
        # FRAMEWORK ONLY BEGIN
        check_positive_number("SobolevCov", "s", s, above=1.0)
        # FRAMEWORK ONLY END
        self.s = s

    def eval(self, omega_i, omega_j):
        r = Length(omega_i - omega_j)
        return (2 ** (2 * self.s - 1)) / self.s - r ** (2 * self.s - 2)

    # FRAMEWORK ONLY BEGIN
    def radial_profile(self):
        if type(self).eval is not SobolevCov.eval:
            return None
        return RadialProfile("sobolev", float(self.s))
    # FRAMEWORK ONLY END


class SECov(CovarianceFunction):
    """The squared exponential kernel of Marques et al. (2013), of length scale l: with
    r = |omega_i - omega_j|,

        k(omega_i, omega_j) = exp(-r^2 / (2 l^2)).

    noise is kept as the attribute noise; the GP's own noise_ is what goes on Q's
    diagonal."""

    def __init__(self, l, noise):
        # FRAMEWORK ONLY BEGIN
        check_positive_number("SECov", "l", l)
        # FRAMEWORK ONLY END
        self.l = l
        self.noise = noise

    def eval(self, omega_i, omega_j):
        r = Length(omega_i - omega_j)
        return exp(-(r ** 2) / (2 * self.l ** 2))

    # FRAMEWORK ONLY BEGIN
    def radial_profile(self):
        if type(self).eval is not SECov.eval:
            return None
        return RadialProfile("se", float(self.l))
    # FRAMEWORK ONLY END


# ------------------------------------------------------------------------------------------
# The Gaussian process
# ------------------------------------------------------------------------------------------
class GP:
    """A Gaussian process of covariance cov_func over f, for the integral of f p with p =
    p_func (a Function or a number) known, from N observations Y_i = f(omega_i) + noise:

        I = sum over i of w_i Y_i,  w = z^T Q^-1,  Q = K + noise^2 I,
        z_i = integral over the hemisphere of k(omega_i, omega) p(omega).

    z_estimate chooses how z is computed: "exact" (PyRT's default), by quadrature, to
    rounding; "course", the course's classic Monte Carlo estimate over 50,000 uniform
    directions from sample_set_hemisphere (100,000 draws of random())."""

    def __init__(self, cov_func, p_func, noise_=0.01, z_estimate="exact"):
        # FRAMEWORK ONLY BEGIN
        check_cov_func(cov_func)
        check_p_func(p_func)
        check_noise("GP", noise_)
        check_z_estimate(z_estimate)
        self.z_estimate = z_estimate  # may be set later too, before add_sample_pos
        self.Q = None  # K + noise^2 I, kept to refine the weights
        # FRAMEWORK ONLY END
        self.cov_func = cov_func
        self.p_func = p_func
        self.noise = noise_
        self.samples_pos = None
        self.samples_val = None
        self.invQ = None
        self.z = None
        self.weights = None

    def add_sample_pos(self, samples_pos_):
        # FRAMEWORK ONLY BEGIN
        positions_array(samples_pos_)  # refuses what is not a set of unit directions
        # FRAMEWORK ONLY END
        self.samples_pos = samples_pos_
        self.invQ = self.compute_inv_Q()
        self.z = self.compute_z()
        self.weights = self.z @ self.invQ
        # FRAMEWORK ONLY BEGIN
        # z @ invQ loses digits as Q's condition number grows: refined against Q itself
        self.weights = refined_weights(self.Q, self.z, self.invQ)
        # FRAMEWORK ONLY END

    def add_sample_val(self, samples_val_):
        # FRAMEWORK ONLY BEGIN
        check_values(samples_val_, None if self.samples_pos is None else
                     len(self.samples_pos))
        # FRAMEWORK ONLY END
        self.samples_val = samples_val_

    def compute_inv_Q(self):
        # FRAMEWORK ONLY BEGIN
        positions = positions_array(self.samples_pos)
        known = covariance_matrix(self.cov_func, positions)  # None: a kernel of one's own
        if known is not None:
            self.Q = check_covariance(known.K + self.noise ** 2 * np.identity(len(positions)),
                                      positions, self.noise, known.positive)
            return np.linalg.inv(self.Q)
        # FRAMEWORK ONLY END
        n = len(self.samples_pos)
        Q = np.zeros((n, n))
        # ASSIGNMENT 3.1 BEGIN
        for i in range(n):
            for j in range(n):
                Q[i, j] = self.cov_func.eval(self.samples_pos[i], self.samples_pos[j])
        # ASSIGNMENT 3.1 END
        Q = Q + self.noise ** 2 * np.identity(n)
        # FRAMEWORK ONLY BEGIN
        self.Q = check_covariance(Q, positions, self.noise)
        # FRAMEWORK ONLY END
        return np.linalg.inv(Q)

    def compute_z(self):
        # FRAMEWORK ONLY BEGIN
        positions = positions_array(self.samples_pos)
        check_z_estimate(self.z_estimate)
        if self.z_estimate == "exact":
            return exact_z(self.cov_func, self.p_func, positions)
        z_vec = course_z(self.cov_func, self.p_func, positions)  # None: a kernel of one's own
        if z_vec is not None:
            return z_vec
        # FRAMEWORK ONLY END
        # The course's estimate: classic Monte Carlo over ns_z uniform directions
        ns_z = 50000
        sample_set_z, probab = sample_set_hemisphere(ns_z, UniformPDF())
        ns = len(self.samples_pos)
        z_vec = np.zeros(ns)
        # ASSIGNMENT 3.1 BEGIN
        for i in range(ns):
            total = 0.0
            for omega_j, prob in zip(sample_set_z, probab):
                if isinstance(self.p_func, Function):
                    p = self.p_func.eval(omega_j)
                else:
                    p = self.p_func
                total += self.cov_func.eval(self.samples_pos[i], omega_j) * p / prob
            z_vec[i] = total / ns_z
        # ASSIGNMENT 3.1 END
        return z_vec

    def compute_integral_BMC(self):
        # FRAMEWORK ONLY BEGIN
        if self.weights is None or self.samples_val is None:
            raise ValueError("GP.compute_integral_BMC: call add_sample_pos(positions), then "
                             "add_sample_val(values), before asking for the integral")
        if not isinstance(self.samples_val[0], RGBColor):  # numbers: the sum is a number
            return float(np.dot(self.weights, np.asarray(self.samples_val, dtype=float)))
        # FRAMEWORK ONLY END
        # ASSIGNMENT 3.1 BEGIN
        res = BLACK
        for i in range(len(self.samples_val)):
            res = res + self.samples_val[i] * self.weights[i]
        return res
        # ASSIGNMENT 3.1 END

    # FRAMEWORK ONLY BEGIN
    def compute_variance_BMC(self):
        """The posterior variance of the integral, k-bar - z^T Q^-1 z (k-bar the double
        integral of k p p), from the exact z whatever z_estimate is: how far, by the GP's
        own belief, its estimate lies from the integral (a belief, not a bound)."""
        if self.weights is None:
            raise ValueError("GP.compute_variance_BMC: call add_sample_pos(positions) "
                             "first")
        z = self.z
        if self.z_estimate != "exact":
            z = exact_z(self.cov_func, self.p_func, positions_array(self.samples_pos))
        return posterior_variance(k_bar(self.cov_func, self.p_func), z,
                                  refined_weights(self.Q, z, self.invQ))
    # FRAMEWORK ONLY END
