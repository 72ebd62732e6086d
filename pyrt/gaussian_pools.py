"""Pools of Gaussian processes for the Bayesian Monte Carlo integrators: checked when an
integrator receives one (check_gp_pool), and made for the command line and the
benchmarks (make_gp_pool), the course's way: GP(SobolevCov(), p_func), each given its own
sample set from sample_set_hemisphere.

A GP of the course (GaussianProcess.py) is read through the attributes students read,
samples_pos and weights; nothing here needs PyRT's own GP, so a student's works too.
"""
import time
from typing import NamedTuple

from PyRT_Common import CosineLobe, is_number, sample_set_hemisphere


def pool_members(my_gp) -> list:
    """The GPs of myGP, one GP or a list (or tuple) of GPs, as a list."""
    return list(my_gp) if isinstance(my_gp, (list, tuple)) else [my_gp]


def check_gp_pool(name, my_gp, n, cosine_prior=False):
    """Raises the error that says what to fix when myGP, handed to the integrator `name`
    with n samples, is not one GP or a non-empty list of GPs, each with n sample positions
    and their weights; with cosine_prior, each GP's p_func must be the cosine,
    CosineLobe(1) (the integrand's known part, which BMC with importance sampling leaves
    to the GP's z)."""
    pool = pool_members(my_gp)
    if not pool:
        raise ValueError(f"{name}: myGP is an empty list; give one GP, or a list of GPs")
    for i, gp in enumerate(pool):
        which = "myGP" if len(pool) == 1 and not isinstance(my_gp, (list, tuple)) else \
            f"myGP[{i}]"
        if not (hasattr(gp, "samples_pos") and hasattr(gp, "weights")):
            raise TypeError(f"{name}: {which} must be a GP of GaussianProcess.py (with "
                            f"samples_pos and weights), got {gp!r}")
        if gp.samples_pos is None or gp.weights is None:
            raise ValueError(f"{name}: {which} has no sample positions yet; call "
                             "gp.add_sample_pos(sample_set) before making the integrator")
        if len(gp.samples_pos) != n or len(gp.weights) != n:
            raise ValueError(f"{name}: n is {n!r} but {which} has "
                             f"{len(gp.samples_pos)} sample positions; give n the number "
                             "of samples of the GPs")
        if cosine_prior and not (isinstance(gp.p_func, CosineLobe) and gp.p_func.exp == 1):
            raise ValueError(f"{name}: {which} must model f = L_i kd alone, the cosine being "
                             "its p: make it with p_func = CosineLobe(1), as in "
                             f"GP(SobolevCov(), CosineLobe(1)); its p_func is {gp.p_func!r}")


class GPPool(NamedTuple):
    """GPs made by make_gp_pool, and the seconds their making took."""
    gps: list
    seconds: float


def make_gp_pool(size, samples, pdf, p_func) -> GPPool:
    """`size` GPs of the course, GP(SobolevCov(), p_func), each with `samples` sample
    positions of its own from sample_set_hemisphere(samples, pdf), drawn one GP after the
    other from random()."""
    if not (is_number(size, whole=True) and size >= 1):
        raise ValueError(f"the pool's size must be a whole number >= 1, got {size!r}")
    from GaussianProcess import GP, SobolevCov  # the course's module, beside the four
    start = time.perf_counter()
    gps = []
    for _ in range(size):
        gp = GP(SobolevCov(), p_func)
        gp.add_sample_pos(sample_set_hemisphere(samples, pdf)[0])
        gps.append(gp)
    return GPPool(gps, time.perf_counter() - start)
