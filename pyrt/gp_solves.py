"""The linear algebra of GaussianProcess.py: Q checked before it is inverted, the weights
w = z^T Q^-1 refined against Q itself, and the posterior variance of the integral.

Q = K + noise^2 I is symmetric positive definite when the kernel is a covariance and the
noise is positive, or the sample positions all differ; np.linalg.inv of a singular Q
returns garbage or a bare LinAlgError, so check_covariance says which samples to blame.
"""
import numpy as np

from pyrt.gp_kernels import pairwise_r2

# Q's condition number beyond which its inverse keeps no digit worth trusting in double
# precision (1 / eps is 4.5e15): the samples are said to be too close for the noise.
WORST_CONDITION = 1e13
# Two positions whose squared distance is below this are the same direction to rounding
SAME_DIRECTION = 1e-24
# Steps of iterative refinement of the weights, each with the residual in extended precision
REFINEMENTS = 2


def closest_pair(positions: np.ndarray):
    """The indices i < j of the two closest sample positions, and their distance."""
    r2 = pairwise_r2(positions, positions)
    r2[np.diag_indices(len(positions))] = np.inf
    i, j = np.unravel_index(np.argmin(r2), r2.shape)
    return min(i, j), max(i, j), float(np.sqrt(r2[i, j]))


def check_covariance(Q: np.ndarray, positions: np.ndarray, noise: float,
                     positive_kernel: bool = False) -> np.ndarray:
    """Q itself when it can be inverted in double precision; else a ValueError that says
    to add noise or remove the duplicate (or nearly equal) sample, or that the kernel is
    not a covariance. positive_kernel: K is known to be positive semi-definite (PyRT's
    kernels), so that Q's eigenvalues are at least noise^2."""
    if not np.all(np.isfinite(Q)):
        raise ValueError("GP: the covariance matrix Q holds values that are not finite; "
                         "the kernel's eval returns inf or NaN for some pair of samples")
    try:
        np.linalg.cholesky(Q)
        # With K positive semi-definite, Q's eigenvalues lie between noise^2 and its trace:
        # the condition number is computed only when that bound does not settle it
        settled = positive_kernel and np.trace(Q) <= WORST_CONDITION * noise ** 2
        singular = not settled and np.linalg.cond(Q) > WORST_CONDITION
    except np.linalg.LinAlgError:
        singular = True
    if not singular:
        return Q
    if len(positions) > 1:
        i, j, distance = closest_pair(positions)
        same = "the same direction" if distance ** 2 < SAME_DIRECTION else (
            f"{distance:.2g} apart")
        if distance < 1e-3:
            raise ValueError(
                f"GP: Q = K + noise^2 I cannot be inverted: sample positions {i} and {j} "
                f"are {same} and noise_ is {noise:g}; pass a noise_ above 0 (the course's "
                f"0.01) or remove the duplicate sample")
    raise ValueError(f"GP: Q = K + noise^2 I is not positive definite (noise_ {noise:g}): "
                     "the kernel's eval is not a covariance function (k(omega, omega) must "
                     "be largest, k symmetric), or noise_ is too small for these samples")


def refined_weights(Q, z: np.ndarray, invQ: np.ndarray) -> np.ndarray:
    """w = z^T Q^-1, from z @ invQ refined by REFINEMENTS steps w += (z - Q w) @ invQ with
    the residual in extended precision (Q symmetric): good to rounding while Q's condition
    number times the rounding of double precision stays well below 1. Without Q (a
    compute_inv_Q of one's own, which keeps none), z @ invQ as it is."""
    weights = z @ invQ
    if Q is None or np.shape(Q) != np.shape(invQ):
        return weights
    extended_Q = Q.astype(np.longdouble)
    for _ in range(REFINEMENTS):
        residual = z.astype(np.longdouble) - extended_Q @ weights.astype(np.longdouble)
        weights = weights + residual.astype(float) @ invQ
    return weights


def posterior_variance(k_bar: float, z: np.ndarray, weights: np.ndarray) -> float:
    """k-bar - z^T Q^-1 z, the variance of the integral given the samples; never below 0
    (rounding can take a variance of 0 a few units of 1e-16 below it)."""
    return max(float(k_bar - weights @ z), 0.0)
